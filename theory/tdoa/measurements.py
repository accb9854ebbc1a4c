"""TDOA measurements of the whole network at one ping (seed 000 eqs. (4.2)–(4.10)).

Agent ``i`` with neighbours ``N_i`` measures ``y_i = h_i(p) + v_i``, ``v_i ~ N(0, r I)``, where
``h_{i,j} = ‖p − p_i‖ − ‖p − p_j‖``. The noise of different agents is independent, as in (4.2):
agent ``j``'s measurement of the pair ``(j, i)`` is not the negative of agent ``i``'s.

The neighbour lists are ragged (one length per agent); every value comes from the one model of
:mod:`theory.tdoa.model`, evaluated for all agents at once and then sliced per agent.
"""

from __future__ import annotations

import numpy as np

from theory.tdoa.model import range_difference_gradients, range_differences

__all__ = ["neighbour_lists", "tdoa_jacobians", "tdoa_predictions", "tdoa_readings"]


def neighbour_lists(hears: np.ndarray) -> list[np.ndarray]:
    """0-based neighbours ``N_i`` of each agent from the boolean ``hears[i, j]`` matrix."""
    return [np.flatnonzero(row) for row in hears]


def tdoa_predictions(
    point: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    *,
    agents: np.ndarray | None = None,
) -> list[np.ndarray]:
    """``h_i(point)`` for every measuring agent (eq. (4.3)).

    Parameters
    ----------
    point : ndarray, shape (d,) or (M, d)
        Where to evaluate (one point, or one per measuring agent).
    positions : ndarray, shape (N, d)
        Agent positions.
    neighbours : list of ndarray
        0-based neighbours (indices into ``positions``) of each measuring agent; ``M`` lists.
    agents : ndarray of int, shape (M,), optional
        Which position each list belongs to (default ``0, 1, …, M − 1``: list ``i`` is agent
        ``i``'s). A network where only some nodes filter (seed 002) passes its filtering nodes.

    Returns
    -------
    list of ndarray
    """
    full = range_differences(*_per_agent(point, positions, neighbours, agents))
    return [full[i, nbrs] for i, nbrs in enumerate(neighbours)]


def tdoa_jacobians(
    point: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    *,
    agents: np.ndarray | None = None,
) -> list[np.ndarray]:
    """``H_i`` of eqs. (4.7)–(4.10), each of shape (|N_i|, 2d).

    Parameters
    ----------
    point, positions, neighbours : ndarray, ndarray, list of ndarray
        As in :func:`tdoa_predictions`.
    agents : ndarray of int, optional
        As in :func:`tdoa_predictions`.

    Returns
    -------
    list of ndarray
    """
    full = range_difference_gradients(*_per_agent(point, positions, neighbours, agents))
    rows = [full[i, nbrs] for i, nbrs in enumerate(neighbours)]
    return [np.hstack([r, np.zeros_like(r)]) for r in rows]


def _per_agent(
    point: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    agents: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Arguments of the model for each measuring agent, each at its own point."""
    count = len(neighbours)
    agents = np.arange(count) if agents is None else np.asarray(agents, dtype=int)
    points = np.asarray(point, dtype=float)
    if points.ndim == 1:
        points = np.broadcast_to(points, (count, positions.shape[1]))
    return points[:count], positions, agents


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
