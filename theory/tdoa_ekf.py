"""A small 2D distributed TDOA EKF, the baseline the PF is compared with (seed 002 §4.3).

This is the averaged EKF of seed 000 eqs. (4.26)–(4.35) (seed 002's reference [36]) in 2D: each
filtering node predicts with the constant-velocity model (seed 000 eqs. (4.5)–(4.6)), corrects
with its own TDOA vector and the Jacobian of seed 000 eqs. (4.7)–(4.10), then averages state and
covariance with its filtering neighbours using consensus weights ``W`` (eqs. (4.28), (4.35)).
Nodes with no measurement only predict and average. It exists here because no simulation engine
was available to reuse (``git log sim`` showed only the skeleton); it is deliberately minimal.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.network import metropolis_weights
from theory.particle_filter import PfNetwork
from theory.tdoa import cv_discrete

__all__ = ["EkfConfig", "consensus_weights", "ekf_step", "run_ekf"]


@dataclass(frozen=True)
class EkfConfig:
    """Parameters of the averaged EKF.

    Attributes
    ----------
    T : float
        Ping period (s).
    accel_sigma : float
        Standard deviation of the white acceleration noise of the CV model (m/s², ``Q = σ_a² I``).
    sigma : float
        TDOA noise standard deviation assumed (m, ``R_i = σ² I``).
    position_sigma, velocity_sigma : float
        Standard deviations of the initial covariance ``P(0)``.
    """

    T: float = 1.0
    accel_sigma: float = 1.5
    sigma: float = 1.0
    position_sigma: float = 35.0
    velocity_sigma: float = 3.0


def consensus_weights(network: PfNetwork) -> np.ndarray:
    """Metropolis weights (DESIGN.md) on the graph of the filtering nodes of ``network``."""
    index = list(network.filters)
    return metropolis_weights(network.hears[np.ix_(index, index)])


def ekf_step(
    x: np.ndarray,
    P: np.ndarray,
    y: np.ndarray,
    network: PfNetwork,
    config: EkfConfig,
    W: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Correct every node with ``y (F, N)``, average (eqs. (4.27)–(4.28), (4.34)–(4.35)), predict.

    Parameters
    ----------
    x : ndarray, shape (F, 4)
        Predicted states ``x̂_i(k|k−1)`` = ``[p; ṗ]``.
    P : ndarray, shape (F, 4, 4)
        Predicted covariances.
    y : ndarray, shape (F, N)
        TDOA measurements (entries outside the measurement mask ignored).
    network, config, W :
        Nodes, parameters and consensus weights.

    Returns
    -------
    (x̄, P̄) :
        The corrected states and covariances averaged over neighbours (eqs. (4.28), (4.35)).
    """
    corrected_x, corrected_P = np.empty_like(x), np.empty_like(P)
    for f, node in enumerate(network.filters):
        neighbours = np.flatnonzero(network.hears[node])
        corrected_x[f], corrected_P[f] = _correct(
            x[f], P[f], y[f, neighbours], node, neighbours, network.nodes, config.sigma
        )
    return np.einsum("ij,jn->in", W, corrected_x), np.einsum("ij,jnm->inm", W, corrected_P)


def _correct(
    x: np.ndarray,
    P: np.ndarray,
    y: np.ndarray,
    node: int,
    neighbours: np.ndarray,
    nodes: np.ndarray,
    sigma: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Eqs. (4.27), (4.32), (4.34) for one node (Joseph form of the covariance update)."""
    if neighbours.size == 0:
        return x, P
    p = x[:2]
    ranges = np.linalg.norm(p[None] - nodes, axis=1)
    units = (p[None] - nodes) / ranges[:, None]
    H = np.hstack([units[node][None] - units[neighbours], np.zeros((neighbours.size, 2))])
    innovation = y - (ranges[node] - ranges[neighbours])
    S = H @ P @ H.T + sigma**2 * np.eye(neighbours.size)
    K = np.linalg.solve(S, H @ P).T
    I_KH = np.eye(4) - K @ H
    return x + K @ innovation, I_KH @ P @ I_KH.T + sigma**2 * K @ K.T


def run_ekf(
    measurements: np.ndarray,
    network: PfNetwork,
    config: EkfConfig,
    initial: np.ndarray,
) -> np.ndarray:
    """Run the averaged EKF on ``measurements`` from ``initial`` positions.

    Parameters
    ----------
    measurements : ndarray, shape (K+1, F, N)
        TDOA measurements (:func:`theory.particle_filter.simulate_measurements`).
    network : PfNetwork
        Nodes and links; the filtering nodes run the EKF.
    config : EkfConfig
        Model and noise parameters.
    initial : ndarray, shape (F, 2)
        Initial position estimates (velocity 0).

    Returns
    -------
    ndarray, shape (K+1, F, 2)
        The averaged position estimates ``x̄_i(k)`` (seed 000 eq. (4.28)).
    """
    A, B = cv_discrete(config.T, dim=2)
    Q = B @ B.T * config.accel_sigma**2
    W = consensus_weights(network)
    n_filters = len(network.filters)
    x = np.hstack([initial, np.zeros((n_filters, 2))])
    P0 = np.diag([config.position_sigma**2] * 2 + [config.velocity_sigma**2] * 2)
    P = np.broadcast_to(P0, (n_filters, 4, 4)).copy()
    estimates = []
    for y in measurements:
        x, P = ekf_step(x, P, y, network, config, W)
        estimates.append(x[:, :2].copy())
        x, P = x @ A.T, A @ P @ A.T + Q
    return np.asarray(estimates)
