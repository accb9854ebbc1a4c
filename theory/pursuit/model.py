"""The seed 003 pursuit model, once: S(ω), Δ, the paths, the errors, the controllers, kinematics.

Every formula is written here once and evaluated on stacked numpy arrays (leading axes are
trackers, or states, and broadcast): the kinematics (2)–(5), S(ω) = [ω]ₓ and exp(S(ω)), Euler
rotations, the paths (15)/(16) as harmonics a cos(fγ + φ), the errors (19)/(27)/(48)/(59), Δ and
Δ̄ of (22)/(26), the tracking input (51), the path-parameter feedback (50b) and the coordination
law (45)–(52) with its weights r of Lemma 1.

The entries of S, Δ, the Euler rotation (``*_rows``) and the path's harmonics take scalar
components of any number type, so :mod:`theory.pursuit.derivations` builds the sympy matrices of
the exact checks from the very same formulas. :func:`closed_loop_rates` evaluates one tracker's
closed loop *from the kinematics* (not from the error equations derived in the paper), so
properties and counterexamples measure V̇ independently of the algebra they check.

seed 003: N. T. Hung, F. Rego, A. M. Pascoal, "Cooperative distributed estimation and control of
multiple autonomous vehicles for range-based underwater target localization and pursuit".
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

__all__ = [
    "ClosedLoopRates",
    "PathHarmonics",
    "body_error",
    "closed_loop_rates",
    "correction_speed",
    "delta_bar",
    "delta_matrix",
    "delta_rows",
    "desired_speed",
    "euler_rotation",
    "euler_rotation_rows",
    "exact_laplacian",
    "exp_skew",
    "gamma_acceleration",
    "input_gains",
    "left_eigenvector",
    "path",
    "path_derivative",
    "path_feedback",
    "path_harmonics",
    "rotate_back",
    "skew",
    "skew_rows",
    "tracker_rates",
    "tracking_input",
]


# ---------------------------------------------------------------------------------------------
# the formulas, on scalar components (shared with theory.pursuit.derivations)


def skew_rows(omega: Sequence[Any]) -> tuple[tuple[Any, ...], ...]:
    """Rows of S(ω) = [ω]ₓ for ω = (p, q, r), or [[0, −r], [r, 0]] for ω = (r,) (seed 003 eq. (3)).

    The matrix for which Ṙ = R S(ω) holds (:func:`theory.pursuit.derivations.rotation_rate_check`);
    eq. (4) prints another (:func:`theory.pursuit.derivations.skew_printed`).
    """
    if len(omega) == 1:
        (r,) = omega
        return ((0, -r), (r, 0))
    p, q, r = omega
    return ((0, -r, q), (r, 0, -p), (-q, p, 0))


def delta_rows(epsilon: Sequence[Any]) -> tuple[tuple[Any, ...], ...]:
    """Rows of Δ as printed in seed 003 eq. (22): Δu = −S(ω)ε + [v₁, 0(, 0)]ᵀ for u = (v₁, ω)."""
    if len(epsilon) == 2:
        e1, e2 = epsilon
        return ((1, e2), (0, -e1))
    e1, e2, e3 = epsilon
    return ((1, 0, -e3, e2), (0, e3, 0, -e1), (0, -e2, e1, 0))


def path_harmonics(
    r_x: Any, r_y: Any, gamma0: Any, r_z: Any = None, c: Any = None, *, pi: Any = np.pi
) -> tuple[tuple[Any, Any, Any], ...]:
    """r(γ) of seed 003 eq. (15) (3D) or (16) (2D) as harmonics r_k(γ) = a_k cos(f_k γ + φ_k).

    r(γ) = [r_x cos(γ + γ₀), r_y sin(γ + γ₀)(, r_z sin(γ/c + γ₀))], i.e. (r_x, 1, γ₀),
    (r_y, 1, γ₀ − π/2) and (r_z, 1/c, γ₀ − π/2); every derivative follows from
    d/dγ a cos(fγ + φ) = a f cos(fγ + φ + π/2). ``pi`` is π of the number type.
    """
    planar = ((r_x, 1, gamma0), (r_y, 1, gamma0 - pi / 2))
    if r_z is None:
        return planar
    return (*planar, (r_z, 1 / c, gamma0 - pi / 2))


def euler_rotation_rows(
    angles: Sequence[Any], *, cos: Callable, sin: Callable
) -> tuple[tuple[Any, ...], ...]:
    """Rows of R(η): yaw (2D, η = (ψ,)) or Z-Y-X R_z(ψ)R_y(θ)R_x(φ) (3D), seed 003 eq. (2)."""
    if len(angles) == 1:
        (psi,) = angles
        return ((cos(psi), -sin(psi)), (sin(psi), cos(psi)))
    phi, theta, psi = angles
    cf, sf, ct, st, cp, sp_ = cos(phi), sin(phi), cos(theta), sin(theta), cos(psi), sin(psi)
    return (
        (cp * ct, cp * st * sf - sp_ * cf, cp * st * cf + sp_ * sf),
        (sp_ * ct, sp_ * st * sf + cp * cf, sp_ * st * cf - cp * sf),
        (-st, ct * sf, ct * cf),
    )


def _stack_rows(rows: tuple[tuple[Any, ...], ...], shape: tuple[int, ...]) -> np.ndarray:
    """A (…, m, n) array from rows of scalars/arrays broadcast to ``shape``."""
    return np.stack(
        [np.stack([np.broadcast_to(np.asarray(x, float), shape) for x in row], -1) for row in rows],
        -2,
    )


# ---------------------------------------------------------------------------------------------
# rotations


def _generators(k: int) -> np.ndarray:
    """G with S(ω) = Σ_k ω_k G_k (S is linear in ω), from :func:`skew_rows` on unit vectors."""
    return np.array([np.array(skew_rows(tuple(np.eye(k)[i])), dtype=float) for i in range(k)])


_GENERATORS = {k: _generators(k).reshape(k, -1) for k in (1, 3)}


def _quaternion_basis() -> np.ndarray:
    """B (16 × 9) with vec(exp(S(ω))) = (q ⊗ q) B for the unit quaternion q = (w, v) of ω.

    Euler–Rodrigues: exp(S(ω)) = (w² − vᵀv) I + 2vvᵀ + 2w S(v), each term a quadratic form in q
    (entry (k, l) of q ⊗ q is q_k q_l), with S of :func:`skew_rows`.
    """
    eye, generators = np.eye(3), _generators(3)
    basis = np.zeros((4, 4, 3, 3))
    basis[0, 0] = eye
    for k in range(3):
        basis[1 + k, 1 + k] -= eye  # −v_k² I
        basis[0, 1 + k] += 2.0 * generators[k]  # 2w v_k G_k
        for m in range(3):
            basis[1 + k, 1 + m, k, m] += 2.0  # 2 v_k v_m
    return basis.reshape(16, 9)


_QUATERNION_BASIS = _quaternion_basis()
_TURN_BASIS = np.array([np.eye(2).ravel(), _GENERATORS[1][0]])
"""Rows vec(I) and vec(S(1)) in 2D: exp(S(ψ)) = cos ψ I + sin ψ S(1)."""
_SINE_SHIFT = np.array([0.0, np.pi / 2])
"""cos(ψ − (0, π/2)) = (cos ψ, sin ψ)."""


def skew(omega: np.ndarray) -> np.ndarray:
    """S(ω) of :func:`skew_rows`, stacked: shape (…, k) → (…, d, d), k = 1 (d = 2) or 3."""
    omega = np.asarray(omega, dtype=float)
    d = 2 if omega.shape[-1] == 1 else 3
    return (omega @ _GENERATORS[omega.shape[-1]]).reshape(*omega.shape[:-1], d, d)


def exp_skew(omega: np.ndarray) -> np.ndarray:
    """exp(S(ω)) stacked: the rotation of a rotation vector ω, (…, k) → (…, d, d).

    3D (Euler–Rodrigues): with θ = ‖ω‖ and the unit quaternion q = (w, v) = (cos(θ/2),
    sin(θ/2) ω/θ), exp(S(ω)) = (w² − vᵀv) I + 2vvᵀ + 2w S(v) — Rodrigues' I + (sin θ/θ) S(ω) +
    ((1 − cos θ)/θ²) S(ω)² written in half angles (no cancellation for small θ), evaluated as
    one product (q ⊗ q) B (:func:`_quaternion_basis`). 2D: the rotation by the angle ω,
    cos ω I + sin ω S(1). Seed 003 eq. (3): R(t + h) = R(t) exp(h S(ω)) for ω constant over h.
    """
    omega = np.asarray(omega, dtype=float)
    stack = omega.shape[:-1]
    if omega.shape[-1] == 1:
        trig = np.cos(omega - _SINE_SHIFT)  # (cos ω, sin ω)
        return (trig @ _TURN_BASIS).reshape(*stack, 2, 2)
    theta = np.sqrt(omega[..., None, :] @ omega[..., :, None])[..., 0]
    np.maximum(theta, 1e-150, out=theta)  # below it, w = 1 and v = ω/2 to the last bit
    half = 0.5 * theta
    quaternion = np.empty((*stack, 4))
    np.cos(half, out=quaternion[..., :1])
    np.sin(half, out=half)
    half /= theta
    np.multiply(omega, half, out=quaternion[..., 1:])
    products = quaternion[..., :, None] * quaternion[..., None, :]
    return (products.reshape(*stack, 16) @ _QUATERNION_BASIS).reshape(*stack, 3, 3)


def euler_rotation(angles: np.ndarray) -> np.ndarray:
    """R(η) of :func:`euler_rotation_rows`, stacked: (…, 1) or (…, 3) → (…, d, d)."""
    angles = np.asarray(angles, dtype=float)
    rows = euler_rotation_rows(np.moveaxis(angles, -1, 0), cos=np.cos, sin=np.sin)
    return _stack_rows(rows, angles.shape[:-1])


def rotate_back(rotation: np.ndarray, vector: np.ndarray) -> np.ndarray:
    """Rᵀx for stacked R (…, d, d) and x (…, d): a vector of {I} expressed in the body frame {B}."""
    return np.matmul(vector[..., None, :], rotation)[..., 0, :]


# ---------------------------------------------------------------------------------------------
# Δ, paths, errors and controllers


def delta_matrix(epsilon: np.ndarray) -> np.ndarray:
    """Δ of seed 003 eq. (22) (:func:`delta_rows`) as a float array, 2 × 2 or 3 × 4."""
    return np.array(delta_rows(np.asarray(epsilon, dtype=float)), dtype=float)


def delta_bar(epsilon: np.ndarray) -> np.ndarray:
    """Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ of seed 003 eq. (26); ValueError when ε₁ = 0 (det ΔΔᵀ = 0, Remark 6)."""
    epsilon = np.asarray(epsilon, dtype=float)
    if epsilon[0] == 0:
        raise ValueError(
            f"epsilon = {epsilon.tolist()}: ε₁ = 0 makes Δ of (22) rank deficient and Δ̄ does not "
            "exist (Remark 6)"
        )
    delta = delta_matrix(epsilon)
    return delta.T @ np.linalg.inv(delta @ delta.T)


@dataclass(frozen=True, eq=False)
class PathHarmonics:
    """Stacked harmonics of :func:`path_harmonics`: r_k(γ) = a_k cos(f_k γ + φ_k), arrays (…, d)."""

    amplitude: np.ndarray
    frequency: np.ndarray
    phase: np.ndarray

    @classmethod
    def of(cls, r_x: Any, r_y: Any, gamma0: Any, r_z: Any = None, c: Any = None):
        """From path constants (floats or per-tracker arrays) of eqs. (15)/(16)."""
        terms = path_harmonics(r_x, r_y, gamma0, r_z, c)
        a, f, phi = (np.stack(np.broadcast_arrays(*(np.asarray(t[k], float) for t in terms)), -1)
                     for k in range(3))  # fmt: skip
        return cls(a, f, phi)

    @functools.cached_property
    def slope(self) -> np.ndarray:
        """a_k f_k: the amplitudes of r′."""
        return self.amplitude * self.frequency

    def derivative(self, gamma: Any, order: int = 0) -> np.ndarray:
        """d^order r/dγ^order at ``gamma`` (…) → (…, d): a f^n cos(fγ + φ + nπ/2)."""
        angle = np.asarray(gamma, float)[..., None] * self.frequency + self.phase
        return self.amplitude * self.frequency**order * np.cos(angle + order * (np.pi / 2))


def path(gamma: Any, r_x: Any, r_y: Any, gamma0: Any, r_z: Any = None, c: Any = None) -> np.ndarray:
    """r(γ) of seed 003 eqs. (15)/(16) (:func:`path_harmonics`), coordinates on the last axis."""
    return PathHarmonics.of(r_x, r_y, gamma0, r_z, c).derivative(gamma)


def path_derivative(
    gamma: Any, r_x: Any, r_y: Any, gamma0: Any, r_z: Any = None, c: Any = None
) -> np.ndarray:
    """r′(γ) = (−r_x sin(γ + γ₀), r_y cos(γ + γ₀)(, (r_z/c) cos(γ/c + γ₀))), eqs. (15)/(16)."""
    return PathHarmonics.of(r_x, r_y, gamma0, r_z, c).derivative(gamma, 1)


def body_error(
    rotation: np.ndarray,
    position: np.ndarray,
    path_point: np.ndarray,
    target: np.ndarray,
    epsilon: np.ndarray,
) -> np.ndarray:
    """e_p = Rᵀ(p − r(γ) − q) − ε: e_p of seed 003 eqs. (19)/(59), ê_p of (27)/(48) with q̂."""
    return rotate_back(rotation, position - path_point - target) - epsilon


def tracking_input(
    rotation: np.ndarray,
    r_prime: np.ndarray,
    omega_d: np.ndarray,
    velocity: np.ndarray,
    e_hat: np.ndarray,
    delta_bar_matrix: np.ndarray,
    K_p: np.ndarray,
) -> np.ndarray:
    """u = (v₁, ω) = Δ̄(Rᵀ(r′(γ)ω_d + v̂) − K_p ê_p), seed 003 eq. (51) ((26)/(30): one tracker)."""
    command = rotate_back(rotation, r_prime * np.asarray(omega_d)[..., None] + velocity)
    return (command - e_hat @ K_p.T) @ delta_bar_matrix.T


def input_gains(
    delta_bar_matrix: np.ndarray, K_p: np.ndarray, epsilon: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(G, g) with u = [c, b] G + g for eq. (51) written on body-frame vectors.

    With the body-frame command c = Rᵀ(r′(γ)ω_d + v̂) and b = Rᵀ(p − r(γ) − q̂) (so ê_p = b − ε),
    u = Δ̄(c − K_p ê_p) = Δ̄c − Δ̄K_p b + Δ̄K_p ε: G = [Δ̄ᵀ; −(Δ̄K_p)ᵀ] (2d × m) and g = Δ̄K_p ε,
    the form the simulator evaluates (one product for every tracker; :func:`tracking_input`
    is the same law on inertial-frame vectors). Seed 003 eqs. (48), (51).
    """
    gain = delta_bar_matrix @ K_p
    return np.vstack([delta_bar_matrix.T, -gain.T]), gain @ epsilon


