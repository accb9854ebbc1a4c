"""The fewest links or agents whose loss breaks TDOA observability (issue 25 item 4, tdoa half).

Checked against an independent exact oracle: connected components from networkx and the exact
affine rank of each component's directions (:func:`exact_direction_rank`). Removing the witness
set breaks observability; every smaller set (all of them, enumerated here) keeps it; the
``tdoa-loss-tolerance`` certificate checks, and claiming one more is refused.
"""

from __future__ import annotations

import copy
import json
from itertools import combinations

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from proofs_check import MalformedError, check_certificate
from proofs_check.observability import MAX_AGENTS
from proofs_check.parse import loads
from theory.kinds import load_case, parse_case
from theory.tdoa.design import _receiver_sets, tdoa_redundancy
from theory.tdoa.geometry.exact import exact_direction_rank, rational_points
from theory.tdoa.geometry.margin import scenes


def verdict(cert: dict) -> str:
    try:
        return "valid" if check_certificate(loads(json.dumps(cert))).valid else "invalid"
    except MalformedError:
        return "malformed"


def every_agent_observable(spec, removed: tuple, links: bool) -> bool:
    """The oracle: each remaining agent's component has directions of affine rank d."""
    n = spec.n_agents
    graph = nx.Graph()
    gone = set() if links else {j - 1 for j in removed}
    graph.add_nodes_from(i for i in range(n) if i not in gone)
    cut = {frozenset((a - 1, b - 1)) for a, b in removed} if links else set()
    for r, s in zip(*np.nonzero(spec.hears[0]), strict=True):
        if r < s and frozenset((r, s)) not in cut and not {r, s} & gone:
            graph.add_edge(int(r), int(s))
    target = rational_points([spec.target[0]])[0]
    points = rational_points(spec.agents[0])
    return all(
        exact_direction_rank(target, [points[j] for j in part]) == spec.dim
        for part in nx.connected_components(graph)
    )


@st.composite
def small_networks(draw: st.DrawFn) -> dict:
    """Up to 6 agents around a target on a random connected edge set of at most 8 links."""
    dim = draw(st.sampled_from([2, 3]))
    n = draw(st.integers(dim + 1, 6))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    target = rng.uniform(-10, 10, dim).round(2)
    agents = (target + rng.uniform(-15, 15, (n, dim))).round(2)
    order = rng.permutation(n)
    edges = {tuple(sorted((int(order[k]), int(order[k + 1])))) for k in range(n - 1)}
    for _ in range(draw(st.integers(0, 3))):
        edges.add(tuple(sorted(map(int, rng.choice(n, 2, replace=False)))))
    block = {"T": 1.0, "agents": agents.tolist(), "target": target.tolist()}
    block["edges"] = [[i + 1, j + 1] for i, j in sorted(edges)]
    return {"name": "net", "kind": "tdoa", "tdoa": block}


@settings(max_examples=20)
@given(small_networks(), st.booleans())
def test_witness_breaks_and_every_smaller_set_keeps(data: dict, links: bool) -> None:
    case = parse_case(data)
    answer = tdoa_redundancy(case, links=links)
    assert answer.exact and answer.k == answer.certified_below == len(answer.witness)
    assert not every_agent_observable(case.spec, answer.witness, links)
    pool = answer_pool(case.spec, links)
    for size in range(answer.k):
        for removed in combinations(pool, size):
            assert every_agent_observable(case.spec, removed, links)


def answer_pool(spec, links: bool) -> list:
    if not links:
        return list(range(1, spec.n_agents + 1))
    return [
        (int(s) + 1, int(r) + 1) for r, s in zip(*np.nonzero(spec.hears[0]), strict=True) if s < r
    ]


@settings(max_examples=15)
@given(small_networks(), st.booleans())
def test_loss_tolerance_certificates_check_and_one_more_is_refused(data: dict, links: bool) -> None:
    answer = tdoa_redundancy(parse_case(data), links=links)
    if answer.certified_below == 0:
        assert not answer.certificates
        return
    (cert,) = answer.certificates
    assert verdict(cert) == "valid"
    tampered = copy.deepcopy(cert)
    tampered["claim"]["fewer_than"] = answer.k + 1  # the witness set is among those enumerated
    assert verdict(tampered) == "invalid"


