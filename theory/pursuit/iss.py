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
:func:`iss_bound`. The quantities a checker must re-verify exactly are listed in
``docs/theory/pursuit-iss.md`` and returned by :func:`iss_certificate_data`.

References
----------
seed 003, Lemma 1, Definition 1, Lemmas 2–4, Theorems 1–2, eqs. (55)–(78).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import scipy.linalg
from scipy.sparse.csgraph import connected_components

from theory.core.errors import InconclusiveError, PropertyFails
from theory.core.exact import exact_decimal
from theory.core.tolerances import INEQUALITY_RTOL, ISS_DIGITS, MARGIN_TOL
from theory.pursuit.case import PursuitSpec, TrackerPath
from theory.pursuit.iss_exact import (
    exact_gain_matrix,
    gain_matrix_definite,
    r_perp_connectivity_positive,
    region_argument_sound,
    safe_constant,
)

__all__ = [
    "Condition",
    "CoordinationIss",
    "IssBound",
    "PursuitIss",
    "coordination_iss",
    "gain_matrix",
    "generalized_algebraic_connectivity",
    "is_psd_exact",
    "iss_bound",
    "iss_certificate_data",
    "iss_conditions",
    "left_eigenvector",
    "path_mu",
    "pursuit_iss",
    "verify_certificate",
]

# ---------------------------------------------------------------------------------------------
# pursuit subsystem (Theorem 1, Lemma 4)


def gain_matrix(spec: PursuitSpec) -> np.ndarray:
    """K = diag(K_p, k_γ) for Type II (eq. (66), ``k_z`` read as k_γ), K = K_p for Type I.

    Parameters
    ----------
    spec : PursuitSpec
        The case.
    """
    if spec.controller == "I":
        return spec.K_p.copy()
    return scipy.linalg.block_diag(spec.K_p, [[spec.k_gamma]])


def path_mu(path: TrackerPath) -> tuple[Fraction, bool]:
    """An exact rational μ_r ≥ sup_γ ‖r′(γ)‖² for path (15)/(16), and whether it is the sup.

    ‖r′‖² = r_x² sin²(γ+γ₀) + r_y² cos²(γ+γ₀) [+ (r_z/c)² cos²(γ/c + γ₀)]. The bound
    max(r_x², r_y²) [+ (r_z/c)²] is the supremum in 2D, and in 3D when r_x = r_y (then the
    vertical term reaches its maximum at some γ); otherwise it is an upper bound.

    Parameters
    ----------
    path : TrackerPath
        One tracker's path constants.

    References
    ----------
    seed 003, eqs. (15), (16), (71).
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

    Attributes
    ----------
    controller : str
    K : ndarray
        Decay matrix of eq. (66).
    lambda_min, norm_K, norm_K_p : float
        λ_min(K), ‖K‖ = λ_max(K) and ‖K_p‖.
    mu_r : Fraction
        max over trackers of the exact bound μ_r ≥ sup_γ ‖r′(γ)‖² (:func:`path_mu`).
    mu : float
        μ = max(1, μ_r) of eq. (71).
    mu_is_supremum : bool
        Whether μ_r is the supremum (otherwise a valid upper bound).
    cross_gain : float
        The paper's c = √μ + ‖K‖ of eqs. (72)/(78).
    paper_gain : float
        c/λ_min(K): the (θ → 1) gain of eq. (78) — valid.
    sharp_cross_gain : float
        c♯ = √(‖K_p‖² + 1 + μ_r) (Type II) or √(‖K_p‖² + 1) (Type I): the cross terms of (70)
        are e_pᵀ[K_p, I](Rᵀq̃, Rᵀṽ) − e_γq̃ᵀr′ ≤ c♯‖e‖‖x̃‖ (k_γ does not enter them).
    decay_rate : float
        λ = λ_min(K): ‖e(t)‖ ≤ e^{−λt}‖e(0)‖ + gain · sup‖x̃‖ (V_e decays at 2λ).
    gain : float
        c♯/λ, the linear ISS gain from ‖x̃‖ to ‖e‖ used by :func:`iss_bound`.
    printed_region_sound : bool
        Whether the printed argument for the region of eq. (72), ‖e‖ ≥ c‖x̃‖/θ, works (iff
        λ_min(K) ≥ 1, decided exactly: K − I ⪰ 0; eq. (78) has the correct c/(θλ_min)).
    printed_region_holds : bool
        Whether the statement (72) is shown to hold for this case by the sufficient test
        c♯ ≤ λ_min·c·(1 − inequality_rtol) (floats, so the test keeps that band from equality;
        ``False`` means not shown this way; see
        :func:`theory.pursuit.iss_counterexamples.eq72_case_search` for the exact criterion).
    """

    controller: str
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


