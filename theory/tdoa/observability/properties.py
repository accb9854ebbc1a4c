"""The falsifiable wordings of the observability claims (``trackcert falsify``).

**Geometry** (seed 000 Thm 4.2.3, §4.2.1): each example is a
:class:`~theory.tdoa.strategies.TdoaScene` whose agents form one connected path. A component
localizes the target iff its stacked position Jacobian (rows ``u_i − u_j``, eqs. (4.8)–(4.10))
has rank ``d``; examples whose rank decision is inside tolerance are not counterexamples.

**Rank sum** (after seed 000 eq. (4.36), seed 001 eq. (36)): ``rank O = Σ_i rank O_i`` is false
in general (singular ``W``, the Fig. 4.3 stars). True: ``rank O ≤ Σ rank O_i``, and the pair is
*detectable* iff every component's stacked Jacobian has full rank ``d``. Examples are 2-D or 3-D
scenes with weights of every kind (Metropolis, uniform, random, singular) on an undirected
network, connected or not; an inconclusive rank or unit-circle decision is never a
counterexample.

**Never wrong near a boundary**: scenes moved toward the boundaries where the verdicts of
:func:`~theory.tdoa.observability.topology.analyze_topology` change, at offsets
``±10⁻³, ±10⁻⁹, ±10⁻¹²`` and ``0``: ``plane`` (3-D, a 4th agent approaching the plane of three),
``collinear`` (2-D, a 3rd agent approaching the line of two), ``mirror`` (3-D, the target
approaching the plane of coplanar receivers), ``split`` (3-D, a bridging pair at the
communication range ± offset, strict ``<``); and ``invariance``: any of these translated, rotated
by a rational rotation and scaled keeps every verdict. Each asserts "correct or inconclusive":
the exactly decided fields (components, the heuristic, the mirror ambiguity) always equal the
truth, the ranks unless the result is inconclusive. The truth comes from an independent exact
computation here — Gaussian elimination in :class:`fractions.Fraction`, and for the rank of the
unit directions a rigorous ball-arithmetic evaluation (python-flint ``arb``) of each sum of
square roots against the algebraic lower bound a non-zero such sum must exceed — not the
square-class grouping of :mod:`~theory.tdoa.geometry.exact` that the library uses.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from itertools import combinations
from typing import Any

import flint
import numpy as np
from hypothesis import assume
from hypothesis import strategies as st

from theory.core.claims import Property
from theory.core.network import components, weights_support
from theory.core.observability import numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR, MIRROR_TOL, RANK_TOL
from theory.tdoa.case import parse_tdoa
from theory.tdoa.model import cv_discrete, tdoa_jacobian, tdoa_measurement, unit_directions
from theory.tdoa.observability.network import NetworkObservability, analyze_network
from theory.tdoa.observability.topology import TopologyResult, analyze_topology
from theory.tdoa.strategies import (
    WEIGHT_KINDS,
    TdoaScene,
    networks,
    rational_rotations,
    similarity_image,
    stochastic_weights,
    tdoa_scenes,
    weight_matrices,
)

__all__ = [
    "OFFSETS",
    "PROPERTIES",
    "BoundaryScene",
    "MovedScene",
    "WeightedScene",
    "analyze_weighted_scene",
    "boundary_scenes",
    "component_rank",
    "component_ranks",
    "invariant",
    "mirror_target",
    "moved_scenes",
    "never_wrong",
    "scene_block",
    "scene_case",
    "truth",
    "weighted_scene_case",
    "weighted_scenes",
]


def component_rank(scene: TdoaScene) -> tuple[int, bool]:
    """Rank of the stacked position Jacobian of all agents of ``scene``, and whether the
    decision is conclusive (every singular value clears the threshold by 10³)."""
    n, dim = scene.agents.shape
    jacobian = tdoa_jacobian(scene.target, scene.agents, 0, range(1, n))[:, :dim]
    result = numeric_rank(jacobian, rank_tol=RANK_TOL)
    return result.rank, result.conclusive(INCONCLUSIVE_FACTOR)


def _coplanar(points: np.ndarray) -> bool:
    centred = points - points.mean(axis=0)
    return numeric_rank(centred, rank_tol=RANK_TOL).rank < points.shape[1]


def _concyclic_directions(scene: TdoaScene) -> bool:
    """Whether some (a, c) ≠ 0 has u_i·a = c for all i: rank [U 1] < d + 1."""
    units = unit_directions(scene.target, scene.agents)
    augmented = np.hstack([units, np.ones((len(units), 1))])
    return numeric_rank(augmented, rank_tol=RANK_TOL).rank < units.shape[1] + 1


def mirror_target(scene: TdoaScene) -> np.ndarray:
    """``scene``'s target reflected through the plane that best fits its agents (least squares)."""
    centre = scene.agents.mean(axis=0)
    normal = np.linalg.svd(scene.agents - centre)[2][-1]
    return scene.target - 2 * np.dot(scene.target - centre, normal) * normal


