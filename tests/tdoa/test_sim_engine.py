"""The simulation engine's parts against their defining equations (seed 000 ch. 4, App. B.2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.errors import CaseError
from theory.core.network import metropolis_weights
from theory.kinds import parse_case
from theory.tdoa.case import CovNorm, Filter, Linearize
from theory.tdoa.estimation.agents import (
    assign_offsets,
    braking_control,
    crown_vertices,
    cube_vertices,
    flat_outputs,
    linearizing_control,
    rk4_step,
    steering_dynamics,
)
from theory.tdoa.estimation.filters import average_round, ekf_update, measurement_step
from theory.tdoa.estimation.scenario import covariance_norms
from theory.tdoa.model import neighbour_lists, tdoa_jacobians, tdoa_predictions
from theory.tdoa.observability.network import network_generic_rank

angles = st.floats(-math.pi, math.pi)
seeds = st.integers(0, 2**32 - 1)


@given(seed=seeds, pole=st.floats(0.2, 2.0))
def test_linearizing_control_makes_jerk_equal_virtual_input(seed: int, pole: float) -> None:
    """(B.10)–(B.12): with u of (B.11), d/dt (p̈) = ρ = −K(ζ − ζ*) exactly (away from v = 0)."""
    rng = np.random.default_rng(seed)
    n = 5
    r = rng.normal(size=(n, 9))
    r[:, 3] = rng.uniform(0.5, 3.0, n) * rng.choice([-1, 1], n)
    r[:, 5] = rng.uniform(-1.2, 1.2, n)
    target = rng.normal(size=(n, 3, 3))
    u = linearizing_control(r, target, pole)
    rdot = steering_dynamics(r, u)
    h = 1e-6
    jerk = (flat_outputs(r + h * rdot)[:, 2] - flat_outputs(r - h * rdot)[:, 2]) / (2 * h)
    error = flat_outputs(r) - target
    rho = -(pole**3 * error[:, 0] + 3 * pole**2 * error[:, 1] + 3 * pole * error[:, 2])
    scale = 1.0 + np.abs(rho).max()
    assert np.allclose(jerk, rho, atol=1e-5 * scale, rtol=0)


@given(seed=seeds)
def test_flat_outputs_are_position_derivatives(seed: int) -> None:
    """(B.8): ζ₂ = ṗ and ζ₃ = p̈ along the drift of (4.44), (B.2)."""
    rng = np.random.default_rng(seed)
    r = rng.normal(size=(4, 9))
    rdot = steering_dynamics(r, np.zeros((4, 3)))
    h = 1e-6
    flat = flat_outputs(r)
    d = (flat_outputs(r + h * rdot) - flat_outputs(r - h * rdot)) / (2 * h)
    assert np.allclose(d[:, 0], flat[:, 1], atol=1e-6)
    assert np.allclose(d[:, 1], flat[:, 2], atol=1e-6)


def test_tracking_converges_to_a_moving_reference() -> None:
    """Closed loop of (B.12): a robot starting at rest reaches p* = c + t·w with speed ‖w‖."""
    r = np.zeros((1, 9))
    w = np.array([0.6, -0.3, 0.2])
    dt = 0.05
    for step in range(1200):
        t = step * dt

        def control(s, state, t=t):
            ref = np.zeros((1, 3, 3))
            ref[0, 0] = np.array([5.0, 3.0, -2.0]) + (t + s) * w
            ref[0, 1] = w
            return linearizing_control(state, ref, 0.8)

        r = rk4_step(r, control, dt)
    t = 1200 * dt
    assert np.linalg.norm(r[0, :3] - (np.array([5.0, 3.0, -2.0]) + t * w)) < 1e-3
    assert abs(abs(r[0, 3]) - np.linalg.norm(w)) < 1e-3


def test_braking_brings_the_robot_to_rest() -> None:
    r = np.array([[0, 0, 0, 2.0, 0.3, 0.1, 0.5, 0.2, -0.1]])
    for _ in range(400):
        r = rk4_step(r, lambda s, state: braking_control(state, 1.0), 0.05)
    assert np.abs(r[0, [3, 6, 7, 8]]).max() < 1e-5


@given(seed=seeds)
def test_joseph_update_equals_standard_form(seed: int) -> None:
    """(4.15): the Joseph form equals (I − KH)P for the optimal gain (4.13)."""
    rng = np.random.default_rng(seed)
    M = rng.normal(size=(6, 6))
    P = M @ M.T + np.eye(6)
    H = rng.normal(size=(2, 6))
    R = np.eye(2)
    x, P_new = ekf_update(np.zeros(6), P, np.ones(2), H, R)
    K = P @ H.T @ np.linalg.inv(H @ P @ H.T + R)
    assert np.allclose(P_new, (np.eye(6) - K @ H) @ P, atol=1e-9 * np.abs(P).max())
    assert np.allclose(x, K @ np.ones(2))


@given(seed=seeds)
def test_metropolis_averaging_preserves_network_mean(seed: int) -> None:
    """(4.28), (4.35) with doubly stochastic W keep Σ_i x̂_i and Σ_i P_i."""
    rng = np.random.default_rng(seed)
    adjacency = np.triu(rng.random((6, 6)) < 0.5, 1)
    adjacency = adjacency | adjacency.T
    W = metropolis_weights(adjacency)
    x = rng.normal(size=(6, 6))
    P = rng.normal(size=(6, 6, 6))
    x_bar, P_bar = average_round(W, x, P)
    assert np.allclose(x_bar.sum(axis=0), x.sum(axis=0))
    assert np.allclose(P_bar.sum(axis=0), P.sum(axis=0))


@given(seed=seeds)
def test_tdoa_jacobians_match_finite_differences(seed: int) -> None:
    """(4.7)–(4.10) against central differences of (4.3)–(4.4)."""
    rng = np.random.default_rng(seed)
    positions = rng.uniform(-10, 10, (5, 3))
    target = rng.uniform(-10, 10, 3) + np.array([25.0, 0, 0])
    nbrs = neighbour_lists(~np.eye(5, dtype=bool))
    H = tdoa_jacobians(target, positions, nbrs)
    for axis in range(3):
        step = np.zeros(3)
        step[axis] = 1e-6
        plus = tdoa_predictions(target + step, positions, nbrs)
        minus = tdoa_predictions(target - step, positions, nbrs)
        for i in range(5):
            assert np.allclose((plus[i] - minus[i]) / 2e-6, H[i][:, axis], atol=1e-6)


def test_cube_and_crown_formations() -> None:
    cube = cube_vertices(10.0)
    assert np.allclose(np.linalg.norm(cube, axis=1), 10.0)
    gaps = np.linalg.norm(cube[:, None] - cube[None], axis=-1)
    assert np.isclose(np.sort(gaps[0])[1], 20 / math.sqrt(3))  # edge of the cube
    crown = crown_vertices(8, 16.0, 5.0)
    gaps = np.linalg.norm(crown[:, None] - crown[None], axis=-1)
    np.fill_diagonal(gaps, np.inf)
    assert ((gaps < 21).sum(axis=1) == 2).all()  # the 8-cycle of docs/simulation.md
    offsets = assign_offsets(crown + 0.1, crown)
    assert np.allclose(offsets, crown)


BASE = {
    "agents": [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]],
    "target": [5, 5, 5],
    "edges": [[1, 2], [2, 3], [3, 4]],
    "formation": [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]],
}


def _case(**changes: object) -> dict:
    block = {**BASE, **changes}
    return {"name": "t", "kind": "tdoa-sim", "tdoa-sim": block}


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"tau": 0.3}, "tdoa-sim.tau"),
        ({"comm_range": 21}, "tdoa-sim.edges"),
        ({"edges": [[1, 5]]}, "tdoa-sim.edges"),
        ({"b": -1}, "tdoa-sim.b"),
        ({"filter": "ukf"}, "tdoa-sim.filter"),
        ({"formation": "cube"}, "tdoa-sim.formation"),
        ({"Q": [[1, 0], [0, 1]]}, "tdoa-sim.Q"),
        ({"colour": "red"}, "tdoa-sim.colour"),
    ],
)
def test_bad_blocks_name_the_field(changes: dict, field: str) -> None:
    with pytest.raises(CaseError) as info:
        parse_case(_case(**changes))
    assert info.value.field == field


def test_block_defaults_and_infinite_threshold() -> None:
    spec = parse_case(_case(b=".inf")).spec
    assert spec.b == math.inf and spec.rounds == 1 and spec.filter == "averaged"
    assert np.allclose(spec.P0, 100 * np.eye(6)) and np.allclose(spec.Q, 0.01 * np.eye(3))
    assert parse_case(_case(tau=0.1)).spec.rounds == 10


def test_closed_vocabularies_refuse_a_misspelling() -> None:
    """A misspelt filter, norm or parametrization raises instead of falling into a default."""
    spec = parse_case(_case(filter="centralized", linearize="truth", cov_norm="frobenius")).spec
    assert (spec.filter, spec.linearize, spec.cov_norm) == (
        Filter.CENTRALIZED,
        Linearize.TRUTH,
        CovNorm.FROBENIUS,
    )
    with pytest.raises(CaseError, match="one of"):
        parse_case(_case(cov_norm="spectrum"))
    x, P = np.zeros((2, 6)), np.tile(np.eye(6), (2, 1, 1))
    positions = np.array([[0.0, 0, 0], [10, 0, 0]])
    neighbours = neighbour_lists(~np.eye(2, dtype=bool))
    readings = [np.zeros(1), np.zeros(1)]
    with pytest.raises(ValueError, match="centralised"):
        measurement_step("centralised", x, P, readings, positions, neighbours, 1.0)
    with pytest.raises(ValueError, match="spectrl"):
        covariance_norms(P, "spectrl")
    with pytest.raises(ValueError, match="edge"):
        network_generic_rank(~np.eye(2, dtype=bool), [[1, 0], [0, 1]], parametrization="edge")
