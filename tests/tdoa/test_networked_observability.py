"""The networked pair (W⊗A, D_H) of seed 000 §4.2.2: structure of O, the rank-sum claim of
eq. (4.36), observability versus detectability (Thm 4.2.3)."""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from theory.core.network import (
    adjacency_from_edges,
    exact_weights,
    metropolis_weights,
    uniform_weights,
)
from theory.core.observability import numeric_rank, observability_matrix
from theory.tdoa.model import cv_discrete, tdoa_jacobian
from theory.tdoa.observability.network import (
    agent_observability_blocks,
    analyze_network,
    exact_network_matrix,
    network_generic_rank,
    network_observability_matrix,
    networked_pair,
    unobservable_subspace,
)
from theory.tdoa.observability.single_agent import exact_rank

SEPARATION = 2.0
"""Near-degenerate draws are rejected: points closer than this (scene units) are discarded."""
SIGMA_MARGIN = 0.05
"""…and so are geometries whose stacked unit-vector differences have σ_min below this."""


@st.composite
def scenes(draw, *, min_agents: int = 4, max_agents: int = 6, dim: int = 3):
    """Integer agent positions and target, well separated, with a well-conditioned geometry."""
    n = draw(st.integers(min_agents, max_agents))
    coords = st.lists(st.integers(-20, 20), min_size=dim, max_size=dim)
    points = np.array(draw(st.lists(coords, min_size=n + 1, max_size=n + 1)), dtype=float)
    gaps = np.linalg.norm(points[:, None] - points[None], axis=-1) + np.eye(n + 1) * 1e9
    assume(gaps.min() > SEPARATION)
    target, agents = points[0], points[1:]
    units = (target - agents) / np.linalg.norm(target - agents, axis=1, keepdims=True)
    assume(np.linalg.svd(units[1:] - units[0], compute_uv=False)[dim - 1] > SIGMA_MARGIN)
    return agents, target


@st.composite
def connected_graphs(draw, n: int):
    """Adjacency of a connected undirected graph on ``n`` nodes (a random tree plus extra edges)."""
    edges = [(draw(st.integers(0, i - 1)), i) for i in range(1, n)]
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    edges += draw(st.lists(st.sampled_from(pairs), max_size=n))
    return adjacency_from_edges(n, np.array(edges))


def jacobians(agents: np.ndarray, target: np.ndarray, adjacency: np.ndarray) -> list[np.ndarray]:
    return [
        tdoa_jacobian(target, agents, i, list(np.flatnonzero(adjacency[i])))
        for i in range(len(agents))
    ]


@given(scenes(max_agents=5), st.data(), st.floats(0.1, 5.0))
def test_whole_matrix_is_the_block_columns_and_the_pair_krylov_matrix(scene, data, T) -> None:
    agents, target = scene
    adjacency = data.draw(connected_graphs(len(agents)))
    A, _ = cv_discrete(T, 3)
    W = metropolis_weights(adjacency)
    H = jacobians(agents, target, adjacency)
    WA, D_H = networked_pair(A, W, H)
    O = network_observability_matrix(A, W, H)
    np.testing.assert_array_equal(O, np.hstack(agent_observability_blocks(A, W, H)))
    np.testing.assert_allclose(O, observability_matrix(WA, D_H), rtol=1e-12, atol=1e-12)


@given(scenes(max_agents=5), st.data())
def test_staircase_rank_agrees_with_svd_of_the_whole_matrix(scene, data) -> None:
    agents, target = scene
    adjacency = data.draw(connected_graphs(len(agents)))
    A, _ = cv_discrete(1.0, 3)
    W = data.draw(st.sampled_from([metropolis_weights, uniform_weights]))(adjacency)
    H = jacobians(agents, target, adjacency)
    basis, margin = unobservable_subspace(*networked_pair(A, W, H), rank_tol=1e-9)
    whole = numeric_rank(network_observability_matrix(A, W, H), rank_tol=1e-9)
    assume(margin >= 1e3 and whole.conclusive())
    assert 6 * len(agents) - basis.shape[1] == whole.rank
    assert analyze_network(A, W, H).rank_method in ("staircase", "svd")


@given(scenes(), st.data())
def test_connected_network_in_general_position_is_detectable(scene, data) -> None:
    """Thm 4.2.3 (corrected): ≥ 4 connected agents whose Jacobians span R³ ⇒ detectable."""
    agents, target = scene
    adjacency = data.draw(connected_graphs(len(agents)))
    W = data.draw(st.sampled_from([metropolis_weights, uniform_weights]))(adjacency)
    result = analyze_network(cv_discrete(1.0, 3)[0], W, jacobians(agents, target, adjacency))
    assert result.conclusive
    assert result.detectable
    assert all(abs(z) < 1 for z in result.unobservable_eigenvalues)
    assert all(rank == 6 for rank in result.agent_ranks)


