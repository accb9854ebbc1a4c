"""ISS Lyapunov analysis of the cooperative pursuit loop of seed 003 (corrected constants).

Two subsystems, connected in cascade (seed 003 Fig. V.3):

* the pursuit error e = col(e^[1], …, e^[N]), e^[i] = [e_p^[i], e_γ^[i]], driven by the estimation
  error x̃ (Theorem 1, Lemma 4). With V_e = ½‖e‖² (eq. (76) with the ½ on both terms),

      V̇_e ≤ −λ_min(K)‖e‖² + c‖e‖‖x̃‖,   c = √μ + ‖K‖, μ = max(1, sup_γ ‖r′(γ)‖²),   (72)/(78)

  and also with the sharper c♯ = √(‖K_p‖² + 1 + μ_r) (Type II; k_γ does not enter the cross
  terms), so ‖e(t)‖ ≤ e^{−λt}‖e(0)‖ + (c♯/λ) sup_{[0,t]}‖x̃‖ with λ = λ_min(K) (comparison
  lemma on W = ‖e‖: Ẇ ≤ −λW + c♯‖x̃‖);
* the coordination error ξ = (I − 1rᵀ)γ (eq. (56)), driven by e_γ (Lemma 3). With
  V_c = ½ξᵀRξ and ξ ⊥ r (not ⊥ 1),

      V̇_c ≤ −k_c a(L) ξᵀRξ + ‖ξ‖_R ‖R^{1/2}W‖ ‖e_γ‖,

  so ‖ξ(t)‖ ≤ κe^{−αt}‖ξ(0)‖ + (b/√r_min)∫₀ᵗ e^{−α(t−s)}‖e_γ(s)‖ds with α = k_c a(L),
  κ = √(r_max/r_min), b = ‖R^{1/2}W‖.

The cascade (Theorem 2) gives ‖μ(t)‖ ≤ β(‖μ(0)‖, t) + γ(sup‖x̃‖) with the explicit β and γ of
:func:`iss_bound`.

Every number of a case denotes its shortest decimal (:func:`theory.core.exact.exact_decimal`), so
the conditions that decide the analysis are decided in rational arithmetic, never by comparing a
float with a threshold: ``K ≻ 0`` (eq. (66)) by Sylvester's test (exact Bareiss elimination);
``λ_min(K) ≥ 1`` (the printed region (72) follows from the argument iff it holds) as K − I ⪰ 0;
``a(L) > 0`` (Definition 1) as BᵀMB ≻ 0 for the rational basis B of r⊥ (M = RL + LᵀR), since
a(L) = λ_min(BᵀMB, 2BᵀRB) and BᵀRB ≻ 0. The float values (λ_min(K), a(L)) are margins only.

The case claims ``seed003.thm1``, ``.lem4``, ``.lem3``, ``.thm2`` state the corrected constants
for a case; :func:`iss_report` is what ``trackcert iss`` reports and :func:`observe_iss` the
``pursuit`` kind's observer.
"""

from __future__ import annotations

import functools
import math
import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from enum import StrEnum
from fractions import Fraction
from typing import Any

import numpy as np

from proofs_check.linalg import positive_definite
from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Finding
from theory.core.errors import CaseError
from theory.core.exact import Matrix, exact_decimal, fractions_of, to_fmpq
from theory.core.expectations import Expectation, Observed, judge
from theory.core.tolerances import INEQUALITY_RTOL, MARGIN_TOL
from theory.core.verdicts import Verdict, all_hold
from theory.pursuit.case import Controller, PursuitSpec, TrackerPath
from theory.pursuit.model import exact_laplacian, left_eigenvector

__all__ = [
    "SCOPE",
    "Condition",
    "ConditionStatus",
    "CoordinationIss",
    "IssBound",
    "IssReport",
    "PursuitIss",
    "claims",
    "coordination_iss",
    "eq72_case_search",
    "exact_gain_matrix",
    "gain_matrix",
    "gain_matrix_definite",
    "generalized_algebraic_connectivity",
    "iss_bound",
    "iss_conditions",
    "iss_observed",
    "iss_record",
    "iss_report",
    "observe_iss",
    "orthogonal_basis",
    "path_mu",
    "pursuit_iss",
    "r_perp_connectivity_positive",
    "r_perp_gram",
    "region_argument_sound",
    "strongly_connected",
]

claims = ClaimSet()

_ANALYSED: weakref.WeakKeyDictionary[PursuitSpec, dict[tuple, Any]] = weakref.WeakKeyDictionary()
"""Per case spec (keyed by the object: a validated spec is frozen and never written), the results
of the analysis functions decorated by :func:`_once_per_spec`."""


def _once_per_spec(function: Callable[..., Any]) -> Any:
    """``function(spec, **options)`` computed once per spec object and options: a sweep point's
    verdict, its run's ISS agreement and the claims ask for the same constants several times."""

    @functools.wraps(function)
    def memoised(spec: PursuitSpec, **options: Any) -> Any:
        results = _ANALYSED.setdefault(spec, {})
        key = (function.__name__, *sorted(options.items()))
        if key not in results:
            results[key] = function(spec, **options)
        return results[key]

    return memoised


# ---------------------------------------------------------------------------------------------
# pursuit subsystem (Theorem 1, Lemma 4)


def gain_matrix(spec: PursuitSpec) -> np.ndarray:
    """K = diag(K_p, k_γ) (Type II; ``k_z`` of seed 003 eq. (66) read as k_γ), K = K_p (Type I)."""
    if spec.controller == Controller.I:
        return spec.K_p.copy()
    n = len(spec.K_p)
    K = np.zeros((n + 1, n + 1))
    K[:n, :n], K[n, n] = spec.K_p, spec.k_gamma
    return K


