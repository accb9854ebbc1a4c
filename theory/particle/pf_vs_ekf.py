"""Distributed PF versus distributed EKF on the same data, and the measurement-count claim.

Seed 002 compares the PF and the averaged EKF only qualitatively (§4.3.2–4.3.3, field data): on
three-node path graphs (one node with two neighbours) "the distributed PF converged and the
distributed EKF diverged" for two of the three topologies. :func:`compare_on_same_data` runs both
on identical DCRW paths and TDOA measurements (the streams of :mod:`theory.particle.experiments`;
the EKF's initial positions come from ``default_rng([seed, r, 3])``) and reports per-node errors.

:func:`measurement_ranks` checks the structural statement behind §3.1 and §4.3.3 (seed 002,
citing [35, 36]): in 2D a node needs two TDOA measurements (three nodes) to localize on its own,
and a node with fewer can still estimate the target if it is connected to a network that has
enough. It decides, at seeded random target positions, the rank of each node's TDOA Jacobian
(position block), the observability of its constant-velocity pair ``(A, H_i)``, and that of its
connected component (all the component's TDOA rows stacked), exactly on the positions as
written (:mod:`theory.tdoa.geometry.exact`), the float SVD at ``rank_tol`` beside it.

The EKF is the simulation engine's averaged EKF of seed 000 eqs. (4.26)–(4.35) (seed 002's
reference [36]), run in 2D on the PF's network: each filtering node corrects with its own TDOA
vector (:func:`theory.tdoa.estimation.filters.ekf_update`, Joseph form, geometry of
:mod:`theory.tdoa.model`), averages state and covariance with its filtering neighbours
(:func:`theory.tdoa.estimation.filters.average_round`, Metropolis weights) and predicts with the
constant-velocity model (:func:`theory.tdoa.estimation.filters.ekf_predict`). Nodes without a
measurement only average and predict.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, status_of
from theory.core.network import components, metropolis_weights
from theory.core.observability import RANK_TOL, numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR
from theory.core.verdicts import all_hold
from theory.particle.case import PfNetwork, PfSpec
from theory.particle.experiments import (
    DEFAULT_TOLERANCES,
    Convergence,
    convergence_margin,
    convergence_verdicts,
    one_run,
    verdict_words,
)
from theory.tdoa.estimation.filters import average_round, ekf_predict, ekf_update
from theory.tdoa.geometry.exact import exact_direction_rank
from theory.tdoa.model import cv_discrete, tdoa_jacobian, tdoa_jacobians, tdoa_predictions

__all__ = [
    "Comparison",
    "EkfConfig",
    "claims",
    "compare_on_same_data",
    "consensus_weights",
    "ekf_step",
    "measurement_ranks",
    "run_ekf",
]

claims = ClaimSet()

RANK_POINTS, RANK_SEED = 25, 0
"""Target positions (and their seed) at which :func:`measurement_ranks` decides the claim."""


@dataclass(frozen=True, eq=False)
class Comparison:
    """PF and EKF norm errors ``(R, K+1, F)`` on the same paths and measurements."""

    pf_errors: np.ndarray
    ekf_errors: np.ndarray
    seed: int

    def tail(self, errors: np.ndarray) -> np.ndarray:
        """``(R, F)`` mean over the second half of the steps of ``errors`` (shape (R, K+1, F),
        e.g. ``pf_errors`` or ``ekf_errors``)."""
        return errors[:, errors.shape[1] // 2 :].mean(axis=1)


@dataclass(frozen=True)
class EkfConfig:
    """The averaged EKF's parameters: ping period ``T`` (s), white-acceleration noise of the CV
    model ``Q = σ_a² I`` (m/s²), TDOA noise assumed ``R_i = σ² I`` (m), and the standard
    deviations of the initial covariance ``P(0)``."""

    T: float = 1.0
    accel_sigma: float = 1.5
    sigma: float = 1.0
    position_sigma: float = 35.0
    velocity_sigma: float = 3.0


def consensus_weights(network: PfNetwork) -> np.ndarray:
    """Metropolis weights on the graph of the filtering nodes of ``network``."""
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
    """Correct every node's predicted ``x̂_i = [p; ṗ]`` ``(F, 4)`` and ``P`` ``(F, 4, 4)`` with
    its TDOAs ``y (F, N)``, then average with weights ``W`` (seed 000 eqs. (4.27)–(4.28),
    (4.34)–(4.35))."""
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
    """The averaged EKF on ``measurements`` ``(K+1, F, N)`` from ``initial`` positions ``(F, 2)``
    (velocity 0): the averaged position estimates ``(K+1, F, 2)`` (seed 000 eq. (4.28))."""
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
    """Run the PF (the case's model) and the averaged EKF (default: ``EkfConfig`` with the
    filter's ``σ``) on identical data (module docstring); ``None``: the case's runs and seed."""
    runs = spec.runs if runs is None else runs
    seed = spec.seed if seed is None else seed
    ekf = EkfConfig(sigma=spec.config.sigma) if ekf is None else ekf
    low, high = spec.workspace[:, 0], spec.workspace[:, 1]
    pf_errors, ekf_errors = [], []
    for r in range(runs):
        path, y, pf = one_run(spec, spec.config, spec.model, [seed, r])
        start = low + (high - low) * np.random.default_rng([seed, r, 3]).random(
            (len(spec.network.filters), 2)
        )
        estimates = run_ekf(y, spec.network, ekf, start)
        pf_errors.append(pf.errors)
        ekf_errors.append(np.linalg.norm(estimates - path[:, None], axis=-1))
    return Comparison(np.asarray(pf_errors), np.asarray(ekf_errors), seed)


def measurement_ranks(
    spec: PfSpec, *, points: int = RANK_POINTS, seed: int = RANK_SEED, rank_tol: float = RANK_TOL
) -> list[dict[str, Any]]:
    """Per node: TDOA count, Jacobian rank, local and component observability ranks (minimum and
    maximum over ``points`` seeded targets uniform in the workspace), and the smallest margin.

    Every rank is exact on the positions as written (the random targets as the decimals of their
    floats): the position block ``G`` of a connected set's stacked TDOA Jacobian has rank
    ``dim aff{u_j}`` (:func:`theory.tdoa.geometry.exact.exact_direction_rank`), and for the
    constant-velocity pair ``rank [G 0; G T G; …] = 2 rank G`` (``T ≠ 0``). The float SVD at
    ``rank_tol`` is kept as evidence: ``min_margin`` is the smallest factor by which a float
    decision on an exactly *full* rank clears its threshold (∞ when every full rank is well
    conditioned or every rank is deficient exactly).
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


def _span(values: Iterable[int]) -> list[int]:
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


@claims.register(
    "seed002.sec3.measurements",
    source="seed 002, §3.1 and §3.3.1 (citing [35, 36]); §4.1.1",
    statement=(
        "In 2D a node needs two TDOA measurements (three non-collinear nodes) to localize the "
        "target on its own; with fewer it can still estimate it if connected to a network with "
        "enough measurements."
    ),
    kinds=("pf",),
)
def check_measurements(case: Case, ctx: Context) -> list[ClaimResult]:
    """Every node's local and pooled observability ranks are the predicted ones (seed 002 §3.1);
    inconclusive when a rank decision lies within ``inconclusive_factor`` of its threshold."""
    records = measurement_ranks(case.spec)
    failures = []
    for r in records:
        alone = 4 if r["measurements"] >= 2 else 2 * r["measurements"]
        if r["local_observability_rank"] != [alone, alone]:
            failures.append(f"node {r['id']}: local rank {r['local_observability_rank']}")
        pooled = 4 if len(r["component"]) >= 3 else 2 * (len(r["component"]) - 1)
        if r["component_observability_rank"] != [pooled, pooled]:
            failures.append(f"node {r['id']}: component rank {r['component_observability_rank']}")
    margin = min(r["min_margin"] for r in records)
    holds = False if failures else None if margin < INCONCLUSIVE_FACTOR else True
    evidence = {
        "nodes": records,
        "failures": failures,
        "points": RANK_POINTS,
        "seed": RANK_SEED,
        "cross_check": "compare with `trackcert topology` on the tdoa case of "
        "the same network (cases/pf-tdoa-*.yaml)",
    }
    return [
        ClaimResult(
            status_of(holds),
            Method.NUMERIC,
            evidence,
            margin=margin,
            tolerance={"rank_tol": RANK_TOL, "inconclusive_factor": INCONCLUSIVE_FACTOR},
            message="local observability needs ≥ 2 TDOA rows; every node of a component of "
            "≥ 3 non-collinear nodes is observable when the component's rows are pooled"
            if not failures
            else "; ".join(failures),
        )
    ]


@claims.register(
    "seed002.sec4.pf_vs_ekf",
    source="seed 002, §4.3.3 and Figs. 4.8–4.11",
    statement=(
        "On a three-node path graph (ends with one TDOA measurement) the distributed PF "
        "converges at every node, while the distributed EKF may diverge."
    ),
    kinds=("pf",),
)
def check_pf_vs_ekf(case: Case, ctx: Context) -> list[ClaimResult]:
    """The PF converges at every node (the verdict; seed 002 §4.3.3), the EKF's errors on the
    same data beside it; only on three-node networks whose case expects ``converges``."""
    spec = case.spec
    if "converges" not in case.expect or len(spec.network.nodes) != 3:
        return []
    tol = {**DEFAULT_TOLERANCES, **case.tolerances}
    bands = {k: tol[k] for k in ("converge_tol", "diverge_tol")}
    comparison = compare_on_same_data(spec)
    errors = {"pf": comparison.pf_errors, "ekf": comparison.ekf_errors}
    verdicts = {
        name: convergence_verdicts(comparison.tail(e), spec.network.filters, **bands)
        for name, e in errors.items()
    }
    per_node = _per_node(spec, comparison, verdicts, tol["diverge_tol"])
    every_node = {node + 1: Convergence.CONVERGES for node in spec.network.filters}
    pf_tail = comparison.tail(comparison.pf_errors)
    evidence = {
        "nodes": per_node,
        "runs": int(comparison.pf_errors.shape[0]),
        "seed": comparison.seed,
        "ekf": vars(EkfConfig(sigma=spec.config.sigma)),
    }
    return [
        ClaimResult(
            status_of(all_hold(v.holds for v in verdicts["pf"].values())),
            Method.SIMULATION,
            evidence,
            margin=convergence_margin(pf_tail, spec.network.filters, every_node, **bands),
            tolerance=bands,
            message=f"PF {verdict_words(verdicts['pf'])}; EKF on the same data "
            f"{verdict_words(verdicts['ekf'])}; runs with tail error ≥ diverge_tol per node: PF "
            f"{[row['pf']['diverged_fraction'] for row in per_node]}, EKF "
            f"{[row['ekf']['diverged_fraction'] for row in per_node]}",
        )
    ]


def _per_node(
    spec: PfSpec,
    comparison: Comparison,
    verdicts: dict[str, dict[int, Convergence]],
    diverge_tol: float,
) -> list[dict[str, Any]]:
    """Per filtering node: its TDOA count and the PF's and the EKF's error statistics."""
    rows = []
    for f, node in enumerate(spec.network.filters):
        row = {"id": node + 1, "measurements": int(spec.network.measurement_mask[f].sum())}
        for name, errors in (("pf", comparison.pf_errors), ("ekf", comparison.ekf_errors)):
            tail = comparison.tail(errors)[:, f]
            row[name] = {
                "mean_error": float(errors[:, :, f].mean()),
                "tail_error_mean": float(tail.mean()),
                "tail_error_median": float(np.median(tail)),
                "tail_error_q90": float(np.quantile(tail, 0.9)),
                "diverged_fraction": float(np.mean(tail >= diverge_tol)),
                "verdict": verdicts[name][node + 1].value,
            }
        rows.append(row)
    return rows
