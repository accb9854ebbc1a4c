"""The certified displacement margin of TDOA observability (issue 25 item 3, ``docs/design.md``).

A certified radius ρ never contains a rank loss: displacements of every point by less than ρ —
random ones, and the witness displacement scaled down to below ρ — keep every agent's stacked
Jacobian of full rank, decided exactly (:func:`exact_direction_rank` on the displaced rational
points, independent of the certificate's inequality); the witness displacement of size ρ̄ ≥ ρ
loses rank exactly; ρ = 0 exactly on the degenerate bundled geometries.
"""

from __future__ import annotations

import copy
import json
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from proofs_check import MalformedError, check_certificate
from proofs_check.parse import loads
from theory.kinds import load_case, parse_case
from theory.tdoa.geometry.exact import exact_direction_rank
from theory.tdoa.geometry.margin import scenes, tdoa_margin
from theory.tdoa.observability.topology import analyze_topology

TDOA_CASES = [
    "coplanar-agents-observable",
    "fig43-case-a",
    "seed000-sec44-ring",
    "topology-2d-collinear-mirror",
    "topology-coplanar-mirror",
    "seed002-topology-a",
    "topology-second-solution",
]


def verdict(cert: dict) -> str:
    try:
        return "valid" if check_certificate(loads(json.dumps(cert))).valid else "invalid"
    except MalformedError:
        return "malformed"


