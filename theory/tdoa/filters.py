"""Network filters: averaged EKF, decentralized EKF, centralized EKF (seed 000 §4.2).

All three share the prediction (:func:`~theory.tdoa.ekf.ekf_predict`) and differ in the update
and in what is averaged afterwards:

``averaged``
    each agent updates with its own TDOA rows (4.27), (4.34), then averages ``x̂`` and ``P`` with
    its neighbours (4.28), (4.35) — the distributed filter of §4.2.2;
``decentralized``
    each agent updates with its own rows and never averages (§4.2.1, eqs. (4.11)–(4.15));
``centralized``
    one EKF processes every agent's rows (independent noises, eq. (4.2)); every agent holds its
    estimate. This is the baseline the distributed filters are compared with.
"""

from __future__ import annotations

import numpy as np

from theory.tdoa.ekf import ekf_update
from theory.tdoa.measurements import tdoa_jacobians, tdoa_predictions

__all__ = ["FILTERS", "measurement_step", "shares_estimates"]

FILTERS = ("averaged", "decentralized", "centralized")


def shares_estimates(kind: str) -> bool:
    """Whether the filter ``kind`` averages estimates with neighbours between pings.

    Parameters
    ----------
    kind : str
        One of :data:`FILTERS`.

    Returns
    -------
    bool
    """
    return kind == "averaged"


def measurement_step(
    kind: str,
    x: np.ndarray,
    P: np.ndarray,
    readings: list[np.ndarray],
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    r: float,
    *,
    linearize_at: np.ndarray | None = None,
    agents: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The measurement update of every agent at one ping.

    Parameters
    ----------
    kind : {"averaged", "decentralized", "centralized"}
        Which network filter.
    x : ndarray, shape (N, 2d)
        Predicted estimates ``x̂_i(k|k−1)``.
    P : ndarray, shape (N, 2d, 2d)
        Predicted covariances.
    readings : list of ndarray
        ``y_i`` of each agent.
    positions : ndarray, shape (N, d)
        Agent positions at the ping.
    neighbours : list of ndarray
        0-based neighbours of each agent (whose TOAs agent ``i`` hears).
    r : float
        Measurement noise variance, ``R_i = r I``.
    linearize_at : ndarray, shape (d,), optional
        Evaluate the Jacobians here (e.g. the true target position: the *linearized* filter whose
        covariance is the Riccati recursion along the true geometry) instead of at each
        agent's prediction (the EKF).
    agents : ndarray of int, shape (N,), optional
        The position (row of ``positions``) of the agent holding estimate ``i``; default
        ``0, 1, …``. With only some nodes filtering (seed 002's networks), their indices.

    Returns
    -------
    x_upd, P_upd : ndarray
        ``x̂_i(k|k)`` and ``P_i(k|k)``.

    References
    ----------
    seed 000, eqs. (4.12)–(4.15), (4.27), (4.32), (4.34).
    """
    dim = positions.shape[1]
    if kind == "centralized":
        return _centralized_step(x, P, readings, positions, neighbours, r, linearize_at, agents)
    points = x[:, :dim]
    predictions = tdoa_predictions(points, positions, neighbours, agents=agents)
    jacobians = tdoa_jacobians(_at(points, linearize_at), positions, neighbours, agents=agents)
    x_new, P_new = np.empty_like(x), np.empty_like(P)
    for i, (y, h, H) in enumerate(zip(readings, predictions, jacobians, strict=True)):
        x_new[i], P_new[i] = ekf_update(x[i], P[i], y - h, H, r * np.eye(y.shape[0]))
    return x_new, P_new


def _centralized_step(
    x: np.ndarray,
    P: np.ndarray,
    readings: list[np.ndarray],
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    r: float,
    linearize_at: np.ndarray | None,
    agents: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray]:
    """One EKF update with every agent's rows stacked (independent noises, eq. (4.2)), held by
    every agent."""
    point = x[0, : positions.shape[1]]
    h = np.concatenate(tdoa_predictions(point, positions, neighbours, agents=agents))
    H = np.vstack(tdoa_jacobians(_at(point, linearize_at), positions, neighbours, agents=agents))
    y = np.concatenate(readings)
    x0, P0 = ekf_update(x[0], P[0], y - h, H, r * np.eye(y.shape[0]))
    n = x.shape[0]
    return np.tile(x0, (n, 1)), np.tile(P0, (n, 1, 1))


def _at(points: np.ndarray, linearize_at: np.ndarray | None) -> np.ndarray:
    return points if linearize_at is None else np.broadcast_to(linearize_at, points.shape)
