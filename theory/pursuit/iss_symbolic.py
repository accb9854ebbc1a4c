"""Symbolic (sympy) checks of seed 003's tracking-error algebra, in 2D and 3D, both controllers.

Each function returns a small frozen result with the residual (which must simplify to zero for a
verified identity) and the expressions it compared, so the claims and the tests can show the
cancellation rather than assert it. Results are cached per (dimension, controller): they depend on
nothing else.

References
----------
seed 003, eqs. (2)–(5), (19)–(30), (65)–(72) and Remark 6.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import sympy as sp

from theory.pursuit.model_symbolic import (
    cayley_rotation,
    delta_from_skew,
    delta_matrix,
    euler_rates,
    euler_rotation,
    skew,
    skew_printed,
)

__all__ = [
    "DeltaCheck",
    "IdentityCheck",
    "delta_check",
    "error_dynamics_check",
    "lyapunov_derivative_check",
    "rotation_rate_check",
]


@dataclass(frozen=True)
class IdentityCheck:
    """An identity ``lhs == rhs`` checked by exact simplification.

    Attributes
    ----------
    name : str
        What was checked.
    residual : sympy.Expr or sympy.Matrix
        ``lhs − rhs`` after simplification (zero when the identity holds).
    holds : bool
        Whether the residual is identically zero.
    lhs, rhs : sympy objects
        The two sides.
    """

    name: str
    residual: object
    holds: bool
    lhs: object
    rhs: object


@dataclass(frozen=True)
class DeltaCheck:
    """Δ of eq. (22) against the Δ derived from S(ω) (standard and as printed in eq. (4)).

    Attributes
    ----------
    dim : int
    printed : sympy.Matrix
        Δ as printed in (22).
    from_standard_skew, from_printed_skew : sympy.Matrix
        Δ derived from Δu = −S(ω)ε + v with S = [ω]ₓ and with S as printed in (4).
    standard_consistent, printed_consistent : bool
        Whether (22) equals each derived Δ.
    gram_determinant : sympy.Expr
        det(ΔΔᵀ) factored: Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ exists iff it is non-zero.
    nonzero_epsilon_singular : dict
        A non-zero ε with det(ΔΔᵀ) = 0 (a counterexample to Remark 6).
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
    """Compare Δ of eq. (22) with the Δ implied by eq. (4), and factor det(ΔΔᵀ).

    References
    ----------
    seed 003, eqs. (4), (21), (22) and Remark 6.
    """
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
    """Ṙ(η) = R(η) S(ω) for Euler angles driven by body rates ω (eq. (3)).

    With ``printed=True`` the S of eq. (4) is used; the residual is then evaluated at the exact
    point φ = π/6, θ = π/4, ψ = π/3, p = 1, q = 0, r = 0 (non-zero shows the identity fails).

    References
    ----------
    seed 003, eqs. (2)–(4), Remark 2.
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
    """``residual`` (rational in sin, cos, tan of ``angles``, and in other symbols) as the zero
    matrix when it vanishes identically, else simplified.

    The exact test substitutes the tangent half-angle parametrization sin a = 2t/(1+t²),
    cos a = (1−t²)/(1+t²) for each angle and cancels: a rational function of the t's that is
    identically zero vanishes for every angle in (−π, π) where it is defined, hence by continuity
    everywhere it is defined. Without angles it is ``cancel``'s canonical form of a rational
    function, zero iff the function is. It costs about 0.1 s where ``simplify``'s search took
    3 s for the 3-D rates of eq. (3); an entry it leaves non-zero (or with trigonometric
    functions of other arguments left) goes to ``simplify``, for display.
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
    """Eq. (21): the derivative of e_p = Rᵀ(p − r(γ) − q) − ε along (2)–(5) equals
    −S(ω)e_p + Δu − Rᵀ(r′γ̇ + v), with Δ of eq. (22) and S = [ω]ₓ.

    The derivative is taken from the kinematics: d/dt(Rᵀd) = (RS)ᵀd + Rᵀ(R[v₁,0,…]ᵀ − r′γ̇ − v)
    with d = p − r(γ) − q, a rotation R (Cayley parameters, so RᵀR = I is exact) and free ω.

    References
    ----------
    seed 003, eqs. (2)–(5), (19), (21), (22).
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
    """V̇ for V = ½‖e‖² along (21), (23) under controller (24)/(25) or (28)/(29).

    With the true target (``estimated=False``) the expected value is −eᵀKe exactly (Lemma 2,
    K = diag(K_p, k_γ), K = K_p for Type I where e_γ ≡ 0). With estimates it is eq. (70):
    −eᵀKe + e_pᵀRᵀṽ + e_pᵀK_pRᵀq̃ − e_γ q̃ᵀr′(γ). K_p is a general symmetric matrix; ω (which
    the input also sets) is left free because e_pᵀS(ω)e_p = 0 for every ω; R is a Cayley rotation.

    References
    ----------
    seed 003, Lemma 2 and eqs. (24)–(30), (65)–(70).
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
