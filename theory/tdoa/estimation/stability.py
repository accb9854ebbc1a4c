"""Seed 000 App. A: the stochastic stability lemma (A.1.1), its use along the averaged EKF
(Lemma A.1.2) and the covariance-bound certificates (Lemma A.2.1, Cor. A.2.2).

**Lemma A.1.1** (refs. [49, 50, 56]). Hypotheses: ``v̲ ‖ζ_k‖² ≤ V_k(ζ_k) ≤ v̄ ‖ζ_k‖²`` (A.9) and
``E{V_{k+1}(ζ_{k+1}) | ζ_k} − V_k(ζ_k) ≤ μ − α V_k(ζ_k)`` (A.10), ``v̲, v̄, μ > 0``,
``0 < α ≤ 1``. The printed bound (A.11)
``E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² (1 − α)^k + (μ/v̲) Σ_{l=1}^{k−1} (1 − α)^l`` needs its sum from
``l = 0``: taking expectations in (A.10) gives ``E V_{k+1} ≤ (1 − α) E V_k + μ``; since
``1 − α ≥ 0`` the inequality propagates, and induction gives
``E V_k ≤ (1 − α)^k E V_0 + μ Σ_{l=0}^{k−1} (1 − α)^l``, whence the corrected bound by (A.9). The
printed bound is smaller by exactly ``μ/v̲`` for every ``k ≥ 1``, and the corrected one is
attained: for ``ζ_{k+1} = a ζ_k + w_k`` (``|a| < 1``, ``w_k`` independent, zero-mean,
``E‖w_k‖² = q``, ``V = ‖ζ‖²``), (A.10) holds with equality for ``μ = q``, ``α = 1 − a²``. With
``a = 0``, ``ζ_0 = 0`` the printed bound says ``E‖ζ_1‖² ≤ 0`` while ``E‖ζ_1‖² = q``. "Bounded with
probability one" does not follow either: i.i.d. ``ζ_k ~ N(0, σ² I)`` meet (A.9)–(A.10) and
``P(max_{k≤K} ‖ζ_k‖ ≤ M) = F(M)^K → 0``; the hypotheses give
``sup_k E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² + μ/(v̲ α)``, hence boundedness in probability (Markov).
:func:`rademacher_law` gives the exact law of the linear process with ``w_k = ±s``.

**Lemma A.1.2** along a run of the averaged EKF with one averaging per ping (``τ = T``, the
filter (A.1)–(A.3)): :func:`lemma_a12_along` rebuilds ``P_k = blkdiag(P_k^i)``, ``H_k``, ``K_k``
(A.17), the constants of (A.18)–(A.23), ``1 − α`` of (A.35) and at every ``k`` the smallest
``c_k`` with ``(I − K_kH_k)ᵀ(W⊗A)ᵀP_{k+1}⁻¹(W⊗A)(I − K_kH_k) ≤ c_k P_k⁻¹`` (a generalized
eigenvalue): (A.24) holds at ``k`` iff ``c_k ≤ 1 − α``. The proof's step after (A.32) needs
``I_N ⊗ BQBᵀ ≥ δσ_w² I``, impossible since ``BQBᵀ`` has rank ``d`` of ``2d``.

**Lemma A.2.1.** With ``M_k^j = A (I − K_k^j H_k^j)`` (A.3), a common ``X ≻ 0`` with
``f₁ⁱ(M, X) ≺ r Xⁱ`` for every mode met keeps ``P_{k+1} = f₁(M_k, P_k) + U_k`` bounded; ``f₁`` is
the operator ``J`` of :mod:`theory.consensus.operators` with ``Γ_j = M^j``, checked exactly by the
``covariance-bound`` kind of :mod:`proofs_check`.
"""

from __future__ import annotations

import dataclasses
from collections import defaultdict
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
import sympy as sp
import sympy.stats as stats
from scipy.linalg import block_diag, eigh