def scene_case(scene: TdoaScene) -> dict[str, Any]:
    """A ready-to-run ``kind: tdoa`` case file reproducing ``scene`` (agents on a path)."""
    n, dim = scene.agents.shape
    rank, _ = component_rank(scene)
    return {
        "name": f"falsify-{scene.family}-{n}-agents",
        "source": "trackcert falsify (shrunk counterexample)",
        "kind": "tdoa",
        "tdoa": {
            "T": 1.0,
            "target": [float(v) for v in scene.target],
            "agents": [[float(v) for v in row] for row in scene.agents],
            "edges": [[i, i + 1] for i in range(1, n)],
            "weights": "metropolis",
        },
        "expect": {"observable": [rank == dim] * n},
    }


def _heuristic_paper(scene: TdoaScene) -> bool:
    rank, conclusive = component_rank(scene)
    enough = len(scene.agents) >= scene.agents.shape[1] + 1 and not _coplanar(scene.agents)
    return not conclusive or not enough or rank == scene.agents.shape[1]


def _heuristic_corrected(scene: TdoaScene) -> bool:
    rank, conclusive = component_rank(scene)
    return not conclusive or (rank == scene.agents.shape[1]) == (not _concyclic_directions(scene))


def _coplanar_paper(scene: TdoaScene) -> bool:
    rank, conclusive = component_rank(scene)
    return not conclusive or not _coplanar(scene.agents) or rank < scene.agents.shape[1]


def _coplanar_corrected(scene: TdoaScene) -> bool:
    if not _coplanar(scene.agents):
        return True
    n = len(scene.agents)
    here = tdoa_measurement(scene.target, scene.agents, 0, range(1, n))
    there = tdoa_measurement(mirror_target(scene), scene.agents, 0, range(1, n))
    scale = float(np.max(np.abs(scene.agents - scene.target)))
    return bool(np.max(np.abs(here - there)) <= MIRROR_TOL * scale)


SCENES_3D = st.one_of(
    tdoa_scenes(dim=3, family="general"),
    tdoa_scenes(dim=3, family="cone"),
    tdoa_scenes(dim=3, family="coplanar"),
    tdoa_scenes(dim=3, family="target-in-plane"),
)


PERIOD = 1.0
"""Ping period T of eq. (4.6) used for the target dynamics A (A is unipotent for every T)."""


@dataclass(frozen=True, eq=False)
class WeightedScene:
    """A TDOA scene with row-stochastic weights (positive diagonal) whose off-diagonal support is
    the undirected network; ``rule`` names them (``metropolis``, ``uniform``) or ``explicit``."""

    scene: TdoaScene
    weights: np.ndarray
    rule: str


@st.composite
def weighted_scenes(draw: st.DrawFn, *, max_agents: int = 5) -> WeightedScene:
    """General-position 2D or 3D scenes of 2 to ``max_agents`` receivers, with weights of a
    drawn kind on an undirected network (connected or not) of the same size."""
    dim = draw(st.sampled_from((2, 3)))
    scene = draw(tdoa_scenes(dim=dim, min_agents=2, max_agents=max_agents))
    n = len(scene.agents)
    kind = draw(st.sampled_from(WEIGHT_KINDS))
    W = draw(weight_matrices(min_agents=n, max_agents=n, kind=kind, connected=None))
    rule = kind if kind in ("metropolis", "uniform") else "explicit"
    return WeightedScene(scene, W, rule)


def _jacobians(example: WeightedScene) -> list[np.ndarray]:
    """Agent i's Jacobian H_i (eqs. (4.7)–(4.10)) over the agents it hears."""
    hears = weights_support(example.weights)
    target, agents = example.scene.target, example.scene.agents
    return [tdoa_jacobian(target, agents, i, np.flatnonzero(hears[i])) for i in range(len(agents))]


