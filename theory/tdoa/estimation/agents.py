"""3D steering robots (seed 000 eq. (4.44)) under dynamic feedback linearization (App. B.2), and
the formations they hold (the offsets ``d_i`` of eq. (4.45), §4.3.1, §4.4).

State of one agent, eqs. (4.44), (B.2), (B.5): ``r = [p_x, p_y, p_z, v, φ, γ, a, ω_φ, ω_γ]`` with
``ṗ = v e(φ, γ)``, ``e = [cos φ cos γ, sin φ cos γ, sin γ]``, ``v̇ = a``, ``ȧ = u₁``,
``φ̇ = ω_φ``, ``γ̇ = ω_γ``, ``ω̇_φ = u₂``, ``ω̇_γ = u₃``. (The text calls γ the angle to the
inertial z axis, but ``ṗ_z = v sin γ`` makes it the elevation above the x–y plane; we follow
the equations.)

With the output ``z = p`` (B.3), ``p⃛ = L_f³q(r) + 𝒜(r) u`` (B.10) where
``𝒜 = [e, v e_φ, v e_γ]`` (B.7), ``det 𝒜 = v² cos γ``, and
``L_f³q = 2a(ω_φ e_φ + ω_γ e_γ) + v(ω_φ² e_φφ + 2ω_φω_γ e_φγ + ω_γ² e_γγ)``.
The linearizing law (B.11) ``u = 𝒜⁻¹(ρ − L_f³q)`` gives three chains of integrators (B.12); the
virtual input ``ρ = −K(ζ − ζ*)`` per axis with ``K = [λ³, 3λ², 3λ]`` places a triple pole at
``−λ``. 𝒜 is singular at ``v = 0`` and ``γ = ±π/2``; robots start at rest, so
:func:`linearizing_control` evaluates 𝒜 with ``|v| ≥ v_floor`` and ``|cos γ| ≥ cos_floor`` (a
regularization, exact away from those sets). When the covariance trigger of §4.3 says "stay",
:func:`braking_control` brings ``v``, ``a`` and the turn rates to zero.

Formations (the dissertation gives the cube, not the "deformed" one): the cube is axis-aligned,
vertices ``(±1, ±1, ±1)·ρ/√3``; the *crown* puts ``n`` points on a horizontal circle of radius
``ρ`` at angles ``2πk/n``, alternately at heights ``±h`` (with ``ρ = 16``, ``h = 5`` and the rule
"distance < 21" each agent keeps exactly its two ring neighbours: a non-planar 8-cycle where no
agent has three TDOA rows); agent ``i`` gets the vertex of a minimum-total-distance matching.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np
from scipy.optimize import linear_sum_assignment

__all__ = [
    "STATE_SIZE",
    "assign_offsets",
    "braking_control",
    "crown_vertices",
    "cube_vertices",
    "flat_outputs",
    "linearizing_control",
    "rest_states",
    "rk4_step",
    "steering_dynamics",
]

STATE_SIZE = 9


def rest_states(positions: np.ndarray) -> np.ndarray:
    """Agents at ``positions`` (N, 3), at rest, heading along +x, shape (N, 9)."""
    states = np.zeros((positions.shape[0], STATE_SIZE))
    states[:, :3] = positions
    return states


def steering_dynamics(r: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``ṙ = f(r) + g(r) u`` for a stack of agents (N, 9), inputs (N, 3) (eqs. (4.44), (B.2))."""
    v, phi, gamma = r[:, 3], r[:, 4], r[:, 5]
    out = np.empty_like(r)
    out[:, 0] = v * np.cos(phi) * np.cos(gamma)
    out[:, 1] = v * np.sin(phi) * np.cos(gamma)
    out[:, 2] = v * np.sin(gamma)
    out[:, 3:6] = r[:, 6:9]
    out[:, 6:9] = u
    return out


def _frame(r: np.ndarray) -> tuple[np.ndarray, ...]:
    """``e``, unit ``ê_φ = e_φ/cos γ``, ``e_γ`` (an orthonormal frame) and ``cos γ``."""
    phi, gamma = r[:, 4], r[:, 5]
    cp, sp, cg, sg = np.cos(phi), np.sin(phi), np.cos(gamma), np.sin(gamma)
    e = np.empty((r.shape[0], 3))
    e[:, 0], e[:, 1], e[:, 2] = cp * cg, sp * cg, sg
    e_phi_unit = np.zeros_like(e)
    e_phi_unit[:, 0], e_phi_unit[:, 1] = -sp, cp
    e_gamma = np.empty_like(e)
    e_gamma[:, 0], e_gamma[:, 1], e_gamma[:, 2] = -cp * sg, -sp * sg, cg
    return e, e_phi_unit, e_gamma, cg


def _flat(r: np.ndarray, frame: tuple[np.ndarray, ...]) -> np.ndarray:
    e, e_phi_unit, e_gamma, cg = frame
    v, a, w_phi, w_gamma = r[:, 3:4], r[:, 6:7], r[:, 7:8], r[:, 8:9]
    out = np.empty((r.shape[0], 3, 3))
    out[:, 0] = r[:, :3]
    out[:, 1] = v * e
    out[:, 2] = a * e + v * (w_phi * cg[:, None] * e_phi_unit + w_gamma * e_gamma)
    return out