from proofs_check.linalg import Matrix, identity, matmul, sub
from theory.consensus.certificates import decrease_strings, float_margin
from theory.core.case_file import Case
from theory.core.certificate_format import envelope, rational_bound, rounded, strings
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, Status
from theory.core.exact import (
    PRECISIONS,
    exact_matrix,
    fraction_strings,
    stochastic_matrix,
    symmetric_projection,
)
from theory.core.network import stationary_vector
from theory.core.tolerances import CERTIFICATE_MARGIN, RANK_TOL
from theory.tdoa.case import Filter, TdoaSimSpec
from theory.tdoa.estimation.filters import kalman_gain
from theory.tdoa.estimation.scenario import TdoaRun, hears_at, run_tdoa_scenario, weights_at
from theory.tdoa.model import cv_discrete, neighbour_lists, tdoa_jacobians

__all__ = [
    "a24_factor",
    "claims",
    "corrected_bound",
    "covariance_bound_certificate",
    "ekf_covariance_bound_certificate",
    "gaussian_drift",
    "lemma_a11_claim",
    "lemma_a12_along",
    "lemma_a12_claim",
    "printed_bound",
    "rademacher_law",
    "symbolic_proof",
]

claims = ClaimSet()


def _check_constants(v_min: Fraction, v_max: Fraction, mu: Fraction, alpha: Fraction) -> None:
    if not (v_min > 0 and v_max >= v_min and mu > 0 and 0 < alpha <= 1):
        raise ValueError(
            f"Lemma A.1.1 needs 0 < v_min ≤ v_max, mu > 0 and 0 < alpha ≤ 1; got v_min={v_min}, "
            f"v_max={v_max}, mu={mu}, alpha={alpha}"
        )


def _bound(
    k: int,
    first: int,
    v_min: Fraction,
    v_max: Fraction,
    mu: Fraction,
    alpha: Fraction,
    mean_square_0: Fraction,
) -> Fraction:
    if k < 0:
        raise ValueError(f"k must be ≥ 0; got {k}")
    _check_constants(v_min, v_max, mu, alpha)
    r = 1 - Fraction(alpha)
    tail = sum((r**l for l in range(first, k)), Fraction(0))
    return Fraction(v_max) / v_min * mean_square_0 * r**k + Fraction(mu) / v_min * tail


def printed_bound(
    k: int,
    *,
    v_min: Fraction,
    v_max: Fraction,
    mu: Fraction,
    alpha: Fraction,
    mean_square_0: Fraction,
) -> Fraction:
    """The right side of (A.11) as printed (``Σ`` from ``l = 1``), exactly; ``0⁰ = 1``."""
    return _bound(k, 1, v_min, v_max, mu, alpha, mean_square_0)


def corrected_bound(
    k: int,
    *,
    v_min: Fraction,
    v_max: Fraction,
    mu: Fraction,
    alpha: Fraction,
    mean_square_0: Fraction,
) -> Fraction:
    """The corrected (A.11), ``Σ`` from ``l = 0``: what Lemma A.1.1's hypotheses imply.

    Equals ``(v̄/v̲) E‖ζ_0‖² (1 − α)^k + μ (1 − (1 − α)^k)/(v̲ α)``.
    """
    return _bound(k, 0, v_min, v_max, mu, alpha, mean_square_0)


def rademacher_law(a: Fraction, s: Fraction, z0: Fraction, k: int) -> dict[Fraction, Fraction]:
    """Exact law (atom → probability) of ``ζ_k`` for ``ζ_{j+1} = a ζ_j ± s`` (probability ½)."""
    if k < 0:
        raise ValueError(f"k must be ≥ 0; got {k}")
    law: dict[Fraction, Fraction] = {Fraction(z0): Fraction(1)}
    half = Fraction(1, 2)
    for _ in range(k):
        step: dict[Fraction, Fraction] = defaultdict(Fraction)
        for z, prob in law.items():
            step[a * z + s] += half * prob
            step[a * z - s] += half * prob
        law = dict(step)
    return law