def analyze_weighted_scene(example: WeightedScene) -> NetworkObservability:
    """Rank of ``O``, ``rank O_i`` and detectability of ``(W ⊗ A, D_H)`` (seed 000 eq. (4.36))
    for ``example``."""
    dim = example.scene.agents.shape[1]
    A = cv_discrete(PERIOD, dim)[0]
    return analyze_network(A, example.weights, _jacobians(example))


def component_ranks(example: WeightedScene) -> list[tuple[int, bool]]:
    """(rank, conclusive) of each connected component's stacked position Jacobian in
    ``example``."""
    parts = components(weights_support(example.weights))
    target, agents = example.scene.target, example.scene.agents
    return [component_rank(TdoaScene(target, agents[part], "component")) for part in parts]


def weighted_scene_case(example: WeightedScene) -> dict[str, Any]:
    """A ready-to-run ``kind: tdoa`` case reproducing ``example`` (explicit weights unless they
    are Metropolis or uniform on the support), with the verdicts it should reproduce."""
    scene, W = example.scene, example.weights
    n, dim = scene.agents.shape
    block: dict[str, Any] = {
        "T": PERIOD,
        "target": [float(v) for v in scene.target],
        "agents": [[float(v) for v in row] for row in scene.agents],
    }
    if example.rule == "explicit":
        block["weights"] = [[float(v) for v in row] for row in W]
    else:
        hears = weights_support(W)
        block["edges"] = [[i + 1, j + 1] for i in range(n) for j in range(i + 1, n) if hears[i, j]]
        block["weights"] = example.rule
    net = analyze_weighted_scene(example)
    return {
        "name": f"falsify-rank-sum-{dim}d-{n}-agents-{example.rule}",
        "source": "trackcert falsify (shrunk counterexample to seed 000 after eq. (4.36))",
        "description": f"rank O = {net.network_rank}, Σ rank O_i = {net.rank_sum} "
        f"(rank O_i = {net.agent_ranks}).",
        "kind": "tdoa",
        "tdoa": block,
        "expect": {
            "network_rank": net.network_rank,
            "network_observable": net.observable,
            "network_detectable": net.detectable,
        },
    }


def _rank_sum_paper(example: WeightedScene) -> bool:
    net = analyze_weighted_scene(example)
    return not net.conclusive or net.rank_sum_claim_holds


def _rank_sum_corrected(example: WeightedScene) -> bool:
    net = analyze_weighted_scene(example)
    ranks = component_ranks(example)
    if not net.conclusive or not all(conclusive for _, conclusive in ranks):
        return True
    dim = example.scene.agents.shape[1]
    full = all(rank == dim for rank, _ in ranks)
    return net.network_rank <= net.rank_sum and net.detectable == full


OFFSETS = (Fraction(1, 10**3), Fraction(1, 10**9), Fraction(1, 10**12), Fraction(0))
"""Distances to the boundary swept (signed in the strategies); 0 is on it."""
FAMILIES = ("plane", "collinear", "mirror", "split")

Point = tuple[Fraction, ...]
F_ = Fraction


@dataclass(frozen=True)
class BoundaryScene:
    """A scene at signed distance ``offset`` (0: on it) from the boundary of its ``family``: exact
    agents and target, 1-based undirected ``edges`` or (``split``) a ``comm_range``."""

    family: str
    offset: Fraction
    agents: tuple[Point, ...]
    target: Point
    edges: tuple[tuple[int, int], ...] | None
    comm_range: Fraction | None = None


def scene_block(scene: BoundaryScene) -> dict[str, Any]:
    """The ``tdoa:`` block of ``scene`` (floats whose shortest decimals are the exact values)."""
    block: dict[str, Any] = {
        "T": 1.0,  # the rank verdicts do not depend on the ping period T > 0
        "agents": [[float(x) for x in p] for p in scene.agents],
        "target": [float(x) for x in scene.target],
        "weights": "metropolis",
    }
    if scene.edges is None:
        block["comm_range"] = float(scene.comm_range)
    else:
        block["edges"] = [list(e) for e in scene.edges]
    return block


def _to_case(scene: BoundaryScene) -> dict[str, Any]:
    return {
        "name": f"falsify-boundary-{scene.family}",
        "source": f"trackcert falsify (boundary sweep, offset {scene.offset})",
        "kind": "tdoa",
        "tdoa": scene_block(scene),
    }


# ----------------------------------------------------------------------------- strategies


_INT = st.integers(-12, 12)