@pytest.mark.parametrize(
    ("name", "links", "k"),
    [
        ("seed000-sec44-ring", True, 2),
        ("seed000-sec44-ring", False, 2),
        ("fig43-case-a", True, 1),
        ("complete-uniform-singular-w", True, 3),
        ("complete-uniform-singular-w", False, 1),
        ("cone-agents-unobservable", True, 0),
        ("topology-directed-chain", True, 0),
        ("topology-distance-rule-21", True, 2),
        ("topology-distance-rule-split", False, 0),
    ],
)
def test_bundled_cases(name: str, links: bool, k: int) -> None:
    answer = tdoa_redundancy(load_case(name), links=links)
    assert (answer.k, answer.certified_below, answer.exact) == (k, k, True)
    assert answer.verdict is (k > 0)
    assert all(verdict(c) == "valid" for c in answer.certificates)


def test_past_the_budget_the_answer_is_a_bracket() -> None:
    """With room for the empty set only, the ring is certified below 1 and the witness isolates
    one agent (2 links): a bracket [1, 2], honestly labelled."""
    answer = tdoa_redundancy(load_case("seed000-sec44-ring"), links=True, max_subsets=1)
    assert (answer.certified_below, answer.k, answer.exact) == (1, 2, False)
    assert "bracket" in answer.note


@st.composite
def random_graph_scenes(draw: st.DrawFn) -> tuple:
    """A scene of 2–12 agents in 3-D on a random directed or undirected link set."""
    n = draw(st.integers(2, 12))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    directed = draw(st.booleans())
    pairs = (rng.random((n, n)) < draw(st.floats(0.05, 0.6))) & ~np.eye(n, dtype=bool)
    if not directed:
        pairs = np.triu(pairs | pairs.T)
    block = {"T": 1.0, "agents": rng.uniform(-9, 9, (n, 3)).round(1).tolist()}
    block |= {"target": [20.0, 0.0, 0.0], "directed": directed, "weights": "uniform"}
    block["edges"] = [[int(a) + 1, int(b) + 1] for a, b in zip(*np.nonzero(pairs), strict=True)]
    return scenes(parse_case({"name": "g", "kind": "tdoa", "tdoa": block}).spec)[0], rng


@settings(max_examples=40)
@given(random_graph_scenes())
def test_receiver_sets_of_a_removal_are_each_agents_receivers(drawn: tuple) -> None:
    """The enumeration's receivers (heard lists built once, one search per component on
    undirected links) are Scene.receivers' for every agent, after removing random links."""
    scene, rng = drawn
    kept = tuple(x for x in scene.links if rng.random() < 0.7)
    assert _receiver_sets(scene, kept) == [
        scene.receivers(i, kept) for i in range(len(scene.agents))
    ]


def ring_case(n: int) -> dict:
    """``n`` agents on a circle of radius 30 around the target (3-D, z alternating), each
    linked to the next: removing two links cuts off a path; every smaller loss keeps the ring."""
    angles = 2 * np.pi * np.arange(n) / n
    agents = np.stack([30 * np.cos(angles), 30 * np.sin(angles), 5.0 * (-1) ** np.arange(n)])
    edges = [[i + 1, (i + 1) % n + 1] for i in range(n)]
    block = {"T": 1.0, "agents": agents.T.round(3).tolist(), "target": [0.0, 0.0, 0.0]}
    return {"name": f"ring-{n}", "kind": "tdoa", "tdoa": block | {"edges": edges}}


def test_a_network_past_64_agents_is_certified() -> None:
    """70 agents: the certificate (70 points, 70 links) is checked, not refused for its size,
    and claiming one more link is refused."""
    answer = tdoa_redundancy(parse_case(ring_case(70)), links=True)
    assert (answer.k, answer.certified_below, answer.exact) == (2, 2, True)
    (cert,) = answer.certificates
    assert len(cert["data"]["agents"]) == 70 and verdict(cert) == "valid"
    tampered = copy.deepcopy(cert)
    tampered["claim"]["fewer_than"] = 3
    assert verdict(tampered) == "invalid"


def test_a_scene_past_the_checkers_agent_limit_is_malformed() -> None:
    """More than MAX_AGENTS points are refused before any arithmetic (exit 2)."""
    (cert,) = tdoa_redundancy(parse_case(ring_case(8)), links=True).certificates
    cert = copy.deepcopy(cert)
    cert["data"]["agents"] = [cert["data"]["agents"][0]] * (MAX_AGENTS + 1)
    assert verdict(cert) == "malformed"