def gaussian_drift(dim: int) -> dict[str, Any]:
    """Prove ``E‖a z + w‖² = a² ‖z‖² + d σ²`` for ``w ~ N(0, σ² I_d)`` (sympy.stats): the Gaussian
    linear process meets (A.10) with equality for ``V = ‖ζ‖²``, ``μ = d σ²``, ``α = 1 − a²``."""
    a = sp.Symbol("a", real=True)
    sigma = sp.Symbol("sigma", positive=True)
    z = sp.symbols(f"z0:{dim}", real=True)
    w = [stats.Normal(f"w{i}", 0, sigma) for i in range(dim)]
    mean = sp.expand(stats.E(sum((a * z[i] + w[i]) ** 2 for i in range(dim))))
    target = a**2 * sum(zi**2 for zi in z) + dim * sigma**2
    return {"conditional_mean": str(mean), "equals": sp.simplify(mean - target) == 0}


def symbolic_proof() -> dict[str, Any]:
    """The induction behind the corrected (A.11) and the printed bound's shortfall, in sympy.

    With ``r = 1 − α``, ``b_k = r^k b_0 + μ Σ_{l=0}^{k−1} r^l``: ``b_{k+1} − (r b_k + μ) = 0``
    identically in ``k``; ``Σ_{l=0}^{k−1} r^l = (1 − r^k)/α``; and the two sums differ by 1, so
    the printed bound is short by ``μ/v̲``. The residuals ``"0"``, ``"0"``, ``"mu/v_min"`` prove it.
    """
    alpha = sp.Symbol("alpha", positive=True)
    mu, v_min, b0 = sp.symbols("mu v_min b_0", positive=True)
    k = sp.Symbol("k", integer=True, positive=True)
    l = sp.Symbol("l", integer=True)
    r = 1 - alpha

    def geometric(first: sp.Expr, last: sp.Expr) -> sp.Expr:
        return sp.Sum(r**l, (l, first, last)).doit()

    def b(j: sp.Expr) -> sp.Expr:
        return r**j * b0 + mu * geometric(0, j - 1)

    recursion = sp.simplify(b(k + 1) - (r * b(k) + mu))
    closed = sp.simplify(geometric(0, k - 1) - (1 - r**k) / alpha)
    shortfall = sp.simplify(mu / v_min * (geometric(0, k - 1) - geometric(1, k - 1)))
    return {
        "recursion_residual": str(recursion),
        "closed_form_residual": str(closed),
        "corrected_minus_printed": str(shortfall),
        "propagation": "m_k ≤ b_k and 1 − α ≥ 0 give m_{k+1} ≤ (1 − α) m_k + μ ≤ b_{k+1}",
    }


PROCESSES = (
    # (a, s, ζ_0, α): ζ_{k+1} = a ζ_k + w_k, w_k = ±s; α ≤ 1 − a² is the declared rate.
    (Fraction(0), Fraction(1), Fraction(0), Fraction(1, 2)),  # the survey's i.i.d. example
    (Fraction(0), Fraction(1), Fraction(0), Fraction(1)),  # same process, sharpest α
    (Fraction(1, 2), Fraction(1), Fraction(0), Fraction(3, 4)),
    (Fraction(1, 2), Fraction(1), Fraction(3), Fraction(3, 4)),
    (Fraction(-2, 3), Fraction(1, 2), Fraction(1), Fraction(5, 9)),
    (Fraction(9, 10), Fraction(1), Fraction(0), Fraction(19, 100)),
)
"""Linear processes checked exactly, with ``V = ζ²`` (so ``v̲ = v̄ = 1``) and ``μ = s²``."""

STEPS = 8
"""Steps ``k = 0 … STEPS`` at which the exact laws are enumerated (``2^k`` atoms at most)."""

GAUSSIAN_DIMENSIONS = (1, 2, 3)
"""Dimensions ``d`` at which the Gaussian drift ``E‖a z + w‖² = a²‖z‖² + d σ²`` is proved."""