def _point(dim: int, draw: st.DrawFn) -> list[Fraction]:
    return [Fraction(draw(_INT)) for _ in range(dim)]


def _signed_offset(draw: st.DrawFn) -> Fraction:
    return draw(st.sampled_from(OFFSETS)) * draw(st.sampled_from((1, -1)))


def _complete(n: int) -> tuple[tuple[int, int], ...]:
    return tuple((i, j) for i, j in combinations(range(1, n + 1), 2))


@st.composite
def _plane(draw: st.DrawFn) -> BoundaryScene:
    base = [[*_point(2, draw), Fraction(0)] for _ in range(3)]
    fourth = [*_point(2, draw), _signed_offset(draw)]
    target = [*_point(2, draw), Fraction(draw(st.integers(1, 12)) * draw(st.sampled_from((1, -1))))]
    agents = [*base, fourth]
    return _scene(draw, "plane", fourth[2], agents, target, _complete(4))


@st.composite
def _collinear(draw: st.DrawFn) -> BoundaryScene:
    a, b = _point(2, draw), _point(2, draw)
    t = Fraction(draw(st.integers(-4, 8)), 2)
    offset = _signed_offset(draw)
    perp = [a[1] - b[1], b[0] - a[0]]
    third = [a[i] + t * (b[i] - a[i]) + offset * perp[i] for i in range(2)]
    return _scene(draw, "collinear", offset, [a, b, third], _point(2, draw), _complete(3))


@st.composite
def _mirror(draw: st.DrawFn) -> BoundaryScene:
    n = draw(st.integers(3, 5))
    agents = [[*_point(2, draw), Fraction(0)] for _ in range(n)]
    height = _signed_offset(draw)
    return _scene(draw, "mirror", height, agents, [*_point(2, draw), height], _complete(n))


@st.composite
def _split(draw: st.DrawFn) -> BoundaryScene:
    """Bridging agents at (0,0,0) and (D,0,0) (before the shift); every other cross pair at least
    D + 1 apart."""
    gap = Fraction(draw(st.integers(10, 14)))
    small = st.integers(0, 3)
    left = [[Fraction(0)] * 3] + [
        [Fraction(-1 - draw(small)), Fraction(draw(small)), Fraction(draw(small))]
        for _ in range(draw(st.integers(1, 3)))
    ]
    right = [[gap, Fraction(0), Fraction(0)]] + [
        [gap + 1 + draw(small), Fraction(draw(small)), Fraction(draw(small))]
        for _ in range(draw(st.integers(1, 3)))
    ]
    offset = _signed_offset(draw)
    target = [Fraction(draw(st.integers(-5, 20))), *_point(2, draw)]
    scene = _scene(draw, "split", offset, [*left, *right], target, None)
    assume(_round_trips([(gap + offset,)]))
    return BoundaryScene(scene.family, offset, scene.agents, scene.target, None, gap + offset)


def _scene(draw, family, offset, agents, target, edges) -> BoundaryScene:
    """Shift the scene by a decimal (non-dyadic) vector, so that float differences round, and
    reject draws with two points (agents or target) less than 1 apart: the case would be
    refused (``coincidence_tol``), and the boundary swept is another one."""
    shift = [Fraction(draw(st.integers(-500, 500)), 10) for _ in target]
    points = [tuple(x + t for x, t in zip(p, shift, strict=True)) for p in agents]
    aim = tuple(x + t for x, t in zip(target, shift, strict=True))
    every = [*points, aim]
    assume(
        all(
            sum((a - b) ** 2 for a, b in zip(p, q, strict=True)) >= 1
            for p, q in combinations(every, 2)
        )
        and _round_trips(every)
    )
    return BoundaryScene(family, offset, tuple(points), aim, edges)


def _round_trips(points: list[Point]) -> bool:
    """Every coordinate's float prints back as the exact rational (the case states it exactly)."""
    return all(Fraction(repr(float(x))) == x for p in points for x in p)


def boundary_scenes(family: str) -> st.SearchStrategy[BoundaryScene]:
    """Scenes of ``family`` (``plane``, ``collinear``, ``mirror`` or ``split``) at the swept
    offsets from its boundary."""
    return {"plane": _plane, "collinear": _collinear, "mirror": _mirror, "split": _split}[family]()


# ------------------------------------------------------------------ the independent oracle


