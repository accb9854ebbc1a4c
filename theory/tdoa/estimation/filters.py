"""The network filters of seed 000 §4.2: EKF steps, averaging, and one measurement update of
every agent (averaged, decentralized or centralized, :class:`~theory.tdoa.case.Filter`).

The update uses the Joseph form (4.15)/(4.34), which keeps ``P`` symmetric positive definite in
floating point; the gain is (4.13)/(4.32). Between two pings the agents average ``x̂_i`` and
``P_i`` with their neighbours (§4.3): ``x̄_i = Σ_j w_ij x̂_j``, ``P̄_i = Σ_j w_ij P_j``; the first
round after a ping is exactly (4.28)/(4.35). The averaged and decentralized filters update each
agent with its own TDOA rows; the centralized one runs one EKF on every agent's rows
(independent noises, eq. (4.2)) and every agent holds its estimate.
"""

from __future__ import annotations

import numpy as np

from theory.tdoa.case import Filter
from theory.tdoa.model import tdoa_jacobians, tdoa_predictions

__all__ = ["average_round", "ekf_predict", "ekf_update", "kalman_gain", "measurement_step"]


def kalman_gain(P: np.ndarray, H: np.ndarray, R: np.ndarray) -> np.ndarray:
    """``K = P H'(H P H' + R)⁻¹`` (``n × 0`` without rows); seed 000 eqs. (4.13), (4.32), (A.17)."""
    if H.shape[0] == 0:
        return np.zeros((P.shape[0], 0))
    return np.linalg.solve(H @ P @ H.T + R, H @ P).T


def ekf_update(
    x: np.ndarray, P: np.ndarray, innovation: np.ndarray, H: np.ndarray, R: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """``x̂(k|k)``, ``P(k|k)`` with the Joseph covariance; unchanged without rows.

    Seed 000 eqs. (4.12)–(4.15), (4.27), (4.32), (4.34).
    """
    if H.shape[0] == 0:
        return x, P
    K = kalman_gain(P, H, R)
    I_KH = np.eye(P.shape[0]) - K @ H
    P_new = I_KH @ P @ I_KH.T + K @ R @ K.T
    return x + K @ innovation, 0.5 * (P_new + P_new.T)


def ekf_predict(
    x: np.ndarray, P: np.ndarray, A: np.ndarray, BQB: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """``x̂ ← A x̂``, ``P ← A P A' + BQB'`` for a stack of agents (seed 000 eqs. (4.26), (4.33))."""
    return x @ A.T, np.einsum("ij,njk,lk->nil", A, P, A) + BQB


def average_round(W: np.ndarray, x: np.ndarray, P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One consensus round ``x̄ = W x``, ``P̄_i = Σ_j w_ij P_j`` (seed 000 eqs. (4.28), (4.35))."""
    return W @ x, np.einsum("ij,jkl->ikl", W, P)


def measurement_step(
    kind: Filter,
    x: np.ndarray,
    P: np.ndarray,
    readings: list[np.ndarray],
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    r: float,
    *,
    linearize_at: np.ndarray | None = None,
    agents: np.ndarray | None = None,
    innovations: list | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """``x̂_i(k|k)``, ``P_i(k|k)`` of every agent at one ping (``R_i = r I``).

    ``linearize_at`` evaluates the Jacobians there (the true target: the linearized filter whose
    covariance is the Riccati recursion along the true geometry) instead of at each prediction;
    ``agents`` are the positions of the estimates' holders (default ``0, 1, …``); a list given as
    ``innovations`` receives ``(ν, S = HPH' + R)`` of every update (one for ``centralized``).
    Seed 000 eqs. (4.12)–(4.15), (4.27), (4.32), (4.34).
    """
    dim = positions.shape[1]
    if Filter(kind) is Filter.CENTRALIZED:
        point, at = x[0, :dim], _at(x[0, :dim], linearize_at)
        h = np.concatenate(tdoa_predictions(point, positions, neighbours, agents=agents))
        H = np.vstack(tdoa_jacobians(at, positions, neighbours, agents=agents))
        y = np.concatenate(readings)
        x0, P0 = _update(x[0], P[0], y - h, H, r, innovations)
        return np.tile(x0, (x.shape[0], 1)), np.tile(P0, (x.shape[0], 1, 1))
    points = x[:, :dim]
    predictions = tdoa_predictions(points, positions, neighbours, agents=agents)
    jacobians = tdoa_jacobians(_at(points, linearize_at), positions, neighbours, agents=agents)
    x_new, P_new = np.empty_like(x), np.empty_like(P)
    for i, (y, h, H) in enumerate(zip(readings, predictions, jacobians, strict=True)):
        x_new[i], P_new[i] = _update(x[i], P[i], y - h, H, r, innovations)
    return x_new, P_new


def _update(
    x: np.ndarray, P: np.ndarray, innovation: np.ndarray, H: np.ndarray, r: float, out: list | None
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`ekf_update` with ``R = rI``, ``(ν, HPH' + R)`` appended to ``out`` (eq. (4.13))."""
    R = r * np.eye(innovation.shape[0])
    if out is not None:
        out.append((innovation, H @ P @ H.T + R))
    return ekf_update(x, P, innovation, H, R)


def _at(points: np.ndarray, linearize_at: np.ndarray | None) -> np.ndarray:
    return points if linearize_at is None else np.broadcast_to(linearize_at, points.shape)
