"""Static CRB of seed 000 §4.3.1 (eqs. 4.38–4.43) and the posterior CRB of the tracking runs."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.kinds import load_case
from theory.sim.simulate import monte_carlo
from theory.tdoa.estimation.scenario import run_tdoa_scenario
from theory.tdoa.estimation.simulation import summarize_runs
from theory.tdoa.geometry.crb import crb_trace, optimal_crb_trace, platonic_solids, tdoa_fisher

BOUND_RTOL = 1e-9
"""Relative tolerance on reaching the bound d²σ²/N² (floating point only)."""


def test_every_platonic_solid_reaches_the_bound() -> None:
    """§4.3.1: Platonic solids centred on the target are optimal for the complete network."""
    target = np.array([3.0, -2.0, 1.0])
    for name, vertices in platonic_solids().items():
        n = len(vertices)
        ratio = crb_trace(target, target + 7.0 * vertices, sigma2=0.5) / optimal_crb_trace(
            n, sigma2=0.5
        )
        assert abs(ratio - 1) <= BOUND_RTOL, name


def test_square_antiprism_is_optimal_too() -> None:
    """Erratum: optimality does not single out the cube among 8-agent formations."""
    h = 1 / np.sqrt(3)
    rho = np.sqrt(1 - h**2)
    top = [[rho * np.cos(a), rho * np.sin(a), h] for a in np.arange(4) * np.pi / 2]
    bottom = [[rho * np.cos(a), rho * np.sin(a), -h] for a in np.pi / 4 + np.arange(4) * np.pi / 2]
    antiprism = np.array(top + bottom)
    cube = platonic_solids()["cube"]
    assert not np.allclose(np.sort(_gaps(antiprism)), np.sort(_gaps(cube)))  # not a cube
    assert abs(crb_trace(np.zeros(3), 5 * antiprism) / optimal_crb_trace(8) - 1) <= BOUND_RTOL


def _gaps(points: np.ndarray) -> np.ndarray:
    return np.array([np.linalg.norm(a - b) for a, b in itertools.combinations(points, 2)])


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(4, 12))
def test_no_formation_beats_the_bound(seed: int, n: int) -> None:
    """tr(J⁻¹) ≥ 9σ²/N² for every formation; dropping pairs never helps."""
    rng = np.random.default_rng(seed)
    positions = rng.normal(size=(n, 3)) * rng.uniform(1, 20)
    target = rng.normal(size=3)
    full = crb_trace(target, positions)
    assert full >= optimal_crb_trace(n) * (1 - BOUND_RTOL)
    pairs = list(itertools.combinations(range(n), 2))
    kept = [pairs[i] for i in sorted(rng.choice(len(pairs), size=len(pairs) // 2, replace=False))]
    assert crb_trace(target, positions, kept) >= full * (1 - BOUND_RTOL)


def test_fisher_is_gram_of_pair_differences() -> None:
    """(4.39)–(4.42) directly: J = Σ (g_i − g_j)(g_i − g_j)'/σ²."""
    positions = np.array([[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2.0]])
    target = np.array([17.0, -5.0, -15.0])
    g = (target - positions) / np.linalg.norm(target - positions, axis=1, keepdims=True)
    J = sum(np.outer(g[i] - g[j], g[i] - g[j]) for i, j in [(0, 1), (1, 2), (2, 3)]) / 2.0
    assert np.allclose(tdoa_fisher(target, positions, [(0, 1), (1, 2), (2, 3)], 2.0), J)


def test_centralized_ekf_attains_the_pcrb_distributed_does_not() -> None:
    """Late-run MSE / PCRB: ≈ 1 for the centralized EKF (within Monte Carlo noise of 3 runs ×
    20 pings), larger for every agent of the averaged EKF."""
    ratios = {}
    for kind in ("centralized", "averaged"):
        spec = dataclasses.replace(load_case("sim-ch4-range21-b0").spec, filter=kind, steps=40)
        summary = summarize_runs(
            spec, monte_carlo(spec, simulate=run_tdoa_scenario, runs=3, seed=2, workers=1)
        )
        ratios[kind] = [agent["mse_to_pcrb"] for agent in summary["agents"]]
    assert all(0.7 < r < 1.4 for r in ratios["centralized"]), ratios
    assert min(ratios["averaged"]) > max(ratios["centralized"]), ratios


def test_crb_near_the_receivers_plane_is_finite_and_grows_like_h_to_the_minus_2() -> None:
    """Exactly observable for h ≠ 0 (finite, ∝ h⁻²), singular at h = 0 (issue 17: the float
    test λ_min ≤ 10⁻¹² λ_max read h = 10⁻⁶ as singular)."""
    agents = np.array([[0, 0, 0], [5, 0, 0], [0, 5, 0], [4, 6, 0.0]])
    traces = {h: crb_trace(np.array([1.0, 1.0, h]), agents) for h in (1e-3, 1e-6, 1e-9)}
    assert all(np.isfinite(t) for t in traces.values())
    assert traces[1e-6] / traces[1e-3] == pytest.approx(1e6, rel=1e-3)
    assert traces[1e-9] / traces[1e-6] == pytest.approx(1e6, rel=1e-3)
    assert crb_trace(np.array([1.0, 1.0, 0.0]), agents) == float("inf")
