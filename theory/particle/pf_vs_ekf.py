"""Distributed PF versus distributed EKF on the same data, and the measurement-count claim.

The claims built on it are in :mod:`theory.particle.pf_vs_ekf_claims`.

Seed 002 compares the PF and the averaged EKF only qualitatively (§4.3.2–4.3.3, field data): on
three-node path graphs (one node with two neighbours) "the distributed PF converged and the
distributed EKF diverged" for two of the three topologies. :func:`compare_on_same_data` runs both
on identical DCRW paths and TDOA measurements (the streams of :mod:`theory.particle.experiments`;
the
EKF's initial positions come from ``default_rng([seed, r, 3])``) and reports per-node errors.

:func:`measurement_ranks` checks the structural statement behind §3.1 and §4.3.3 (seed 002,
citing [35, 36]): in 2D a node needs two TDOA measurements (three nodes) to localize on its own,
and a node with fewer can still estimate the target if it is connected to a network that has
enough. It decides, at seeded random target positions, the rank of each node's TDOA Jacobian
(position block), the observability of its constant-velocity pair ``(A, H_i)``, and that of its
connected component (all the component's TDOA rows stacked), exactly on the positions as
written (:mod:`theory.tdoa.exact_geometry`), the float SVD at ``rank_tol`` beside it.

The EKF is the simulation engine's averaged EKF of seed 000 eqs. (4.26)–(4.35) (seed 002's
reference [36]), run in 2D on the PF's network: each filtering node corrects with its own TDOA
vector (:func:`theory.tdoa.ekf.ekf_update`, Joseph form, geometry of
:mod:`theory.tdoa.measurements`), averages state and covariance with its filtering neighbours
(:func:`theory.tdoa.averaging.average_round`, Metropolis weights) and predicts with the
constant-velocity model (:func:`theory.tdoa.ekf.ekf_predict`). Nodes without a measurement only
average and predict.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.network import components, metropolis_weights
from theory.core.observability import RANK_TOL, numeric_rank
from theory.particle.case import PfSpec
from theory.particle.dcrw import sample_dcrw_path
from theory.particle.experiments import build_motion
from theory.particle.filter import PfNetwork, run_filter, simulate_measurements
from theory.tdoa.averaging import average_round
from theory.tdoa.ekf import ekf_predict, ekf_update
from theory.tdoa.exact_geometry import exact_direction_rank
from theory.tdoa.measurements import tdoa_jacobians, tdoa_predictions
from theory.tdoa.model import cv_discrete, tdoa_jacobian

__all__ = [
    "Comparison",
    "EkfConfig",
    "compare_on_same_data",
    "consensus_weights",
    "ekf_step",
    "measurement_ranks",
    "run_ekf",
]


@dataclass(frozen=True, eq=False)
class Comparison:
    """PF and EKF norm errors on the same paths and measurements.

    Attributes
    ----------
    pf_errors, ekf_errors : ndarray, shape (R, K+1, F)
        ``E_i(k)`` of each filter.
    seed : int
        Base seed.
    """

    pf_errors: np.ndarray
    ekf_errors: np.ndarray
    seed: int

    def tail(self, errors: np.ndarray) -> np.ndarray:
        """``(R, F)`` mean over the second half of the steps of ``errors`` (shape (R, K+1, F),
        e.g. ``pf_errors`` or ``ekf_errors``)."""
        return errors[:, errors.shape[1] // 2 :].mean(axis=1)


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
    """Correct every node with ``y (F, N)``, average (eqs. (4.27)–(4.28), (4.34)–(4.35)).

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
        # the node first, then its neighbours: agent 0 of the engine's TDOA geometry
        local, pairs = network.nodes[np.r_[node, neighbours]], [np.arange(1, neighbours.size + 1)]
        (h,) = tdoa_predictions(x[f, :2], local, pairs)
        (H,) = tdoa_jacobians(x[f, :2], local, pairs)
        R = config.sigma**2 * np.eye(neighbours.size)
        corrected_x[f], corrected_P[f] = ekf_update(x[f], P[f], y[f, neighbours] - h, H, R)
    return average_round(W, corrected_x, corrected_P)


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
        TDOA measurements (:func:`theory.particle.filter.simulate_measurements`).
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
        x, P = ekf_predict(x, P, A, Q)
    return np.asarray(estimates)