def _rank(rows: list[list[Fraction]]) -> int:
    """Rank by Gaussian elimination in Fractions."""
    return len(_echelon(rows)[1])


def _echelon(rows: list[list[Fraction]]) -> tuple[list[list[Fraction]], list[int]]:
    """Reduced row echelon form and pivot columns (Fractions, no flint)."""
    m = [list(r) for r in rows]
    pivots: list[int] = []
    r = 0
    for c in range(len(m[0]) if m else 0):
        k = next((i for i in range(r, len(m)) if m[i][c] != 0), None)
        if k is None:
            continue
        m[r], m[k] = m[k], m[r]
        m[r] = [x / m[r][c] for x in m[r]]
        for i in range(len(m)):
            if i != r and m[i][c] != 0:
                m[i] = [x - m[i][c] * y for x, y in zip(m[i], m[r], strict=True)]
        pivots.append(c)
        r += 1
    return m, pivots


def _affine_rank(points: list[Point]) -> int:
    if not points:
        return -1
    return _rank([[x - y for x, y in zip(p, points[0], strict=True)] for p in points[1:]])


def _sqrt_sum_is_zero(terms: list[tuple[Fraction, Fraction]]) -> bool:
    """``Σ c √q = 0``? Rigorous ball arithmetic against the root-separation bound.

    ``M Σ c_k √q_k = Σ m_k √n_k`` (integers, ``M`` the common denominator) is an algebraic
    integer of degree ≤ 2^K whose conjugates are bounded by ``B = Σ |m_k| √n_k``; if non-zero,
    its norm is a non-zero integer, so ``|Σ m_k √n_k| ≥ B^{1 − 2^K}``.
    """
    terms = [(c, q) for c, q in terms if c != 0]
    if not terms:
        return True
    scaled = [(c / q.denominator, q.numerator * q.denominator) for c, q in terms]
    lcm = math.lcm(*(c.denominator for c, _ in scaled))
    ints = [(int(c * lcm), n) for c, n in scaled]
    log_bound = math.log2(sum(abs(m) * math.isqrt(n + 1) + abs(m) for m, n in ints))
    bits = (int(log_bound) + 2) * 2 ** len(ints) + 64
    old = flint.ctx.prec
    flint.ctx.prec = bits
    try:
        value = sum((flint.arb(m) * flint.arb(n).sqrt() for m, n in ints), flint.arb(0))
        gap = flint.arb(2) ** (-(int(log_bound) + 1) * (2 ** len(ints) - 1))
        if not value.contains(0):
            return False
        if (abs(value) < gap) is True:
            return True
        raise ArithmeticError(f"ball {value} too wide for the separation bound")
    finally:
        flint.ctx.prec = old


def _direction_rank(target: Point, points: list[Point]) -> int:
    """``dim aff{u_j}`` via ``rank [V, r] − 1`` and the left kernel of ``V`` (see module)."""
    V = [[a - x for a, x in zip(p, target, strict=True)] for p in points]
    q = [sum(x * x for x in v) for v in V]
    reduced, pivots = _echelon([[v[c] for v in V] for c in range(len(target))])
    outside = any(
        not _sqrt_sum_is_zero(
            [(Fraction(-1), q[j])] + [(reduced[r][j], q[b]) for r, b in enumerate(pivots)]
        )
        for j in range(len(V))
        if j not in pivots
    )
    return len(pivots) + int(outside) - 1


def _components(scene: BoundaryScene) -> list[list[int]]:
    n = len(scene.agents)
    if scene.edges is None:
        linked = [
            (i, j)
            for i, j in combinations(range(n), 2)
            if sum((a - b) ** 2 for a, b in zip(scene.agents[i], scene.agents[j], strict=True))
            < scene.comm_range**2
        ]
    else:
        linked = [(i - 1, j - 1) for i, j in scene.edges]
    label = list(range(n))
    for _ in range(n):
        for i, j in linked:
            label[i] = label[j] = min(label[i], label[j])
    return [[i for i in range(n) if label[i] == k] for k in sorted(set(label))]


