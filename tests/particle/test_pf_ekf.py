"""The averaged TDOA EKF baseline and the PF-vs-EKF / measurement-count claims (seed 002 §4.3)."""

from __future__ import annotations

import dataclasses

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from theory.kinds import load_case
from theory.particle.case import PfNetwork
from theory.particle.filter import simulate_measurements
from theory.particle.pf_vs_ekf import (
    EkfConfig,
    compare_on_same_data,
    consensus_weights,
    ekf_step,
    measurement_ranks,
    run_ekf,
)
from theory.registry import get_claim
from theory.tdoa.model import cv_discrete

TRIANGLE = np.array([[0.0, 35.0], [-30.31, -17.5], [30.31, -17.5]])


def _path_network(edges: list[tuple[int, int]]) -> PfNetwork:
    hears = np.zeros((3, 3), bool)
    for i, j in edges:
        hears[i, j] = hears[j, i] = True
    return PfNetwork(TRIANGLE, hears, (0, 1, 2))


def test_consensus_weights_are_metropolis_on_the_filter_graph():
    W = consensus_weights(_path_network([(0, 1), (0, 2)]))
    np.testing.assert_allclose(W, [[1 / 3, 1 / 3, 1 / 3], [1 / 3, 2 / 3, 0], [1 / 3, 0, 2 / 3]])


@given(st.integers(0, 2**32 - 1))
def test_correction_is_the_kalman_update(seed: int):
    rng = np.random.default_rng(seed)
    network = _path_network([(0, 1), (0, 2)])
    x = np.hstack([rng.uniform(-20, 20, (3, 2)), rng.normal(0, 1, (3, 2))])
    L = rng.normal(0, 1, (3, 4, 4))
    P = L @ L.transpose(0, 2, 1) + np.eye(4)
    y = simulate_measurements(rng.uniform(-20, 20, (1, 2)), network, 1.0, rng)[0]
    x_bar, P_bar = ekf_step(x, P, y, network, EkfConfig(sigma=0.7), np.eye(3))
    # node 1 (two neighbours) with the textbook formulas (seed 000 eqs. (4.12)–(4.13)):
    p = x[0, :2]
    r = np.linalg.norm(p - TRIANGLE, axis=1)
    u = (p - TRIANGLE) / r[:, None]
    H = np.hstack([u[0] - u[1:], np.zeros((2, 2))])
    K = P[0] @ H.T @ np.linalg.inv(H @ P[0] @ H.T + 0.49 * np.eye(2))
    np.testing.assert_allclose(x_bar[0], x[0] + K @ (y[0, 1:] - (r[0] - r[1:])), rtol=1e-9)
    np.testing.assert_allclose(P_bar[0], (np.eye(4) - K @ H) @ P[0], rtol=1e-8, atol=1e-9)


def test_ekf_tracks_a_constant_velocity_target():
    network = _path_network([(0, 1), (0, 2), (1, 2)])
    A, _ = cv_discrete(1.0, dim=2)
    state = np.array([-10.0, 5.0, 0.3, -0.2])
    path = []
    for _ in range(60):
        path.append(state[:2].copy())
        state = A @ state
    path = np.asarray(path)
    y = simulate_measurements(path, network, 0.1, np.random.default_rng(0))
    start = np.array([[5.0, 5.0], [-5.0, 0.0], [0.0, -8.0]])
    estimates = run_ekf(y, network, EkfConfig(sigma=0.1, accel_sigma=0.05), start)
    final = np.linalg.norm(estimates[-10:] - path[-10:, None], axis=-1)
    assert final.max() < 0.5  # 0.1 m TDOA noise, complete graph: decimetres


def test_measurement_ranks_of_topology_a():
    records = measurement_ranks(load_case("pf-topology-a").spec)
    table = {
        r["id"]: (
            r["measurements"],
            r["local_observability_rank"],
            r["component_observability_rank"],
        )
        for r in records
    }
    assert table == {
        1: (2, [4, 4], [4, 4]),
        2: (1, [2, 2], [4, 4]),
        3: (1, [2, 2], [4, 4]),
        4: (1, [2, 2], [2, 2]),
        5: (1, [2, 2], [2, 2]),
    }


def test_collinear_nodes_keep_the_rank_but_not_uniqueness():
    # seed 002 §4.1.1 asks for non-collinear nodes: the rank (local observability) survives
    # collinearity, but the target and its mirror image in the nodes' line give the same TDOA.
    case = load_case("pf-path3")
    line = dataclasses.replace(
        case.spec.network, nodes=np.array([[-30.0, 0.0], [0.0, 0.0], [30.0, 0.0]])
    )
    (result,) = get_claim("seed002.sec3.measurements").run(
        dataclasses.replace(case, spec=dataclasses.replace(case.spec, network=line))
    )
    assert result.status == "verified"
    target = np.array([[7.0, 11.0], [7.0, -11.0]])
    y = simulate_measurements(target, line, 0.0, np.random.default_rng(0))
    np.testing.assert_allclose(y[0], y[1], atol=1e-12)


def test_pf_and_ekf_see_the_same_data():
    spec = dataclasses.replace(load_case("pf-path3").spec, steps=20)
    comparison = compare_on_same_data(spec, runs=3, seed=4)
    assert comparison.pf_errors.shape == comparison.ekf_errors.shape == (3, 21, 3)
    again = compare_on_same_data(spec, runs=3, seed=4)
    np.testing.assert_array_equal(comparison.ekf_errors, again.ekf_errors)
    np.testing.assert_array_equal(comparison.pf_errors, again.pf_errors)


def test_pf_vs_ekf_claim_on_the_path_graph():
    case = load_case("pf-path3")
    small = dataclasses.replace(case, spec=dataclasses.replace(case.spec, runs=10))
    (result,) = get_claim("seed002.sec4.pf_vs_ekf").run(small)
    assert result.status == "verified", result.message
    assert {row["id"] for row in result.evidence["nodes"]} == {1, 2, 3}
