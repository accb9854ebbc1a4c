"""When the stacked TDOA Jacobian loses rank (docs/theory/tdoa-observability.md, Theorems 1–2),
with the properties of issue 2 item 7: small components never observable, general position is,
invariance under relabelling / rigid motion / scaling, edges never hurt, exact = floating."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp
from hypothesis import assume, given
from hypothesis import strategies as st

from theory.core.network import adjacency_from_edges, metropolis_weights
from theory.kinds import load_case
from theory.tdoa.geometry.directions import (
    analyze_geometry,
    direction_differences,
)
from theory.tdoa.geometry.exact import exact_direction_rank
from theory.tdoa.model import cv_discrete, tdoa_jacobian, unit_directions
from theory.tdoa.observability.network import analyze_network

SEPARATION = 2.0
"""Draws with two points closer than this (scene units) are rejected as near-degenerate."""
SIGMA_MARGIN = 0.02
"""Draws whose direction differences have σ_min (or the gap to a lower rank) below this are
rejected: near the cone set a floating verdict is not decidable, by design."""


@st.composite
def integer_scenes(draw, *, min_agents: int, max_agents: int, dim: int = 3):
    """``(target, agents)`` with integer coordinates in [-30, 30], pairwise separated."""
    n = draw(st.integers(min_agents, max_agents))
    coords = st.lists(st.integers(-30, 30), min_size=dim, max_size=dim)
    points = np.array(draw(st.lists(coords, min_size=n + 1, max_size=n + 1)), dtype=float)
    gaps = np.linalg.norm(points[:, None] - points[None], axis=-1) + np.eye(n + 1) * 1e9
    assume(gaps.min() > SEPARATION)
    return points[0], points[1:]


def well_conditioned(target: np.ndarray, agents: np.ndarray) -> bool:
    sv = np.linalg.svd(direction_differences(target, agents), compute_uv=False)
    rank = int(np.sum(sv > 1e-9 * sv[0]))
    return sv[rank - 1] > SIGMA_MARGIN and (rank == len(sv) or sv[rank] < 1e-12)


@st.composite
def rational_rotations(draw):
    """Rational orthogonal matrices by the Cayley transform of an integer skew matrix."""
    a, b, c = (draw(st.integers(-4, 4)) for _ in range(3))
    S = sp.Matrix([[0, -c, b], [c, 0, -a], [-b, a, 0]])
    Q = (sp.eye(3) - S) * (sp.eye(3) + S).inv()
    return [[Fraction(int(x.p), int(x.q)) for x in Q.row(i)] for i in range(3)]


def rational_unit(t: int, s: int) -> list[Fraction]:
    """Inverse stereographic projection of (t, s): a rational point of the unit sphere."""
    d = t * t + s * s + 1
    return [Fraction(2 * t, d), Fraction(2 * s, d), Fraction(t * t + s * s - 1, d)]


@given(integer_scenes(min_agents=1, max_agents=3))
def test_fewer_than_four_agents_never_observable(scene) -> None:
    target, agents = scene
    exact = exact_direction_rank(target.tolist(), agents.tolist())
    assert exact <= len(agents) - 1 < 3
    assert analyze_geometry(target, agents).full_rank is False


@given(integer_scenes(min_agents=4, max_agents=7))
def test_exact_and_floating_rank_agree_away_from_the_cone_set(scene) -> None:
    target, agents = scene
    assume(well_conditioned(target, agents))
    geometry = analyze_geometry(target, agents)
    assert geometry.conclusive
    assert geometry.rank == exact_direction_rank(target.tolist(), agents.tolist())


@given(integer_scenes(min_agents=4, max_agents=6), st.data())
def test_general_position_connected_set_is_observable_for_every_agent(scene, data) -> None:
    """Theorem 1 + 4a: any connected graph on a full-rank set gives every O_i rank 6."""
    target, agents = scene
    assume(well_conditioned(target, agents))
    assume(exact_direction_rank(target.tolist(), agents.tolist()) == 3)
    n = len(agents)
    edges = [(data.draw(st.integers(0, i - 1)), i) for i in range(1, n)]
    adjacency = adjacency_from_edges(n, np.array(edges))
    units = unit_directions(target, agents)
    pairs = np.argwhere(adjacency)
    stacked = units[pairs[:, 0]] - units[pairs[:, 1]]
    assert np.linalg.matrix_rank(stacked, tol=1e-9 * np.linalg.norm(stacked, 2)) == 3
    H = [tdoa_jacobian(target, agents, i, list(np.flatnonzero(adjacency[i]))) for i in range(n)]
    result = analyze_network(cv_discrete(1.0, 3)[0], metropolis_weights(adjacency), H)
    assert result.agent_ranks == [6] * n
    if result.conclusive:  # the whole-O staircase may be ill-conditioned; then it says so
        assert result.detectable


@given(
    integer_scenes(min_agents=4, max_agents=6),
    rational_rotations(),
    st.lists(st.integers(-50, 50), min_size=3, max_size=3),
    st.fractions(Fraction(1, 10), Fraction(10)),
    st.randoms(use_true_random=False),
)
def test_verdict_invariant_under_relabelling_rigid_motion_and_scaling(
    scene, Q, shift, scale, random
) -> None:
    target, agents = scene
    exact = exact_direction_rank(target.tolist(), agents.tolist())
    order = list(range(len(agents)))
    random.shuffle(order)

    def move(point):
        rotated = [sum(Q[i][j] * int(point[j]) for j in range(3)) for i in range(3)]
        return [scale * x + s for x, s in zip(rotated, shift, strict=True)]

    moved_agents = [move(agents[i]) for i in order]
    assert exact_direction_rank(move(target), moved_agents) == exact
    if well_conditioned(target, agents):
        as_float = np.array([[float(x) for x in a] for a in moved_agents])
        moved = analyze_geometry(np.array([float(x) for x in move(target)]), as_float)
        assert moved.rank == analyze_geometry(target, agents).rank == exact


@given(
    st.integers(-5, 5),
    st.integers(-5, 5),
    st.integers(2, 6),
    rational_rotations(),
    st.lists(
        st.tuples(st.integers(-6, 6), st.integers(1, 40)),
        min_size=4,
        max_size=7,
        unique_by=lambda ray: ray[0],
    ),
)
def test_agents_on_a_cone_with_apex_at_target_lose_rank(t, s, k, Q, rays) -> None:
    """Theorem 2: n·u_i = c for all i ⇒ rank 2, whether or not the agents are coplanar."""
    cos, sin = Fraction(2 * k, k * k + 1), Fraction(k * k - 1, k * k + 1)
    target = [Fraction(t), Fraction(s), Fraction(3)]
    agents = []
    for param, distance in rays:
        h = [Fraction(2 * param, param**2 + 1), Fraction(param**2 - 1, param**2 + 1)]
        local = [sin * h[0], sin * h[1], cos]
        u = [sum(Q[i][j] * local[j] for j in range(3)) for i in range(3)]
        agents.append([p - distance * x for p, x in zip(target, u, strict=True)])
    assert exact_direction_rank(target, agents) == 2
    geometry = analyze_geometry(
        np.array(target, dtype=float), np.array([[float(x) for x in a] for a in agents])
    )
    # floats of a rational cone are off it by rounding: rank-deficient, or full but inconclusive
    assert not (geometry.full_rank and geometry.conclusive)
    axis = np.array([float(Q[i][2]) for i in range(3)])
    assert abs(abs(np.dot(axis, geometry.cone_axis)) - 1) < 1e-9
    assert abs(geometry.cone_cos - float(cos)) < 1e-9


@given(integer_scenes(min_agents=4, max_agents=6), st.integers(1, 30))
def test_coplanar_agents_with_target_off_plane_are_mirror_ambiguous(scene, height) -> None:
    target, agents = scene
    agents = agents.copy()
    agents[:, 2] = 0.0
    target = np.array([target[0], target[1], float(height)])
    assume(len({tuple(a) for a in agents}) == len(agents))
    geometry = analyze_geometry(target, agents)
    assert geometry.agents_coplanar and geometry.mirror_ambiguous
    assert not geometry.heuristic_4_noncoplanar
    mirror = target * np.array([1, 1, -1])
    ranges = np.linalg.norm(agents - target, axis=1)
    np.testing.assert_allclose(ranges, np.linalg.norm(agents - mirror, axis=1), rtol=1e-12)


@given(integer_scenes(min_agents=4, max_agents=6), st.data())
def test_adding_an_edge_never_removes_agent_observability_or_detectability(scene, data) -> None:
    target, agents = scene
    assume(well_conditioned(target, agents))
    n = len(agents)
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    edges = data.draw(st.lists(st.sampled_from(pairs), min_size=1, unique=True))
    extra = data.draw(st.sampled_from(pairs))
    A = cv_discrete(1.0, 3)[0]

    def analyze(edge_list):
        adjacency = adjacency_from_edges(n, np.array(edge_list))
        H = [tdoa_jacobian(target, agents, i, list(np.flatnonzero(adjacency[i]))) for i in range(n)]
        return analyze_network(A, metropolis_weights(adjacency), H)

    before, after = analyze(edges), analyze([*edges, extra])
    assume(before.conclusive and after.conclusive)
    assert all(b <= a for b, a in zip(before.agent_ranks, after.agent_ranks, strict=True))
    assert after.detectable or not before.detectable


def test_planar_agents_on_two_rays_lose_rank_three_directions_do_not() -> None:
    target = np.array([0.0, 0.0])
    two_rays = np.array([[1.0, 1.0], [3.0, 3.0], [-2.0, 1.0], [-6.0, 3.0]])
    assert analyze_geometry(target, two_rays).rank == 1
    assert exact_direction_rank(target.tolist(), two_rays.tolist()) == 1
    three = np.array([[1.0, 1.0], [3.0, 3.0], [-2.0, 1.0], [0.0, -5.0]])
    assert analyze_geometry(target, three).rank == 2


def test_bundled_counterexamples_disagree_with_the_paper_both_ways() -> None:
    for name, heuristic, rank in [
        ("coplanar-agents-observable", False, 3),
        ("cone-agents-unobservable", True, 2),
    ]:
        spec = load_case(name).spec
        target, agents = spec.target[0], spec.agents[0]
        geometry = analyze_geometry(target, agents)
        assert geometry.heuristic_4_noncoplanar is heuristic
        assert geometry.full_rank is not heuristic
        assert exact_direction_rank(target.tolist(), agents.tolist()) == rank