def pursuit_iss(spec: PursuitSpec) -> PursuitIss:
    """The corrected constants of (72)/(78) for ``spec``.

    Parameters
    ----------
    spec : PursuitSpec
        The case.

    References
    ----------
    seed 003, eqs. (65)–(72), (76)–(78).
    """
    K = gain_matrix(spec)
    eigenvalues = np.linalg.eigvalsh(K)
    lam, norm_k = float(eigenvalues[0]), float(eigenvalues[-1])
    norm_kp = float(np.linalg.eigvalsh(spec.K_p)[-1])
    bounds = [path_mu(p) for p in spec.trackers]
    mu_r = max(b for b, _ in bounds)
    mu = float(max(Fraction(1), mu_r))
    is_sup = any(exact and b == mu_r for b, exact in bounds)
    c = math.sqrt(mu) + norm_k
    sharp_sq = norm_kp**2 + 1.0 + (float(mu_r) if spec.controller == "II" else 0.0)
    sharp = math.sqrt(sharp_sq)
    return PursuitIss(
        spec.controller, K, lam, norm_k, norm_kp, mu_r, mu, is_sup, c, c / lam, sharp, lam,
        sharp / lam, region_argument_sound(K), sharp <= lam * c * (1 - INEQUALITY_RTOL),
    )  # fmt: skip


# ---------------------------------------------------------------------------------------------
# coordination subsystem (Lemma 1, Definition 1, Lemma 3)


def left_eigenvector(laplacian: np.ndarray) -> tuple[Fraction, ...] | None:
    """The exact r with rᵀL = 0, rᵀ1 = 1, or ``None`` if the zero eigenvalue is not simple.

    Parameters
    ----------
    laplacian : ndarray of int
        L = D_in − A.

    References
    ----------
    seed 003, Lemma 1.
    """
    import flint

    n = laplacian.shape[0]
    basis, nullity = flint.fmpz_mat(laplacian.T.astype(int).tolist()).nullspace()
    if nullity != 1:
        return None
    vector = [int(basis[i, 0]) for i in range(n)]
    total = sum(vector)
    if total == 0:
        return None
    return tuple(Fraction(x, total) for x in vector)


def _orthogonal_basis(r: np.ndarray) -> np.ndarray:
    """Columns e_i − (r_i / r_N) e_N, i < N: a basis of r⊥ (rational when r is)."""
    n = r.size
    basis = np.zeros((n, n - 1))
    basis[: n - 1, :] = np.eye(n - 1)
    basis[n - 1, :] = -r[: n - 1] / r[n - 1]
    return basis


def generalized_algebraic_connectivity(laplacian: np.ndarray, r: np.ndarray) -> float:
    """a(L) of Definition 1 as a generalized symmetric eigenvalue problem on r⊥.

    a(L) = min over x ⊥ r, x ≠ 0 of xᵀ(RL + LᵀR)x / (2xᵀRx) = λ_min(BᵀMB, 2BᵀRB) for any basis
    B of r⊥ (here the rational basis of :func:`_orthogonal_basis`), M = RL + LᵀR.

    Parameters
    ----------
    laplacian : ndarray
        L = D_in − A of a digraph whose left eigenvector is positive.
    r : ndarray
        That left eigenvector (rᵀL = 0, rᵀ1 = 1, r > 0).

    References
    ----------
    seed 003, Definition 1, eq. (1).
    """
    R = np.diag(r)
    M = R @ laplacian + laplacian.T @ R
    B = _orthogonal_basis(r)
    values = scipy.linalg.eigh(B.T @ M @ B, 2.0 * B.T @ R @ B, eigvals_only=True)
    return float(values[0])


