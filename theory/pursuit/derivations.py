"""Seed 003's derivations checked on the model: exact identities and explicit counterexamples.

The sympy model (S(ω), Δ, Euler and Cayley rotations) is built from the same ``*_rows`` formulas
as the numeric one (:mod:`theory.pursuit.model`); only what the exact checks alone need lives
here: S as printed in eq. (4), Δ derived from a given S, the Euler-angle rates and the rational
Cayley rotation. Identities (eq. (3), (21), Lemma 2, (70)) are shown by exact cancellation and
return their residual, so a reader sees the cancellation rather than an assertion. The
counterexamples to inequalities printed in Appendices B–C build one concrete state, evaluate the
*actual* Lyapunov derivative from the closed-loop dynamics and the printed bound, exactly
(``Fraction``) wherever the numbers allow; the one floating-point counterexample, (72), has a
violation many orders above rounding. The claims here are about the model alone (run once).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from theory.core.claims import ClaimResult, ClaimSet, Context
from theory.core.tolerances import VIOLATION_TOL
from theory.pursuit.model import (
    closed_loop_rates,
    delta_rows,
    euler_rotation_rows,
    exp_skew,
    left_eigenvector,
    path,
    skew_rows,
)

__all__ = [
    "DeltaCheck",
    "IdentityCheck",
    "cayley_rotation",
    "claims",
    "delta_check",
    "delta_from_skew",
    "delta_matrix",
    "eq71_strict_inequality",
    "eq72_printed_region",
    "eq74_missing_connectivity",
    "eq75_missing_norm",
    "error_dynamics_check",
    "euler_rates",
    "euler_rotation",
    "lyapunov_derivative_check",
    "rotation_rate_check",
    "skew",
    "skew_printed",
    "xi_not_orthogonal_to_ones",
]

claims = ClaimSet()

# ---------------------------------------------------------------------------------------------
# the model as sympy matrices


def skew(omega: sp.Matrix) -> sp.Matrix:
    """S(ω) = [ω]ₓ (3D) or [[0, −r], [r, 0]] (2D), seed 003 eq. (3) (:func:`model.skew_rows`)."""
    return sp.Matrix(skew_rows(list(omega)))


def skew_printed(omega: sp.Matrix) -> sp.Matrix:
    """S(ω) as printed in seed 003 eq. (4): [[0, −r, p], [r, 0, −q], [−p, q, 0]] = [(q, p, r)]ₓ.

    Skew-symmetric, but roll and pitch rates are swapped (in 2D it equals :func:`skew`).
    """
    if len(omega) == 1:
        return skew(omega)
    p, q, r = omega
    return skew(sp.Matrix([q, p, r]))


def delta_matrix(epsilon: sp.Matrix) -> sp.Matrix:
    """Δ exactly as printed in seed 003 eq. (22) (:func:`theory.pursuit.model.delta_rows`)."""
    return sp.Matrix(delta_rows(list(epsilon)))


def delta_from_skew(skew_fn: Callable[[sp.Matrix], sp.Matrix], epsilon: sp.Matrix) -> sp.Matrix:
    """The Δ with Δu = −S(ω)ε + [v₁, 0, …]ᵀ for u = [v₁, ω] and S = ``skew_fn`` (eqs. (5), (21)).

    The expression is linear in u, so Δ is its Jacobian.
    """
    dim = len(epsilon)
    u = sp.symbols("v1 p q r") if dim == 3 else sp.symbols("v1 r")
    omega = sp.Matrix(u[1:])
    body_velocity = sp.Matrix([u[0]] + [0] * (dim - 1))
    expression = -skew_fn(omega) * epsilon + body_velocity
    return expression.jacobian(sp.Matrix(u))


def euler_rotation(angles: sp.Matrix) -> sp.Matrix:
    """R(η): yaw rotation in 2D, Z-Y-X Euler rotation in 3D (seed 003 eq. (2))."""
    return sp.Matrix(euler_rotation_rows(list(angles), cos=sp.cos, sin=sp.sin))


def euler_rates(angles: sp.Matrix, omega: sp.Matrix) -> sp.Matrix:
    """η̇ = T(η)ω for Z-Y-X Euler angles and body rates ω (ψ̇ = r in 2D), behind eq. (2)."""
    if len(angles) == 1:
        return sp.Matrix([omega[0]])
    phi, theta, _ = angles
    p, q, r = omega
    return sp.Matrix(
        [
            p + (q * sp.sin(phi) + r * sp.cos(phi)) * sp.tan(theta),
            q * sp.cos(phi) - r * sp.sin(phi),
            (q * sp.sin(phi) + r * sp.cos(phi)) / sp.cos(theta),
        ]
    )


def cayley_rotation(params: sp.Matrix) -> sp.Matrix:
    """R = (I − A)⁻¹(I + A) for the skew A of ``params`` (1 in 2D, 3 in 3D), rational entries.

    RRᵀ = I holds as a rational identity, so identities using orthogonality cancel exactly; it
    covers every rotation but the half-turns (measure zero). Built in closed form,
    R = I + 2(A + A²)/(1 + ‖a‖²), since A³ = −‖a‖²A for the skew A in 2D and 3D (``simplify`` of
    the inverse took about 1 s in every process that ran a seed 003 check).
    """
    dim = 2 if len(params) == 1 else 3
    a = skew(params)
    norm = sum(x**2 for x in params)
    numerator = ((1 + norm) * sp.eye(dim) + 2 * a + 2 * a * a).applyfunc(sp.expand)
    return numerator / (1 + norm)


# ---------------------------------------------------------------------------------------------
# identities (cached per dimension and controller: they depend on nothing else)


@dataclass(frozen=True)
class IdentityCheck:
    """An identity ``lhs == rhs``: ``residual`` after exact simplification (zero iff it holds)."""

    name: str
    residual: object
    holds: bool
    lhs: object
    rhs: object


@dataclass(frozen=True)
class DeltaCheck:
    """Δ of eq. (22) against the Δ derived from S(ω) (standard and as printed in eq. (4)).

    ``gram_determinant`` is det(ΔΔᵀ) factored (Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ exists iff it is non-zero);
    ``nonzero_epsilon_singular`` a non-zero ε making it vanish (against Remark 6).
    """

    dim: int
    printed: sp.Matrix
    from_standard_skew: sp.Matrix
    from_printed_skew: sp.Matrix
    standard_consistent: bool
    printed_consistent: bool
    gram_determinant: sp.Expr
    nonzero_epsilon_singular: dict


def _epsilon(dim: int) -> sp.Matrix:
    return sp.Matrix(sp.symbols(f"epsilon1:{dim + 1}", real=True))


def _omega(dim: int) -> sp.Matrix:
    return sp.Matrix(sp.symbols("p q r", real=True)) if dim == 3 else sp.Matrix([sp.Symbol("r")])


@functools.cache
def delta_check(dim: int) -> DeltaCheck:
    """Δ of seed 003 eq. (22) against the Δ implied by eq. (4), and det(ΔΔᵀ) (Remark 6)."""
    eps = _epsilon(dim)
    printed = delta_matrix(eps)
    standard = delta_from_skew(skew, eps)
    from_printed = delta_from_skew(skew_printed, eps)
    gram = sp.factor((printed * printed.T).det())
    witness = {str(s): (0 if k == 0 else 1) for k, s in enumerate(eps)}
    value = gram.subs({s: witness[str(s)] for s in eps})
    return DeltaCheck(
        dim,
        printed,
        standard,
        from_printed,
        printed == standard,
        printed == from_printed,
        gram,
        {"epsilon": list(witness.values()), "det_gram": int(value)},
    )


@functools.cache
def rotation_rate_check(dim: int, printed: bool = False) -> IdentityCheck:
    """Ṙ(η) = R(η) S(ω) for Euler angles driven by body rates ω (seed 003 eq. (3)).

    With ``printed=True`` S is that of eq. (4) and the residual is evaluated at the exact point
    φ = π/6, θ = π/4, ψ = π/3, (p, q, r) = (1, 0, 0) (non-zero: the identity fails).
    """
    angles = (
        sp.Matrix(sp.symbols("phi theta psi", real=True))
        if dim == 3
        else sp.Matrix([sp.Symbol("psi")])
    )
    omega = _omega(dim)
    rotation = euler_rotation(angles)
    rates = euler_rates(angles, omega)
    rotation_dot = sp.zeros(dim, dim)
    for angle, rate in zip(angles, rates, strict=True):
        rotation_dot += rotation.diff(angle) * rate
    s = skew_printed(omega) if printed else skew(omega)
    residual = rotation_dot - rotation * s
    if printed and dim == 3:
        point = dict(zip(angles, (sp.pi / 6, sp.pi / 4, sp.pi / 3), strict=True))
        point.update(dict(zip(omega, (1, 0, 0), strict=True)))
        residual = sp.simplify(residual.subs(point))
    else:
        residual = _exact_zero(residual, angles)
    name = "Ṙ = R S(ω) with S " + ("as printed in eq. (4)" if printed else "= [ω]ₓ")
    return IdentityCheck(name, residual, residual.is_zero_matrix, rotation_dot, rotation * s)


def _exact_zero(residual: sp.Matrix, angles: sp.Matrix | tuple = ()) -> sp.Matrix:
    """``residual`` as the zero matrix when it vanishes identically, else simplified.

    The exact test substitutes the tangent half-angle parametrization sin a = 2t/(1+t²),
    cos a = (1−t²)/(1+t²) for each angle and cancels: a rational function of the t's that is
    identically zero vanishes for every angle in (−π, π) where it is defined, hence by continuity
    everywhere it is defined. Without angles it is ``cancel``'s canonical form of a rational
    function, zero iff the function is. It costs about 0.1 s where ``simplify``'s search took
    3 s for the 3-D rates of eq. (3); an entry it leaves non-zero goes to ``simplify``, for display.
    """
    half = {}
    for angle in angles:
        t = sp.Symbol(f"t_{angle}", real=True)
        half[sp.sin(angle)] = 2 * t / (1 + t**2)
        half[sp.cos(angle)] = (1 - t**2) / (1 + t**2)
    rational = residual.applyfunc(
        lambda e: sp.cancel(e.replace(sp.tan, lambda x: sp.sin(x) / sp.cos(x)).xreplace(half))
    )
    if rational.is_zero_matrix and not rational.has(sp.sin, sp.cos, sp.tan):
        return sp.zeros(*residual.shape)
    return sp.simplify(residual)


def _rotation(dim: int) -> sp.Matrix:
    params = sp.Matrix(sp.symbols("a1:4", real=True)) if dim == 3 else sp.Matrix([sp.Symbol("a1")])
    return cayley_rotation(params)


def _vector(name: str, dim: int) -> sp.Matrix:
    return sp.Matrix(sp.symbols(f"{name}1:{dim + 1}", real=True))


@functools.cache
def error_dynamics_check(dim: int) -> IdentityCheck:
    """Seed 003 eq. (21): ė_p = −S(ω)e_p + Δu − Rᵀ(r′γ̇ + v) along the kinematics (2)–(5).

    The derivative of e_p = Rᵀ(p − r(γ) − q) − ε is taken from the kinematics,
    d/dt(Rᵀd) = (RS)ᵀd + Rᵀ(R[v₁,0,…]ᵀ − r′γ̇ − v) with d = p − r(γ) − q, a Cayley rotation R
    (RᵀR = I exact) and free ω.
    """
    rotation = _rotation(dim)
    omega = _omega(dim)
    v1, gamma_dot = sp.symbols("v1 gamma_dot", real=True)
    d, r_prime, target_v, eps = (
        _vector("d", dim),
        _vector("rp", dim),
        _vector("vt", dim),
        _epsilon(dim),
    )
    body = sp.Matrix([v1] + [0] * (dim - 1))
    s = skew(omega)
    kinematic = (rotation * s).T * d + rotation.T * (
        rotation * body - r_prime * gamma_dot - target_v
    )
    e_p = rotation.T * d - eps
    u = sp.Matrix([v1, *omega])
    printed = -s * e_p + delta_matrix(eps) * u - rotation.T * (r_prime * gamma_dot + target_v)
    residual = _exact_zero(kinematic - printed)
    return IdentityCheck(
        "eq. (21) from (2)–(5), (19)", residual, residual.is_zero_matrix, kinematic, printed
    )


@functools.cache
def lyapunov_derivative_check(dim: int, controller: str, estimated: bool) -> IdentityCheck:
    """V̇ for V = ½‖e‖² along (21), (23) under controller (24)/(25) or (28)/(29) (seed 003).

    With the true target (``estimated=False``) V̇ = −eᵀKe exactly (Lemma 2, K = diag(K_p, k_γ),
    K_p for Type I where e_γ ≡ 0); with estimates it is eq. (70): −eᵀKe + e_pᵀRᵀṽ +
    e_pᵀK_pRᵀq̃ − e_γ q̃ᵀr′(γ). K_p is a general symmetric matrix; ω is left free because
    e_pᵀS(ω)e_p = 0 for every ω; R is a Cayley rotation.
    """
    rotation = _rotation(dim)
    omega = _omega(dim)
    eps = _epsilon(dim)
    e_p, r_prime, target_v = _vector("ep", dim), _vector("rp", dim), _vector("vt", dim)
    q_err = _vector("qt", dim) if estimated else sp.zeros(dim, 1)
    v_err = _vector("vtil", dim) if estimated else sp.zeros(dim, 1)
    k_p = sp.Matrix(dim, dim, lambda i, j: sp.Symbol(f"k{min(i, j) + 1}{max(i, j) + 1}", real=True))
    omega_d, k_gamma = sp.symbols("omega_d k_gamma", real=True)
    e_gamma = sp.Symbol("e_gamma", real=True) if controller == "II" else sp.Integer(0)
    gamma_dot = omega_d + e_gamma
    e_hat = e_p - rotation.T * q_err
    delta = delta_matrix(eps)
    delta_bar = delta.T * (delta * delta.T).inv()
    command = rotation.T * (r_prime * omega_d + target_v + v_err) - k_p * e_hat
    delta_u = (delta * delta_bar).applyfunc(sp.cancel) * command
    de_p = -skew(omega) * e_p + delta_u - rotation.T * (r_prime * gamma_dot + target_v)
    v_dot = (e_p.T * de_p)[0, 0]
    if controller == "II":
        de_gamma = -k_gamma * e_gamma + (e_hat.T * rotation.T * r_prime)[0, 0]
        v_dot += e_gamma * de_gamma
    expected = -(e_p.T * k_p * e_p)[0, 0] - k_gamma * e_gamma**2
    if estimated:
        expected += (e_p.T * rotation.T * v_err)[0, 0] + (e_p.T * k_p * rotation.T * q_err)[0, 0]
        expected -= e_gamma * (q_err.T * r_prime)[0, 0]
    residual = sp.simplify(sp.cancel(sp.expand(v_dot - expected)))
    name = f"V̇ in {dim}D, Type {controller}, " + (
        "estimated target (70)" if estimated else "Lemma 2"
    )
    return IdentityCheck(name, residual, residual == 0, v_dot, expected)


# ---------------------------------------------------------------------------------------------
# counterexamples to inequalities printed in Appendices B–C


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
    """(71) prints ‖Φ‖² < μ‖x̃‖²; equality is attained exactly, so only ≤ holds (seed 003).

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
    """(72) prints V̇ ≤ −(1−θ)λ_min(K)‖e‖² for ‖e‖ ≥ c‖x̃‖/θ; false when λ_min(K) < 1 (seed 003).

    2D, Type II, K_p = 0.1 I, k_γ = 0.1 (λ_min(K) = ‖K‖ = 0.1), r_x = r_y = 1 (μ = 1),
    c = √μ + ‖K‖ = 1.1. State: R = I, e_p = (1, 0), e_γ = 0 and x̃ on the printed region's edge
    ‖x̃‖ = 0.99·θ‖e‖/c, aligned with the cross term (ṽ ∥ Re_p, q̃ ∥ Re_p, ‖ṽ‖ : ‖q̃‖ = 1 : 0.1). V̇ is
    evaluated from the kinematics (:func:`theory.pursuit.model.closed_loop_rates`); the corrected
    region ‖e‖ ≥ c‖x̃‖/(θλ_min) of (78) excludes this state.
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
    constants = {"r_x": 1.0, "r_y": 1.0, "gamma0": 0.0}
    gamma, epsilon = 0.7, np.array([1.0, 0.0])
    target, target_v = np.array([5.0, -2.0]), np.array([0.3, 0.1])
    position = rotation @ (e_p + epsilon) + path(gamma, **constants) + target
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
        path_params=constants,
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


# ---------------------------------------------------------------------------------------------
# claims about the model alone (run once, case "-")


def _symbolic(status: str, evidence: dict[str, Any], message: str) -> list[ClaimResult]:
    return [ClaimResult(status, "symbolic", evidence, message=message)]


@claims.register(
    "seed003.eq4",
    source="seed 003 eq. (4), (3), (22)",
    statement="S(ω) = [[0, −r, p], [r, 0, −q], [−p, q, 0]] satisfies Ṙ = RS(ω) and gives Δ of (22)",
)
def check_eq4(case: None, ctx: Context) -> list[ClaimResult]:
    """Printed S(ω) of (4) against Ṙ = RS(ω) (Z-Y-X Euler angles) and Δ of (22)."""
    printed = rotation_rate_check(3, printed=True)
    standard = rotation_rate_check(3)
    delta = delta_check(3)
    evidence = {
        "standard_skew": "S(ω) = [[0, −r, q], [r, 0, −p], [−q, p, 0]] = [ω]ₓ",
        "rdot_equals_R_S_standard": standard.holds,
        "rdot_minus_R_S_printed_at_point": str(printed.residual),
        "point": "φ = π/6, θ = π/4, ψ = π/3, (p, q, r) = (1, 0, 0)",
        "delta22_equals_delta_from_standard_S": delta.standard_consistent,
        "delta22_equals_delta_from_printed_S": delta.printed_consistent,
        "delta_from_printed_S": str(delta.from_printed_skew.tolist()),
        "two_d": "2D (Remark 2) is consistent: S = [[0, −r], [r, 0]], Δ = [[1, ε₂], [0, −ε₁]]",
    }
    ok = standard.holds and delta.standard_consistent and not printed.holds
    status = "corrected" if ok and not delta.printed_consistent else "inconclusive"
    return _symbolic(status, evidence, "eq. (4) swaps p and q; S(ω) = [ω]ₓ is right")


@claims.register(
    "seed003.eq21",
    source="seed 003 eqs. (2)–(5), (19), (21)",
    statement="ė_p = −S(ω)e_p + Δu − Rᵀ(r′(γ)γ̇ + v), in 2D and 3D",
)
def check_eq21(case: None, ctx: Context) -> list[ClaimResult]:
    """Eq. (21) derived from the kinematics, in 2D and 3D (Cayley rotation, exact)."""
    checks = {dim: error_dynamics_check(dim) for dim in (2, 3)}
    rates = {dim: rotation_rate_check(dim).holds for dim in (2, 3)}
    evidence = {f"{d}D": {"residual": str(c.residual), "holds": c.holds} for d, c in checks.items()}
    evidence["rdot_equals_R_S"] = {f"{d}D": h for d, h in rates.items()}
    ok = all(c.holds for c in checks.values()) and all(rates.values())
    return _symbolic("verified" if ok else "refuted", evidence, "eq. (21) holds")


@claims.register(
    "seed003.eq22.delta-bar",
    source="seed 003 eq. (22), (26), Remark 6",
    statement="a non-zero ε makes Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ well defined (Remark 6)",
)
def check_delta_bar(case: None, ctx: Context) -> list[ClaimResult]:
    """det(ΔΔᵀ) as a polynomial in ε, with a non-zero ε making it vanish."""
    evidence = {}
    for dim in (2, 3):
        check = delta_check(dim)
        evidence[f"{dim}D"] = {
            "det_gram": str(check.gram_determinant),
            "nonzero_epsilon_with_singular_gram": check.nonzero_epsilon_singular,
        }
    message = "Δ̄ exists iff ε₁ ≠ 0 (det ΔΔᵀ = ε₁² in 2D, ε₁²‖ε‖² in 3D), not iff ε ≠ 0"
    return _symbolic("corrected", evidence, message)


@claims.register(
    "seed003.lem2",
    source="seed 003 Lemma 2, eqs. (24)–(26), (65)–(66)",
    statement="with the true target, V̇ = −eᵀKe for both controllers (exponential convergence)",
)
def check_lemma2(case: None, ctx: Context) -> list[ClaimResult]:
    """Exact cancellation V̇ + eᵀKe = 0 in 2D/3D, Type I/II, for any symmetric K_p and any ω."""
    checks = {
        f"{d}D type {c}": lyapunov_derivative_check(d, c, False)
        for d in (2, 3)
        for c in ("I", "II")
    }
    evidence: dict[str, Any] = {k: {"residual": str(v.residual)} for k, v in checks.items()}
    evidence["proof_typos"] = [
        "λ₂(K_p) should read λ_min(K_p)",
        "(65) V₂ = ‖e‖² should read V₂ = ½‖e‖²",
        "(66) K = diag(K_p, k_z) should read diag(K_p, k_γ)",
    ]
    ok = all(c.holds for c in checks.values())
    return _symbolic("verified" if ok else "refuted", evidence, "V̇ = −eᵀKe exactly")


@claims.register(
    "seed003.eq70",
    source="seed 003 eq. (70)",
    statement="V̇₂ = −eᵀKe + e_pᵀRᵀṽ + e_pᵀK_pRᵀq̃ − e_γq̃ᵀr′(γ) with estimated target",
)
def check_eq70(case: None, ctx: Context) -> list[ClaimResult]:
    """Eq. (70) as an exact identity (uses RRᵀ = I via a Cayley rotation)."""
    checks = {
        f"{d}D type {c}": lyapunov_derivative_check(d, c, True) for d in (2, 3) for c in ("I", "II")
    }
    evidence = {k: {"residual": str(v.residual)} for k, v in checks.items()}
    ok = all(c.holds for c in checks.values())
    return _symbolic("verified" if ok else "refuted", evidence, "eq. (70) holds")


@claims.register(
    "seed003.eq71",
    source="seed 003 eq. (71)",
    statement="‖Φ‖² < μ‖x̃‖², μ = max_γ{1, ‖r′(γ)‖²}",
)
def check_eq71(case: None, ctx: Context) -> list[ClaimResult]:
    """The strict inequality fails (equality attained); ≤ holds."""
    evidence = eq71_strict_inequality()
    status = "corrected" if not evidence["printed_strict_holds"] else "verified"
    return [ClaimResult(status, "exact", evidence, message="only ‖Φ‖² ≤ μ‖x̃‖²")]


@claims.register(
    "seed003.eq72",
    source="seed 003 eq. (72) (vs. (78))",
    statement="V̇₂ ≤ −(1−θ)λ_min(K)‖e‖² for all ‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/θ",
)
def check_eq72(case: None, ctx: Context) -> list[ClaimResult]:
    """Counterexample (closed-loop V̇ from the kinematics) to the region printed in (72)."""
    evidence = eq72_printed_region()
    evidence["corrected"] = "‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/(θ λ_min(K)), as printed in (78)"
    status = "corrected" if evidence["violation"] > VIOLATION_TOL else "inconclusive"
    return [
        ClaimResult(
            status, "numeric", evidence, margin=evidence["violation"],
            tolerance={"violation_tol": VIOLATION_TOL}, message="(72) lacks the factor 1/λ_min(K)",
        )
    ]  # fmt: skip


@claims.register(
    "seed003.eq74",
    source="seed 003 eq. (74) and the sentence before it",
    statement="ξ ⊥ 1, so by Definition 1 V̇_c ≤ −k_c r_min‖ξ‖² + ‖ξ‖‖RW‖‖e_γ‖",
)
def check_eq74(case: None, ctx: Context) -> list[ClaimResult]:
    """ξ ⊥ r (not 1), and the factor a(L) is missing: exact counterexamples."""
    evidence = {
        "missing_a_L": eq74_missing_connectivity(),
        "orthogonality": xi_not_orthogonal_to_ones(),
    }
    evidence["corrected"] = "V̇_c ≤ −k_c a(L) ξᵀRξ + ‖R^{1/2}ξ‖‖R^{1/2}W‖‖e_γ‖, ξ ⊥ r"
    failed = not evidence["missing_a_L"]["printed_holds"]
    status = (
        "corrected" if failed and evidence["missing_a_L"]["corrected_holds"] else "inconclusive"
    )
    return [ClaimResult(status, "exact", evidence, message="a(L) dropped")]


@claims.register(
    "seed003.eq75",
    source="seed 003 eq. (75)",
    statement="V̇_c ≤ −k_c r_min‖ξ‖² + ‖RW‖‖e‖",
)
def check_eq75(case: None, ctx: Context) -> list[ClaimResult]:
    """The first line of (75) drops ‖ξ‖ from the cross term: exact counterexample."""
    evidence = eq75_missing_norm()
    ok = not evidence["printed_holds"] and evidence["corrected_holds"]
    status = "corrected" if ok else "inconclusive"
    return [ClaimResult(status, "exact", evidence, message="‖ξ‖ dropped")]