def compare_on_same_data(
    spec: PfSpec,
    *,
    runs: int | None = None,
    seed: int | None = None,
    ekf: EkfConfig | None = None,
) -> Comparison:
    """Run the PF (the case's model) and the averaged EKF on identical data (module docstring).

    Parameters
    ----------
    spec : PfSpec
        The scenario.
    runs, seed : int, optional
        Override the case's runs and base seed.
    ekf : EkfConfig, optional
        EKF parameters (default: ``EkfConfig`` with the filter's ``σ``).

    Returns
    -------
    Comparison
    """
    runs = spec.runs if runs is None else runs
    seed = spec.seed if seed is None else seed
    ekf = EkfConfig(sigma=spec.config.sigma) if ekf is None else ekf
    low, high = spec.workspace[:, 0], spec.workspace[:, 1]
    pf_errors, ekf_errors = [], []
    for r in range(runs):
        path_rng = np.random.default_rng([seed, r, 0])
        path = sample_dcrw_path(
            spec.target, spec.steps, path_rng, start=low + (high - low) * path_rng.random(2)
        )
        y = simulate_measurements(
            path, spec.network, spec.noise_sigma, np.random.default_rng([seed, r, 2])
        )
        pf = run_filter(
            path,
            spec.network,
            spec.config,
            build_motion(spec, spec.model),
            np.random.default_rng([seed, r, 1]),
            bounds=spec.workspace,
            measurements=y,
        )
        start = low + (high - low) * np.random.default_rng([seed, r, 3]).random(
            (len(spec.network.filters), 2)
        )
        estimates = run_ekf(y, spec.network, ekf, start)
        pf_errors.append(pf.errors)
        ekf_errors.append(np.linalg.norm(estimates - path[:, None], axis=-1))
    return Comparison(np.asarray(pf_errors), np.asarray(ekf_errors), seed)


def measurement_ranks(
    spec: PfSpec, *, points: int = 25, seed: int = 0, rank_tol: float = RANK_TOL
) -> list[dict[str, Any]]:
    """Per node: TDOA count, Jacobian rank, local and component observability (module docstring).

    Every rank is exact on the positions as written (the random targets as the decimals of their
    floats): the position block ``G`` of a connected set's stacked TDOA Jacobian has rank
    ``dim aff{u_j}`` (:func:`theory.tdoa.exact_geometry.exact_direction_rank`), and for the
    constant-velocity pair ``rank [G 0; G T G; …] = 2 rank G`` (``T ≠ 0``). The float SVD at
    ``rank_tol`` is kept as evidence: ``min_margin`` is the smallest factor by which a float
    decision on an exactly *full* rank clears its threshold (∞ when every full rank is well
    conditioned or every rank is deficient exactly).

    Parameters
    ----------
    spec : PfSpec
        Nodes, links and workspace.
    points : int
        Number of target positions drawn uniformly in the workspace.
    seed : int
        Seed of those positions.
    rank_tol : float
        Relative rank tolerance of the float evidence (:func:`numeric_rank`).

    Returns
    -------
    list of dict
        One record per node with the minimum and maximum of each rank over the positions and the
        smallest decision margin seen.
    """
    rng = np.random.default_rng(seed)
    low, high = spec.workspace[:, 0], spec.workspace[:, 1]
    targets = low + (high - low) * rng.random((points, 2))
    nodes, hears = spec.network.nodes, spec.network.hears
    parts = components(hears)
    records = []
    for i in range(len(nodes)):
        part = next(c for c in parts if i in c)
        star = [i, *(int(j) for j in np.flatnonzero(hears[i]))]
        local = [_exact_rank(p, nodes, star, rank_tol) for p in targets]
        pooled = [_exact_rank(p, nodes, part, rank_tol) for p in targets]
        records.append(
            {
                "id": i + 1,
                "measurements": int(hears[i].sum()),
                "jacobian_rank": _span(r for r, _ in local),
                "local_observability_rank": _span(2 * r for r, _ in local),
                "component": [j + 1 for j in part],
                "component_observability_rank": _span(2 * r for r, _ in pooled),
                "min_margin": float(min(m for _, m in local + pooled)),
                "rank_method": "exact",
            }
        )
    return records


def _span(values) -> list[int]:
    values = list(values)
    return [min(values), max(values)]


def _exact_rank(
    target: np.ndarray, nodes: np.ndarray, members: list[int], rank_tol: float
) -> tuple[int, float]:
    """Exact rank of the connected set ``members``' TDOA position block at ``target``, and the
    float margin when that rank is full (∞ otherwise): rows ``g_a − g_b`` of seed 000
    eqs. (4.7)–(4.10) (:func:`theory.tdoa.model.tdoa_jacobian`)."""
    if len(members) < 2:
        return 0, float("inf")
    dim = nodes.shape[1]
    exact = exact_direction_rank(target.tolist(), nodes[members].tolist())
    if exact < dim:
        return exact, float("inf")
    G = tdoa_jacobian(target, nodes[members], 0, range(1, len(members)))[:, :dim]
    numeric = numeric_rank(G, rank_tol=rank_tol)
    return exact, numeric.margin if numeric.rank == dim else 0.0