@given(scenes(min_agents=4, max_agents=6))
def test_complete_graph_with_uniform_weights_refutes_the_rank_sum(scene) -> None:
    """W = 11ᵀ/N is singular: every z ⊗ [0; q] with z ⟂ 1 is unobservable (mode 0)."""
    agents, target = scene
    n = len(agents)
    adjacency = ~np.eye(n, dtype=bool)
    result = analyze_network(
        cv_discrete(1.0, 3)[0], uniform_weights(adjacency), jacobians(agents, target, adjacency)
    )
    assert result.conclusive
    assert result.rank_sum == 6 * n
    assert result.network_rank == 6 * n - 3 * (n - 1)
    assert not result.rank_sum_claim_holds
    assert not result.observable and result.detectable
    assert result.unobservable_eigenvalues == [0j] * (3 * (n - 1))


@given(scenes(min_agents=5, max_agents=6))
def test_star_with_metropolis_weights_hides_a_leaf_difference(scene) -> None:
    """Leaves of a star share the eigenvalue 1 − 1/N of W (repeated for ≥ 3 leaves); the
    eigenvector e_a − e_b sees only two TDOA rows, so a direction is unobservable but stable."""
    agents, target = scene
    n = len(agents)
    adjacency = adjacency_from_edges(n, np.array([[0, j] for j in range(1, n)]))
    W = metropolis_weights(adjacency)
    result = analyze_network(cv_discrete(1.0, 3)[0], W, jacobians(agents, target, adjacency))
    assert result.conclusive
    assert result.detectable and not result.observable
    assert any(abs(z - (1 - 1 / n)) < 1e-9 for z in result.unobservable_eigenvalues)


def test_small_component_is_not_detectable() -> None:
    """Two components of 2 agents: the consensus mode 1 hides a position direction in each."""
    agents = np.array([[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]], dtype=float)
    target = np.array([17.0, -5, -15])
    adjacency = adjacency_from_edges(4, np.array([[0, 1], [2, 3]]))
    result = analyze_network(
        cv_discrete(1.0, 3)[0], metropolis_weights(adjacency), jacobians(agents, target, adjacency)
    )
    assert result.conclusive and not result.detectable and not result.observable
    assert sum(1 for z in result.unobservable_eigenvalues if z == 1) == 8


def test_isolated_agent_with_no_rows_is_accepted() -> None:
    A, _ = cv_discrete(1.0, 2)
    H = [np.array([[1.0, 0, 0, 0]]), np.array([[-1.0, 0, 0, 0]]), np.zeros((0, 4))]
    W = np.array([[0.5, 0.5, 0], [0.5, 0.5, 0], [0, 0, 1.0]])
    WA, D_H = networked_pair(A, W, H)
    assert WA.shape == (12, 12) and D_H.shape == (2, 12)
    result = analyze_network(A, W, H)
    assert result.agent_ranks[2] == 0 and not result.detectable


def test_mismatched_shapes_raise() -> None:
    A, _ = cv_discrete(1.0, 3)
    with pytest.raises(ValueError, match="one Jacobian per agent"):
        networked_pair(A, np.eye(2), [np.zeros((1, 6))])


def test_staircase_on_a_textbook_pair() -> None:
    """Double integrator observed in position: observable; in velocity: position unobservable."""
    F = np.array([[1.0, 1.0], [0.0, 1.0]])
    assert unobservable_subspace(F, np.array([[1.0, 0.0]]))[0].shape == (2, 0)
    basis, _ = unobservable_subspace(F, np.array([[0.0, 1.0]]))
    np.testing.assert_allclose(np.abs(basis[:, 0]), [1.0, 0.0], atol=1e-12)


def test_path_of_four_is_observable_like_fig43_case_d() -> None:
    agents = np.array([[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]], dtype=float)
    adjacency = adjacency_from_edges(4, np.array([[0, 1], [1, 2], [2, 3]]))
    assert nx.is_connected(nx.from_numpy_array(adjacency.astype(int)))
    result = analyze_network(
        cv_discrete(1.0, 3)[0],
        metropolis_weights(adjacency),
        jacobians(agents, np.array([17.0, -5, -15]), adjacency),
    )
    assert result.observable and result.rank_sum_claim_holds and result.conclusive


@given(st.integers(3, 5), st.data())
def test_floating_analysis_agrees_with_exact_rank_on_rational_instances(n, data) -> None:
    """Same instance both ways: integer TDOA rows, exact Metropolis W, T = 1."""
    adjacency = data.draw(connected_graphs(n))
    W = exact_weights(adjacency, data.draw(st.sampled_from(["metropolis", "uniform"])))
    dim = data.draw(st.sampled_from([2, 3]))
    vectors = st.lists(st.integers(-9, 9), min_size=dim, max_size=dim)
    edge_vector = {}
    rows = []
    for r in range(n):
        agent_rows = []
        for s in np.flatnonzero(adjacency[r]):
            key = (min(r, int(s)), max(r, int(s)))
            if key not in edge_vector:
                edge_vector[key] = data.draw(vectors)
            agent_rows.append(edge_vector[key] if r < s else [-x for x in edge_vector[key]])
        rows.append(agent_rows)
    exact = exact_network_matrix(rows, W, dim, Fraction(1))
    H = [np.array([[*row, *[0] * dim] for row in agent], dtype=float) for agent in rows]
    W_float = np.array([[float(x) for x in row] for row in W])
    result = analyze_network(cv_discrete(1.0, dim)[0], W_float, H)
    assume(result.conclusive)
    assert result.network_rank == exact_rank(exact)
    blocks = [
        exact_rank([line[i * 2 * dim : (i + 1) * 2 * dim] for line in exact]) for i in range(n)
    ]
    assert result.agent_ranks == blocks


