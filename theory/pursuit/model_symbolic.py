"""The seed 003 model as sympy matrices, built from the formulas of :mod:`theory.pursuit.model`.

S(ω), Δ of (22), the path (15)/(16) and the Euler rotation come from the same ``*_rows``
functions the numeric model and the simulator use; only what exists for the exact checks alone
lives here: S as printed in eq. (4), Δ derived from a given S, the Euler-angle rates and the
rational (Cayley) rotation.

References
----------
seed 003, eqs. (2)–(5), (15)–(16), (21)–(22).
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from theory.pursuit.model import delta_rows, euler_rotation_rows, path_harmonics, skew_rows

__all__ = [
    "cayley_rotation",
    "delta_from_skew",
    "delta_matrix",
    "euler_rates",
    "euler_rotation",
    "path",
    "skew",
    "skew_printed",
]


def skew(omega: sp.Matrix) -> sp.Matrix:
    """S(ω) = [ω]ₓ (3D) or [[0, −r], [r, 0]] (2D) of :func:`theory.pursuit.model.skew_rows`.

    Parameters
    ----------
    omega : sympy.Matrix
        [p, q, r] (3D) or [r] (2D).

    References
    ----------
    seed 003, eq. (3) and Remark 2; eq. (4) prints a different matrix (see :func:`skew_printed`).
    """
    return sp.Matrix(skew_rows(list(omega)))


def skew_printed(omega: sp.Matrix) -> sp.Matrix:
    """S(ω) exactly as printed in seed 003 eq. (4): [[0, −r, p], [r, 0, −q], [−p, q, 0]].

    It is skew-symmetric but equals [ω']ₓ with ω' = [q, p, r]: roll and pitch rates are swapped.

    Parameters
    ----------
    omega : sympy.Matrix
        [p, q, r] (3D) or [r] (2D, where it equals :func:`skew`).

    References
    ----------
    seed 003, eq. (4).
    """
    if len(omega) == 1:
        return skew(omega)
    p, q, r = omega
    return skew(sp.Matrix([q, p, r]))


def delta_matrix(epsilon: sp.Matrix) -> sp.Matrix:
    """Δ exactly as printed in seed 003 eq. (22) (:func:`theory.pursuit.model.delta_rows`).

    Parameters
    ----------
    epsilon : sympy.Matrix
        ε of eq. (19), 2 or 3 entries.

    References
    ----------
    seed 003, eq. (22).
    """
    return sp.Matrix(delta_rows(list(epsilon)))


def delta_from_skew(skew_fn: Callable[[sp.Matrix], sp.Matrix], epsilon: sp.Matrix) -> sp.Matrix:
    """The matrix Δ with Δu = −S(ω)ε + v for u = [v₁, ω], derived from a given S.

    Parameters
    ----------
    skew_fn : callable
        :func:`skew` or :func:`skew_printed`.
    epsilon : sympy.Matrix
        ε (2 or 3 entries).

    Returns
    -------
    sympy.Matrix
        The Jacobian of −S(ω)ε + [v₁, 0, …]ᵀ with respect to u (the expression is linear in u).

    References
    ----------
    seed 003, eqs. (5), (21), (22).
    """
    dim = len(epsilon)
    u = sp.symbols("v1 p q r") if dim == 3 else sp.symbols("v1 r")
    omega = sp.Matrix(u[1:])
    body_velocity = sp.Matrix([u[0]] + [0] * (dim - 1))
    expression = -skew_fn(omega) * epsilon + body_velocity
    return expression.jacobian(sp.Matrix(u))


def euler_rotation(angles: sp.Matrix) -> sp.Matrix:
    """R(η): yaw rotation in 2D, Z-Y-X (yaw-pitch-roll) Euler rotation in 3D (seed 003 eq. (2)).

    Parameters
    ----------
    angles : sympy.Matrix
        [ψ] (2D) or [φ, θ, ψ] (3D).
    """
    return sp.Matrix(euler_rotation_rows(list(angles), cos=sp.cos, sin=sp.sin))


def euler_rates(angles: sp.Matrix, omega: sp.Matrix) -> sp.Matrix:
    """η̇ = T(η) ω for Z-Y-X Euler angles and body rates ω = [p, q, r] (ψ̇ = r in 2D).

    Parameters
    ----------
    angles : sympy.Matrix
        [φ, θ, ψ] (3D) or [ψ] (2D).
    omega : sympy.Matrix
        Body rates [p, q, r] (3D) or [r] (2D).

    References
    ----------
    seed 003, eq. (2) (the attitude kinematics behind Ṙ = R S(ω)).
    """
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
    """Rotation R = (I − A)⁻¹(I + A) for the skew A built from ``params`` (1 in 2D, 3 in 3D).

    Its entries are rational in ``params`` and RRᵀ = I holds as a rational identity, so identities
    that use orthogonality can be checked by exact cancellation. Covers every rotation except the
    half-turns (a set of measure zero, so polynomial identities extend by continuity).

    Built in closed form, R = I + 2(A + A²)/(1 + ‖a‖²): (I − A)R = I + A because A³ = −‖a‖²A
    for the skew A in 2D and 3D (the tests compare it with the inverse by cancellation);
    ``simplify`` of the inverse took about 1 s in every process that ran a seed 003 check.

    Parameters
    ----------
    params : sympy.Matrix
        One parameter (2D) or three (3D).
    """
    dim = 2 if len(params) == 1 else 3
    a = skew(params)
    norm = sum(x**2 for x in params)
    numerator = ((1 + norm) * sp.eye(dim) + 2 * a + 2 * a * a).applyfunc(sp.expand)
    return numerator / (1 + norm)


def path(gamma: sp.Symbol, r_x, r_y, gamma0, r_z=None, c=None) -> sp.Matrix:
    """r(γ) of seed 003 eq. (15) (3D, when ``r_z`` and ``c`` are given) or eq. (16) (2D).

    Parameters
    ----------
    gamma : sympy.Symbol
        Path parameter γ.
    r_x, r_y, gamma0, r_z, c : sympy expressions or numbers
        Path constants of eq. (15); ``r_z`` and ``c`` only in 3D.
    """
    terms = path_harmonics(r_x, r_y, gamma0, r_z, c, pi=sp.pi)
    return sp.Matrix([a * sp.cos(sp.sympify(f) * gamma + phi) for a, f, phi in terms])