def _process_rows(a: Fraction, s: Fraction, z0: Fraction, alpha: Fraction) -> dict[str, Any]:
    mu = s * s
    constants = {"v_min": Fraction(1), "v_max": Fraction(1), "mu": mu, "alpha": alpha}
    m0 = z0 * z0
    rows = []
    drift_ok = True
    for k in range(STEPS + 1):
        law = rademacher_law(a, s, z0, k)
        mean_square = sum((p * z * z for z, p in law.items()), Fraction(0))
        for z in law:  # (A.10) at every atom: E{V(a z ± s)} − V(z) ≤ μ − α V(z)
            drift = ((a * z + s) ** 2 + (a * z - s) ** 2) / 2 - z * z
            drift_ok &= drift <= mu - alpha * z * z
        printed = printed_bound(k, mean_square_0=m0, **constants)
        corrected = corrected_bound(k, mean_square_0=m0, **constants)
        rows.append(
            {
                "k": k,
                "E_V": str(mean_square),
                "printed_bound": str(printed),
                "corrected_bound": str(corrected),
                "printed_holds": mean_square <= printed,
                "corrected_holds": mean_square <= corrected,
                "corrected_tight": mean_square == corrected,
            }
        )
    return {
        "a": str(a),
        "s": str(s),
        "zeta_0": str(z0),
        "alpha": str(alpha),
        "mu": str(mu),
        "A10_holds_at_every_atom": drift_ok,
        "steps": rows,
    }


def _gaussian_boundedness() -> dict[str, Any]:
    """Numbers for the note on "bounded with probability one" (i.i.d. N(0, 1), M = 5)."""
    per_step = mpmath.erfc(5 / mpmath.sqrt(2))
    stay = {f"K=10^{e}": float((1 - per_step) ** (10**e)) for e in (6, 7, 8)}
    return {
        "statement": "false in general: for i.i.d. ζ_k ~ N(0, σ² I), k ≥ 1 (which meets (A.9)–"
        "(A.10)), P(max_{k≤K} ‖ζ_k‖ ≤ M) = F(M)^K → 0 for every M, so sup_k ‖ζ_k‖ = ∞ almost "
        "surely (second Borel–Cantelli lemma)",
        "d=1_sigma=1_M=5": {"P(|ζ_k| > 5) per step": float(per_step), "P(stay ≤ 5)": stay},
        "what_is_true": "sup_k E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² + μ/(v̲ α), hence bounded in "
        "probability uniformly in k (Markov); almost surely bounded when μ = 0 with (A.10) given "
        "the whole past (non-negative supermartingale) or when the noise is bounded",
    }


@claims.register(
    "seed000.lemA.1.1",
    source="seed 000 App. A, Lemma A.1.1, eqs. (A.9)–(A.11) (from refs. [49, 50, 56])",
    statement="(A.9)–(A.10) imply E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² (1 − α)^k + (μ/v̲) "
    "Σ_{l=1}^{k−1} (1 − α)^l for every k ≥ 0, and ζ_k is bounded with probability one",
)
def lemma_a11_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """Refute the printed (A.11) exactly and prove the bound with the sum from ``l = 0``.

    ``corrected`` when, on the exact laws of :data:`PROCESSES` up to :data:`STEPS`, (A.10) holds
    at every atom, the corrected bound at every ``k`` (tight when ``α = 1 − a²``), the printed
    one fails somewhere and the symbolic proofs succeed. The margin is ``E‖ζ_1‖²`` minus the
    printed bound for the survey's example (``a = 0``, ``ζ_0 = 0``, ``α = ½``, ``s = 1``).
    """
    processes = [_process_rows(*spec) for spec in PROCESSES]
    proof = symbolic_proof()
    gaussian = {f"d={d}": gaussian_drift(d) for d in GAUSSIAN_DIMENSIONS}
    tight, printed_fails = _tightness(processes), _printed_failures(processes)
    holds = _corrected_holds(processes, proof, gaussian) and all(tight)
    status = Status.CORRECTED if any(printed_fails.values()) else Status.VERIFIED
    status = status if holds else Status.REFUTED
    survey = processes[0]["steps"][1]
    evidence = {
        **_counterexample(survey),
        "symbolic_proof": proof,
        "gaussian_drift": gaussian,
        "processes": processes,
        "printed_fails_at_k": printed_fails,
        "tight_when_alpha_is_1_minus_a2": tight,
        "bounded_with_probability_one": _gaussian_boundedness(),
    }
    margin = float(Fraction(survey["E_V"]) - Fraction(survey["printed_bound"]))
    return [ClaimResult(status, Method.EXACT, evidence, margin=margin, message=_message(holds))]