def truth(scene: BoundaryScene) -> dict[str, list[Any]]:
    """The exact per-agent verdicts (``component``, ``observable``, ``heuristic_4_noncoplanar``,
    ``mirror_ambiguous``), independently of the library's exact geometry."""
    dim, n = len(scene.target), len(scene.agents)
    out: dict[str, list[Any]] = {
        k: [None] * n
        for k in ("component", "observable", "heuristic_4_noncoplanar", "mirror_ambiguous")
    }
    for part in _components(scene):
        points = [scene.agents[i] for i in part]
        hull = _affine_rank(points)
        rank = _direction_rank(scene.target, points) if len(part) > 1 else 0
        for i in part:
            out["component"][i] = part
            out["observable"][i] = rank == dim
            out["heuristic_4_noncoplanar"][i] = len(part) >= dim + 1 and hull == dim
            out["mirror_ambiguous"][i] = hull < dim and _affine_rank([*points, scene.target]) > hull
    return out


def never_wrong(scene: BoundaryScene, result: TopologyResult | None = None) -> bool:
    """Exact fields equal the truth; ranks equal it unless ``result`` (default: the analysis of
    ``scene``) is inconclusive."""
    result = result or analyze_topology(parse_tdoa(scene_block(scene)))
    expected = truth(scene)
    members: dict[int, list[int]] = {}
    for index, agent in enumerate(result.agents):
        members.setdefault(agent.component, []).append(index)
    exact_ok = all(
        members[a.component] == expected["component"][i]
        and a.heuristic_4_noncoplanar == expected["heuristic_4_noncoplanar"][i]
        and a.mirror_ambiguous == expected["mirror_ambiguous"][i]
        for i, a in enumerate(result.agents)
    )
    ranks_ok = not result.conclusive or all(
        a.observable == expected["observable"][i] == a.localizes
        for i, a in enumerate(result.agents)
    )
    return exact_ok and ranks_ok


@dataclass(frozen=True)
class MovedScene:
    """A boundary scene and its image under ``x ↦ scale · R x + shift`` (exact rationals)."""

    scene: BoundaryScene
    moved: BoundaryScene


@st.composite
def moved_scenes(draw: st.DrawFn) -> MovedScene:
    """A boundary scene of any family moved by a rational rotation, scale and shift."""
    scene = draw(st.one_of(*(boundary_scenes(f) for f in FAMILIES)))
    dim = len(scene.target)
    rotation = draw(rational_rotations(dim=dim))
    scale = draw(st.sampled_from((F_(1, 4), F_(1), F_(5, 2), F_(8))))
    shift = [F_(draw(st.integers(-40, 40))) for _ in range(dim)]
    agents = similarity_image(list(scene.agents), rotation, scale, shift)
    target = similarity_image([scene.target], rotation, scale, shift)[0]
    points = [tuple(p) for p in agents]
    assume(_round_trips([*points, tuple(target)]))
    comm_range = None if scene.comm_range is None else scene.comm_range * scale
    assume(comm_range is None or _round_trips([(comm_range,)]))
    moved = BoundaryScene(
        scene.family, scene.offset * scale, tuple(points), tuple(target), scene.edges, comm_range
    )
    return MovedScene(scene, moved)


def _verdicts(scene: BoundaryScene) -> list[tuple]:
    result = analyze_topology(parse_tdoa(scene_block(scene)))
    return [
        (a.component, a.rank, a.observable, a.heuristic_4_noncoplanar, a.mirror_ambiguous)
        for a in result.agents
    ]


def invariant(example: MovedScene) -> bool:
    """The verdicts of a scene and of its moved image are equal (exact decisions: always)."""
    return _verdicts(example.scene) == _verdicts(example.moved)


_STATEMENTS = {
    "plane": "a 4th agent at distance 0, 10⁻¹², 10⁻⁹ or 10⁻³ from the plane of three others",
    "collinear": "a 3rd agent at distance 0, 10⁻¹², 10⁻⁹ or 10⁻³ (scaled) from the line of two "
    "others (2-D)",
    "mirror": "the target at height 0, 10⁻¹², 10⁻⁹ or 10⁻³ above the plane of its receivers",
    "split": "a bridging pair at the communication range ± 0, 10⁻¹², 10⁻⁹ or 10⁻³",
}


def _scene_property(
    property_id: str,
    statement: str,
    holds: Callable[[TdoaScene], bool],
    *,
    expected_to_hold: bool = True,
) -> Property:
    """``property_id = "<claim>/<wording>"`` over :data:`SCENES_3D`."""
    claim, wording = property_id.split("/")
    return Property(
        id=property_id,
        claim=claim,
        wording=wording,
        statement=statement,
        examples=SCENES_3D,
        holds=holds,
        to_case=scene_case,
        expected_to_hold=expected_to_hold,
    )