def path_mu(path: TrackerPath) -> tuple[Fraction, bool]:
    """An exact μ_r ≥ sup_γ ‖r′(γ)‖² for path (15)/(16), and whether it is the sup (eq. (71)).

    ‖r′‖² = r_x² sin²(γ+γ₀) + r_y² cos²(γ+γ₀) [+ (r_z/c)² cos²(γ/c + γ₀)]. The bound
    max(r_x², r_y²) [+ (r_z/c)²] is the supremum in 2D, and in 3D when r_x = r_y (then the
    vertical term reaches its maximum at some γ); otherwise it is an upper bound.
    """
    rx, ry = exact_decimal(path.r_x), exact_decimal(path.r_y)
    bound = max(rx, ry) ** 2
    if path.r_z is None:
        return bound, True
    rz, c = exact_decimal(path.r_z), exact_decimal(path.c)
    return bound + (rz / c) ** 2, rx == ry


@dataclass(frozen=True)
class PursuitIss:
    """Constants of the pursuit-error ISS estimate (Theorem 1 / Lemma 4, corrected).

    ``K`` is the decay matrix of eq. (66), ``mu_r`` the exact path bound (:func:`path_mu`),
    ``mu`` = max(1, μ_r) of eq. (71); ``cross_gain`` is the paper's c = √μ + ‖K‖ and
    ``paper_gain`` = c/λ_min(K) (the θ → 1 gain of (78), valid); ``sharp_cross_gain`` is
    c♯ = √(‖K_p‖² + 1 + μ_r) (Type II) or √(‖K_p‖² + 1) (Type I) — the cross terms of (70) are
    e_pᵀ[K_p, I](Rᵀq̃, Rᵀṽ) − e_γq̃ᵀr′ ≤ c♯‖e‖‖x̃‖ — and ``gain`` = c♯/λ the linear gain with
    ``decay_rate`` λ = λ_min(K). ``printed_region_sound``: the printed argument for (72) works
    (iff λ_min(K) ≥ 1, exactly); ``printed_region_holds``: (72) is shown for the case by the
    sufficient test c♯ ≤ λ_min·c·(1 − inequality_rtol) (``False``: not shown this way).
    """

    controller: Controller
    K: np.ndarray
    lambda_min: float
    norm_K: float
    norm_K_p: float
    mu_r: Fraction
    mu: float
    mu_is_supremum: bool
    cross_gain: float
    paper_gain: float
    sharp_cross_gain: float
    decay_rate: float
    gain: float
    printed_region_sound: bool
    printed_region_holds: bool

    def constants(self) -> dict[str, Any]:
        """λ_min(K), ‖K‖, μ (and whether it is the supremum), c and c♯, as reported."""
        return {
            "lambda_min_K": self.lambda_min,
            "norm_K": self.norm_K,
            "mu": self.mu,
            "mu_is_supremum": self.mu_is_supremum,
            "c_paper": self.cross_gain,
            "c_sharp": self.sharp_cross_gain,
        }


@_once_per_spec
def pursuit_iss(spec: PursuitSpec) -> PursuitIss:
    """The corrected constants of seed 003 (72)/(78) for ``spec`` (eqs. (65)–(72), (76)–(78))."""
    K = gain_matrix(spec)
    eigenvalues = np.linalg.eigvalsh(K)
    lam, norm_k = float(eigenvalues[0]), float(eigenvalues[-1])
    norm_kp = float(np.linalg.eigvalsh(spec.K_p)[-1])
    bounds = [path_mu(p) for p in spec.trackers]
    mu_r = max(b for b, _ in bounds)
    mu = float(max(Fraction(1), mu_r))
    is_sup = any(exact and b == mu_r for b, exact in bounds)
    c = math.sqrt(mu) + norm_k
    sharp_sq = norm_kp**2 + 1.0 + (float(mu_r) if spec.controller == Controller.II else 0.0)
    sharp = math.sqrt(sharp_sq)
    return PursuitIss(
        spec.controller, K, lam, norm_k, norm_kp, mu_r, mu, is_sup, c, c / lam, sharp, lam,
        sharp / lam, region_argument_sound(K), sharp <= lam * c * (1 - INEQUALITY_RTOL),
    )  # fmt: skip


def exact_gain_matrix(K: np.ndarray) -> list[list[Fraction]]:
    """``K`` (seed 003 eq. (66)) with every entry read as its shortest decimal."""
    return [[exact_decimal(float(x)) for x in row] for row in np.asarray(K, dtype=float)]


def _symmetric_part(matrix: list[list[Fraction]]) -> list[list[Fraction]]:
    n = len(matrix)
    return [[(matrix[i][j] + matrix[j][i]) / 2 for j in range(n)] for i in range(n)]


def gain_matrix_definite(K: np.ndarray) -> tuple[bool, bool]:
    """(K exactly symmetric, sym(K) ≻ 0 exactly), seed 003 Lemma 2.

    eᵀKe = eᵀ sym(K) e, so V̇ = −eᵀKe ≤ −λ_min(sym K)‖e‖² needs only the symmetric part; the
    ``iss`` certificate (E2) states K itself and needs it symmetric.
    """
    exact = exact_gain_matrix(K)
    symmetric = all(exact[i][j] == exact[j][i] for i in range(len(exact)) for j in range(i))
    return symmetric, positive_definite(_symmetric_part(exact)).positive


def region_argument_sound(K: np.ndarray) -> bool:
    """Whether λ_min(sym K) ≥ 1 exactly, the condition for the printed region (72) to follow."""
    S = _symmetric_part(exact_gain_matrix(K))
    shifted = [[x - (1 if i == j else 0) for j, x in enumerate(row)] for i, row in enumerate(S)]
    return positive_definite(shifted, semi=True).positive


