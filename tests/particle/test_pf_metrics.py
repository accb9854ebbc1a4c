"""NEES of the weighted particle cloud, NIS of the predicted TDOA measurements and OSPA of the
estimates (seed 002 §3.2.1; issue 26 item 4), against plain references."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import trackcert
from theory.core.consistency import nis
from theory.particle.case import PfNetwork
from theory.particle.filter import PfState, cloud_moments, measure, predicted_measurements

NODES = np.array([[0.0, 30.0], [-26.0, -15.0], [26.0, -15.0], [40.0, 40.0]])
seeds = st.integers(0, 2**32 - 1)


def _network() -> PfNetwork:
    hears = np.zeros((4, 4), bool)
    for i, j in [(0, 1), (0, 2), (1, 2), (2, 3)]:
        hears[i, j] = hears[j, i] = True
    return PfNetwork(NODES, hears, (0, 2, 3))


def _state(rng: np.random.Generator, filters: int, particles: int) -> PfState:
    weights = rng.random((filters, particles)) ** 2
    return PfState(
        rng.normal(5, 15, (filters, particles, 2)),
        rng.uniform(-np.pi, np.pi, (filters, particles)),
        weights / weights.sum(1, keepdims=True),
    )


@given(seeds)
def test_cloud_moments_are_the_weighted_mean_and_covariance(seed: int) -> None:
    rng = np.random.default_rng(seed)
    state = _state(rng, 3, 40)
    mean, cov = cloud_moments(state)
    for f in range(3):
        w, x = state.weights[f], state.positions[f]
        np.testing.assert_allclose(mean[f], np.average(x, axis=0, weights=w), rtol=1e-12)
        reference = np.cov(x.T, aweights=w, bias=True)
        np.testing.assert_allclose(cov[f], reference, rtol=1e-10, atol=1e-10)


@settings(deadline=None)
@given(seeds, st.floats(0.1, 5.0))
def test_predicted_measurements_on_the_measured_rows_only(seed: int, sigma: float) -> None:
    """ŷ = Σ w h(x), S = Σ w (h − ŷ)(h − ŷ)ᵀ + σ²I on node i's rows (eqs. (3.6)–(3.9)); the
    NIS equals the quadratic form on those rows alone."""
    rng = np.random.default_rng(seed)
    network = _network()
    state = _state(rng, 3, 30)
    y = measure(rng.uniform(-20, 20, 2), network, sigma, rng)
    nu, S = predicted_measurements(state, y, network, sigma)
    values = nis(nu, S)
    for f, node in enumerate(network.filters):
        rows = network.measurement_mask[f]
        h = np.array(
            [
                [np.linalg.norm(p - NODES[node]) - np.linalg.norm(p - NODES[j]) for j in range(4)]
                for p in state.positions[f]
            ]
        )[:, rows]
        mean = state.weights[f] @ h
        spread = h - mean
        cov = (state.weights[f][:, None] * spread).T @ spread + sigma**2 * np.eye(rows.sum())
        innovation = y[f, rows] - mean
        np.testing.assert_allclose(nu[f, rows], innovation, rtol=1e-10, atol=1e-10)
        assert np.all(nu[f, ~rows] == 0)
        expected = innovation @ np.linalg.solve(cov, innovation)
        assert values[f] == pytest.approx(expected, rel=1e-9)


def test_pf_result_reports_nees_nis_and_ospa_per_node() -> None:
    result = trackcert.pf("cases/pf-topology-a.yaml", runs=2)
    metrics = result.metrics
    spec = result.report.case.spec
    steps = spec.steps + 1
    dims = spec.network.measurement_mask.sum(axis=1)
    assert len(metrics["nees"]) == len(spec.network.filters)
    for test, dim in zip(metrics["nis"], dims, strict=True):
        assert test["band"]["dof"] == 2 * steps * dim
    for test in metrics["nees"]:
        assert test["band"]["dof"] == 2 * 2 * steps
        assert test["verdict"] in {"consistent", "optimistic", "pessimistic", "inconclusive"}
    cutoff = metrics["positions"]["tolerance"]["ospa_cutoff"]
    for agent, ospa in zip(result.agents, metrics["positions"]["ospa"], strict=True):
        assert agent["mean_ospa"] == ospa <= cutoff
        assert ospa <= agent["mean_localization_error"] + 1e-12  # min(c, e) ≤ e, same steps