def _tightness(processes: list[dict]) -> list[bool]:
    """For each process with ``α = 1 − a²``: the corrected bound is attained at every ``k``."""
    return [
        all(row["corrected_tight"] for row in p["steps"])
        for p, (a, _, _, alpha) in zip(processes, PROCESSES, strict=True)
        if alpha == 1 - a * a
    ]


def _printed_failures(processes: list[dict]) -> dict[str, list[int]]:
    """The steps ``k`` at which the printed bound (A.11) fails, per process."""
    return {
        f"a={p['a']}, zeta_0={p['zeta_0']}, alpha={p['alpha']}": [
            row["k"] for row in p["steps"] if not row["printed_holds"]
        ]
        for p in processes
    }


def _corrected_holds(processes: list[dict], proof: dict, gaussian: dict) -> bool:
    """(A.10) at every atom, the corrected bound at every k, and the proofs all succeed."""
    drift_ok = all(p["A10_holds_at_every_atom"] for p in processes)
    corrected_ok = all(row["corrected_holds"] for p in processes for row in p["steps"])
    proved = (
        proof["recursion_residual"] == "0"
        and proof["closed_form_residual"] == "0"
        and proof["corrected_minus_printed"] == "mu/v_min"
        and all(g["equals"] for g in gaussian.values())
    )
    return drift_ok and corrected_ok and proved


def _counterexample(survey: dict[str, Any]) -> dict[str, Any]:
    """The survey's i.i.d. example refuting the printed (A.11), and the corrected statement."""
    return {
        "counterexample": {
            "process": "ζ_0 = 0, ζ_k i.i.d. (k ≥ 1) with E‖ζ_k‖² = μ; V = ‖ζ‖², v̲ = v̄ = 1; "
            "E{V(ζ_{k+1}) | ζ_k} − V(ζ_k) = μ − V(ζ_k) ≤ μ − ½ V(ζ_k), so α = ½ (any α ≤ 1)",
            "checked_with": "w_k = ±1 (μ = 1), exact law",
            "printed_bound_k1": survey["printed_bound"],
            "E_norm_sq_k1": survey["E_V"],
            "printed_bound_k": "μ (1 − 2^{1−k}) < μ = E‖ζ_k‖² for every k ≥ 1 (α = ½)",
        },
        "corrected_statement": "E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² (1 − α)^k + (μ/v̲) Σ_{l=0}^{k−1} "
        "(1 − α)^l = (v̄/v̲) E‖ζ_0‖² (1 − α)^k + μ (1 − (1 − α)^k)/(v̲ α); tight",
    }


def _message(holds: bool) -> str:
    if not holds:
        return "the corrected bound or its proof failed a check (see evidence)"
    return (
        "the printed (A.11) (sum from l = 1) fails: ζ_0 = 0, ζ_k i.i.d. with E‖ζ_k‖² = μ, "
        "V = ‖ζ‖², α = ½ gives the bound 0 at k = 1 against E‖ζ_1‖² = μ; with the sum from "
        "l = 0 the bound follows from (A.10) by induction and is attained by ζ_{k+1} = a ζ_k + "
        f"w_k (exact laws, k ≤ {STEPS}); the printed one is short by μ/v̲ at every k ≥ 1. "
        "'Bounded with probability one' does not follow (i.i.d. Gaussian ζ_k are a.s. "
        "unbounded); bounded in probability does"
    )