def eq72_case_search(spec: PursuitSpec, *, starts: int = 64, seed: int = 0) -> dict[str, Any]:
    """Search the case's parameters for a violation of the region printed in seed 003 (72).

    The printed statement holds for every θ ∈ (0, 1) iff c·eᵀKe ≥ σ(e) for every unit e, where
    σ(e) = sup over R, γ of the cross-term gain, σ(e)² = (‖K_p e_p‖ + |e_γ|√μ_r)² + ‖e_p‖² (the
    sup is attained with Rᵀr′ anti-parallel to K_p e_p). A multi-start Nelder–Mead search
    (``starts`` starts drawn with ``seed``) minimises c·eᵀKe − σ(e); a minimum below
    −inequality_rtol·c·‖K‖ is a counterexample (θ close to 1), anything else only "none found".
    """
    from scipy.optimize import minimize

    pursuit = pursuit_iss(spec)
    K = gain_matrix(spec)
    dim = spec.dim
    type_two = spec.controller == Controller.II
    root_mu = math.sqrt(float(pursuit.mu_r)) if type_two else 0.0

    def objective(x: np.ndarray) -> float:
        e = x / np.linalg.norm(x)
        e_p, e_gamma = e[:dim], (e[dim] if type_two else 0.0)
        sigma = math.hypot(
            float(np.linalg.norm(spec.K_p @ e_p)) + abs(e_gamma) * root_mu,
            float(np.linalg.norm(e_p)),
        )
        return pursuit.cross_gain * float(e @ K @ e) - sigma

    rng = np.random.default_rng(seed)
    best = None
    for _ in range(starts):
        result = minimize(objective, rng.standard_normal(K.shape[0]), method="Nelder-Mead")
        if best is None or result.fun < best.fun:
            best = result
    minimizer = best.x / np.linalg.norm(best.x)
    return {
        "minimum": float(best.fun),
        "minimizer": minimizer.tolist(),
        "violation_found": bool(best.fun < -INEQUALITY_RTOL * pursuit.cross_gain * pursuit.norm_K),
        "starts": starts,
        "seed": seed,
    }


# ---------------------------------------------------------------------------------------------
# coordination subsystem (Lemma 1, Definition 1, Lemma 3)


def orthogonal_basis(r: np.ndarray) -> np.ndarray:
    """Columns e_i − (r_i / r_N) e_N, i < N: a basis of r⊥ (rational when r is)."""
    n = r.size
    basis = np.zeros((n, n - 1))
    basis[: n - 1, :] = np.eye(n - 1)
    basis[n - 1, :] = -r[: n - 1] / r[n - 1]
    return basis


def generalized_algebraic_connectivity(laplacian: np.ndarray, r: np.ndarray) -> float:
    """a(L) of seed 003 Definition 1 as a generalized symmetric eigenvalue problem on r⊥.

    a(L) = min over x ⊥ r, x ≠ 0 of xᵀ(RL + LᵀR)x / (2xᵀRx) = λ_min(BᵀMB, 2BᵀRB) for any basis
    B of r⊥ (here :func:`orthogonal_basis`), M = RL + LᵀR, r > 0 the left eigenvector.
    """
    import scipy.linalg  # not on a simulation's path (its ISS agreement needs none of it)

    R = np.diag(r)
    M = R @ laplacian + laplacian.T @ R
    B = orthogonal_basis(r)
    values = scipy.linalg.eigh(B.T @ M @ B, 2.0 * B.T @ R @ B, eigvals_only=True)
    return float(values[0])


def r_perp_gram(laplacian: Any, r: Sequence[Fraction], a: Fraction = Fraction(0)) -> Matrix:
    """Bᵀ(M − 2aR)B for M = RL + LᵀR, R = diag(r) and the rational basis B of r⊥ (exact).

    With a = 0 it decides a(L) > 0 (BᵀMB ≻ 0); with a > 0, a ≤ a(L) (Bᵀ(M − 2aR)B ⪰ 0).
    """
    from flint import fmpq  # exact; imported on use

    n = len(r)
    L = to_fmpq(exact_laplacian(laplacian))
    R = to_fmpq([[r[i] if i == j else Fraction(0) for j in range(n)] for i in range(n)])
    B = to_fmpq([[Fraction(int(i == j)) if i < n - 1 else -r[j] / r[n - 1] for j in range(n - 1)]
                 for i in range(n)])  # fmt: skip
    shifted = R * L + L.transpose() * R - fmpq(2 * a.numerator, a.denominator) * R
    return fractions_of(B.transpose() * shifted * B)


def r_perp_connectivity_positive(laplacian: np.ndarray, r: tuple[Fraction, ...]) -> bool:
    """a(L) > 0 decided exactly as BᵀMB ≻ 0 (Sylvester), seed 003 Definition 1 (r > 0, N ≥ 2)."""
    return positive_definite(r_perp_gram(laplacian, r)).positive


@dataclass(frozen=True)
class CoordinationIss:
    """Constants of the coordination-error ISS estimate (seed 003 Lemma 3, corrected).

    Graph facts: strong connectivity (Lemma 3's hypothesis), a simple zero eigenvalue of L (a
    spanning tree, what consensus needs), the exact left eigenvector ``r`` (rᵀL = 0, rᵀ1 = 1),
    ``r_positive`` (Lemma 1) and ``rl_psd``: RL + LᵀR ⪰ 0 shown exactly (symmetric, off-diagonal
    ≤ 0, zero row sums). Rates: ``a_L`` (None when N = 1 or r ≯ 0), ``spectral_rate`` k_c·min Re λ
    over the non-zero eigenvalues of L (ξ̇ = −k_cLξ's true rate), ``decay_rate`` α = k_c a(L)
    (what the corrected proof supports) and ``printed_decay_coefficient`` k_c r_min of (74)–(75).
    Gains: b = ‖R^{1/2}W‖, κ = √(r_max/r_min), ``gain`` = b/(√r_min α) from ‖e_γ‖ to ‖ξ‖ and
    ``printed_input_gain`` = ‖RW‖/(k_c r_min) of (75).
    """

    n: int
    laplacian: np.ndarray
    k_c: float | None
    strongly_connected: bool
    zero_eigenvalue_simple: bool
    r: tuple[Fraction, ...] | None = None
    r_positive: bool = False
    rl_psd: bool = False
    a_L: float | None = None
    spectral_rate: float | None = None
    decay_rate: float | None = None
    printed_decay_coefficient: float | None = None
    r_min: float | None = None
    r_max: float | None = None
    b: float | None = None
    kappa: float | None = None
    gain: float | None = None
    printed_input_gain: float | None = None


