"""Explicit counterexamples to inequalities printed in seed 003's proofs (Appendix B–C).

Each function builds one concrete state, evaluates the *actual* Lyapunov derivative from the
closed-loop dynamics (the kinematics for the pursuit loop, γ̇ of (45)–(47) for the coordination
loop) and the printed bound, and returns both, so a reader can recompute the violation. Exact
(``fractions.Fraction``) wherever the numbers allow; the one floating-point counterexample (72)
has a violation margin many orders above rounding.

References
----------
seed 003, eqs. (71), (72), (74), (75) and the text after (55).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from theory.core.tolerances import INEQUALITY_RTOL
from theory.pursuit.iss import left_eigenvector
from theory.pursuit.model import closed_loop_rates, exp_skew
from theory.pursuit.model import path as path_numeric

__all__ = [
    "eq71_strict_inequality",
    "eq72_case_search",
    "eq72_printed_region",
    "eq74_missing_connectivity",
    "eq75_missing_norm",
    "xi_not_orthogonal_to_ones",
]


def _ring_laplacian(n: int) -> list[list[Fraction]]:
    """L = I − P of the directed ring 1 ← 2 ← … ← n ← 1 (tracker i hears tracker i+1)."""
    return [
        [Fraction(int(i == j)) - Fraction(int(j == (i + 1) % n)) for j in range(n)]
        for i in range(n)
    ]


def _coordination_vdot(
    laplacian: list[list[Fraction]],
    r: list[Fraction],
    gamma: list[Fraction],
    e_gamma: list[Fraction],
    k_c: Fraction,
    omega_bar: Fraction,
) -> tuple[list[Fraction], Fraction]:
    """ξ = (I − 1rᵀ)γ and V̇_c = ξᵀRξ̇ with ξ̇ = (I − 1rᵀ)γ̇, γ̇ = ω̄1 − k_cLγ + e_γ ((45)–(47))."""
    n = len(r)
    mean = sum(ri * gi for ri, gi in zip(r, gamma, strict=True))
    xi = [g - mean for g in gamma]
    gamma_dot = [
        omega_bar - k_c * sum(laplacian[i][j] * gamma[j] for j in range(n)) + e_gamma[i]
        for i in range(n)
    ]
    mean_dot = sum(ri * gi for ri, gi in zip(r, gamma_dot, strict=True))
    xi_dot = [g - mean_dot for g in gamma_dot]
    return xi, sum(r[i] * xi[i] * xi_dot[i] for i in range(n))


def eq71_strict_inequality() -> dict[str, Any]:
    """(71) prints ‖Φ‖² < μ‖x̃‖²; equality is attained (exactly), so only ≤ holds.

    Table I path r_x = r_y = 30, γ₀ = 0 at γ = π/2: r′(γ) = (−30, 0), μ = 900. With q̃ = (1, 0),
    ṽ = 0: ‖Φ‖² = (q̃ᵀr′)² + ‖Rᵀṽ‖² = 900 = μ‖x̃‖².
    """
    r_prime = (Fraction(-30), Fraction(0))
    q_err, v_err = (Fraction(1), Fraction(0)), (Fraction(0), Fraction(0))
    mu = max(Fraction(1), sum(x * x for x in r_prime))
    phi_sq = sum(a * b for a, b in zip(q_err, r_prime, strict=True)) ** 2 + sum(
        x * x for x in v_err
    )
    x_sq = sum(x * x for x in (*q_err, *v_err))
    return {
        "path": "r_x = r_y = 30, gamma0 = 0, gamma = pi/2",
        "r_prime": [str(x) for x in r_prime],
        "q_tilde": [str(x) for x in q_err],
        "v_tilde": [str(x) for x in v_err],
        "phi_norm_sq": str(phi_sq),
        "mu_x_tilde_sq": str(mu * x_sq),
        "printed_strict_holds": phi_sq < mu * x_sq,
        "corrected_nonstrict_holds": phi_sq <= mu * x_sq,
    }


def eq72_printed_region(theta: float = 0.5) -> dict[str, Any]:
    """(72) prints V̇ ≤ −(1−θ)λ_min(K)‖e‖² for ‖e‖ ≥ c‖x̃‖/θ; false when λ_min(K) < 1.

    2D, Type II, K_p = 0.1 I, k_γ = 0.1 (λ_min(K) = ‖K‖ = 0.1), r_x = r_y = 1 (μ = 1),
    c = √μ + ‖K‖ = 1.1. State: R = I, e_p = (1, 0), e_γ = 0 and x̃ on the printed region's edge
    ‖x̃‖ = 0.99·θ‖e‖/c, aligned with the cross term (ṽ ∥ Re_p, q̃ ∥ Re_p, ‖ṽ‖ : ‖q̃‖ = 1 : 0.1). V̇ is
    evaluated from the kinematics (:func:`theory.pursuit.model.closed_loop_rates`); the corrected
    region ‖e‖ ≥ c‖x̃‖/(θλ_min) of (78) excludes this state.

    Parameters
    ----------
    theta : float
        θ ∈ (0, 1) of eq. (72).
    """
    k = 0.1
    K_p = k * np.eye(2)
    c = 1.0 + k
    e_p = np.array([1.0, 0.0])
    x_norm = 0.99 * theta * float(np.linalg.norm(e_p)) / c  # strictly inside the printed region
    scale = x_norm / math.sqrt(1.0 + k * k)
    rotation = exp_skew([0.3])
    v_err = rotation @ e_p * scale
    q_err = rotation @ e_p * (k * scale)
    path = {"r_x": 1.0, "r_y": 1.0, "gamma0": 0.0}
    gamma, epsilon = 0.7, np.array([1.0, 0.0])
    target, target_v = np.array([5.0, -2.0]), np.array([0.3, 0.1])
    position = rotation @ (e_p + epsilon) + path_numeric(gamma, **path) + target
    omega_d = 0.05
    rates = closed_loop_rates(
        position=position,
        rotation=rotation,
        gamma=gamma,
        gamma_dot=omega_d,
        target_position=target,
        target_velocity=target_v,
        estimate_position=target + q_err,
        estimate_velocity=target_v + v_err,
        epsilon=epsilon,
        K_p=K_p,
        k_gamma=k,
        controller="II",
        omega_d=omega_d,
        omega_d_dot=0.0,
        path_params=path,
    )
    e_norm_sq = float(rates.e_p @ rates.e_p + rates.e_gamma**2)
    printed_bound = -(1.0 - theta) * k * e_norm_sq
    return {
        "parameters": {"dim": 2, "controller": "II", "K_p": "0.1 I", "k_gamma": k, "mu": 1.0},
        "theta": theta,
        "e_norm": math.sqrt(e_norm_sq),
        "x_tilde_norm": x_norm,
        "printed_region_threshold": c * x_norm / theta,
        "corrected_region_threshold": c * x_norm / (theta * k),
        "v_dot": rates.v_dot,
        "printed_bound": printed_bound,
        "violation": rates.v_dot - printed_bound,
    }


def eq74_missing_connectivity() -> dict[str, Any]:
    """(74) prints V̇_c ≤ −k_c r_min‖ξ‖² + …; the factor a(L) is missing (false when a(L) < 1).

    Directed 6-ring (a(L) = 1/2, r = 1/6·1), k_c = 1, e_γ = 0, γ = ξ = (2, 1, −1, −2, −1, 1) (the
    minimiser of Definition 1). Exactly: V̇_c = −1 > −2 = −k_c r_min‖ξ‖².
    """
    n = 6
    L = _ring_laplacian(n)
    r = [Fraction(1, n)] * n
    gamma = [Fraction(x) for x in (2, 1, -1, -2, -1, 1)]
    xi, v_dot = _coordination_vdot(L, r, gamma, [Fraction(0)] * n, Fraction(1), Fraction(1, 10))
    printed = -min(r) * sum(x * x for x in xi)
    corrected = -Fraction(1, 2) * min(r) * sum(x * x for x in xi)
    return {
        "graph": "directed ring of 6 (tracker i hears tracker i+1)",
        "a_L": "1/2",
        "k_c": "1",
        "xi": [str(x) for x in xi],
        "v_dot": str(v_dot),
        "printed_bound": str(printed),
        "corrected_bound": str(corrected),
        "printed_holds": v_dot <= printed,
        "corrected_holds": v_dot <= corrected,
    }


def eq75_missing_norm() -> dict[str, Any]:
    """(75) prints V̇_c ≤ −k_c r_min‖ξ‖² + ‖RW‖‖e‖ (a factor ‖ξ‖ dropped); false for ‖ξ‖ > 1.

    Directed 3-ring, k_c = 1, Type II, e_p = 0, γ = ξ = (10, −10, 0), e_γ = (10, −10, 0).
    Exactly V̇_c = −100/3, while the printed bound is −200/3 + (1/3)·10√2 < −61: compared exactly
    through squares (V̇_c + 200/3 = 100/3 > 10√2/3).
    """
    n = 3
    L = _ring_laplacian(n)
    r = [Fraction(1, n)] * n
    gamma = [Fraction(10), Fraction(-10), Fraction(0)]
    e_gamma = [Fraction(10), Fraction(-10), Fraction(0)]
    xi, v_dot = _coordination_vdot(L, r, gamma, e_gamma, Fraction(1), Fraction(1, 10))
    xi_sq = sum(x * x for x in xi)
    e_sq = sum(x * x for x in e_gamma)
    norm_rw = Fraction(1, 3)  # R W = W/3 and ‖W‖ = 1 (W is the orthogonal projector onto 1⊥)
    slack = v_dot + min(r) * xi_sq  # printed claims slack ≤ ‖RW‖‖e‖
    printed_fails = slack > 0 and slack * slack > norm_rw**2 * e_sq
    corrected_rhs_sq = (norm_rw**2) * xi_sq * e_sq  # ‖ξ‖‖RW‖‖e_γ‖ squared
    corrected_slack = v_dot + Fraction(3, 2) * min(r) * xi_sq  # a(L) = 3/2 for the 3-ring
    return {
        "graph": "directed ring of 3",
        "k_c": "1",
        "xi": [str(x) for x in xi],
        "e_gamma": [str(x) for x in e_gamma],
        "v_dot": str(v_dot),
        "printed_bound": f"-{min(r) * xi_sq} + (1/3)*sqrt({e_sq})",
        "printed_holds": not printed_fails,
        "corrected_holds": corrected_slack <= 0 or corrected_slack**2 <= corrected_rhs_sq,
    }


def xi_not_orthogonal_to_ones() -> dict[str, Any]:
    """The text before (74) says ξ ⊥ 1; in fact ξ = (I − 1rᵀ)γ ⊥ r, and 1ᵀξ ≠ 0 unless r = 1/N.

    Strongly connected, unbalanced digraph on 3 trackers: 1 ↔ 2, 2 → 3, 3 → 1 (a_12 = a_21 =
    a_32 = a_13 = 1). Its left eigenvector is r = (1/4, 1/2, 1/4); with γ = (1, 0, 0),
    ξ = (3/4, −1/4, −1/4): rᵀξ = 0 but 1ᵀξ = 1/4.
    """
    adjacency = [[0, 1, 1], [1, 0, 0], [0, 1, 0]]
    n = 3
    L = [
        [Fraction(sum(adjacency[i]) if i == j else -adjacency[i][j]) for j in range(n)]
        for i in range(n)
    ]
    r = list(left_eigenvector(np.array(adjacency).sum(axis=1) * np.eye(n, dtype=int) - adjacency))
    left_ok = all(sum(r[i] * L[i][j] for i in range(n)) == 0 for j in range(n))
    gamma = [Fraction(1), Fraction(0), Fraction(0)]
    mean = sum(ri * gi for ri, gi in zip(r, gamma, strict=True))
    xi = [g - mean for g in gamma]
    return {
        "adjacency": adjacency,
        "r": [str(x) for x in r],
        "r_is_left_eigenvector": left_ok and sum(r) == 1,
        "xi": [str(x) for x in xi],
        "r_dot_xi": str(sum(ri * x for ri, x in zip(r, xi, strict=True))),
        "ones_dot_xi": str(sum(xi)),
    }


def eq72_case_search(spec, *, starts: int = 64, seed: int = 0) -> dict[str, Any]:
    """Search the case's parameters for a violation of the region printed in (72).

    The printed statement holds for every θ ∈ (0, 1) iff c·eᵀKe ≥ σ(e) for every unit e, where
    σ(e) = sup over R, γ of the cross-term gain, σ(e)² = (‖K_p e_p‖ + |e_γ|√μ_r)² + ‖e_p‖² (the
    sup is attained with Rᵀr′ anti-parallel to K_p e_p; μ_r is the path bound of
    :func:`theory.pursuit.iss.path_mu`). A multi-start local search (``starts`` starts from a seeded
    generator) minimises c·eᵀKe − σ(e); a minimum below −inequality_rtol·c·‖K‖ is a
    counterexample (with θ close to 1), anything else is only "none found".

    Parameters
    ----------
    spec : PursuitSpec
        The case.
    starts : int
        Number of local searches.
    seed : int
        Seed of the ``numpy.random.Generator`` drawing the starting points.

    Returns
    -------
    dict
        ``{"minimum", "minimizer", "violation_found", "starts", "seed"}``.
    """
    from scipy.optimize import minimize

    from theory.pursuit.iss import gain_matrix, pursuit_iss

    pursuit = pursuit_iss(spec)
    K = gain_matrix(spec)
    dim = spec.dim
    root_mu = math.sqrt(float(pursuit.mu_r)) if spec.controller == "II" else 0.0

    def objective(x: np.ndarray) -> float:
        e = x / np.linalg.norm(x)
        e_p, e_gamma = e[:dim], (e[dim] if spec.controller == "II" else 0.0)
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
