"""The topology checker against the definitions: O_i and the whole O of seed 000 eq. (4.36),
detectability, global uniqueness of the TDOA fix, and time-varying verdicts (Cor. 4.2.4)."""

from __future__ import annotations

import networkx as nx
import numpy as np
import pytest
import scipy.optimize
from hypothesis import assume, given
from hypothesis import strategies as st
from topology_strategies import edge_lists, scenes, spec_of

from theory.core.case_file import bundled_cases
from theory.core.network import adjacency_from_range
from theory.core.observability import numeric_rank
from theory.kinds import load_case
from theory.tdoa.geometry.uniqueness import tdoa_solutions
from theory.tdoa.model import cv_discrete, tdoa_jacobian, tdoa_measurement
from theory.tdoa.observability.network import agent_observability_blocks, analyze_network
from theory.tdoa.observability.topology import analyze_topology
from theory.tdoa.observability.trajectory import analyze_trajectory


def dense_blocks(spec, step=0):
    """The actual H_i of eq. (4.7) for every agent (independent of the checker's code path)."""
    positions, target, hears = spec.agents[step], spec.target[step], spec.hears[step]
    return [
        tdoa_jacobian(target, positions, i, list(np.flatnonzero(hears[i])))
        for i in range(spec.n_agents)
    ]


@given(scenes(max_agents=5), st.data(), st.booleans())
def test_rank_O_i_equals_the_block_column_of_the_full_matrix(scene, data, directed) -> None:
    """rank O_i = 2·rank G_{R(i)} (docs/topology.md) against O_i formed by eq. (4.36)."""
    agents, target = scene
    edges = data.draw(edge_lists(len(agents), directed=directed))
    spec = spec_of(agents, target, edges, directed=directed)
    result = analyze_topology(spec)
    assume(result.conclusive)
    A, _ = cv_discrete(spec.T, spec.dim)
    blocks = agent_observability_blocks(A, spec.weights[0], dense_blocks(spec))
    for agent, block in zip(result.agents, blocks, strict=True):
        reference = numeric_rank(block)
        assume(reference.conclusive())
        assert agent.rank == reference.rank


@given(scenes(max_agents=5), st.data(), st.sampled_from(["metropolis", "uniform"]))
def test_network_rank_and_detectability_match_the_dense_pair(scene, data, weights) -> None:
    """The spectral, per-component rank equals the staircase rank of the whole (W⊗A, D_H)."""
    agents, target = scene
    spec = spec_of(agents, target, data.draw(edge_lists(len(agents))), weights=weights)
    result = analyze_topology(spec)
    A, _ = cv_discrete(spec.T, spec.dim)
    dense = analyze_network(A, spec.weights[0], dense_blocks(spec))
    assume(result.conclusive and dense.conclusive)
    assume(result.network.margin >= 1e3)
    assert result.network.method.startswith("spectral")
    assert result.network.rank == dense.network_rank
    assert result.network.detectable == dense.detectable
    mine = sorted(round(z.real, 6) for z in result.network.unobservable_eigenvalues)
    theirs = sorted(round(z.real, 6) for z in dense.unobservable_eigenvalues)
    assert mine == theirs


@given(scenes(max_agents=5), st.data())
def test_directed_network_uses_the_dense_pair_and_detectability_agrees(scene, data) -> None:
    agents, target = scene
    edges = data.draw(edge_lists(len(agents), directed=True))
    spec = spec_of(agents, target, edges, directed=True)
    assume(not np.array_equal(spec.hears[0], spec.hears[0].T))
    result = analyze_topology(spec)
    A, _ = cv_discrete(spec.T, spec.dim)
    dense = analyze_network(A, spec.weights[0], dense_blocks(spec))
    assume(result.conclusive and dense.conclusive)
    assert result.information_flow.startswith("directed")
    assert result.network.detectable == dense.detectable
    assert result.network.rank == dense.network_rank


@given(scenes(max_agents=6), st.data())
def test_undirected_localizes_iff_observable_iff_component_rank(scene, data) -> None:
    agents, target = scene
    spec = spec_of(agents, target, data.draw(edge_lists(len(agents))))
    result = analyze_topology(spec)
    assume(result.conclusive)
    for agent in result.agents:
        assert agent.localizes == agent.observable
        members = [j - 1 for j, a in enumerate(result.agents, 1) if a.component == agent.component]
        assert set(agent.reach) == {j + 1 for j in members}
    assert result.network.detectable == all(a.observable for a in result.agents)


def test_directed_chain_localization_is_decided_by_the_closed_class() -> None:
    """Agent 1 hears nobody: no TDOA, so nobody downstream localizes although O_1 is full."""
    case = load_case("topology-directed-chain")
    result = analyze_topology(case.spec)
    assert [a.rank for a in result.agents] == [6, 6, 4, 2]
    assert not any(a.localizes for a in result.agents)
    assert result.network.detectable


@given(scenes(min_agents=2, max_agents=6))
def test_every_reported_second_solution_reproduces_the_tdoas(scene) -> None:
    agents, target = scene
    result = tdoa_solutions(agents, target)
    reference = tdoa_measurement(target, agents, 0, range(1, len(agents)))
    scale = np.abs(np.vstack([agents, target])).max()
    for point in result.solutions:
        other = tdoa_measurement(np.array(point), agents, 0, range(1, len(agents)))
        np.testing.assert_allclose(other, reference, atol=1e-6 * scale)
        assert np.linalg.norm(np.array(point) - target) > 1e-6 * scale