SCENES_2D_3D = st.one_of(SCENES_3D, tdoa_scenes(dim=2, family="general"))
"""Scenes in 3-D (every family) and in the plane: Thm 4.2.3's heuristic is stated for both."""


@st.composite
def networked_scenes(draw: st.DrawFn, *, max_agents: int = 6) -> WeightedScene:
    """A 2-D or 3-D scene of any family with any row-stochastic ``W`` (``w_ii > 0``,
    ``w_ij > 0`` exactly on the links) of an undirected network, connected or not: the class of
    seed 000 §4.2.2 (before eq. (4.26)) behind Thm 4.2.3 and Cor. 4.2.4."""
    scene = draw(st.one_of(SCENES_3D, tdoa_scenes(dim=2, family="general")))
    n = len(scene.agents)
    hears = draw(networks(min_agents=n, max_agents=n, connected=None))
    if n > max_agents:
        scene = TdoaScene(scene.target, scene.agents[:max_agents], scene.family)
        hears = hears[:max_agents, :max_agents]
    return WeightedScene(scene, draw(stochastic_weights(hears)), "explicit")


def _heuristic_met(example: WeightedScene) -> bool:
    """Every agent is in a connected component of ≥ d + 1 agents not in one hyperplane."""
    agents, d = example.scene.agents, example.scene.agents.shape[1]
    parts = components(weights_support(example.weights))
    return all(len(part) >= d + 1 and not _coplanar(agents[part]) for part in parts)


def _network_paper(example: WeightedScene) -> bool:
    """Thm 4.2.3 (network): observable iff the heuristic holds for every agent."""
    net = analyze_weighted_scene(example)
    return not net.conclusive or net.observable == _heuristic_met(example)


def _network_corrected(example: WeightedScene) -> bool:
    """Detectable iff every component's stacked position Jacobian has full rank."""
    return _rank_sum_corrected(example)


@dataclass(frozen=True, eq=False)
class SwitchingScene:
    """A scene and the networks it switches between (one W per step), seed 000 Cor. 4.2.4."""

    steps: tuple[WeightedScene, ...]


@st.composite
def switching_scenes(draw: st.DrawFn) -> SwitchingScene:
    """2–3 networks with any weights on one scene (:func:`networked_scenes`' class)."""
    first = draw(networked_scenes())
    n = len(first.scene.agents)
    others = [
        WeightedScene(first.scene, draw(stochastic_weights(draw(networks(
            min_agents=n, max_agents=n, connected=None)))), "explicit")
        for _ in range(draw(st.integers(1, 2)))
    ]  # fmt: skip
    return SwitchingScene((first, *others))


def _switching_paper(example: SwitchingScene) -> bool:
    """Cor. 4.2.4: the heuristic at every step ⇒ observable at every step."""
    if not all(_heuristic_met(step) for step in example.steps):
        return True
    nets = [analyze_weighted_scene(step) for step in example.steps]
    return not all(n.conclusive for n in nets) or all(n.observable for n in nets)


def switching_case(example: SwitchingScene) -> dict[str, Any]:
    """The case of the first step that is not observable (else of the first step)."""
    steps = example.steps
    worst = next((s for s in steps if not analyze_weighted_scene(s).observable), steps[0])
    return weighted_scene_case(worst)


def _switching_corrected(example: SwitchingScene) -> bool:
    """Every step: detectable iff every component's stacked Jacobian has full rank."""
    return all(_rank_sum_corrected(step) for step in example.steps)


def _network_property(claim: str, wording: str, statement: str, examples, holds, to_case,
                      expected_to_hold: bool = True) -> Property:  # fmt: skip
    return Property(
        f"{claim}/{wording}", claim, wording, statement, examples, holds, to_case,
        expected_to_hold,
    )  # fmt: skip


def _boundary_property(family: str) -> Property:
    return Property(
        id=f"seed000.thm4.2.3.boundary-{family}/corrected",
        claim=f"seed000.thm4.2.3.boundary-{family}",
        wording="corrected",
        statement=f"With {_STATEMENTS[family]}, trackcert topology is never wrong: "
        "components, the ≥ d + 1 non-coplanar heuristic and the mirror ambiguity equal an "
        "independent exact computation, and observable/localizes equal it unless the "
        "verdict is inconclusive.",
        examples=boundary_scenes(family),
        holds=never_wrong,
        to_case=_to_case,
    )


