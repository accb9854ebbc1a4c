"""The public strategies produce what they promise, and refuse impossible arguments."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.strategies import (
    digraph_laplacians,
    dkf_problems,
    is_connected,
    networks,
    pursuit_cases,
    pursuit_parameters,
    state_space_pairs,
    tdoa_scenes,
    tracker_states,
    weight_matrices,
)
from theory.tdoa.model import unit_directions


def stacked_position_jacobian(scene) -> np.ndarray:
    units = unit_directions(scene.target, scene.agents)
    return units[0][None, :] - units[1:]


@given(state_space_pairs(max_condition=10.0, spectral_radius=(0.5, 0.9)))
def test_state_space_pairs_respect_bounds(pair) -> None:
    A, C = pair
    eigenvalues = np.linalg.eigvals(A)
    assert np.all(np.abs(eigenvalues) <= 0.9 * (1 + 1e-8))
    assert np.all(np.abs(eigenvalues) >= 0.5 * (1 - 1e-8))
    assert C.shape[1] == A.shape[0]


@given(networks(connected=True, directed=True))
def test_connected_directed_networks_are_strongly_connected(hears) -> None:
    assert is_connected(hears, strongly=True)
    assert not np.any(np.diag(hears))


@given(networks(connected=False))
def test_disconnected_networks_are_disconnected(hears) -> None:
    assert not is_connected(hears)
    assert np.array_equal(hears, hears.T)


@pytest.mark.parametrize("kind", ["metropolis", "uniform", "random", "singular"])
@given(data=st.data())
def test_weight_matrices_are_row_stochastic(kind, data) -> None:
    W = data.draw(weight_matrices(kind=kind))
    np.testing.assert_allclose(W.sum(axis=1), 1.0, atol=1e-12)
    assert np.all(W >= 0) and np.all(np.diag(W) > 0)
    if kind == "metropolis":
        np.testing.assert_allclose(W, W.T, atol=1e-15)
    if kind == "singular":
        assert np.linalg.matrix_rank(W) == 1


@given(tdoa_scenes(family="cone"))
def test_cone_scenes_lose_rank(scene) -> None:
    sv = np.linalg.svd(stacked_position_jacobian(scene), compute_uv=False)
    assert sv[-1] <= 1e-9 * sv[0]


@given(tdoa_scenes(family="target-in-plane"))
def test_target_in_plane_scenes_lose_rank(scene) -> None:
    sv = np.linalg.svd(stacked_position_jacobian(scene), compute_uv=False)
    assert sv[-1] <= 1e-9 * sv[0]


@given(tdoa_scenes(family="coplanar"))
def test_coplanar_receivers_are_coplanar(scene) -> None:
    centred = scene.agents - scene.agents.mean(axis=0)
    sv = np.linalg.svd(centred, compute_uv=False)
    assert sv[-1] <= 1e-9 * sv[0]


@given(pursuit_parameters(dim=3))
def test_pursuit_parameters_have_nonzero_first_epsilon(params) -> None:
    assert params.epsilon[0] < 0 and params.epsilon[-1] == 0
    assert len(params.K_p) == 3 and min(params.K_p) > 0


@given(data=st.data())
def test_pursuit_cases_and_tracker_states_respect_bounds(data) -> None:
    case = data.draw(pursuit_cases(n_trackers=3, dims=(3,), gains=(0.1, 0.2), path_sizes=(1, 2)))
    spec = case.spec
    eigenvalues = np.linalg.eigvalsh(spec.K_p)
    assert spec.dim == 3 and spec.n_trackers == 3 and spec.k_c is not None
    assert 0.1 * (1 - 1e-9) <= eigenvalues[0] and eigenvalues[-1] <= 0.2 * (1 + 1e-9)
    assert all(1 <= t.r_x <= 2 and 1 <= t.r_z <= 2 for t in spec.trackers)
    state = data.draw(tracker_states(spec=spec, bound=3.0))
    assert np.allclose(state.rotation @ state.rotation.T, np.eye(3))
    assert max(np.abs(state.e_p).max(), np.abs(state.q_err).max()) <= 3.0
    assert state.e_gamma == 0.0 or spec.controller == "II"
    assert np.allclose(state.rates(spec).e_p, state.e_p, atol=1e-9)


@pytest.mark.parametrize(
    "strategy",
    [
        lambda: tdoa_scenes(dim=4),
        lambda: digraph_laplacians(max_extra_edges=-1),
        lambda: tdoa_scenes(family="sphere"),
        lambda: tdoa_scenes(dim=2, family="cone"),
        lambda: weight_matrices(kind="metropolis", directed=True),
        lambda: weight_matrices(kind="magic"),
        lambda: networks(min_agents=5, max_agents=3),
        lambda: state_space_pairs(max_condition=0.5),
        lambda: pursuit_parameters(dim=1),
        lambda: pursuit_cases(n_trackers=0),
        lambda: pursuit_cases(dims=(4,)),
        lambda: pursuit_cases(controllers=("III",)),
        lambda: pursuit_cases(gains=(0.0, 1.0)),
        lambda: pursuit_cases(path_sizes=(2.0, 1.0)),
        lambda: pursuit_cases().flatmap(lambda case: tracker_states(spec=case.spec, bound=-1)),
    ],
)
def test_impossible_arguments_raise(strategy) -> None:
    @given(strategy())
    def draw_one(value) -> None:
        pass

    with pytest.raises(InvalidArgument):
        draw_one()


def test_dkf_weights_spread_over_the_decades_asked_for() -> None:
    """With ``weight_decades`` the ratio of a row's positive weights exceeds the default's 10
    (seed 000 (5.3): any positive w_ij on the links)."""
    from hypothesis import find

    def spread(problem) -> float:
        return max(row[row > 0].max() / row[row > 0].min() for row in problem.W)

    problem = find(dkf_problems(max_agents=4, weight_decades=4), lambda p: spread(p) > 100)
    assert np.allclose(problem.W.sum(axis=1), 1) and np.all(np.diag(problem.W) > 0)
    with pytest.raises(InvalidArgument, match="weight_decades"):
        dkf_problems(weight_decades=0)