@st.composite
def connected_scenes(draw: st.DrawFn) -> dict:
    """A static tdoa case: ``d + 1`` to ``d + 3`` agents (3 decimals) around a target, on a
    random connected edge set (a path plus random chords)."""
    dim = draw(st.sampled_from([2, 3]))
    n = draw(st.integers(dim + 1, dim + 3))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    target = rng.uniform(-10, 10, dim).round(3)
    directions = rng.standard_normal((n, dim))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    agents = (target + directions * rng.uniform(5, 20, (n, 1))).round(3)
    order = rng.permutation(n)
    edges = {tuple(sorted((int(order[k]), int(order[k + 1])))) for k in range(n - 1)}
    edges |= {tuple(sorted(map(int, rng.choice(n, 2, replace=False)))) for _ in range(n // 2)}
    block = {"T": 1.0, "agents": agents.tolist(), "target": target.tolist()}
    block["edges"] = [[i + 1, j + 1] for i, j in sorted(edges)]
    return {"name": "scene", "kind": "tdoa", "tdoa": block}


def full_rank_after(case, moves: list[np.ndarray]) -> bool:
    """Every agent keeps rank d after moving the target by ``moves[0]`` and agent j by
    ``moves[j + 1]`` (exact: floats read as their binary values; the graph is connected)."""
    scene = scenes(case.spec)[0]
    target = [x + Fraction(float(m)) for x, m in zip(scene.exact_target, moves[0], strict=True)]
    agents = [
        [x + Fraction(float(m)) for x, m in zip(point, move, strict=True)]
        for point, move in zip(scene.exact_agents, moves[1:], strict=True)
    ]
    return exact_direction_rank(target, agents) == scene.dim


def inside(moves: list[np.ndarray], radius: Fraction) -> bool:
    return all(sum(Fraction(float(x)) ** 2 for x in m) < radius**2 for m in moves)


@settings(max_examples=15)
@given(connected_scenes(), st.integers(0, 2**32 - 1))
def test_no_rank_loss_inside_the_certified_radius(data: dict, seed: int) -> None:
    case = parse_case(data)
    margin = tdoa_margin(case, seed=0)
    if margin.verdict is not True:
        return
    rho = margin.radius
    assert margin.upper_bound is None or float(rho) <= margin.upper_bound
    rng = np.random.default_rng(seed)
    points = 1 + case.spec.n_agents
    trials = []
    for _ in range(20):
        v = rng.standard_normal((points, case.spec.dim))
        v *= rng.uniform(0.5, 1.0, (points, 1)) / np.linalg.norm(v, axis=1, keepdims=True)
        trials.append(list(v * float(rho) * (1 - 1e-9)))
    if margin.witness is not None and margin.witness.size > 0:  # the witness scaled below ρ
        shrink = float(rho) / margin.witness.size * (1 - 1e-9)
        trials.append([np.array(m) * shrink for m in margin.witness.moves])
    for moves in trials:
        assert inside(moves, rho)
        assert full_rank_after(case, moves)


@settings(max_examples=15)
@given(connected_scenes())
def test_the_witness_loses_rank_exactly_at_its_size(data: dict) -> None:
    case = parse_case(data)
    margin = tdoa_margin(case, seed=0)
    if margin.witness is None:
        return
    w = margin.witness
    scene = scenes(case.spec)[0]
    before = [scene.exact_target, *scene.exact_agents]
    after = [list(w.target), *(list(a) for a in w.agents)]
    largest = max(
        sum((y - x) ** 2 for x, y in zip(a, b, strict=True))
        for a, b in zip(before, after, strict=True)
    )
    assert float(largest) ** 0.5 <= w.size * (1 + 1e-9)
    assert exact_direction_rank(after[0], after[1:]) < scene.dim  # connected: one receivers set
    assert float(margin.radius) <= w.size


@settings(max_examples=10)
@given(connected_scenes())
def test_margin_certificates_check_and_a_radius_past_the_witness_is_refused(data: dict) -> None:
    """Past ``ρ̄`` the claim is false (the witness is a smaller displacement that loses rank):
    the checker must refuse a radius just beyond it."""
    case = parse_case(data)
    margin = tdoa_margin(case, seed=0)
    for cert in margin.certificates:
        assert verdict(cert) == "valid"
        if margin.upper_bound is not None:
            tampered = copy.deepcopy(cert)
            past = Fraction(margin.upper_bound) * (1 + Fraction(1, 10**9))
            tampered["claim"]["radius"] = str(past)
            assert verdict(tampered) == "invalid"


@pytest.mark.parametrize(
    "name", ["cone-agents-unobservable", "topology-cone-unobservable", "topology-2d-same-ray"]
)
def test_degenerate_geometries_have_margin_zero_exactly(name: str) -> None:
    margin = tdoa_margin(load_case(name))
    assert margin.radius == 0 and margin.exact and margin.verdict is False
    assert margin.upper_bound == 0 and margin.witness.mechanism == "none"
    assert all(a.degenerate for a in margin.per_agent)


@pytest.mark.parametrize("name", TDOA_CASES)
def test_bundled_cases_bracket_the_margin(name: str) -> None:
    margin = tdoa_margin(load_case(name))
    assert margin.verdict is True and 0 < margin.radius
    assert float(margin.radius) <= margin.upper_bound < 5 * float(margin.radius)
    assert all(verdict(c) == "valid" for c in margin.certificates)


@pytest.mark.parametrize(
    "name", ["pf-tdoa-topology-a", "topology-directed-chain", "seed002-fig32-split", "fig43-case-b"]
)
def test_degenerate_agents_are_exactly_the_unobservable_ones(name: str) -> None:
    """Per agent, ``degenerate`` is the exact verdict of ``trackcert topology``."""
    case = load_case(name)
    margin = tdoa_margin(case, search=False)
    observable = [a.observable for a in analyze_topology(case.spec, 0).agents]
    assert [not a.degenerate for a in margin.per_agent] == observable
    assert all((a.radius > 0) == ok for a, ok in zip(margin.per_agent, observable, strict=True))


def test_distance_rule_margin_counts_links_that_may_break() -> None:
    """Under ``comm_range`` the certificates list only links at most ``R − 2ρ`` long, and the
    margin is the least over the 30 steps."""
    case = load_case("topology-distance-rule-21")
    margin = tdoa_margin(case)
    assert margin.verdict is True and len(margin.certificates) >= case.spec.steps
    for cert in margin.certificates:
        assert cert["data"]["comm_range"] == "21"
        assert verdict(cert) == "valid"
    tampered = copy.deepcopy(margin.certificates[0])
    tampered["data"]["comm_range"] = "1"  # no listed link survives
    assert verdict(tampered) == "invalid"


def test_claiming_an_unobservable_agent_is_refused() -> None:
    margin = tdoa_margin(load_case("pf-tdoa-topology-a"), search=False)
    cert = copy.deepcopy(margin.certificates[0])
    cert["claim"]["agents"] = [*cert["claim"]["agents"], 4]
    assert verdict(cert) == "invalid"
    cert["claim"]["radius"] = "0"
    assert verdict(cert) == "malformed"


def test_moving_the_data_onto_the_cone_is_refused() -> None:
    """The cone case's agents with the ring's witness numbers: the directions no longer match."""
    good = tdoa_margin(load_case("fig43-case-a")).certificates[0]
    cone = load_case("cone-agents-unobservable").spec
    tampered = copy.deepcopy(good)
    tampered["data"]["agents"] = [
        [str(Fraction(str(x))) for x in p] for p in cone.agents[0].tolist()
    ]
    tampered["data"]["target"] = [str(Fraction(str(x))) for x in cone.target[0].tolist()]
    assert verdict(tampered) == "invalid"


def test_the_covering_work_is_bounded_before_the_searches(monkeypatch) -> None:
    """Each covered agent costs the checker a search of the graph (agents + 2 links): a
    certificate asking for more than MAX_WORK of them is refused (exit 2), not searched."""
    import proofs_check.observability as observability

    (cert, *_) = tdoa_margin(load_case("seed000-sec44-ring")).certificates
    covers = sum(len(s["covers"]) for s in cert["witness"]["sets"])
    per_search = len(cert["data"]["agents"]) + 2 * len(cert["data"]["links"])
    monkeypatch.setattr(observability, "MAX_WORK", covers * per_search)
    assert verdict(cert) == "valid"
    monkeypatch.setattr(observability, "MAX_WORK", covers * per_search - 1)
    assert verdict(cert) == "malformed"