@dataclass(frozen=True)
class CoordinationIss:
    """Constants of the coordination-error ISS estimate (Lemma 3, corrected).

    Attributes
    ----------
    n : int
        Number of trackers.
    laplacian : ndarray
        L = D_in − A.
    strongly_connected, zero_eigenvalue_simple : bool
        Graph facts (strong connectivity is Lemma 3's hypothesis; a simple zero eigenvalue, i.e.
        a spanning tree, is what consensus needs).
    r : tuple of Fraction or None
        Exact left eigenvector (rᵀL = 0, rᵀ1 = 1).
    r_positive : bool
        r > 0 (Lemma 1).
    rl_psd : bool
        RL + LᵀR ⪰ 0, shown exactly: it is symmetric with non-positive off-diagonal entries and
        zero row sums (a weighted undirected Laplacian).
    a_L : float or None
        Generalized algebraic connectivity (None when N = 1 or r is not positive).
    spectral_rate : float or None
        k_c · min Re λ over the non-zero eigenvalues of L (the true decay rate of ξ̇ = −k_cLξ).
    decay_rate : float or None
        α = k_c a(L), the rate of ‖ξ‖_R the corrected proof supports.
    printed_decay_coefficient : float or None
        k_c r_min, the coefficient printed in eq. (74)–(75).
    r_min, r_max, b, kappa, gain : float or None
        min/max r_i, b = ‖R^{1/2}W‖, κ = √(r_max/r_min), gain = b/(√r_min α) from ‖e_γ‖ to ‖ξ‖.
    printed_input_gain : float or None
        ‖RW‖/(k_c r_min), the (θ → 1) gain of eq. (75) as printed.
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


def coordination_iss(spec: PursuitSpec) -> CoordinationIss:
    """The corrected constants of Lemma 3 for ``spec``'s digraph and k_c.

    Parameters
    ----------
    spec : PursuitSpec
        The case.

    References
    ----------
    seed 003, Lemma 1, Definition 1, eqs. (55)–(58), (73)–(75).
    """
    L = spec.laplacian
    n = L.shape[0]
    strongly = n == 1 or connected_components(spec.adjacency, connection="strong")[0] == 1
    r_exact = left_eigenvector(L)
    if r_exact is None:
        return CoordinationIss(n, L, spec.k_c, strongly, zero_eigenvalue_simple=False)
    graph_facts = {
        "r": r_exact,
        "r_positive": all(x > 0 for x in r_exact),
        "rl_psd": _rl_is_laplacian(L, r_exact),
    }
    if n == 1:
        return CoordinationIss(
            n, L, spec.k_c, True, True, **graph_facts, r_min=1.0, r_max=1.0, b=0.0, kappa=1.0,
            gain=0.0, printed_input_gain=0.0,
        )  # fmt: skip
    eigenvalues = np.linalg.eigvals(L.astype(float))
    nonzero = np.delete(eigenvalues, np.argmin(np.abs(eigenvalues)))
    spectral = spec.k_c * float(np.min(nonzero.real))
    if not graph_facts["r_positive"]:
        return CoordinationIss(
            n, L, spec.k_c, strongly, True, **graph_facts, spectral_rate=spectral
        )
    r = np.array([float(x) for x in r_exact])
    a = generalized_algebraic_connectivity(L.astype(float), r)
    R = np.diag(r)
    W = np.eye(n) - np.outer(np.ones(n), r)
    b = math.sqrt(max(float(np.linalg.eigvalsh(W.T @ R @ W)[-1]), 0.0))
    r_min, r_max = float(r.min()), float(r.max())
    alpha = spec.k_c * a
    return CoordinationIss(
        n, L, spec.k_c, strongly, True, **graph_facts,
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
    )  # fmt: skip


def _rl_is_laplacian(L: np.ndarray, r: tuple[Fraction, ...]) -> bool:
    """Exact test that M = RL + LᵀR is symmetric, off-diagonal ≤ 0, with zero row sums (⇒ M ⪰ 0)."""
    n = L.shape[0]
    M = [[r[i] * int(L[i, j]) + int(L[j, i]) * r[j] for j in range(n)] for i in range(n)]
    off_ok = all(M[i][j] <= 0 for i in range(n) for j in range(n) if i != j)
    return off_ok and all(sum(row) == 0 for row in M)


# ---------------------------------------------------------------------------------------------
# the cascade (Theorem 2) and its explicit bound


@dataclass(frozen=True)
class IssBound:
    """‖μ(t)‖ ≤ beta(‖μ(0)‖, t) + gamma(sup_{s∈[0,t]} ‖x̃(s)‖) for μ = col(ξ, e).

    Attributes
    ----------
    beta : callable (r, t) -> float
        Class-KL: r·[κe^{−αt} + (b/√r_min)ψ(t) + e^{−λt}], ψ(t) = sup_{s≥t} φ(s),
        φ(s) = (e^{−λs} − e^{−αs})/(α − λ) (s·e^{−αs} when α = λ); the ψ-term is absent for
        Type I (e_γ ≡ 0) and the ξ-terms for N = 1 (ξ ≡ 0).
    gamma : callable (s) -> float
        Linear gain s·gain.
    gain : float
        g_e(1 + g_ξ) for Type II (N > 1), g_e otherwise.
    constants : dict
        λ, α, κ, b, r_min, g_e, g_ξ used.
    """

    beta: Callable[[float, float], float]
    gamma: Callable[[float], float]
    gain: float
    constants: dict[str, float] = field(default_factory=dict)


def _peak_response(lam: float, alpha: float) -> Callable[[float], float]:
    """ψ(t) = sup_{s≥t} φ(s) for φ(s) = ∫₀ˢ e^{−α(s−u)} e^{−λu} du (non-increasing, → 0)."""

    def phi(s: float) -> float:
        if math.isclose(alpha, lam, rel_tol=1e-12):
            return s * math.exp(-alpha * s)
        return (math.exp(-lam * s) - math.exp(-alpha * s)) / (alpha - lam)

    if math.isclose(alpha, lam, rel_tol=1e-12):
        peak_time = 1.0 / alpha
    else:
        peak_time = math.log(alpha / lam) / (alpha - lam)
    peak = phi(peak_time)
    return lambda t: peak if t <= peak_time else phi(t)


def iss_bound(spec: PursuitSpec) -> IssBound:
    """The explicit ISS estimate of the cascade (Theorem 2, with Lemma 3 and 4 corrected).

    Parameters
    ----------
    spec : PursuitSpec
        The case (use ``load_case(...).spec``).

    Returns
    -------
    IssBound
        Plain callables ``beta(r, t)`` and ``gamma(s)``; ``t`` in seconds, norms Euclidean on the
        stacked vectors μ = col(ξ, e) and x̃ = col(x̃^[1], …, x̃^[N]).

    Raises
    ------
    ValueError
        If the conditions of the analysis fail (see :func:`iss_conditions`).

    References
    ----------
    seed 003, Theorem 2, Lemmas 3–4; Khalil (2002) Lemma 3.4 (comparison lemma).
    """
    failing = [c.name for c in iss_conditions(spec) if c.status == "fails"]
    if failing:
        raise ValueError(f"no ISS estimate: conditions {failing} fail (see iss_conditions)")
    pursuit = pursuit_iss(spec)
    coordination = coordination_iss(spec)
    lam, g_e = pursuit.decay_rate, pursuit.gain
    if spec.n_trackers == 1:
        return IssBound(
            lambda r, t: r * math.exp(-lam * t),
            lambda s: g_e * s,
            g_e,
            {"lambda": lam, "g_e": g_e},
        )
    alpha, kappa, b = coordination.decay_rate, coordination.kappa, coordination.b
    coupling = b / math.sqrt(coordination.r_min)
    constants = {"lambda": lam, "alpha": alpha, "kappa": kappa, "b": b}
    constants.update({"r_min": coordination.r_min, "g_e": g_e})
    if spec.controller == "I":
        constants["g_xi"] = 0.0
        return IssBound(
            lambda r, t: r * (kappa * math.exp(-alpha * t) + math.exp(-lam * t)),
            lambda s: g_e * s,
            g_e,
            constants,
        )
    psi = _peak_response(lam, alpha)
    g_xi = coupling / alpha
    gain = g_e * (1.0 + g_xi)
    constants["g_xi"] = g_xi
    return IssBound(
        lambda r, t: r * (kappa * math.exp(-alpha * t) + coupling * psi(t) + math.exp(-lam * t)),
        lambda s: gain * s,
        gain,
        constants,
    )


# ---------------------------------------------------------------------------------------------
# conditions checked by `trackcert iss`


@dataclass(frozen=True)
class Condition:
    """One condition of the analysis; ``status``: holds, fails, inconclusive or not-applicable.

    Attributes
    ----------
    name : str
        Stable identifier, e.g. ``delta_full_rank``.
    source : str
        Where the condition comes from in the paper (seed 003).
    status : str
        ``holds``, ``fails``, ``inconclusive`` or ``not-applicable``.
    value : object
        The quantity decided (exact values as strings), ``None`` when there is none.
    margin : float or None
        How far ``value`` is from deciding the other way, relative to its scale; compared with
        the margin tolerance.
    detail : str
        One line on how the condition was decided.
    """

    name: str
    source: str
    status: str
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
    det = eps[0] ** 2 * (sum(x * x for x in eps) if spec.dim == 3 else 1)
    norm = math.sqrt(float(sum(x * x for x in eps)))
    margin = abs(float(eps[0])) / norm if norm > 0 else 0.0
    source = "seed 003 eq. (22), Remark 6 (corrected: needs ε₁ ≠ 0)"
    formula = "ε₁²·‖ε‖²" if spec.dim == 3 else "ε₁²"
    if det == 0:
        detail = f"det(ΔΔᵀ) = {formula} = 0: Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ does not exist (ε₁ = 0)"
        return Condition("delta_full_rank", source, "fails", str(det), margin, detail)
    status = "inconclusive" if margin < tol else "holds"
    detail = f"det(ΔΔᵀ) = {formula} = {det} (exact); margin |ε₁|/‖ε‖"
    return Condition("delta_full_rank", source, status, str(det), margin, detail)


def iss_conditions(spec: PursuitSpec, *, margin_tol: float = MARGIN_TOL) -> list[Condition]:
    """Every condition the corrected analysis needs, with its status.

    Parameters
    ----------
    spec : PursuitSpec
    margin_tol : float
        Relative margin under which a numeric condition is inconclusive.

    Returns
    -------
    list of Condition

    References
    ----------
    seed 003, Remark 6, Lemma 1, Definition 1, Lemmas 2–4.
    """
    conditions = [_delta_condition(spec, margin_tol), _gain_condition(pursuit_iss(spec))]
    if spec.n_trackers == 1:
        conditions.append(
            Condition(
                "graph_strongly_connected",
                "seed 003 Lemma 3",
                "not-applicable",
                detail="one tracker: ξ ≡ 0",
            )
        )
        return conditions
    coordination = coordination_iss(spec)
    conditions.append(
        Condition(
            "graph_strongly_connected",
            "seed 003 Lemma 3 (hypothesis)",
            "holds" if coordination.strongly_connected else "fails",
            coordination.strongly_connected,
            detail="networkx strong connectivity of the communication digraph",
        )
    )
    conditions.append(_left_vector_condition(coordination))
    conditions.append(
        Condition(
            "rl_plus_ltr_psd",
            "seed 003 Lemma 1",
            "holds" if coordination.rl_psd else ("fails" if coordination.r else "not-applicable"),
            coordination.rl_psd,
            detail="exact: RL + LᵀR symmetric, off-diagonal ≤ 0, zero row sums",
        )
    )
    conditions.append(_connectivity_condition(coordination))
    return conditions


def _gain_condition(pursuit: PursuitIss) -> Condition:
    symmetric, definite = gain_matrix_definite(pursuit.K)
    ratio = pursuit.lambda_min / pursuit.norm_K if pursuit.norm_K > 0 else 0.0
    status = "holds" if definite and symmetric else "fails" if not definite else "inconclusive"
    detail = {
        "holds": "exact Sylvester test of K (Bareiss on the decimals as written)",
        "fails": "exact Sylvester test: the symmetric part of K is not positive definite",
        "inconclusive": "sym(K) ≻ 0 exactly, but K is not exactly symmetric (the analysis and "
        "the iss certificate state a symmetric K)",
    }[status]
    return Condition(
        "K_positive_definite", "seed 003 eq. (66)", status, pursuit.lambda_min, ratio,
        detail + "; margin λ_min/λ_max (float, informative)",
    )  # fmt: skip


def _left_vector_condition(coordination: CoordinationIss) -> Condition:
    source = "seed 003 Lemma 1"
    if coordination.r is None:
        return Condition(
            "left_eigenvector_positive", source, "fails", None,
            detail="the zero eigenvalue of L is not simple: no unique r (no spanning tree)",
        )  # fmt: skip
    value = [str(x) for x in coordination.r]
    status = "holds" if coordination.r_positive else "fails"
    return Condition(
        "left_eigenvector_positive", source, status, value, float(min(coordination.r)),
        detail="exact rᵀL = 0, rᵀ1 = 1, r > 0",
    )  # fmt: skip


def _connectivity_condition(coordination: CoordinationIss) -> Condition:
    source = "seed 003 Definition 1"
    if coordination.a_L is None:
        return Condition("algebraic_connectivity_positive", source, "not-applicable",
                         detail="a(L) needs a positive left eigenvector")  # fmt: skip
    scale = max(1.0, float(np.max(np.abs(coordination.laplacian))))
    positive = r_perp_connectivity_positive(coordination.laplacian, coordination.r)
    return Condition(
        "algebraic_connectivity_positive", source, "holds" if positive else "fails",
        coordination.a_L, coordination.a_L / scale,
        detail="exact: BᵀMB ≻ 0 on r⊥ (Sylvester), equivalent to a(L) > 0; a(L) = "
        "λ_min(BᵀMB, 2BᵀRB) by scipy eigh, margin a(L)/max|L_ij| (informative)",
    )  # fmt: skip


# ---------------------------------------------------------------------------------------------
# certificate data (for the `iss` certificate kind of proofs_check)


def _grid(x: float, digits: int) -> int:
    """Decimal exponent k so that 10^-k is about 10^-digits relative to |x|."""
    return digits - math.floor(math.log10(abs(x))) if x != 0 else digits


def _rational_above(x: float, *, digits: int = ISS_DIGITS) -> Fraction:
    """A short decimal rational ≥ x (rounded up at ``digits`` significant digits)."""
    k = _grid(x, digits)
    return Fraction(math.ceil(x * 10**k), 10**k) + Fraction(1, 10**k)


def _rational_below(x: float, *, digits: int = ISS_DIGITS) -> Fraction:
    """A short decimal rational ≤ x (rounded down at ``digits`` significant digits)."""
    k = _grid(x, digits)
    return Fraction(math.floor(x * 10**k), 10**k) - Fraction(1, 10**k)


def _sqrt_above(value: Fraction) -> Fraction:
    """A short decimal rational s ≥ √value (checked exactly)."""
    s = _rational_above(math.sqrt(float(value)))
    while s * s < value:
        s += Fraction(1, 10 ** _grid(float(s), ISS_DIGITS))
    return s


def is_psd_exact(matrix: list[list[Fraction]]) -> bool:
    """Exact positive-semidefiniteness of a symmetric rational matrix (LDLᵀ with zero pivots).

    A symmetric matrix is PSD iff symmetric Gaussian elimination meets only pivots ≥ 0 and every
    zero pivot has a zero row below it.

    Parameters
    ----------
    matrix : list of lists of Fraction
        A square matrix (non-symmetric input returns ``False``).
    """
    a = [list(row) for row in matrix]
    n = len(a)
    if any(a[i][j] != a[j][i] for i in range(n) for j in range(i)):
        return False
    for k in range(n):
        pivot = a[k][k]
        if pivot < 0:
            return False
        if pivot == 0:
            if any(a[k][j] != 0 for j in range(k + 1, n)):
                return False
            continue
        for i in range(k + 1, n):
            factor = a[i][k] / pivot
            if factor:
                for j in range(k + 1, n):
                    a[i][j] -= factor * a[k][j]
    return True


def _shifted(matrix: list[list[Fraction]], shift: Fraction, weight=None) -> list[list[Fraction]]:
    """matrix − shift·diag(weight) (weight defaults to the identity)."""
    n = len(matrix)
    w = weight or [Fraction(1)] * n
    return [[matrix[i][j] - (shift * w[i] if i == j else 0) for j in range(n)] for i in range(n)]


def iss_certificate_data(spec: PursuitSpec) -> dict[str, Any]:
    """Plain data for an exact ISS certificate of ``spec`` (see docs/theory/pursuit-iss.md).

    ``data`` holds the case's matrices and constants as exact rationals (``fractions.Fraction``;
    a case number denotes its shortest decimal, :func:`theory.core.exact.exact_decimal`),
    ``witness`` the certificate's constants, rounded in the safe direction at ``iss_digits``
    significant digits (λ below λ_min(K), k̄ above ‖K‖, s above √μ, a below a(L), b above
    ‖R^{1/2}W‖, ρ below √r_min, κ above √(r_max/r_min)) and moved further that way until their
    exact checks pass. Every inequality of
    :data:`CERTIFICATE_INEQUALITIES` is re-verified exactly by :func:`verify_certificate` before
    the data is returned; ``numeric`` repeats the matrices as numpy arrays for convenience.

    Parameters
    ----------
    spec : PursuitSpec
        The case.

    Returns
    -------
    dict
        ``{"data": {...}, "witness": {...}, "inequalities": [...], "numeric": {...}}``.

    Raises
    ------
    PropertyFails
        If a condition of the analysis fails (the corrected Theorem 2 does not apply).
    InconclusiveError
        If a condition lies inside its tolerance.

    References
    ----------
    seed 003, Lemma 1, Definition 1, eqs. (66), (71)–(78); DESIGN.md *Certificates*.
    """
    conditions = iss_conditions(spec)
    failing = [c.name for c in conditions if c.status == "fails"]
    if failing:
        raise PropertyFails(
            f"no ISS certificate: conditions {failing} do not hold (see trackcert iss)"
        )
    undecided = [c.name for c in conditions if c.status == "inconclusive"]
    if undecided:
        raise InconclusiveError(f"no ISS certificate: conditions {undecided} are inconclusive")
    pursuit = pursuit_iss(spec)
    data = _pursuit_data(spec, pursuit)
    witness = _pursuit_witness(spec, pursuit)
    numeric: dict[str, Any] = {"K": pursuit.K, "lambda_min": pursuit.lambda_min}
    if spec.n_trackers > 1:
        _coordination_certificate(spec, data, witness, numeric)
    failed = [name for name, ok in verify_certificate(data, witness) if not ok]
    if failed:
        raise ValueError(f"certificate generation failed its own exact checks: {failed}")
    return {
        "data": data,
        "witness": witness,
        "inequalities": list(CERTIFICATE_INEQUALITIES),
        "numeric": numeric,
    }


def _pursuit_data(spec: PursuitSpec, pursuit: PursuitIss) -> dict[str, Any]:
    """The pursuit part of a certificate's ``data``: the case's numbers as exact rationals."""
    size = len(pursuit.K)
    return {
        "dim": spec.dim,
        "controller": spec.controller,
        "n_trackers": spec.n_trackers,
        "epsilon": [exact_decimal(x) for x in spec.epsilon],
        "K": [[exact_decimal(x) for x in row] for row in pursuit.K],
        "K_p": [[exact_decimal(x) for x in row] for row in spec.K_p],
        "P_e": [[Fraction(int(i == j), 2) for j in range(size)] for i in range(size)],
        "paths": [
            {"r_x": exact_decimal(p.r_x), "r_y": exact_decimal(p.r_y)}
            | ({} if p.r_z is None else {"r_z": exact_decimal(p.r_z), "c": exact_decimal(p.c)})
            for p in spec.trackers
        ],
    }


def _pursuit_witness(spec: PursuitSpec, pursuit: PursuitIss) -> dict[str, Any]:
    """λ below λ_min(K), k̄ above ‖K_p‖, μ_r, s ≥ √(k̄² + 1 (+ μ_r)) and g_e = s/λ (E1–E5).

    λ and k̄ are the float values rounded in the safe direction, then halved (λ) or doubled (k̄)
    until their exact checks E2, E3 pass (:func:`~theory.pursuit.iss_exact.safe_constant`).
    """
    K = exact_gain_matrix(pursuit.K)
    K_p = exact_gain_matrix(spec.K_p)
    lam = safe_constant(
        _rational_below(pursuit.lambda_min), lambda x: _e2_holds(K, x), towards_zero=True
    )
    kp_bar = safe_constant(
        _rational_above(pursuit.norm_K_p), lambda x: _e3_holds(K_p, x), towards_zero=False
    )
    if lam is None or kp_bar is None:
        raise InconclusiveError("no rational λ or k̄_p passes its exact check (E2, E3)")
    needed = kp_bar * kp_bar + 1 + (pursuit.mu_r if spec.controller == "II" else 0)
    witness: dict[str, Any] = {"lambda": lam, "kp_bar": kp_bar, "mu_r": pursuit.mu_r}
    witness["s"] = _sqrt_above(needed)
    witness["g_e"] = witness["s"] / witness["lambda"]
    witness["gain"] = witness["g_e"]
    return witness


def _coordination_certificate(
    spec: PursuitSpec, data: dict[str, Any], witness: dict[str, Any], numeric: dict[str, Any]
) -> None:
    coordination = coordination_iss(spec)
    r = list(coordination.r)
    n = len(r)
    k_c = exact_decimal(spec.k_c)
    data.update({"laplacian": spec.laplacian.astype(int).tolist(), "k_c": k_c})
    witness.update({"r": r, **_coordination_constants(data["laplacian"], r, coordination)})
    witness["alpha"] = k_c * witness["a"]
    two_stage = spec.controller == "II"
    witness["g_xi"] = (
        witness["b"] / (witness["rho"] * witness["alpha"]) if two_stage else Fraction(0)
    )
    witness["gain"] = witness["g_e"] * (1 + witness["g_xi"])
    r_float = np.array([float(x) for x in r])
    numeric.update(
        {
            "R": np.diag(r_float),
            "W": np.eye(n) - np.outer(np.ones(n), r_float),
            "a_L": coordination.a_L,
            "basis_r_perp": _orthogonal_basis(r_float),
        }
    )


def _coordination_constants(
    laplacian: list[list[int]], r: list[Fraction], coordination: CoordinationIss
) -> dict[str, Fraction]:
    """a, b, ρ, κ rounded in the safe direction and moved until C3, C4, C5 pass exactly."""
    L = [[Fraction(x) for x in row] for row in laplacian]
    estimates = {
        "a": (_rational_below(coordination.a_L), lambda x: _c3_holds(L, r, x), True),
        "b": (_rational_above(coordination.b), lambda x: _c4_holds(r, x), False),
        "rho": (_rational_below(math.sqrt(coordination.r_min)), lambda x: _rho_holds(r, x), True),
        "kappa": (_rational_above(coordination.kappa), lambda x: _kappa_holds(r, x), False),
    }
    out = {}
    for name, (estimate, holds, towards_zero) in estimates.items():
        value = safe_constant(estimate, holds, towards_zero=towards_zero)
        if value is None:
            raise InconclusiveError(f"no rational {name} passes its exact check (C3–C5)")
        out[name] = value
    return out


def _matmul(a: list[list[Fraction]], b: list[list[Fraction]]) -> list[list[Fraction]]:
    return [[sum((a[i][k] * b[k][j] for k in range(len(b))), Fraction(0)) for j in range(len(b[0]))]
            for i in range(len(a))]  # fmt: skip


def _transpose(a: list[list[Fraction]]) -> list[list[Fraction]]:
    return [list(col) for col in zip(*a, strict=True)]


def _e2_holds(K: list[list[Fraction]], lam: Fraction) -> bool:
    """E2: λ > 0 and K − λI ⪰ 0 (K symmetric)."""
    return lam > 0 and is_psd_exact(_shifted(K, lam))


def _e3_holds(K_p: list[list[Fraction]], kp_bar: Fraction) -> bool:
    """E3: k̄_p I − K_p ⪰ 0."""
    n = len(K_p)
    return is_psd_exact([[(kp_bar if i == j else 0) - K_p[i][j] for j in range(n)]
                         for i in range(n)])  # fmt: skip


def _c3_holds(L: list[list[Fraction]], r: list[Fraction], a: Fraction) -> bool:
    """C3: a > 0 and Bᵀ(M − 2aR)B ⪰ 0, M = RL + LᵀR, B the rational basis of r⊥."""
    n = len(r)
    M = [[r[i] * L[i][j] + L[j][i] * r[j] for j in range(n)] for i in range(n)]
    B = [[Fraction(int(i == j)) if i < n - 1 else -r[j] / r[n - 1] for j in range(n - 1)]
         for i in range(n)]  # fmt: skip
    return a > 0 and is_psd_exact(_matmul(_matmul(_transpose(B), _shifted(M, 2 * a, r)), B))


def _c4_holds(r: list[Fraction], b: Fraction) -> bool:
    """C4: b ≥ 0 and b²I − WᵀRW ⪰ 0, W = I − 1rᵀ."""
    n = len(r)
    W = [[Fraction(int(i == j)) - r[j] for j in range(n)] for i in range(n)]
    RW = [[r[i] * W[i][j] for j in range(n)] for i in range(n)]
    gap = _shifted(_matmul(_transpose(W), RW), b * b)  # WᵀRW − b²I, must be ⪯ 0
    return b >= 0 and is_psd_exact([[-x for x in row] for row in gap])


def _rho_holds(r: list[Fraction], rho: Fraction) -> bool:
    """C5, first half: ρ > 0 and ρ² ≤ min r_i."""
    return rho > 0 and rho * rho <= min(r)


def _kappa_holds(r: list[Fraction], kappa: Fraction) -> bool:
    """C5, second half: κ² min r_i ≥ max r_i."""
    return kappa * kappa * min(r) >= max(r)


def verify_certificate(data: dict[str, Any], witness: dict[str, Any]) -> list[tuple[str, bool]]:
    """Re-verify :data:`CERTIFICATE_INEQUALITIES` in exact rational arithmetic.

    This is trackcert's own check, used before a certificate is emitted; the independent checker
    (``proofs_check``) re-implements the same list without importing this module.

    Parameters
    ----------
    data : dict
        The ``data`` part of :func:`iss_certificate_data` (exact rationals).
    witness : dict
        The ``witness`` part.

    Returns
    -------
    list of (str, bool)
        Each inequality's label and whether it holds.
    """
    K, K_p, eps = data["K"], data["K_p"], data["epsilon"]
    lam, kp_bar, s = witness["lambda"], witness["kp_bar"], witness["s"]
    mu_paths = [
        max(p["r_x"], p["r_y"]) ** 2 + ((p["r_z"] / p["c"]) ** 2 if "r_z" in p else 0)
        for p in data["paths"]
    ]
    mu_r = max(mu_paths)
    needed = kp_bar * kp_bar + 1 + (mu_r if data["controller"] == "II" else 0)
    results = [
        ("E1", eps[0] != 0),
        ("E2", _e2_holds(K, lam)),
        ("E3", _e3_holds(K_p, kp_bar)),
        ("E4", witness["mu_r"] == mu_r and s >= 0 and s * s >= needed),
        ("E5", witness["g_e"] == s / lam),
    ]
    if data["n_trackers"] == 1:
        return [*results, ("C6", witness["gain"] == witness["g_e"])]
    return results + _verify_coordination(data, witness)


def _verify_coordination(data: dict[str, Any], witness: dict[str, Any]) -> list[tuple[str, bool]]:
    L = [[Fraction(x) for x in row] for row in data["laplacian"]]
    r, a, b, rho, kappa = (witness[k] for k in ("r", "a", "b", "rho", "kappa"))
    n = len(r)
    left = all(sum((r[i] * L[i][j] for i in range(n)), Fraction(0)) == 0 for j in range(n))
    c1 = left and sum(r) == 1 and all(x > 0 for x in r)
    M = [[r[i] * L[i][j] + L[j][i] * r[j] for j in range(n)] for i in range(n)]
    c2 = all(M[i][j] == M[j][i] and (i == j or M[i][j] <= 0) for i in range(n) for j in range(n))
    c2 = c2 and all(sum(row) == 0 for row in M)
    c5 = _rho_holds(r, rho) and _kappa_holds(r, kappa)
    alpha = data["k_c"] * a
    g_xi = b / (rho * alpha) if data["controller"] == "II" else Fraction(0)
    c6 = data["k_c"] > 0 and witness["alpha"] == alpha and witness["g_xi"] == g_xi
    c6 = c6 and witness["gain"] == witness["g_e"] * (1 + g_xi)
    checks = [("C1", c1), ("C2", c2), ("C3", _c3_holds(L, r, a)), ("C4", _c4_holds(r, b))]
    return [*checks, ("C5", c5), ("C6", c6)]


CERTIFICATE_INEQUALITIES = (
    "E1  epsilon_1 != 0 (then det(Delta Delta^T) = eps1^2*|eps|^2 > 0 in 3D, eps1^2 in 2D)",
    "E2  K = diag(K_p, k_gamma) (K_p for Type I) symmetric; K - lambda*I PSD; lambda > 0",
    "E3  kp_bar*I - K_p is positive semidefinite (kp_bar >= ||K_p||)",
    "E4  mu_r = max_i [max(r_x,r_y)^2 (+ (r_z/c)^2 in 3D)]; s >= 0 and "
    "s^2 >= kp_bar^2 + 1 + mu_r (Type II) or kp_bar^2 + 1 (Type I)",
    "E5  g_e = s / lambda  (then ||e(t)|| <= exp(-lambda t)||e(0)|| + g_e sup||x~||)",
    "C1  L = D_in - A from the edges; r^T L = 0, sum(r) = 1, r_i > 0",
    "C2  M = R L + L^T R symmetric, M_ij <= 0 (i != j), row sums 0  (hence M >= 0)",
    "C3  B^T (M - 2 a R) B positive semidefinite for B = [e_i - (r_i/r_N) e_N]_{i<N}, a > 0",
    "C4  b^2 I - W^T R W positive semidefinite, W = I - 1 r^T",
    "C5  rho > 0, rho^2 <= min_i r_i;  kappa^2 * min_i r_i >= max_i r_i",
    "C6  k_c > 0; alpha = k_c a; g_xi = b / (rho alpha) (Type II; 0 for Type I); "
    "gain = g_e (1 + g_xi)",
)
"""The exact list a checker verifies (E: pursuit subsystem, C: coordination, N > 1 only)."""