@given(scenes(min_agents=3, max_agents=4, dims=(2,)), st.integers(0, 2**32 - 1))
def test_multistart_search_finds_no_solution_the_algebra_missed_2d(scene, seed) -> None:
    """Cross-check: least squares from 24 seeded starts lands only on known solutions."""
    agents, target = scene
    result = tdoa_solutions(agents, target)
    assume(result.unique is not None and result.free_dims <= 1)
    units = (target - agents) / np.linalg.norm(target - agents, axis=1, keepdims=True)
    assume(numeric_rank(units[1:] - units[0]).rank == 2)
    known = [target, *map(np.array, result.solutions)]
    measured = tdoa_measurement(target, agents, 0, range(1, len(agents)))
    rng = np.random.default_rng(seed)
    for start in rng.uniform(-60, 60, size=(24, 2)):
        fit = scipy.optimize.least_squares(
            lambda p: tdoa_measurement(p, agents, 0, range(1, len(agents))) - measured,
            start,
            xtol=1e-14,
            ftol=1e-14,
            gtol=1e-14,
        )
        if np.max(np.abs(fit.fun)) < 1e-9:
            assert min(np.linalg.norm(fit.x - k) for k in known) < 1e-4


def test_mirror_and_second_solution_cases() -> None:
    mirror = analyze_topology(load_case("topology-coplanar-mirror").spec)
    assert all(a.observable and a.mirror_ambiguous for a in mirror.agents)
    np.testing.assert_allclose(mirror.agents[0].mirror_point, [3, 2, -5], atol=1e-12)
    np.testing.assert_allclose(mirror.agents[0].uniqueness.solutions, [[3, 2, -5]], atol=1e-9)
    second = analyze_topology(load_case("topology-second-solution").spec)
    assert all(a.observable and a.uniqueness.unique is False for a in second.agents)
    assert not any(a.mirror_ambiguous for a in second.agents)


@given(scenes(min_agents=5, max_agents=7, dims=(3,)))
def test_five_or_more_receivers_in_general_position_fix_the_target_uniquely(scene) -> None:
    agents, target = scene
    centred = agents - agents.mean(axis=0)
    assume(np.linalg.svd(centred, compute_uv=False)[-1] > 1.0)
    lifted = np.hstack([agents - agents[0], np.linalg.norm(target - agents, axis=1)[:, None]])
    assume(numeric_rank(lifted[1:]).rank == 4 and numeric_rank(lifted[1:]).margin > 1e6)
    assert tdoa_solutions(agents, target).unique is True


def test_time_varying_verdicts_follow_the_distance_graph() -> None:
    """Independent check of the split trajectory: an agent can localize at a step iff its
    distance-graph component has ≥ 4 agents (the geometry is non-degenerate throughout)."""
    case = load_case("topology-distance-rule-split")
    spec = case.spec
    result = analyze_trajectory(spec)
    expected_counts = np.zeros(spec.n_agents, dtype=int)
    first = None
    for k, step in enumerate(result.steps):
        graph = nx.from_numpy_array(adjacency_from_range(spec.agents[k], 21).astype(int))
        sizes = {i: len(c) for c in nx.connected_components(graph) for i in c}
        expected = [sizes[i] >= 4 for i in range(spec.n_agents)]
        assert [a.observable for a in step.agents] == expected
        expected_counts += ~np.array(expected)
        if first is None and not all(expected):
            first = k + 1
    assert result.first_failure_step == first
    assert list(result.unobservable_steps) == expected_counts.tolist()


def test_spectral_rank_reproduces_the_star_defect() -> None:
    """Fig. 4.3 (a): Metropolis W of a star is singular and has 3/4 twice (docs/topology.md)."""
    result = analyze_topology(load_case("fig43-case-a").spec)
    eigs = sorted(round(z.real, 12) for z in result.network.unobservable_eigenvalues)
    assert eigs == [0.0] * 3 + [0.75] * 6
    assert result.network.rank == 24 - len(eigs)


@pytest.mark.parametrize("tol", [1e-9, 1e-6])
def test_tolerances_are_echoed(tol) -> None:
    result = analyze_topology(load_case("fig43-case-d").spec, rank_tol=tol)
    assert result.tolerances["rank_tol"] == tol
    assert result.to_json()["tolerances"]["rank_tol"] == tol


def test_topologies_a_and_b_have_identical_verdicts() -> None:
    """Seed 002 §4.3.3: same nodes and target, different hub; the exact verdicts coincide."""
    a = analyze_topology(load_case("seed002-topology-a").spec)
    b = analyze_topology(load_case("seed002-topology-b").spec)

    def summary(result):
        return [
            (x.rank, x.localizes, x.mirror_ambiguous, x.uniqueness.unique) for x in result.agents
        ]

    assert summary(a) == summary(b)
    assert a.network.detectable == b.network.detectable


STATIC_UNDIRECTED = [
    name
    for name, path in bundled_cases().items()
    if (case := load_case(path)).kind == "tdoa" and case.spec.steps == 1 and not case.spec.directed
]


@pytest.mark.parametrize("name", STATIC_UNDIRECTED)
def test_spectral_rank_matches_the_dense_pair_on_every_bundled_case(name) -> None:
    """Bundled networks include repeated eigenvalues (rings, stars) and singular W."""
    spec = load_case(name).spec
    result = analyze_topology(spec)
    A, _ = cv_discrete(spec.T, spec.dim)
    dense = analyze_network(A, spec.weights[0], dense_blocks(spec))
    assert dense.conclusive and result.conclusive
    assert result.network.rank == dense.network_rank
    assert result.network.detectable == dense.detectable