def flat_outputs(r: np.ndarray) -> np.ndarray:
    """``ζ = (p, ṗ, p̈)`` of eq. (B.8) from the robot states ``r``; shape (N, 3, 3)."""
    return _flat(r, _frame(r))


def _drift(r: np.ndarray, frame: tuple[np.ndarray, ...]) -> np.ndarray:
    """``L_f³q(r)`` with ``e_φφ = −cos γ (cos φ, sin φ, 0)``, ``e_φγ = sin γ (sin φ, −cos φ, 0)``,
    ``e_γγ = −e``."""
    e, e_phi_unit, e_gamma, cg = frame
    v, a, w_phi, w_gamma = r[:, 3:4], r[:, 6:7], r[:, 7:8], r[:, 8:9]
    sg = e[:, 2:3]
    horizontal = np.zeros_like(e)
    horizontal[:, 0], horizontal[:, 1] = e_phi_unit[:, 1], -e_phi_unit[:, 0]
    e_phiphi = -cg[:, None] * horizontal
    e_phigamma = -sg * e_phi_unit
    return 2.0 * a * (w_phi * cg[:, None] * e_phi_unit + w_gamma * e_gamma) + v * (
        w_phi**2 * e_phiphi + 2.0 * w_phi * w_gamma * e_phigamma - w_gamma**2 * e
    )


def linearizing_control(
    r: np.ndarray,
    target_flat: np.ndarray,
    pole: float,
    *,
    v_floor: float = 0.1,
    cos_floor: float = 0.1,
    max_input: tuple[float, float, float] = (np.inf, np.inf, np.inf),
) -> np.ndarray:
    """The law (B.11) tracking ``ζ*`` (N, 3, 3) with the error poles at ``−pole``, clipped to
    ``|u| ≤ max_input`` (seed 000 App. B.2, eqs. (B.7)–(B.13)).

    The columns ``e``, ``v e_φ``, ``v e_γ`` of ``𝒜`` are orthogonal with norms ``1``,
    ``|v| cos γ``, ``|v|``, so ``𝒜⁻¹ w = (e·w, ê_φ·w/(v cos γ), e_γ·w/v)`` in closed form.
    """
    frame = _frame(r)
    e, e_phi_unit, e_gamma, cg = frame
    v = r[:, 3]
    v_safe = np.where(v >= 0, 1.0, -1.0) * np.maximum(np.abs(v), v_floor)
    c_safe = np.where(cg >= 0, 1.0, -1.0) * np.maximum(np.abs(cg), cos_floor)
    error = _flat(r, frame) - target_flat
    rho = -(pole**3 * error[:, 0] + 3.0 * pole**2 * error[:, 1] + 3.0 * pole * error[:, 2])
    w = rho - _drift(r, frame)
    u = np.empty((r.shape[0], 3))
    u[:, 0] = np.einsum("nk,nk->n", e, w)
    u[:, 1] = np.einsum("nk,nk->n", e_phi_unit, w) / (v_safe * c_safe)
    u[:, 2] = np.einsum("nk,nk->n", e_gamma, w) / v_safe
    limit = np.asarray(max_input, dtype=float)
    return np.clip(u, -limit, limit)


def braking_control(r: np.ndarray, pole: float) -> np.ndarray:
    """``u₁ = −λ²v − 2λa``, ``u₂,₃ = −2λ ω``: bring speed and turn rates to rest."""
    v, a, w_phi, w_gamma = r[:, 3], r[:, 6], r[:, 7], r[:, 8]
    return np.column_stack(
        [-(pole**2) * v - 2.0 * pole * a, -2.0 * pole * w_phi, -2.0 * pole * w_gamma]
    )


def rk4_step(
    r: np.ndarray, control: Callable[[float, np.ndarray], np.ndarray], dt: float
) -> np.ndarray:
    """One classical Runge–Kutta step of ``ṙ = f(r) + g(r) u(s, r)``, ``s ∈ [0, dt]``."""
    k1 = steering_dynamics(r, control(0.0, r))
    r2 = r + 0.5 * dt * k1
    k2 = steering_dynamics(r2, control(0.5 * dt, r2))
    r3 = r + 0.5 * dt * k2
    k3 = steering_dynamics(r3, control(0.5 * dt, r3))
    r4 = r + dt * k3
    k4 = steering_dynamics(r4, control(dt, r4))
    return r + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


def cube_vertices(radius: float) -> np.ndarray:
    """The 8 vertices of the axis-aligned cube inscribed in a sphere of ``radius``, shape (8, 3)."""
    signs = np.array(list(itertools.product((-1.0, 1.0), repeat=3)))
    return signs * radius / np.sqrt(3.0)


def crown_vertices(n: int, radius: float, height: float) -> np.ndarray:
    """``n`` points on a horizontal circle of ``radius``, at heights ``+height``, ``−height``, …"""
    angles = 2.0 * np.pi * np.arange(n) / n
    z = height * np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    return np.column_stack([radius * np.cos(angles), radius * np.sin(angles), z])


def assign_offsets(initial: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Offsets ``d_i``: the vertex matched to each agent (minimum total distance from the
    agents' centroid)."""
    relative = initial - initial.mean(axis=0)
    cost = np.linalg.norm(relative[:, None, :] - vertices[None, :, :], axis=-1)
    rows, cols = linear_sum_assignment(cost)
    offsets = np.empty_like(vertices)
    offsets[rows] = vertices[cols]
    return offsets
