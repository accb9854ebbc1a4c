"""``generic-rank`` certificates of TDOA network observability (seed 000 eqs. (4.36)–(4.37))."""

from __future__ import annotations

import copy
import dataclasses
import json
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from proofs_check import MalformedError, check_certificate
from theory.core.exact import RationalizationError, rational_unit_vector
from theory.core.observability import numeric_rank
from theory.core.sparse_weights import SparseWeights
from theory.kinds import load_case, parse_case
from theory.registry import get_claim
from theory.tdoa.model import neighbour_lists
from theory.tdoa.observability.certificates import (
    generic_rank_certificates,
    network_observability,
    scene_weights,
)

CASE = Path(__file__).resolve().parents[2] / "cases" / "fig43-case-d.yaml"


@st.composite
def tdoa_scenes(draw, *, max_agents: int = 4):
    """Random static scenes: agents in a box, a target outside, a random connected edge set."""
    dim = draw(st.sampled_from([2, 3]))
    n = draw(st.integers(2, max_agents))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    agents = rng.uniform(-10, 10, (n, dim)).round(3)
    target = (rng.uniform(-10, 10, dim) + 25).round(3)
    order = rng.permutation(n)
    edges = {tuple(sorted((int(order[k]), int(order[k + 1])))) for k in range(n - 1)}
    edges |= {tuple(sorted(map(int, rng.choice(n, 2, replace=False)))) for _ in range(n // 2)}
    block = {
        "T": float(draw(st.sampled_from([0.5, 1.0, 2.0]))),
        "agents": agents.tolist(),
        "target": target.tolist(),
        "edges": [[i + 1, j + 1] for i, j in sorted(edges)],
        "weights": draw(st.sampled_from(["metropolis", "uniform"])),
    }
    return parse_case({"name": "scene", "kind": "tdoa", "tdoa": block}).spec


@settings(max_examples=12)
@given(tdoa_scenes(), st.integers(0, 10))
def test_round_trip_and_the_certified_rank_is_the_generic_one(spec, seed) -> None:
    """Each certificate checks; its rank equals the float rank at an independent random point
    (compared only when that float rank clears its tolerance by the default factor)."""
    certs = generic_rank_certificates(spec, seed=seed)
    probe = np.random.default_rng(seed + 1000).standard_normal((spec.n_agents, spec.dim))
    probe /= np.linalg.norm(probe, axis=1, keepdims=True)
    W = np.array(scene_weights(spec), dtype=float)
    O = network_observability(probe, neighbour_lists(spec.hears[0]), W, spec.T)
    width = 2 * spec.dim
    for cert in certs:
        assert check_certificate(json.loads(json.dumps(cert))).valid
        agent = cert["claim"]["agent"]
        cols = slice(None) if agent == 0 else slice((agent - 1) * width, agent * width)
        probe_rank = numeric_rank(O[:, cols])
        if probe_rank.conclusive():
            assert cert["claim"]["rank_at_least"] == probe_rank.rank


def test_exact_weights_are_the_design_rules() -> None:
    spec = load_case(CASE).spec
    W = scene_weights(spec)
    assert np.allclose(np.array(W, dtype=float), spec.weights[0], atol=1e-15)
    assert W[0][:2] == [Fraction(2, 3), Fraction(1, 3)]
    assert all(sum(row) == 1 for row in W)


def test_fig43_case_d_is_generically_observable() -> None:
    """Seed 000 Fig. 4.3 (d): a path of 4 agents; O (24 columns) has generic rank 24 and every
    agent's block column generic rank 6."""
    (result,) = get_claim("seed000.eq4.36.certified").run(load_case(CASE))
    assert result.evidence["ranks_at_least"] == {0: 24, 1: 6, 2: 6, 3: 6, 4: 6}
    assert result.status == "verified" and result.evidence["steps"] == [1]
    assert "at least 24 of 24" in result.message and "at least 6, 6, 6, 6" in result.message


def test_a_time_varying_scene_is_certified_once_per_network() -> None:
    """Seed 000 Cor. 4.2.4: each distinct network along the trajectory gets its certificates;
    together they cover every step, and each checks exactly."""
    spec = load_case("topology-distance-rule-split").spec
    groups = spec.networks()
    assert sorted(k for steps in groups for k in steps) == list(range(spec.steps))
    certs = generic_rank_certificates(spec)
    covered = {tuple(c["produced_by"]["steps"]) for c in certs}
    assert covered == {tuple(k + 1 for k in steps) for steps in groups}
    assert all(check_certificate(json.loads(json.dumps(c))).valid for c in certs)
    results = get_claim("seed000.eq4.36.certified").run(load_case("topology-distance-rule-split"))
    assert len(results) == len(groups) and {r.status for r in results} == {"verified"}
    for result, steps in zip(results, groups, strict=True):
        assert result.evidence["steps"] == [k + 1 for k in steps]
        assert "of the trajectory" in result.message


def test_network_steps_group_equal_networks() -> None:
    spec = load_case(CASE).spec
    repeated = dataclasses.replace(
        spec,
        agents=np.concatenate([spec.agents, spec.agents + 1.0, spec.agents]),
        target=np.concatenate([spec.target] * 3),
        links=(
            spec.links[0],
            SparseWeights.named(4, *np.nonzero(~spec.hears[0] & ~np.eye(4, dtype=bool)), "uniform"),
            spec.links[0],
        ),
    )
    assert repeated.networks() == [(0, 2), (1,)]


def _leaves(value, path=()):
    if isinstance(value, dict):
        for key, item in value.items():
            if key not in ("statement", "produced_by", "source", "case"):
                yield from _leaves(item, (*path, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from _leaves(item, (*path, index))
    else:
        yield path, value


def _rejected(cert: dict) -> bool:
    try:
        return not check_certificate(cert).valid
    except MalformedError:
        return True


def test_changing_any_number_of_a_generic_rank_certificate_is_rejected() -> None:
    """Directions, weights, T, neighbours, rows, columns, rank, agent and the stated minor."""
    cert = generic_rank_certificates(load_case(CASE).spec)[1]
    survivors = []
    for path, value in _leaves(cert):
        tampered = copy.deepcopy(cert)
        node = tampered
        for key in path[:-1]:
            node = node[key]
        if path[0] not in ("claim", "data", "witness") or path == ("data", "model"):
            continue
        node[path[-1]] = value + 1 if isinstance(value, int) else str(Fraction(value) + 1)
        if not _rejected(tampered):
            survivors.append(path)
    assert survivors == []


def test_rational_unit_vectors_are_exactly_unit_and_close() -> None:
    rng = np.random.default_rng(3)
    for _ in range(50):
        u = rng.standard_normal(rng.integers(2, 4))
        u /= np.linalg.norm(u)
        q = rational_unit_vector(u, 30)
        assert sum(x * x for x in q) == 1
        assert np.allclose(np.array(q, dtype=float), u, atol=1e-8)


def test_moving_agents_on_one_network_share_one_certificate_set() -> None:
    block = {
        "T": 1.0,
        "agents": [[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 1], [1, 0, 1], [0, 1, 1]]],
        "target": [5, 5, 5],
        "edges": [[1, 2], [2, 3]],
    }
    spec = parse_case({"name": "moving", "kind": "tdoa", "tdoa": block}).spec
    static = parse_case(
        {"name": "still", "kind": "tdoa", "tdoa": {**block, "agents": block["agents"][0]}}
    ).spec
    moving, still = generic_rank_certificates(spec), generic_rank_certificates(static)
    assert [c["produced_by"]["steps"] for c in moving] == [[1, 2]] * len(still)
    assert [c["witness"] for c in moving] == [c["witness"] for c in still]
    assert all(c["claim"]["statement"].endswith("at steps 1–2 of the trajectory") for c in moving)


def test_a_scene_without_tdoa_rows_gets_no_certificate() -> None:
    block = {"T": 1.0, "agents": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "target": [5, 5, 5]}
    block["edges"] = []
    spec = parse_case({"name": "mute", "kind": "tdoa", "tdoa": block}).spec
    with pytest.raises(RationalizationError, match="no TDOA rows"):
        generic_rank_certificates(spec)
