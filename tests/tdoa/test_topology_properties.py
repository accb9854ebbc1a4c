"""Properties the verdicts must have whatever the scene: invariance under relabelling, rigid motion
and scaling; monotonicity in the edges; small components never localize (seed 000 Thm 4.2.3)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st
from topology_strategies import edge_lists, scenes, spec_of

from theory.core.exact import exact_decimal
from theory.tdoa.observability.topology import analyze_topology
from theory.tdoa.strategies import rational_rotations, similarity_image


def verdicts(result):
    return [
        (a.observable, a.localizes, a.heuristic_4_noncoplanar, a.mirror_ambiguous, a.rank)
        for a in result.agents
    ]


@st.composite
def scenes_maybe_flat(draw):
    """Scenes, half of them with every agent in the plane z = 0 (or on the line y = 0 in 2-D)."""
    agents, target = draw(scenes(max_agents=6))
    if draw(st.booleans()):
        agents = agents.copy()
        agents[:, -1] = 0.0
        gaps = np.linalg.norm(agents[:, None] - agents[None], axis=-1) + np.eye(len(agents)) * 1e9
        assume(gaps.min() > 1.0 and np.linalg.norm(agents - target, axis=1).min() > 1.0)
    return agents, target


FACTORS = tuple(Fraction(x) for x in ("0.01", "0.2", "1", "2.5", "4", "100"))


def exactly_moved(points, rotation, factor, shift):
    """``factor · R p + shift`` as floats that read back as the exact rationals (else reject)."""
    image = similarity_image(points, rotation, factor, shift)
    floats = np.array([[float(x) for x in row] for row in image])
    assume(
        all(
            exact_decimal(f) == x
            for f, x in zip(floats.ravel(), (x for row in image for x in row), strict=True)
        )
    )
    return floats


@given(scenes_maybe_flat(), st.data(), st.sampled_from(FACTORS))
def test_rigid_motion_and_scaling_leave_verdicts_unchanged(scene, data, factor) -> None:
    """Translating, rotating (a rational rotation: exactly orthogonal) and scaling all positions
    keeps every verdict, inconclusive ones included: the decisions are exact on the rationals,
    and the float singular values only scale (relative thresholds)."""
    agents, target = scene
    edges = data.draw(edge_lists(len(agents)))
    dim = agents.shape[1]
    R = data.draw(rational_rotations(dim=dim))
    shift = [
        Fraction(v) for v in data.draw(st.lists(st.integers(-50, 50), min_size=dim, max_size=dim))
    ]
    before = analyze_topology(spec_of(agents, target, edges))
    moved = analyze_topology(
        spec_of(
            exactly_moved(agents, R, factor, shift),
            exactly_moved([target], R, factor, shift)[0],
            edges,
        )
    )
    assert verdicts(moved) == verdicts(before)
    assert moved.network.detectable == before.network.detectable
    assert moved.conclusive == before.conclusive


@given(scenes(max_agents=6), st.data())
def test_adding_an_edge_never_removes_observability(scene, data) -> None:
    agents, target = scene
    n = len(agents)
    edges = data.draw(edge_lists(n))
    missing = [[i, j] for i in range(1, n + 1) for j in range(i + 1, n + 1) if [i, j] not in edges]
    assume(missing)
    extra = data.draw(st.sampled_from(missing))
    before = analyze_topology(spec_of(agents, target, edges))
    after = analyze_topology(spec_of(agents, target, [*edges, extra]))
    assume(before.conclusive and after.conclusive)
    for old, new in zip(before.agents, after.agents, strict=True):
        assert new.rank >= old.rank
        assert new.localizes or not old.localizes
    assert after.network.detectable or not before.network.detectable


@given(scenes(max_agents=7), st.data())
def test_components_smaller_than_d_plus_1_never_localize(scene, data) -> None:
    agents, target = scene
    dim = agents.shape[1]
    result = analyze_topology(spec_of(agents, target, data.draw(edge_lists(len(agents)))))
    sizes = {}
    for agent in result.agents:
        sizes[agent.component] = sizes.get(agent.component, 0) + 1
    for agent in result.agents:
        if sizes[agent.component] < dim + 1:
            assert not agent.observable and not agent.localizes
            assert agent.rank <= 2 * (sizes[agent.component] - 1)
            assert not agent.heuristic_4_noncoplanar