def strongly_connected(adjacency: np.ndarray) -> bool:
    """Whether the digraph of ``adjacency`` (nonzero: an edge) is strongly connected: vertex 0
    reaches every vertex along the edges and against them (seed 003 Lemma 3's hypothesis)."""
    edges = np.asarray(adjacency) != 0
    return _reaches_all(edges) and _reaches_all(edges.T)


def _reaches_all(edges: np.ndarray) -> bool:
    """Breadth-first search from vertex 0 over ``edges[i, j]`` (i → j): every vertex reached."""
    seen = np.zeros(len(edges), dtype=bool)
    seen[0] = True
    frontier = seen.copy()
    while frontier.any():
        frontier = edges[frontier].any(axis=0) & ~seen
        seen |= frontier
    return bool(seen.all())


@_once_per_spec
def coordination_iss(spec: PursuitSpec) -> CoordinationIss:
    """The corrected constants of seed 003 Lemma 3 for ``spec``'s digraph and k_c."""
    L = spec.laplacian
    n = L.shape[0]
    strongly = n == 1 or strongly_connected(spec.adjacency)
    r_exact = left_eigenvector(L)
    if r_exact is None:
        return CoordinationIss(n, L, spec.k_c, strongly, zero_eigenvalue_simple=False)
    r_positive = all(x > 0 for x in r_exact)
    facts = CoordinationIss(
        n, L, spec.k_c, strongly, True, r_exact, r_positive, _rl_is_laplacian(L, r_exact)
    )
    if n == 1:
        return replace(
            facts, r_min=1.0, r_max=1.0, b=0.0, kappa=1.0, gain=0.0, printed_input_gain=0.0
        )
    eigenvalues = np.linalg.eigvals(L.astype(float))
    nonzero = np.delete(eigenvalues, np.argmin(np.abs(eigenvalues)))
    spectral = spec.k_c * float(np.min(nonzero.real))
    if not r_positive:
        return replace(facts, spectral_rate=spectral)
    r = np.array([float(x) for x in r_exact])
    a = generalized_algebraic_connectivity(L.astype(float), r)
    R = np.diag(r)
    W = np.eye(n) - np.outer(np.ones(n), r)
    b = math.sqrt(max(float(np.linalg.eigvalsh(W.T @ R @ W)[-1]), 0.0))
    r_min, r_max = float(r.min()), float(r.max())
    alpha = spec.k_c * a
    return replace(
        facts,
        a_L=a,
        spectral_rate=spectral,
        decay_rate=alpha,
        printed_decay_coefficient=spec.k_c * r_min,
        r_min=r_min,
        r_max=r_max,
        b=b,
        kappa=math.sqrt(r_max / r_min),
        gain=b / (math.sqrt(r_min) * alpha) if alpha > 0 else math.inf,
        printed_input_gain=float(np.linalg.norm(R @ W, 2)) / (spec.k_c * r_min),
    )


def _rl_is_laplacian(L: np.ndarray, r: tuple[Fraction, ...]) -> bool:
    """Exact test that M = RL + LᵀR is symmetric, off-diagonal ≤ 0, with zero row sums (⇒ M ⪰ 0)."""
    n, L = L.shape[0], exact_laplacian(L)
    M = [[r[i] * L[i][j] + L[j][i] * r[j] for j in range(n)] for i in range(n)]
    off_ok = all(M[i][j] <= 0 for i in range(n) for j in range(n) if i != j)
    return off_ok and all(sum(row) == 0 for row in M)


# ---------------------------------------------------------------------------------------------
# the cascade (Theorem 2) and its explicit bound


@dataclass(frozen=True)
class IssBound:
    """‖μ(t)‖ ≤ beta(‖μ(0)‖, t) + gamma(sup_{s∈[0,t]} ‖x̃(s)‖) for μ = col(ξ, e).

    ``beta`` is class-KL: r·[κe^{−αt} + (b/√r_min)ψ(t) + e^{−λt}], ψ(t) = sup_{s≥t} φ(s),
    φ(s) = (e^{−λs} − e^{−αs})/(α − λ) (s·e^{−αs} when α = λ); the ψ-term is absent for Type I
    (e_γ ≡ 0) and the ξ-terms for N = 1 (ξ ≡ 0). ``gamma`` is s·gain with gain = g_e(1 + g_ξ)
    for Type II (N > 1), g_e otherwise; ``constants`` lists λ, α, κ, b, r_min, g_e, g_ξ. Both
    take numbers or arrays of them (NumPy broadcasting: a whole run's records in one call).
    """

    beta: Callable[[Any, Any], Any]
    gamma: Callable[[Any], Any]
    gain: float
    constants: dict[str, float] = field(default_factory=dict)


def _peak_response(lam: float, alpha: float) -> Callable[[Any], Any]:
    """ψ(t) = sup_{s≥t} φ(s) for φ(s) = ∫₀ˢ e^{−α(s−u)} e^{−λu} du (non-increasing, → 0), at a
    time or an array of times."""

    def phi(s: Any) -> Any:
        if math.isclose(alpha, lam, rel_tol=1e-12):
            return s * np.exp(-alpha * s)
        return (np.exp(-lam * s) - np.exp(-alpha * s)) / (alpha - lam)

    if math.isclose(alpha, lam, rel_tol=1e-12):
        peak_time = 1.0 / alpha
    else:
        peak_time = math.log(alpha / lam) / (alpha - lam)
    peak = phi(peak_time)
    return lambda t: np.where(np.asarray(t) <= peak_time, peak, phi(t))[()]