@given(st.integers(4, 6), st.data())
def test_generic_rank_by_random_evaluation_matches_a_random_float_instance(n, data) -> None:
    """Exact generic rank (random rational point) = floating rank at an independent random
    geometry (almost surely generic), when the latter is conclusive."""
    adjacency = data.draw(connected_graphs(n))
    W = exact_weights(adjacency, "metropolis")
    generic = network_generic_rank(adjacency, W, seed=data.draw(st.integers(0, 1000)))
    rng = np.random.default_rng(data.draw(st.integers(0, 1000)))
    units = rng.normal(size=(n, 3))
    units /= np.linalg.norm(units, axis=1, keepdims=True)
    H = [
        np.array([np.r_[units[r] - units[s], np.zeros(3)] for s in np.flatnonzero(adjacency[r])])
        for r in range(n)
    ]
    W_float = np.array([[float(x) for x in row] for row in W])
    result = analyze_network(cv_discrete(1.0, 3)[0], W_float, H)
    assume(result.conclusive)
    assert result.network_rank == generic.network_rank
    assert result.agent_ranks == generic.agent_ranks


@st.composite
def any_graphs(draw, n: int):
    """Adjacency of an arbitrary undirected graph on ``n`` nodes (possibly disconnected)."""
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    edges = draw(st.lists(st.sampled_from(pairs), unique=True, max_size=2 * n))
    return adjacency_from_edges(n, np.array(edges, dtype=int).reshape(-1, 2))


@given(scenes(min_agents=4, max_agents=7), st.data())
def test_block_column_rank_is_twice_the_stacked_rank_of_the_component(scene, data) -> None:
    """docs/theory/tdoa-observability.md, Theorem 4(a): rank O_i = 2·rank [Λ_m]_{m ∈ R(i)}."""
    agents, target = scene
    adjacency = data.draw(any_graphs(len(agents)))
    H = jacobians(agents, target, adjacency)
    W = data.draw(st.sampled_from([metropolis_weights, uniform_weights]))(adjacency)
    result = analyze_network(cv_discrete(1.0, 3)[0], W, H)
    for part in nx.connected_components(nx.from_numpy_array(adjacency.astype(int))):
        stacked = np.vstack([H[m][:, :3] for m in part])
        rank = numeric_rank(stacked) if stacked.size else None
        assume(rank is None or rank.conclusive())
        for i in part:
            assert result.agent_ranks[i] == 2 * (rank.rank if rank else 0)


@given(scenes(min_agents=4, max_agents=7), st.data())
def test_detectable_iff_every_component_has_full_stacked_rank(scene, data) -> None:
    """Theorem 4(c): for undirected graphs the pair is detectable iff each component's stacked
    Jacobian has rank 3 (components of < 4 agents never do)."""
    agents, target = scene
    adjacency = data.draw(any_graphs(len(agents)))
    H = jacobians(agents, target, adjacency)
    W = data.draw(st.sampled_from([metropolis_weights, uniform_weights]))(adjacency)
    result = analyze_network(cv_discrete(1.0, 3)[0], W, H)
    assume(result.conclusive)
    full = []
    for part in nx.connected_components(nx.from_numpy_array(adjacency.astype(int))):
        stacked = np.vstack([H[m][:, :3] for m in part])
        rank = numeric_rank(stacked) if stacked.size else None
        assume(rank is None or rank.conclusive())
        full.append(rank is not None and rank.rank == 3)
    assert result.detectable == all(full)


@pytest.mark.parametrize(
    ("w_diag", "seen", "detectable", "conclusive"),
    [
        ((2.0, 0.5), (False, False), False, True),  # unstable unobservable mode
        ((2.0, 0.5), (True, False), True, True),  # only the stable mode is hidden
        ((1.0, 0.5), (False, True), False, True),  # marginal mode exactly on the circle
        ((1.0 - 5e-7, 0.5), (False, True), False, False),  # inside the tolerance band
        ((1.0 - 1e-3, 0.5), (False, True), True, True),  # clearly stable
    ],
)
def test_detectability_against_the_unit_circle(w_diag, seen, detectable, conclusive) -> None:
    """Modes |μ| ≥ 1 − unit_circle_tol hidden from the outputs make the pair undetectable; a
    mode within a factor unit_circle_factor of the tolerance is reported inconclusive."""
    A = np.array([[1.0]])
    H = [np.array([[1.0]]) if s else np.zeros((0, 1)) for s in seen]
    result = analyze_network(A, np.diag(w_diag), H)
    assert result.detectable is detectable
    assert result.conclusive is conclusive
    assert len(result.unobservable_eigenvalues) == sum(not s for s in seen)
