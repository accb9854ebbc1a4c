"""TDOA measurements of the whole network at one ping (seed 000 eqs. (4.2)–(4.10)).

Agent ``i`` with neighbours ``N_i`` measures ``y_i = h_i(p) + v_i``, ``v_i ~ N(0, r I)``, where
``h_{i,j} = ‖p − p_i‖ − ‖p − p_j‖``. The noise of different agents is independent, as in (4.2):
agent ``j``'s measurement of the pair ``(j, i)`` is not the negative of agent ``i``'s.
"""

from __future__ import annotations

import numpy as np

__all__ = ["neighbour_lists", "tdoa_jacobians", "tdoa_predictions", "tdoa_readings"]


def neighbour_lists(hears: np.ndarray) -> list[np.ndarray]:
    """0-based neighbours ``N_i`` of each agent from the boolean ``hears[i, j]`` matrix."""
    return [np.flatnonzero(row) for row in hears]


def tdoa_predictions(
    point: np.ndarray, positions: np.ndarray, neighbours: list[np.ndarray]
) -> list[np.ndarray]:
    """``h_i(point)`` for every agent (eq. (4.3)).

    Parameters
    ----------
    point : ndarray, shape (d,) or (N, d)
        Where to evaluate (one point, or one per agent).
    positions : ndarray, shape (N, d)
        Agent positions.
    neighbours : list of ndarray
        0-based neighbours of each agent.

    Returns
    -------
    list of ndarray
    """
    ranges = np.linalg.norm(_offsets(point, positions), axis=2)
    return [ranges[i, i] - ranges[i, nbrs] for i, nbrs in enumerate(neighbours)]


def tdoa_jacobians(
    point: np.ndarray, positions: np.ndarray, neighbours: list[np.ndarray]
) -> list[np.ndarray]:
    """``H_i`` of eqs. (4.7)–(4.10), each of shape (|N_i|, 2d).

    Parameters
    ----------
    point, positions, neighbours : ndarray, ndarray, list of ndarray
        As in :func:`tdoa_predictions`.

    Returns
    -------
    list of ndarray
    """
    diff = _offsets(point, positions)
    units = diff / np.linalg.norm(diff, axis=2, keepdims=True)
    rows = [units[i, i][None, :] - units[i, nbrs] for i, nbrs in enumerate(neighbours)]
    return [np.hstack([r, np.zeros_like(r)]) for r in rows]


def _offsets(point: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """``point_i − p_j`` for every agent ``i`` and position ``p_j``, shape (N, N, d)."""
    return np.broadcast_to(point, positions.shape)[:, None, :] - positions[None, :, :]


def tdoa_readings(
    target: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    r: float,
    rng: np.random.Generator,
) -> list[np.ndarray]:
    """Noisy measurements ``y_i = h_i(p) + v_i`` with ``v_i ~ N(0, r I)`` (eq. (4.2)).

    Parameters
    ----------
    target : ndarray, shape (d,)
        True target position.
    positions : ndarray, shape (N, d)
        Agent positions at the ping.
    neighbours : list of ndarray
        0-based neighbours of each agent.
    r : float
        Measurement noise variance (``R_i = r I``).
    rng : numpy.random.Generator
        Source of the noise.

    Returns
    -------
    list of ndarray
        ``y_i`` for each agent (empty arrays for agents without neighbours).
    """
    clean = tdoa_predictions(target, positions, neighbours)
    return [h + np.sqrt(r) * rng.standard_normal(h.shape[0]) for h in clean]