@_once_per_spec
def iss_bound(spec: PursuitSpec) -> IssBound:
    """The explicit ISS estimate of the cascade (seed 003 Theorem 2, Lemmas 3–4 corrected).

    ``t`` in seconds, norms Euclidean on the stacked μ = col(ξ, e) and x̃ (comparison lemma,
    Khalil (2002) Lemma 3.4); ValueError if a condition of :func:`iss_conditions` fails.
    """
    failing = [c.name for c in iss_conditions(spec) if c.status == ConditionStatus.FAILS]
    if failing:
        raise ValueError(f"no ISS estimate: conditions {failing} fail (see iss_conditions)")
    pursuit = pursuit_iss(spec)
    lam, g_e = pursuit.decay_rate, pursuit.gain
    if spec.n_trackers == 1:
        return IssBound(
            lambda r, t: r * np.exp(-lam * t),
            lambda s: g_e * s,
            g_e,
            {"lambda": lam, "g_e": g_e},
        )
    coordination = coordination_iss(spec)
    alpha, kappa, b = coordination.decay_rate, coordination.kappa, coordination.b
    coupling = b / math.sqrt(coordination.r_min)
    constants = {"lambda": lam, "alpha": alpha, "kappa": kappa, "b": b}
    constants.update({"r_min": coordination.r_min, "g_e": g_e})
    if spec.controller == Controller.I:
        constants["g_xi"] = 0.0
        return IssBound(
            lambda r, t: r * (kappa * np.exp(-alpha * t) + np.exp(-lam * t)),
            lambda s: g_e * s,
            g_e,
            constants,
        )
    psi = _peak_response(lam, alpha)
    g_xi = coupling / alpha
    gain = g_e * (1.0 + g_xi)
    constants["g_xi"] = g_xi
    return IssBound(
        lambda r, t: r * (kappa * np.exp(-alpha * t) + coupling * psi(t) + np.exp(-lam * t)),
        lambda s: gain * s,
        gain,
        constants,
    )


# ---------------------------------------------------------------------------------------------
# conditions checked by `trackcert iss`


class ConditionStatus(StrEnum):
    """The status of one condition of the analysis (its value is what the JSON records)."""

    HOLDS = "holds"
    FAILS = "fails"
    INCONCLUSIVE = "inconclusive"
    NOT_APPLICABLE = "not-applicable"


@dataclass(frozen=True)
class Condition:
    """One condition of the analysis, with where it comes from in seed 003 and its status.

    ``value`` is the quantity decided (exact values as strings), ``margin`` how far it is from
    deciding the other way, relative to its scale (compared with the margin tolerance).
    """

    name: str
    source: str
    status: ConditionStatus
    value: Any = None
    margin: float | None = None
    detail: str = ""

    def to_json(self, tolerance: float) -> dict[str, Any]:
        """Plain JSON record, echoing the margin ``tolerance`` the status was decided with."""
        return {
            "name": self.name,
            "source": self.source,
            "status": self.status,
            "value": self.value,
            "margin": self.margin,
            "tolerance": tolerance,
            "detail": self.detail,
        }


def _delta_condition(spec: PursuitSpec, tol: float) -> Condition:
    eps = [exact_decimal(x) for x in spec.epsilon]
    squares = sum(x * x for x in eps)
    det = eps[0] ** 2 * (squares if spec.dim == 3 else 1)
    norm = math.sqrt(float(squares)) if squares < 10**300 else math.inf
    margin = abs(float(eps[0])) / norm if 1e-150 < norm < math.inf else 0.0
    if squares and margin == 0.0:  # ‖ε‖² under- or overflows a float: the exact ratio
        margin = math.sqrt(float(eps[0] ** 2 / squares))
    source = "seed 003 eq. (22), Remark 6 (corrected: needs ε₁ ≠ 0)"
    formula = "ε₁²·‖ε‖²" if spec.dim == 3 else "ε₁²"
    if det == 0:
        detail = f"det(ΔΔᵀ) = {formula} = 0: Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ does not exist (ε₁ = 0)"
        return Condition("delta_full_rank", source, ConditionStatus.FAILS, str(det), margin, detail)
    status = ConditionStatus.INCONCLUSIVE if margin < tol else ConditionStatus.HOLDS
    detail = f"det(ΔΔᵀ) = {formula} = {det} (exact); margin |ε₁|/‖ε‖"
    return Condition("delta_full_rank", source, status, str(det), margin, detail)


def iss_conditions(spec: PursuitSpec, *, margin_tol: float = MARGIN_TOL) -> list[Condition]:
    """Every condition the corrected analysis needs (seed 003 Remark 6, Lemmas 1–4, Def. 1).

    A numeric condition whose relative margin is below ``margin_tol`` is inconclusive.
    """
    return list(_conditions(spec, margin_tol=margin_tol))


@_once_per_spec
def _conditions(spec: PursuitSpec, *, margin_tol: float) -> tuple[Condition, ...]:
    """The conditions of :func:`iss_conditions`, once per spec and tolerance."""
    conditions = [_delta_condition(spec, margin_tol), _gain_condition(pursuit_iss(spec))]
    not_applicable = ConditionStatus.NOT_APPLICABLE
    if spec.n_trackers == 1:
        source, detail = "seed 003 Lemma 3", "one tracker: ξ ≡ 0"
        one = Condition("graph_strongly_connected", source, not_applicable, detail=detail)
        return (*conditions, one)
    coordination = coordination_iss(spec)
    strongly, rl_psd = coordination.strongly_connected, coordination.rl_psd
    rl_status = _holds_or_fails(rl_psd) if rl_psd or coordination.r else not_applicable
    return (
        *conditions,
        Condition(
            "graph_strongly_connected", "seed 003 Lemma 3 (hypothesis)", _holds_or_fails(strongly),
            strongly, detail="networkx strong connectivity of the communication digraph",
        ),
        _left_vector_condition(coordination),
        Condition(
            "rl_plus_ltr_psd", "seed 003 Lemma 1", rl_status, rl_psd,
            detail="exact: RL + LᵀR symmetric, off-diagonal ≤ 0, zero row sums",
        ),
        _connectivity_condition(coordination),
    )  # fmt: skip