PROPERTIES = (
    _scene_property(
        "seed000.thm4.2.3/paper",
        "A connected component of ≥ 4 non-coplanar agents can localize the target.",
        _heuristic_paper,
        expected_to_hold=False,
    ),
    _scene_property(
        "seed000.thm4.2.3/corrected",
        "A connected component can localize the target iff the unit directions from the agents "
        "to the target do not lie on one circle of the unit sphere (equivalently, the agents do "
        "not lie on one circular cone, or plane, through the target).",
        _heuristic_corrected,
    ),
    _scene_property(
        "seed000.sec4.2.1.coplanar/paper",
        "det Λ = 0 when the 4 agents are coplanar: coplanar agents cannot localize.",
        _coplanar_paper,
        expected_to_hold=False,
    ),
    _scene_property(
        "seed000.sec4.2.1.coplanar/corrected",
        "Coplanar receivers hear the target and its mirror image through their plane with "
        "identical TDOAs (a global ambiguity), whatever the local rank.",
        _coplanar_corrected,
    ),
    Property(
        id="seed000.eq4.36.rank-sum/paper",
        claim="seed000.eq4.36.rank-sum",
        wording="paper",
        statement="From the structure of D_H, rank O = Σ_i rank O_i (seed 000 after eq. (4.36)).",
        examples=weighted_scenes(),
        holds=_rank_sum_paper,
        to_case=weighted_scene_case,
        expected_to_hold=False,
    ),
    Property(
        id="seed000.eq4.36.rank-sum/corrected",
        claim="seed000.eq4.36.rank-sum",
        wording="corrected",
        statement=(
            "rank O ≤ Σ_i rank O_i, and (W ⊗ A, D_H) is detectable iff every connected "
            "component's stacked position Jacobian has full rank d."
        ),
        examples=weighted_scenes(),
        holds=_rank_sum_corrected,
        to_case=weighted_scene_case,
    ),
    *(_boundary_property(family) for family in FAMILIES),
    _network_property(
        "seed000.thm4.2.3.heuristic",
        "paper",
        "An agent can localize the target iff it belongs to a connected (sub)network of ≥ 4 "
        "non-coplanar agents (3 non-collinear in 2-D).",
        SCENES_2D_3D,
        _heuristic_paper,
        scene_case,
        expected_to_hold=False,
    ),
    _network_property(
        "seed000.thm4.2.3.heuristic",
        "corrected",
        "A connected (sub)network localizes the target iff the unit directions from its agents "
        "to the target do not lie on one circle (2-D: one line) of the unit sphere.",
        SCENES_2D_3D,
        _heuristic_corrected,
        scene_case,
    ),
    _network_property(
        "seed000.thm4.2.3.network",
        "paper",
        "For any stochastic W with w_ij > 0 exactly on the links, (W ⊗ A, D_H) is observable iff "
        "every agent is part of a connected (sub)network of ≥ 4 non-coplanar agents.",
        networked_scenes(),
        _network_paper,
        weighted_scene_case,
        expected_to_hold=False,
    ),
    _network_property(
        "seed000.thm4.2.3.network",
        "corrected",
        "For any such W, (W ⊗ A, D_H) is detectable iff every connected component's stacked "
        "position Jacobian has full rank d (observability also needs W nonsingular).",
        networked_scenes(),
        _network_corrected,
        weighted_scene_case,
    ),
    _network_property(
        "seed000.cor4.2.4",
        "paper",
        "On a time-varying undirected network, if at every step every agent is part of a "
        "connected network of ≥ 4 non-coplanar agents, the networked system is observable.",
        switching_scenes(),
        _switching_paper,
        switching_case,
        expected_to_hold=False,
    ),
    _network_property(
        "seed000.cor4.2.4",
        "corrected",
        "On a time-varying network, at every step (W_k ⊗ A, D_H(k)) is detectable iff every "
        "connected component's stacked position Jacobian has full rank.",
        switching_scenes(),
        _switching_corrected,
        switching_case,
    ),
    Property(
        id="seed000.thm4.2.3.invariance/corrected",
        claim="seed000.thm4.2.3.invariance",
        wording="corrected",
        statement="Translating, rotating (a rational rotation) and scaling every position of a "
        "boundary scene leaves every trackcert topology verdict unchanged (components, ranks, "
        "the heuristic, the mirror ambiguity).",
        examples=moved_scenes(),
        holds=invariant,
        to_case=lambda example: _to_case(example.moved),
    ),
)
