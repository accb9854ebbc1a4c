"""Tracker kinematics, S-T curves, errors and controllers of seed 003, symbolic and numeric.

Symbolic (sympy) objects reproduce the paper's equations in 2D and 3D:

* kinematics (2)–(5): ṗ = R(η) v, Ṙ = R S(ω), v = [v₁, 0, 0], u = [v₁, p, q, r];
* the path (15)/(16) and the S-T curve (17);
* the errors (19)–(23) and the matrix Δ of (22);
* the controllers (24)–(30) (Type I and II, with the true or the estimated target).

Numeric (numpy) functions evaluate the same closed loop at a state, *from the kinematics* (not from
the error equations derived in the paper), so that the falsification tests and the simulation can
measure V̇ independently of the algebra being checked.

References
----------
seed 003: N. T. Hung, F. Rego, A. M. Pascoal, "Cooperative distributed estimation and control of
multiple autonomous vehicles for range-based underwater target localization and pursuit".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

__all__ = [
    "ClosedLoopRates",
    "cayley_rotation",
    "closed_loop_rates",
    "delta_from_skew",
    "delta_matrix",
    "delta_numeric",
    "euler_rates",
    "euler_rotation",
    "path",
    "path_derivative_numeric",
    "path_numeric",
    "rotation_numeric",
    "skew",
    "skew_numeric",
    "skew_printed",
]


def skew(omega: sp.Matrix) -> sp.Matrix:
    """S(ω) = [ω]ₓ, the matrix with S(ω)x = ω × x (3D), or [[0, −r], [r, 0]] (2D, Remark 2).

    Parameters
    ----------
    omega : sympy.Matrix
        [p, q, r] (3D) or [r] (2D).

    Returns
    -------
    sympy.Matrix
        The skew-symmetric matrix for which Ṙ = R S(ω) holds (checked by
        :func:`theory.pursuit.iss.rotation_rate_residual`).

    References
    ----------
    seed 003, eq. (3) and Remark 2; eq. (4) prints a different matrix (see :func:`skew_printed`).
    """
    if len(omega) == 1:
        r = omega[0]
        return sp.Matrix([[0, -r], [r, 0]])
    p, q, r = omega
    return sp.Matrix([[0, -r, q], [r, 0, -p], [-q, p, 0]])


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
    return sp.Matrix([[0, -r, p], [r, 0, -q], [-p, q, 0]])


def delta_matrix(epsilon: sp.Matrix) -> sp.Matrix:
    """Δ exactly as printed in seed 003 eq. (22) (3 × 4 in 3D, 2 × 2 in 2D).

    Parameters
    ----------
    epsilon : sympy.Matrix
        ε of eq. (19), 2 or 3 entries.

    References
    ----------
    seed 003, eq. (22).
    """
    if len(epsilon) == 2:
        e1, e2 = epsilon
        return sp.Matrix([[1, e2], [0, -e1]])
    e1, e2, e3 = epsilon
    return sp.Matrix([[1, 0, -e3, e2], [0, e3, 0, -e1], [0, -e2, e1, 0]])


def delta_from_skew(skew_fn, epsilon: sp.Matrix) -> sp.Matrix:
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
    if len(angles) == 1:
        psi = angles[0]
        return sp.Matrix([[sp.cos(psi), -sp.sin(psi)], [sp.sin(psi), sp.cos(psi)]])
    phi, theta, psi = angles
    rz = sp.Matrix([[sp.cos(psi), -sp.sin(psi), 0], [sp.sin(psi), sp.cos(psi), 0], [0, 0, 1]])
    ry = sp.Matrix(
        [[sp.cos(theta), 0, sp.sin(theta)], [0, 1, 0], [-sp.sin(theta), 0, sp.cos(theta)]]
    )
    rx = sp.Matrix([[1, 0, 0], [0, sp.cos(phi), -sp.sin(phi)], [0, sp.sin(phi), sp.cos(phi)]])
    return rz * ry * rx


def euler_rates(angles: sp.Matrix, omega: sp.Matrix) -> sp.Matrix:
    """η̇ = T(η) ω for Z-Y-X Euler angles and body rates ω = [p, q, r] (ψ̇ = r in 2D).

    Parameters
    ----------
    angles : sympy.Matrix
        [φ, θ, ψ] (3D) or [ψ] (2D).
    omega : sympy.Matrix
        Body rates [p, q, r] (3D) or [r] (2D).
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

    Parameters
    ----------
    params : sympy.Matrix
        One parameter (2D) or three (3D).
    """
    dim = 2 if len(params) == 1 else 3
    a = skew(params)
    eye = sp.eye(dim)
    return sp.simplify((eye - a).inv() * (eye + a))


def path(gamma: sp.Symbol, r_x, r_y, gamma0, r_z=None, c=None) -> sp.Matrix:
    """r(γ) of seed 003 eq. (15) (3D, when ``r_z`` and ``c`` are given) or eq. (16) (2D).

    Parameters
    ----------
    gamma : sympy.Symbol
        Path parameter γ.
    r_x, r_y, gamma0, r_z, c : sympy expressions or numbers
        Path constants of eq. (15); ``r_z`` and ``c`` only in 3D.
    """
    planar = [r_x * sp.cos(gamma + gamma0), r_y * sp.sin(gamma + gamma0)]
    if r_z is None:
        return sp.Matrix(planar)
    return sp.Matrix([*planar, r_z * sp.sin(gamma / c + gamma0)])


# ---------------------------------------------------------------------------------------------
# numeric closed loop (numpy), evaluated from the kinematics


def skew_numeric(omega: np.ndarray) -> np.ndarray:
    """Numeric S(ω) = [ω]ₓ (3D) or [[0, −r], [r, 0]] (2D).

    Parameters
    ----------
    omega : array_like
        [p, q, r] or [r].
    """
    omega = np.asarray(omega, dtype=float)
    if omega.size == 1:
        r = float(omega.reshape(-1)[0])
        return np.array([[0.0, -r], [r, 0.0]])
    p, q, r = omega
    return np.array([[0.0, -r, q], [r, 0.0, -p], [-q, p, 0.0]])


def delta_numeric(epsilon: np.ndarray) -> np.ndarray:
    """Numeric Δ of eq. (22).

    Parameters
    ----------
    epsilon : array_like
        ε, 2 or 3 entries.
    """
    e = np.asarray(epsilon, dtype=float)
    if e.size == 2:
        return np.array([[1.0, e[1]], [0.0, -e[0]]])
    return np.array([[1.0, 0.0, -e[2], e[1]], [0.0, e[2], 0.0, -e[0]], [0.0, -e[1], e[0], 0.0]])


def rotation_numeric(params: np.ndarray) -> np.ndarray:
    """Numeric rotation matrix (Rodrigues' formula in 3D).

    Parameters
    ----------
    params : array_like
        The angle ψ (one entry, 2D) or a rotation vector axis·angle (three entries, 3D).
    """
    params = np.asarray(params, dtype=float).reshape(-1)
    if params.size == 1:
        c, s = np.cos(params[0]), np.sin(params[0])
        return np.array([[c, -s], [s, c]])
    angle = float(np.linalg.norm(params))
    if angle == 0.0:
        return np.eye(3)
    k = skew_numeric(params / angle)
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def path_numeric(
    gamma: float, r_x: float, r_y: float, gamma0: float, r_z=None, c=None
) -> np.ndarray:
    """r(γ), eqs. (15)/(16).

    Parameters
    ----------
    gamma : float
        Path parameter.
    r_x, r_y, gamma0, r_z, c : float
        Path constants (``r_z``, ``c`` only in 3D).
    """
    planar = [r_x * np.cos(gamma + gamma0), r_y * np.sin(gamma + gamma0)]
    if r_z is None:
        return np.array(planar)
    return np.array([*planar, r_z * np.sin(gamma / c + gamma0)])


def path_derivative_numeric(
    gamma: float, r_x: float, r_y: float, gamma0: float, r_z=None, c=None
) -> np.ndarray:
    """r′(γ) = ∂r/∂γ of eqs. (15)/(16).

    Parameters
    ----------
    gamma, r_x, r_y, gamma0, r_z, c : float
        As in :func:`path_numeric`.
    """
    planar = [-r_x * np.sin(gamma + gamma0), r_y * np.cos(gamma + gamma0)]
    if r_z is None:
        return np.array(planar)
    return np.array([*planar, (r_z / c) * np.cos(gamma / c + gamma0)])


@dataclass(frozen=True)
class ClosedLoopRates:
    """Tracking errors and their time derivatives at one state of one tracker.

    Attributes
    ----------
    e_p, e_gamma : ndarray, float
        e_p of eq. (19) (true target) and e_γ of eq. (20)/(47).
    de_p, de_gamma : ndarray, float
        Their time derivatives, computed from the kinematics (2)–(5) and the controller.
    u : ndarray
        The input [v₁, ω] applied.
    """

    e_p: np.ndarray
    e_gamma: float
    de_p: np.ndarray
    de_gamma: float
    u: np.ndarray

    @property
    def v_dot(self) -> float:
        """V̇ for V = ½‖e‖² (eq. (65) corrected), e = [e_p, e_γ]."""
        return float(self.e_p @ self.de_p + self.e_gamma * self.de_gamma)


def closed_loop_rates(
    *,
    position: np.ndarray,
    rotation: np.ndarray,
    gamma: float,
    gamma_dot: float,
    target_position: np.ndarray,
    target_velocity: np.ndarray,
    estimate_position: np.ndarray,
    estimate_velocity: np.ndarray,
    epsilon: np.ndarray,
    K_p: np.ndarray,
    k_gamma: float | None,
    controller: str,
    omega_d: float,
    omega_d_dot: float,
    path_params: dict,
) -> ClosedLoopRates:
    """Errors and error rates of one tracker under controller (49)/(50) with estimates.

    The input is u = Δ̄(Rᵀ(r′ω_d + v̂) − K_p ê_p) (eq. (30)/(51)); γ̈ follows (29)/(50b) for Type II
    (with ``omega_d_dot`` = v̇_c), while Type I imposes γ̇ = ω_d (so e_γ = 0 and ``gamma_dot`` is
    ignored). The error rates are obtained by differentiating e_p = Rᵀ(p − r(γ) − q) − ε with
    ṗ = R[v₁, 0, …]ᵀ, Ṙ = R S(ω), q̇ = v — the kinematics, not eq. (21).

    Parameters
    ----------
    position, rotation : ndarray
        Tracker position p and attitude R.
    gamma, gamma_dot : float
        Path parameter and its rate.
    target_position, target_velocity : ndarray
        True q and v.
    estimate_position, estimate_velocity : ndarray
        Estimates q̂ and v̂.
    epsilon, K_p, k_gamma, controller : see :class:`theory.pursuit.case.PursuitSpec`.
    omega_d, omega_d_dot : float
        Desired speed ω_d (eq. (18)/(46)) and its derivative v̇_c (eq. (52)).
    path_params : dict
        Keyword arguments of :func:`path_numeric` except ``gamma``.

    Returns
    -------
    ClosedLoopRates

    References
    ----------
    seed 003, eqs. (2)–(5), (19)–(30), (46)–(52).
    """
    dim = len(position)
    r_gamma = path_numeric(gamma, **path_params)
    r_prime = path_derivative_numeric(gamma, **path_params)
    if controller == "I":
        gamma_dot = omega_d
    e_p = rotation.T @ (position - r_gamma - target_position) - epsilon
    e_hat = rotation.T @ (position - r_gamma - estimate_position) - epsilon
    delta = delta_numeric(epsilon)
    delta_bar = delta.T @ np.linalg.inv(delta @ delta.T)
    u = delta_bar @ (rotation.T @ (r_prime * omega_d + estimate_velocity) - K_p @ e_hat)
    body_velocity = np.zeros(dim)
    body_velocity[0] = u[0]
    rotation_dot = rotation @ skew_numeric(u[1:])
    position_dot = rotation @ body_velocity
    de_p = rotation_dot.T @ (position - r_gamma - target_position) + rotation.T @ (
        position_dot - r_prime * gamma_dot - target_velocity
    )
    e_gamma = gamma_dot - omega_d
    if controller == "I":
        de_gamma = 0.0
    else:
        gamma_ddot = -k_gamma * e_gamma + e_hat @ rotation.T @ r_prime + omega_d_dot
        de_gamma = gamma_ddot - omega_d_dot
    return ClosedLoopRates(e_p, float(e_gamma), de_p, float(de_gamma), u)