def _holds_or_fails(holds: bool) -> ConditionStatus:
    return ConditionStatus.HOLDS if holds else ConditionStatus.FAILS


def _gain_condition(pursuit: PursuitIss) -> Condition:
    symmetric, definite = gain_matrix_definite(pursuit.K)
    ratio = pursuit.lambda_min / pursuit.norm_K if pursuit.norm_K > 0 else 0.0
    if not definite:
        status = ConditionStatus.FAILS
    else:
        status = ConditionStatus.HOLDS if symmetric else ConditionStatus.INCONCLUSIVE
    detail = {
        ConditionStatus.HOLDS: "exact Sylvester test of K (Bareiss on the decimals as written)",
        ConditionStatus.FAILS: "exact Sylvester test: the symmetric part of K is not positive "
        "definite",
        ConditionStatus.INCONCLUSIVE: "sym(K) ≻ 0 exactly, but K is not exactly symmetric (the "
        "analysis and the iss certificate state a symmetric K)",
    }[status]
    return Condition(
        "K_positive_definite", "seed 003 eq. (66)", status, pursuit.lambda_min, ratio,
        detail + "; margin λ_min/λ_max (float, informative)",
    )  # fmt: skip


def _left_vector_condition(coordination: CoordinationIss) -> Condition:
    source = "seed 003 Lemma 1"
    if coordination.r is None:
        return Condition(
            "left_eigenvector_positive", source, ConditionStatus.FAILS, None,
            detail="the zero eigenvalue of L is not simple: no unique r (no spanning tree)",
        )  # fmt: skip
    value = [str(x) for x in coordination.r]
    return Condition(
        "left_eigenvector_positive", source, _holds_or_fails(coordination.r_positive), value,
        float(min(coordination.r)), detail="exact rᵀL = 0, rᵀ1 = 1, r > 0",
    )  # fmt: skip


def _connectivity_condition(coordination: CoordinationIss) -> Condition:
    source = "seed 003 Definition 1"
    if coordination.a_L is None:
        return Condition("algebraic_connectivity_positive", source, ConditionStatus.NOT_APPLICABLE,
                         detail="a(L) needs a positive left eigenvector")  # fmt: skip
    scale = max(1.0, float(np.max(np.abs(coordination.laplacian))))
    positive = r_perp_connectivity_positive(coordination.laplacian, coordination.r)
    return Condition(
        "algebraic_connectivity_positive", source, _holds_or_fails(positive),
        coordination.a_L, coordination.a_L / scale,
        detail="exact: BᵀMB ≻ 0 on r⊥ (Sylvester), equivalent to a(L) > 0; a(L) = "
        "λ_min(BᵀMB, 2BᵀRB) by scipy eigh, margin a(L)/max|L_ij| (informative)",
    )  # fmt: skip


# ---------------------------------------------------------------------------------------------
# case claims: Theorem 1, Lemmas 3–4, Theorem 2 with the case's constants


def _tol(case: Case) -> float:
    return float(case.tolerances.get("margin_tol", MARGIN_TOL))


def _with_status(case: Case, status: ConditionStatus) -> list[str]:
    conditions = iss_conditions(case.spec, margin_tol=_tol(case))
    return [c.name for c in conditions if c.status == status]


def _refuted_delta(case: Case) -> ClaimResult:
    evidence = {"epsilon": case.spec.epsilon.tolist(), "reason": "ε₁ = 0: Δ̄ does not exist"}
    return ClaimResult(
        "refuted", "exact", evidence, message="controller (26) undefined",
        finding=Finding.HYPOTHESES_UNMET,
    )  # fmt: skip


@claims.register(
    "seed003.thm1",
    source="seed 003 Theorem 1, eqs. (67)–(72)",
    statement="controllers (28)/(29) make the tracking error ISS w.r.t. the estimation error",
    kinds=("pursuit",),
)
def check_theorem1(case: Case, ctx: Context) -> list[ClaimResult]:
    """Theorem 1 with the case's constants; the printed region (72) is sound iff λ_min(K) ≥ 1."""
    spec = case.spec
    pursuit = pursuit_iss(spec)
    if "delta_full_rank" in _with_status(case, ConditionStatus.FAILS):
        return [_refuted_delta(case)]
    evidence = pursuit.constants() | {
        "decay_rate": pursuit.decay_rate,
        "iss_gain": pursuit.gain,
        "iss_gain_paper_constants": pursuit.paper_gain,
        "beta": "‖e(0)‖·exp(−λ_min(K)·t)",
        "printed_region_argument_sound": pursuit.printed_region_sound,
        "printed_region_statement_holds_by_sharp_bound": pursuit.printed_region_holds,
        "printed_region_counterexample_search": eq72_case_search(spec),
        "corrected_region": "‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/(θ λ_min(K))",
    }
    status = "verified" if pursuit.printed_region_sound else "corrected"
    message = f"ISS with gain {pursuit.gain:.6g} and rate {pursuit.decay_rate:.6g}"
    return [
        ClaimResult(
            status, "numeric", evidence, margin=pursuit.lambda_min,
            tolerance={"margin_tol": _tol(case)}, message=message,
        )
    ]  # fmt: skip