def lemma_a12_along(spec: TdoaSimSpec, run: TdoaRun) -> dict[str, Any]:
    """Constants of Lemma A.1.2, ``1 − α`` of (A.35) and the factor ``c_k`` of (A.24) at each ping.

    ``spec`` must run the averaged EKF with ``τ = T`` (else ``ValueError``); ``bqb_lower_bound``
    is the largest ``c`` with ``BQBᵀ ≥ cI`` (0). Seed 000 App. A, eqs. (A.1)–(A.35).
    """
    if spec.filter != Filter.AVERAGED or spec.rounds != 1:
        raise ValueError("App. A analyses the averaged EKF with one averaging per ping (tau = T)")
    A, B = cv_discrete(spec.T, 3)
    predicted_x, predicted_P = _predictions(spec, run, A, B @ spec.Q @ B.T)
    factors, weighted, h_norms = _step_factors(spec, run, A, predicted_x, predicted_P)
    eig = np.linalg.eigvalsh(predicted_P[: len(factors) + 1])
    constants = {
        "a_bar": float(np.linalg.norm(A, 2)),
        "delta": float(np.linalg.eigvalsh(B @ B.T)[-1]),
        "h_bar": max(h_norms),
        "p_low": float(eig.min()),
        "p_high": float(eig.max()),
        "sigma_w2": float(np.linalg.eigvalsh(spec.Q)[0]),
        "sigma_v2": spec.r,
    }
    c = constants
    gain_bound = c["p_high"] * c["h_bar"] / c["sigma_v2"]
    one_minus_alpha = 1.0 / (
        1.0 + c["delta"] * c["sigma_w2"] / (c["p_high"] * (1 + gain_bound) ** 2)
    )
    bqb_eig = np.linalg.eigvalsh(B @ spec.Q @ B.T)
    return {
        "constants": constants,
        "one_minus_alpha": one_minus_alpha,
        "factors": np.array(factors),
        "weighted_factors": np.array(weighted),
        "holds": np.array(factors) <= one_minus_alpha,
        "bqb_rank": int(np.sum(bqb_eig > RANK_TOL * bqb_eig[-1])),
        "bqb_lower_bound": float(max(bqb_eig[0], 0.0)),
    }