def tracker_rates(rotation: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(ṗ = R[v₁, 0(, 0)]ᵀ, body rates ω) of u = (v₁, ω), seed 003 eqs. (2)–(5), Remark 2."""
    return rotation[..., :, 0] * u[..., :1], u[..., 1:]


def path_feedback(e_hat: np.ndarray, rotation: np.ndarray, r_prime: np.ndarray) -> np.ndarray:
    """ê_pᵀRᵀr′(γ): the feedback term of the path-parameter law, seed 003 eqs. (25)/(29)/(50b)."""
    return (e_hat * rotate_back(rotation, r_prime)).sum(axis=-1)


def gamma_acceleration(
    k_gamma: float, e_gamma: np.ndarray, feedback: np.ndarray, v_c_dot: np.ndarray
) -> np.ndarray:
    """γ̈ = −k_γ e_γ + ê_pᵀRᵀr′(γ) + v̇_c, seed 003 eq. (50b) (so ė_γ = −k_γ e_γ + ê_pᵀRᵀr′, (62))."""
    return -k_gamma * e_gamma + feedback + v_c_dot


def correction_speed(laplacian: np.ndarray, values: np.ndarray, k_c: float) -> np.ndarray:
    """−k_c (L x)_i for x = γ (v_c, seed 003 eq. (45)) or x = γ̇ (v̇_c, eq. (52)), L = D_in − A."""
    return -k_c * (laplacian @ values)


def desired_speed(
    omega_bar: float, laplacian: np.ndarray, gamma: np.ndarray, k_c: float
) -> np.ndarray:
    """ω_d = ω̄ + v_c, seed 003 eqs. (45)–(46) (ω_d = ω̄ for one tracker, eq. (18))."""
    return omega_bar + correction_speed(laplacian, gamma, k_c)


def left_eigenvector(laplacian: Any) -> tuple[Fraction, ...] | None:
    """The exact r with rᵀL = 0, rᵀ1 = 1 (seed 003 Lemma 1), or ``None`` if 0 is not simple.

    ``laplacian``'s entries are read as the decimals they print as (weighted digraphs included,
    :func:`exact_laplacian`); r weighs the coordination error ξ = (I − 1rᵀ)γ of eq. (56).
    """
    import flint  # exact; imported on use (the simulator never needs it)

    L = exact_laplacian(laplacian)
    n = len(L)
    scale = math.lcm(*(x.denominator for row in L for x in row))
    integer = [[int(L[j][i] * scale) for j in range(n)] for i in range(n)]  # (scale·L)ᵀ
    basis, nullity = flint.fmpz_mat(integer).nullspace()
    if nullity != 1:
        return None
    vector = [int(basis[i, 0]) for i in range(n)]
    total = sum(vector)
    if total == 0:
        return None
    return tuple(Fraction(x, total) for x in vector)


def exact_laplacian(laplacian: Any) -> list[list[Fraction]]:
    """``L = D_in − A`` in rationals (seed 003 §II-B): each ``−a_ij`` the decimal it prints as
    (integers, ``Fraction``s, or floats of decimal weights), each ``L_ii = Σ_j a_ij`` summed
    exactly (a float diagonal such as 0.07 + 0.5 = 0.5700000000000001 is not read)."""
    from theory.core.exact import exact_decimal

    n = len(laplacian)
    off = [
        [exact_decimal(_scalar(laplacian[i][j])) if i != j else Fraction(0) for j in range(n)]
        for i in range(n)
    ]
    return [[off[i][j] if i != j else -sum(off[i]) for j in range(n)] for i in range(n)]


def _scalar(x: Any) -> Any:
    """A numpy scalar as the Python number it holds (an ``int`` stays exact)."""
    return x.item() if isinstance(x, np.generic) else x


# ---------------------------------------------------------------------------------------------
# one tracker's closed loop, from the kinematics


@dataclass(frozen=True)
class ClosedLoopRates:
    """One tracker's errors e_p (19), e_γ (47), their rates from the kinematics, the input u,
    ṗ, γ̇ and the feedback ê_pᵀRᵀr′ of (50b) (0 for Type I), at one state."""

    e_p: np.ndarray
    e_gamma: float
    de_p: np.ndarray
    de_gamma: float
    u: np.ndarray
    position_dot: np.ndarray
    gamma_dot: float
    feedback: float

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
    """Errors and error rates of one tracker under controller (49)/(50) with estimates (seed 003).

    The input is u = k(x̂) (eq. (51)); γ̈ follows (50b) for Type II (``omega_d_dot`` = v̇_c of
    (52)), while Type I imposes γ̇ = ω_d (so e_γ = 0 and ``gamma_dot`` is ignored). The rates come
    from differentiating e_p = Rᵀ(p − r(γ) − q) − ε with ṗ = R[v₁, 0, …]ᵀ, Ṙ = R S(ω), q̇ = v —
    the kinematics, not eq. (21). ``path_params``: the keywords of :func:`path` but ``gamma``.
    """
    r_gamma = path(gamma, **path_params)
    r_prime = path_derivative(gamma, **path_params)
    if controller == "I":
        gamma_dot = omega_d
    e_p = body_error(rotation, position, r_gamma, target_position, epsilon)
    e_hat = body_error(rotation, position, r_gamma, estimate_position, epsilon)
    u = tracking_input(
        rotation, r_prime, omega_d, estimate_velocity, e_hat, delta_bar(epsilon), K_p
    )
    position_dot, omega = tracker_rates(rotation, u)
    de_p = _body_error_rate(
        rotation, omega, position - r_gamma - target_position,
        position_dot - r_prime * gamma_dot - target_velocity,
    )  # fmt: skip
    e_gamma = gamma_dot - omega_d
    feedback, de_gamma = 0.0, 0.0
    if controller == "II":
        feedback = float(path_feedback(e_hat, rotation, r_prime))
        de_gamma = float(gamma_acceleration(k_gamma, e_gamma, feedback, omega_d_dot)) - omega_d_dot
    return ClosedLoopRates(
        e_p, float(e_gamma), de_p, de_gamma, u, position_dot, float(gamma_dot), feedback
    )


def _body_error_rate(
    rotation: np.ndarray, omega: np.ndarray, offset: np.ndarray, offset_rate: np.ndarray
) -> np.ndarray:
    """ė_p = ṘᵀΔp + RᵀΔṗ for e_p = RᵀΔp − ε, Δp = p − r(γ) − q, with Ṙ = R S(ω) (eqs. (3), (19))."""
    rotation_dot = rotation @ skew(omega)
    return rotation_dot.T @ offset + rotation.T @ offset_rate