@claims.register(
    "seed003.lem4",
    source="seed 003 Lemma 4, eqs. (76)–(78)",
    statement="the stacked pursuit error of N trackers is ISS w.r.t. the stacked estimation error",
    kinds=("pursuit",),
)
def check_lemma4(case: Case, ctx: Context) -> list[ClaimResult]:
    """Lemma 4: (78) with the case's constants (its region is the correct one)."""
    if "delta_full_rank" in _with_status(case, ConditionStatus.FAILS):
        return [_refuted_delta(case)]
    pursuit = pursuit_iss(case.spec)
    evidence = {
        "n_trackers": case.spec.n_trackers,
        "lyapunov": "V_e = ½ Σ‖e^[i]‖² ((76) with ½ on both terms)",
        "decay_rate": pursuit.decay_rate,
        "iss_gain": pursuit.gain,
        "iss_gain_paper_constants": pursuit.paper_gain,
        "region": "‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/(θ λ_min(K)) (as printed in (78))",
    }
    return [
        ClaimResult(
            "verified", "numeric", evidence, margin=pursuit.lambda_min,
            tolerance={"margin_tol": _tol(case)}, message=f"ISS with gain {pursuit.gain:.6g}",
        )
    ]  # fmt: skip


@claims.register(
    "seed003.lem3",
    source="seed 003 Lemma 3, Lemma 1, Definition 1, eqs. (55)–(58), (73)–(75)",
    statement="for a strongly connected digraph the coordination error ξ is ISS w.r.t. e",
    kinds=("pursuit",),
)
def check_lemma3(case: Case, ctx: Context) -> list[ClaimResult]:
    """Lemma 3 with the case's graph: corrected rate k_c·a(L), or the failure of its hypothesis."""
    spec = case.spec
    coordination = coordination_iss(spec)
    if spec.n_trackers == 1:
        evidence = {"reason": "one tracker: ξ = (1 − 1·1)γ ≡ 0"}
        message = "trivial for one tracker (ξ ≡ 0)"
        return [ClaimResult("verified", "exact", evidence, message=message)]
    evidence: dict[str, Any] = {
        "strongly_connected": coordination.strongly_connected,
        "zero_eigenvalue_simple": coordination.zero_eigenvalue_simple,
        "r": [str(x) for x in coordination.r] if coordination.r else None,
        "spectral_rate": coordination.spectral_rate,
    }
    if not coordination.zero_eigenvalue_simple:
        evidence["reason"] = "L has a repeated zero eigenvalue: ξ̇ = −k_cLξ does not decay"
        message = "no spanning tree: the coordination error does not converge"
        unmet = Finding.HYPOTHESES_UNMET  # not strongly connected: Lemma 3 says nothing
        return [ClaimResult("refuted", "exact", evidence, message=message, finding=unmet)]
    if coordination.a_L is None:
        evidence["reason"] = (
            "not strongly connected but the zero eigenvalue is simple: ξ still decays at the "
            "spectral rate, though r has zero entries and V_c = ½ξᵀRξ is not a Lyapunov function"
        )
        message = "hypothesis stronger than needed: a spanning tree suffices"
        unmet = Finding.HYPOTHESES_UNMET  # ξ decays, but Lemma 3 as stated says nothing here
        return [ClaimResult("corrected", "numeric", evidence, message=message, finding=unmet)]
    evidence.update(
        {
            "a_L": coordination.a_L,
            "r_min": coordination.r_min,
            "decay_rate_R_norm": coordination.decay_rate,
            "printed_decay_coefficient": coordination.printed_decay_coefficient,
            "corrected_decay_coefficient": coordination.decay_rate * coordination.r_min,
            "input_gain": coordination.gain,
            "printed_input_gain": coordination.printed_input_gain,
            "kappa": coordination.kappa,
        }
    )
    return [
        ClaimResult(
            "corrected", "numeric", evidence, margin=coordination.a_L,
            tolerance={"margin_tol": _tol(case)},
            message=f"decay k_c a(L) = {coordination.decay_rate:.6g} (paper: k_c r_min)",
        )
    ]  # fmt: skip


@claims.register(
    "seed003.thm2",
    source="seed 003 Theorem 2 (cascade of Lemmas 3 and 4)",
    statement="the complete DEC error μ = (ξ, e) is ISS w.r.t. the stacked estimation error",
    kinds=("pursuit",),
)
def check_theorem2(case: Case, ctx: Context) -> list[ClaimResult]:
    """The cascade gain from the corrected lemmas, or the failing condition."""
    failing = _with_status(case, ConditionStatus.FAILS)
    if failing:
        evidence = {"failing_conditions": failing}
        message = (
            f"hypotheses unmet, conditions {failing} fail: Theorem 2 says nothing about this "
            "system (no ISS estimate for the cascade)"
        )
        unmet = Finding.HYPOTHESES_UNMET
        return [ClaimResult("refuted", "numeric", evidence, message=message, finding=unmet)]
    undecided = _with_status(case, ConditionStatus.INCONCLUSIVE)
    if undecided:
        evidence = {"inconclusive_conditions": undecided}
        message = f"conditions {undecided} are inconclusive (margin below margin_tol)"
        return [
            ClaimResult(
                "inconclusive", "numeric", evidence, tolerance={"margin_tol": _tol(case)},
                message=message,
            )
        ]  # fmt: skip
    bound = iss_bound(case.spec)
    conditions = iss_conditions(case.spec, margin_tol=_tol(case))
    margins = [c.margin for c in conditions if c.margin is not None]
    evidence = {
        "gain": bound.gain,
        "constants": bound.constants,
        "beta": "r·[κe^{−αt} + (b/√r_min)ψ(t) + e^{−λt}]",
        "beta_at_0": bound.beta(1.0, 0.0),
    }
    return [
        ClaimResult(
            "verified", "numeric", evidence, margin=min(margins, default=None),
            tolerance={"margin_tol": _tol(case)}, message=f"ISS gain {bound.gain:.6g}",
        )
    ]  # fmt: skip


# ---------------------------------------------------------------------------------------------
# what `trackcert iss` reports, and the kind's observer

SOURCE = "trackcert iss"
"""The observations' source in the command's verdict records."""

SCOPE = (
    "the pursuit and coordination errors μ = (ξ, e) are ISS with respect to the DEKF's "
    "estimation error x̃ (Theorem 2, corrected); x̃ is the input: whether the DEKF keeps it "
    "bounded in closed loop is not part of the certificate"
)
"""What a ``holds`` verdict of ``trackcert iss`` covers (and what it does not)."""