def _predictions(
    spec: TdoaSimSpec, run: TdoaRun, A: np.ndarray, BQB: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Predicted estimates ``x̂_k^i`` and covariances ``P_k^i`` (A.1)–(A.2) at every ping, rebuilt
    from the recorded averaged ones (and ``x_0``, ``P_0`` at ping 0)."""
    n = spec.n_agents
    predicted_x = np.vstack([np.tile(spec.x0, (1, n, 1)), run.estimates[:-1] @ A.T])
    predicted_P = np.concatenate(
        [np.tile(spec.P0, (1, n, 1, 1)), np.einsum("ij,knjl,ml->knim", A, run.covariances, A)[:-1]]
    )
    predicted_P[1:] += BQB
    return predicted_x, predicted_P


def a24_factor(
    W: np.ndarray,
    A: np.ndarray,
    I_KH: np.ndarray,
    P: np.ndarray,
    P_next: np.ndarray,
    *,
    weights: np.ndarray | None = None,
) -> float:
    """Smallest ``c`` with ``(I − KH)ᵀ(W⊗A)ᵀ Π P_{k+1}⁻¹ (W⊗A)(I − KH) ≤ c Π P_k⁻¹``, a generalized
    eigenvalue; ``Π = diag(weights) ⊗ I`` (``I`` by default: (A.24) as printed).

    Parameters
    ----------
    W : ndarray, shape (N, N)
        The averaging weights.
    A : ndarray, shape (n, n)
        The state transition matrix.
    I_KH : ndarray, shape (nN, nN)
        ``I − K_kH_k`` of the network, block diagonal.
    P, P_next : ndarray, shape (nN, nN)
        ``P_k`` and ``P_{k+1}``, block diagonal, positive definite.
    weights : ndarray, shape (N,), optional
        Positive agent weights ``π`` (the stationary vector of ``W`` in the corrected lemma).

    Returns
    -------
    float
        The factor ``c``; (A.24) holds at this step with ``1 − α`` iff ``c ≤ 1 − α``.

    References
    ----------
    seed 000, App. A, eq. (A.24); docs/errata.md, "Lemma A.1.2 with row-stochastic weights".
    """
    Pi = np.kron(np.diag(np.ones(len(W)) if weights is None else weights), np.eye(A.shape[0]))
    WA = np.kron(W, A) @ I_KH
    lhs = WA.T @ Pi @ np.linalg.inv(P_next) @ WA
    rhs = Pi @ np.linalg.inv(P)
    return float(eigh(0.5 * (lhs + lhs.T), 0.5 * (rhs + rhs.T), eigvals_only=True)[-1])


def _step_factors(
    spec: TdoaSimSpec,
    run: TdoaRun,
    A: np.ndarray,
    predicted_x: np.ndarray,
    predicted_P: np.ndarray,
) -> tuple[list[float], list[float], list[float]]:
    """Per ping ``k``: the smallest ``c_k`` of (A.24), the same in the ``π``-weighted norm of the
    corrected lemma (``π`` the stationary vector of ``W_k``), and ``‖H_k‖``."""
    n = spec.n_agents
    factors, weighted, h_norms = [], [], []
    for k in range(run.truth.shape[0] - 1):
        positions = run.paths[k * spec.rounds]
        W = weights_at(spec, positions)
        neighbours = neighbour_lists(hears_at(spec, positions))
        H = tdoa_jacobians(predicted_x[k, :, :3], positions, neighbours)
        gains_H = [
            kalman_gain(predicted_P[k, i], H[i], spec.r * np.eye(H[i].shape[0])) @ H[i]
            for i in range(n)
        ]
        I_KH = np.eye(6 * n) - block_diag(*gains_H)
        P, P_next = block_diag(*predicted_P[k]), block_diag(*predicted_P[k + 1])
        factors.append(a24_factor(W, A, I_KH, P, P_next))
        weighted.append(a24_factor(W, A, I_KH, P, P_next, weights=stationary_vector(W)))
        h_norms.append(float(np.linalg.norm(block_diag(*H), 2)) if any(h.size for h in H) else 0.0)
    return factors, weighted, h_norms


APPENDIX_A_MAX_STEPS = 40


@claims.register(
    "seed000.lemA.1.2",
    source="seed 000, App. A, Lemma A.1.2, eqs. (A.18)-(A.24), (A.35)",
    statement="Under (A.18)-(A.23), inequality (A.24) holds for all k with alpha of (A.35).",
    kinds=("tdoa-sim",),
)
def lemma_a12_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """Run the case's averaged EKF with ``τ = T`` (seed 0) and check (A.24) at every ping."""
    spec = dataclasses.replace(
        case.spec,
        filter=Filter.AVERAGED,
        tau=case.spec.T,
        steps=min(case.spec.steps, APPENDIX_A_MAX_STEPS),
    )
    out = lemma_a12_along(spec, run_tdoa_scenario(spec, np.random.default_rng(0)))
    margin = float(out["one_minus_alpha"] - out["factors"].max())
    holds = bool(out["holds"].all())
    evidence = {
        "constants": out["constants"],
        "one_minus_alpha": out["one_minus_alpha"],
        "max_factor": float(out["factors"].max()),
        "max_weighted_factor": float(out["weighted_factors"].max()),
        "first_failure_step": None if holds else int(np.argmin(out["holds"])),
        "bqb_rank": out["bqb_rank"],
        "bqb_lower_bound": out["bqb_lower_bound"],
        "seed": 0,
        "steps": spec.steps,
    }
    message = (
        "(A.24) holds along the run, but the proof needs BQB' >= delta sigma_w^2 I, "
        f"impossible for BQB' of rank {out['bqb_rank']} of 6; alpha of (A.35) is "
        f"{1 - out['one_minus_alpha']:.2e}, so the bound (A.11) decays only after "
        "~1/alpha steps"
        if holds
        else "(A.24) fails along the run; in the norm weighted by W's stationary vector (the "
        f"corrected Lemma A.1.2′, docs/errata.md) the largest factor is "
        f"{evidence['max_weighted_factor']:.6g} (proved ≤ 1)"
    )
    status = Status.CORRECTED if holds else Status.REFUTED
    return [ClaimResult(status, Method.SIMULATION, evidence, margin=margin, message=message)]


SOURCE = "seed 000, Lemma A.2.1 and Corollary A.2.2"


def covariance_bound_certificate(
    W: np.ndarray,
    modes: Sequence[Sequence[np.ndarray]],
    X: Sequence[np.ndarray],
    *,
    rate: float | Fraction = 1,
    lmi_margin: float = CERTIFICATE_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Certificate of ``Xⁱ ≻ f₁ⁱ(M, X)`` for each mode ``(M¹ … M^N)`` with one common float
    witness ``X`` (seed 000 Lemma A.2.1, eqs. (A.53)–(A.54)); ``RationalizationError`` if no
    rounding of ``X`` passes the exact check."""
    modes_q = [[exact_matrix(m) for m in mode] for mode in modes]
    data = {
        "W": fraction_strings(stochastic_matrix(W)),
        "modes": [{"M": strings(m)} for m in modes_q],
    }
    floats = [[np.asarray(m, float) for m in mode] for mode in modes]
    return _covariance(data, W, floats, modes_q, X, rate, lmi_margin, precisions, case)


def ekf_covariance_bound_certificate(
    A: np.ndarray,
    Ks: Sequence[Sequence[np.ndarray]],
    Hs: Sequence[Sequence[np.ndarray]],
    W: np.ndarray,
    X: Sequence[np.ndarray],
    *,
    rate: float | Fraction = 1,
    lmi_margin: float = CERTIFICATE_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Cor. A.2.2's hypothesis at listed steps, modes ``M_k^j = A (I − K_k^j H_k^j)`` from the
    gains and Jacobians taken exactly as given (seed 000 eq. (A.55)); as
    :func:`covariance_bound_certificate`."""
    A_q = exact_matrix(A)
    Ks_q = [[exact_matrix(k) for k in ks] for ks in Ks]
    Hs_q = [[exact_matrix(h) for h in hs] for hs in Hs]
    modes_q = _closed_loop_modes(A_q, Ks_q, Hs_q)
    data = {
        "W": fraction_strings(stochastic_matrix(W)),
        "A": fraction_strings(A_q),
        "modes": [{"K": strings(ks), "H": strings(hs)} for ks, hs in zip(Ks_q, Hs_q, strict=True)],
    }
    floats = [[np.array(m, dtype=float) for m in mode] for mode in modes_q]
    return _covariance(data, W, floats, modes_q, X, rate, lmi_margin, precisions, case)


def _closed_loop_modes(
    A: Matrix, Ks: list[list[Matrix]], Hs: list[list[Matrix]]
) -> list[list[Matrix]]:
    """``M_k^j = A (I − K_k^j H_k^j)`` in exact rationals (seed 000 eq. (A.3))."""
    eye = identity(len(A))
    return [
        [matmul(A, sub(eye, matmul(k, h))) for k, h in zip(ks, hs, strict=True)]
        for ks, hs in zip(Ks, Hs, strict=True)
    ]


def _covariance(data, W, modes, modes_q, X, rate, lmi_margin, precisions, case) -> dict:
    bound = rational_bound(rate)
    claim = {
        "statement": "f₁^i(M, X) ≺ rate · X^i for every listed mode M: f_n(M, P) → 0 and "
        "P_{k+1} = f₁(M_k, P_k) + U_k stays bounded for modes M_k from the list (Lemma A.2.1)",
        "rate": str(bound),
    }
    W_q = stochastic_matrix(W)
    margin = min(float_margin("J", W, m, X, float(bound)) for m in modes)

    def build(exact: dict[str, list[Matrix]]) -> dict:
        X_q = exact["X"]
        witness = {
            "X": strings(X_q),
            "decrease": [decrease_strings("J", W_q, m, X_q, bound) for m in modes_q],
        }
        return envelope("covariance-bound", claim, data, witness, source=SOURCE, case=case)

    return rounded(
        build,
        {"X": [symmetric_projection(x) for x in X]},
        margin=margin,
        lmi_margin=lmi_margin,
        precisions=precisions,
        what="covariance-bound",
    )