@dataclass(frozen=True)
class IssReport:
    """The record ``trackcert iss`` prints and the case's ``expect`` block judged against it."""

    record: dict[str, Any]
    expectations: tuple[Expectation, ...]

    @property
    def verdict(self) -> Verdict:
        """False if a condition fails, None if one is inconclusive, else True."""
        return all_hold(_verdict(c["status"]) for c in self.record["conditions"])

    def to_json(self) -> dict[str, Any]:
        """The ``--json`` record with its ``expectations``."""
        return {**self.record, "expectations": [e.to_json() for e in self.expectations]}


def iss_report(case: Case, *, margin_tol: float | None = None) -> IssReport:
    """``trackcert iss``: analyze ``case``, run its seed 003 case claims, judge its expectations.

    ``margin_tol`` overrides the case's ``tolerances.margin_tol``; CaseError if the case is not
    of kind ``pursuit`` or ``margin_tol`` is not positive.
    """
    record = iss_record(case, margin_tol=margin_tol)
    record["claims"] = [r.to_json(c.source) for c in claims for r in c.results(case)]
    expectations = judge(case, iss_observed(record), source=SOURCE)
    return IssReport(record, tuple(expectations))


def iss_record(case: Case, *, margin_tol: float | None = None) -> dict[str, Any]:
    """The analysis part of :func:`iss_report` (no claims, no expectations)."""
    from theory.pursuit.derivations import lyapunov_derivative_check  # sympy: imported on use

    if case.kind != "pursuit":
        raise CaseError(
            "kind", "pursuit (trackcert iss analyses seed 003 cases)", case.kind, file=case.file
        )
    tol = _margin_tol(case, margin_tol)
    spec = case.spec
    conditions = iss_conditions(spec, margin_tol=tol)
    pursuit, coordination = pursuit_iss(spec), coordination_iss(spec)
    statuses = {c.status for c in conditions}
    gains: dict[str, Any] = {"pursuit": pursuit.gain, "pursuit_paper": pursuit.paper_gain}
    gains["coordination"] = coordination.gain
    gains["cascade"] = iss_bound(spec).gain if ConditionStatus.FAILS not in statuses else None
    r = [float(x) for x in coordination.r] if coordination.r else None
    identity = lyapunov_derivative_check(spec.dim, spec.controller, True)
    return {
        "case": case.name,
        "source": case.source,
        "controller": spec.controller,
        "dim": spec.dim,
        "n_trackers": spec.n_trackers,
        "holds": not statuses & {ConditionStatus.FAILS, ConditionStatus.INCONCLUSIVE},
        "scope": SCOPE,
        "lyapunov": _lyapunov(spec, len(pursuit.K), r, identity.holds),
        "decay_rate": {
            "pursuit": pursuit.decay_rate,
            "pursuit_lyapunov": 2 * pursuit.decay_rate,
            "coordination": coordination.decay_rate,
            "coordination_spectral": coordination.spectral_rate,
            "coordination_printed_eq75": coordination.printed_decay_coefficient,
        },
        "iss_gain": gains,
        "constants": pursuit.constants()
        | {
            "printed_region_eq72_argument_sound": pursuit.printed_region_sound,
            "printed_region_eq72_holds_by_sharp_bound": pursuit.printed_region_holds,
            "a_L": coordination.a_L,
            "r": r,
            "kappa": coordination.kappa,
            "b": coordination.b,
        },
        "conditions": [c.to_json(tol) for c in conditions],
        "tolerances": {"margin_tol": tol, "inequality_rtol": INEQUALITY_RTOL},
    }


def iss_observed(record: dict[str, Any]) -> Observed:
    """The ``iss``, ``delta_full_rank`` and ``strongly_connected`` keys of an ISS record.

    An inconclusive condition leaves its key (and ``iss``) undecided.
    """
    status = {c["name"]: c["status"] for c in record["conditions"]}
    values = {
        "iss": record["holds"],
        "delta_full_rank": _holds(status.get("delta_full_rank")),
        "strongly_connected": _holds(status.get("graph_strongly_connected", "holds")),
    }
    if ConditionStatus.INCONCLUSIVE in status.values():
        values["iss"] = None
    return Observed(values, frozenset(k for k, v in values.items() if v is None))


def observe_iss(case: Case, ctx: Context) -> Observed:
    """The observer of ``kind: pursuit``: :func:`iss_observed` of the case's :func:`iss_record`."""
    return iss_observed(iss_record(case))


def _verdict(status: str) -> Verdict:
    """A condition's status as a verdict: fails False, inconclusive None, otherwise True."""
    return {ConditionStatus.FAILS: False, ConditionStatus.INCONCLUSIVE: None}.get(status, True)


def _holds(status: str | None) -> bool | None:
    """An observed key: whether the condition holds (``None`` when undecided or absent)."""
    if status in (None, ConditionStatus.INCONCLUSIVE):
        return None
    return status == ConditionStatus.HOLDS


def _margin_tol(case: Case, margin_tol: float | None) -> float:
    if margin_tol is not None and not margin_tol > 0:
        raise CaseError("--margin-tol", "a number > 0", margin_tol, file=case.file)
    tol = margin_tol if margin_tol is not None else case.tolerances.get("margin_tol")
    return float(MARGIN_TOL) if tol is None else float(tol)


def _lyapunov(spec: PursuitSpec, size: int, r: list[float] | None, identity: bool) -> dict:
    return {
        "pursuit": {
            "function": "V_e = ½‖e‖² = eᵀ P_e e, e = col(e_p^[i], e_γ^[i])",
            "P_e": 0.5 * np.eye(size * spec.n_trackers),
            "derivative_identity_eq70": identity,
        },
        "coordination": {
            "function": "V_c = ½ ξᵀ R ξ, ξ = (I − 1rᵀ)γ, R = diag(r)",
            "R": np.diag(r) if r else None,
        },
    }
