"""Public hypothesis strategies for TDOA scenes, networks and consensus weights (seed 000 ch. 4).

Users import these in their own property tests::

    from hypothesis import given
    from theory.tdoa.strategies import tdoa_scenes

    @given(tdoa_scenes(dim=3, family="cone"))
    def test_cone_scenes_lose_rank(scene): ...

They are also re-exported by :mod:`theory.strategies`. Names are plural nouns, bounds are
keyword-only, conditioning is bounded, and impossible arguments raise
:class:`hypothesis.errors.InvalidArgument` with the offending value.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from itertools import product

import networkx as nx
import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.core.exact import exact_decimal
from theory.core.network import metropolis_weights, uniform_weights
from theory.strategy_helpers import check_range, generators, orthonormal_matrix

__all__ = [
    "FORMATION_FAMILIES",
    "RANDOM_WEIGHT_DECADES",
    "SCENE_FAMILIES",
    "WEIGHT_KINDS",
    "TdoaScene",
    "formations",
    "is_connected",
    "networks",
    "rational_rotations",
    "similarity_image",
    "stochastic_weights",
    "tdoa_scenes",
    "weight_matrices",
]

SCENE_FAMILIES = ("general", "coplanar", "cone", "target-in-plane")
"""The ``family`` values of :func:`tdoa_scenes`."""
WEIGHT_KINDS = ("metropolis", "uniform", "random", "singular")
"""The ``kind`` values of :func:`weight_matrices`."""
RANDOM_WEIGHT_DECADES = 4
"""Decades spanned by the raw weights of ``weight_matrices(kind="random")``, as in
:func:`stochastic_weights`."""
FORMATION_FAMILIES = ("general", "uniform", "union", "degenerate")
"""The ``family`` values of :func:`formations`."""


@dataclass(frozen=True, eq=False)
class TdoaScene:
    """A target (``dim``,) and receivers (N, dim); ``family`` is the geometric family it was drawn
    from (:data:`SCENE_FAMILIES`)."""

    target: np.ndarray
    agents: np.ndarray
    family: str


@st.composite
def networks(
    draw: st.DrawFn,
    *,
    min_agents: int = 2,
    max_agents: int = 8,
    connected: bool | None = True,
    directed: bool = False,
) -> np.ndarray:
    """Boolean "hears" matrices ``H[r, s]`` (no self-loops) of ``min_agents`` to ``max_agents``
    agents (``InvalidArgument`` for impossible bounds).

    ``connected=True`` gives (strongly, when ``directed``) connected graphs, ``False`` graphs with
    at least two (weak) components, ``None`` either; undirected graphs give symmetric ``H``."""
    check_range("min_agents", min_agents, "max_agents", max_agents, 1)
    if connected is False and max_agents < 2:
        raise InvalidArgument("a disconnected network needs max_agents ≥ 2")
    low = 2 if connected is False else min_agents
    n = draw(st.integers(max(low, min_agents), max_agents))
    rng = draw(generators())
    density = draw(st.floats(0.1, 0.9))
    hears = rng.random((n, n)) < density
    if not directed:
        hears = np.triu(hears, 1)
        hears = hears | hears.T
    np.fill_diagonal(hears, False)
    order = rng.permutation(n)
    if connected:
        ring = np.roll(order, 1)
        hears[order, ring] = True
        if not directed:
            hears[ring, order] = True
    elif connected is False:
        cut = int(rng.integers(1, n))
        left, right = order[:cut], order[cut:]
        hears[np.ix_(left, right)] = False
        hears[np.ix_(right, left)] = False
    np.fill_diagonal(hears, False)
    return hears


@st.composite
def weight_matrices(
    draw: st.DrawFn,
    *,
    min_agents: int = 2,
    max_agents: int = 6,
    kind: str = "metropolis",
    directed: bool = False,
    connected: bool | None = True,
) -> np.ndarray:
    """Row-stochastic ``W`` with positive diagonal on a network drawn by :func:`networks`.

    ``kind`` (:data:`WEIGHT_KINDS`): ``metropolis`` (symmetric, doubly stochastic; undirected only),
    ``uniform``, ``random`` (any positive weights on the support: log-uniform over
    :data:`RANDOM_WEIGHT_DECADES` decades before normalisation, seed 000 §4.2.2), or
    ``singular`` (uniform weights on a complete graph, ``W = J/N`` of rank 1; ``directed`` and
    ``connected`` ignored).
    ``InvalidArgument`` for an unknown ``kind``, ``metropolis`` with ``directed``, or impossible
    bounds."""
    if kind not in WEIGHT_KINDS:
        raise InvalidArgument(f"kind={kind!r}; expected one of {WEIGHT_KINDS}")
    if kind == "metropolis" and directed:
        raise InvalidArgument("Metropolis weights need an undirected network (directed=False)")
    if kind == "singular":
        check_range("min_agents", min_agents, "max_agents", max_agents, 2)
        n = draw(st.integers(min_agents, max_agents))
        return uniform_weights(~np.eye(n, dtype=bool))
    hears = draw(
        networks(
            min_agents=min_agents, max_agents=max_agents, connected=connected, directed=directed
        )
    )
    if kind == "metropolis":
        return metropolis_weights(hears)
    if kind == "uniform":
        return uniform_weights(hears)
    return _log_uniform_weights(draw(generators()), hears, RANDOM_WEIGHT_DECADES)


@st.composite
def tdoa_scenes(
    draw: st.DrawFn,
    *,
    dim: int = 3,
    min_agents: int = 4,
    max_agents: int = 8,
    family: str = "general",
    scale: float = 20.0,
    min_separation: float = 0.5,
) -> TdoaScene:
    """TDOA scenes in ``dim`` dimensions with ``min_agents`` to ``max_agents`` receivers.

    ``family`` (:data:`SCENE_FAMILIES`): ``general`` (random points at least
    ``min_separation·scale`` from the target), ``coplanar`` (3-D: receivers in a plane, target off
    it), ``cone`` (3-D: receivers on a circular cone with apex at the target, where the stacked TDOA
    Jacobian loses rank), ``target-in-plane`` (3-D: receivers and target in one plane); exact up to
    the rounding of the coordinates. The target is drawn in ``[−scale, scale]^dim``, the receivers'
    offsets are shorter than ``scale``. ``InvalidArgument`` for an unknown ``dim`` or ``family``, a
    3-D family with ``dim=2``, or impossible bounds."""
    _check_scene_arguments(dim, min_agents, max_agents, family, scale, min_separation)
    n = draw(st.integers(min_agents, max_agents))
    rng = draw(generators())
    target = rng.uniform(-scale, scale, dim)
    offsets = _family_offsets(rng, family, n, dim, scale, min_separation)
    return TdoaScene(target, target + offsets, family)


def _check_scene_arguments(
    dim: int, min_agents: int, max_agents: int, family: str, scale: float, min_separation: float
) -> None:
    if dim not in (2, 3):
        raise InvalidArgument(f"dim={dim}; expected 2 or 3")
    if family not in SCENE_FAMILIES:
        raise InvalidArgument(f"family={family!r}; expected one of {SCENE_FAMILIES}")
    if family != "general" and dim != 3:
        raise InvalidArgument(f"family={family!r} is a 3D family; use dim=3")
    check_range("min_agents", min_agents, "max_agents", max_agents, 2)
    if not scale > 0 or not 0 < min_separation < 1:
        raise InvalidArgument(
            f"scale={scale} must be > 0 and min_separation={min_separation} in (0, 1)"
        )


def _family_offsets(
    rng: np.random.Generator, family: str, n: int, dim: int, scale: float, min_separation: float
) -> np.ndarray:
    """Receivers' offsets from the target for one of :data:`SCENE_FAMILIES` (see
    :func:`tdoa_scenes`)."""
    frame = orthonormal_matrix(rng, dim)
    radii = rng.uniform(min_separation, 1.0, n) * scale
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    if family == "general":
        directions = rng.standard_normal((n, dim))
        return directions / np.linalg.norm(directions, axis=1, keepdims=True) * radii[:, None]
    if family == "cone":
        half_angle = rng.uniform(0.2, 1.3)
        local = np.column_stack(
            [
                np.full(n, np.cos(half_angle)),
                np.sin(half_angle) * np.cos(angles),
                np.sin(half_angle) * np.sin(angles),
            ]
        )
        return (local @ frame.T) * radii[:, None]
    height = 0.0 if family == "target-in-plane" else rng.uniform(0.2, 1.0) * scale
    local = np.column_stack([np.full(n, -height), radii * np.cos(angles), radii * np.sin(angles)])
    return local @ frame.T


def is_connected(hears: np.ndarray, *, strongly: bool = False) -> bool:
    """Whether the "hears" graph is (strongly) connected: used to test :func:`networks`."""
    graph = nx.from_numpy_array(hears.T.astype(int), create_using=nx.DiGraph)
    return nx.is_strongly_connected(graph) if strongly else nx.is_weakly_connected(graph)


_DECIMAL_NORMS = frozenset({1, 2, 4, 5, 8, 10, 16, 20, 25})
"""Quaternion norms ``w² + x² + y² + z²`` whose rotations have finite-decimal entries."""
_QUATERNIONS = tuple(
    q for q in product(range(-2, 3), repeat=4) if sum(x * x for x in q) in _DECIMAL_NORMS
)
_PYTHAGOREAN = ((3, 4, 5), (7, 24, 25), (44, 117, 125), (336, 527, 625))
"""Pythagorean triples with hypotenuse a power of 5: cos and sin are finite decimals."""


def _quaternion_rotation(q: tuple[int, int, int, int]) -> list[list[Fraction]]:
    """The rotation of the (unnormalized) quaternion ``q``: rational, exactly orthogonal."""
    w, x, y, z = q
    n = Fraction(1, w * w + x * x + y * y + z * z)
    return [
        [n * (w * w + x * x - y * y - z * z), 2 * n * (x * y - w * z), 2 * n * (x * z + w * y)],
        [2 * n * (x * y + w * z), n * (w * w - x * x + y * y - z * z), 2 * n * (y * z - w * x)],
        [2 * n * (x * z - w * y), 2 * n * (y * z + w * x), n * (w * w - x * x - y * y + z * z)],
    ]


@st.composite
def rational_rotations(draw: st.DrawFn, *, dim: int = 3) -> list[list[Fraction]]:
    """Exactly orthogonal rational rotations with finite-decimal entries, so rotated decimal
    coordinates stay finite decimals a case file states exactly.

    2-D: ``[[c, −s], [s, c]]`` from a Pythagorean triple with hypotenuse ``5^k``; 3-D: the rotation
    of an integer quaternion of norm ``2^a 5^b``. ``InvalidArgument`` for another ``dim``."""
    if dim == 3:
        return _quaternion_rotation(draw(st.sampled_from(_QUATERNIONS)))
    if dim != 2:
        raise InvalidArgument(f"dim={dim!r}; expected 2 or 3")
    a, b, c = draw(st.sampled_from(_PYTHAGOREAN))
    cos, sin = (
        (Fraction(a, c), Fraction(b, c))
        if draw(st.booleans())
        else (
            Fraction(b, c),
            Fraction(a, c),
        )
    )
    cos, sin = cos * draw(st.sampled_from((1, -1))), sin * draw(st.sampled_from((1, -1)))
    return [[cos, -sin], [sin, cos]]


def similarity_image(
    points: np.ndarray | list,
    rotation: list[list[Fraction]],
    scale: Fraction,
    shift: list[Fraction],
) -> list[list[Fraction]]:
    """``scale · R p + shift`` for every point (floats read as the decimals they print as), in
    exact rationals."""
    rows = [[exact_decimal(x) for x in point] for point in np.asarray(points).tolist()]
    return [
        [
            scale * sum(r * x for r, x in zip(row, p, strict=True)) + t
            for row, t in zip(rotation, shift, strict=True)
        ]
        for p in rows
    ]


@st.composite
def stochastic_weights(draw: st.DrawFn, hears: np.ndarray, *, decades: int = 4) -> np.ndarray:
    """Any row-stochastic ``W`` with ``w_ii > 0`` and ``w_ij > 0`` exactly on the links
    ``hears[i, j]`` (directed or not): the class seed 000 §4.2.2 allows (before eq. (4.26)).

    The raw weights are log-uniform over ``decades`` decades before normalisation, or one of the
    named rules (Metropolis on a symmetric support, uniform); ``InvalidArgument`` for
    ``decades < 0``."""
    if decades < 0:
        raise InvalidArgument(f"decades={decades} must be ≥ 0")
    rule = draw(st.sampled_from(("any", "uniform", "metropolis")))
    if rule == "metropolis" and np.array_equal(hears, np.asarray(hears).T):
        return metropolis_weights(np.asarray(hears, bool))
    if rule == "uniform":
        return uniform_weights(np.asarray(hears, bool))
    return _log_uniform_weights(draw(generators()), hears, decades)


def _log_uniform_weights(rng: np.random.Generator, hears: np.ndarray, decades: int) -> np.ndarray:
    """Raw weights log-uniform over ``decades`` decades on the links and the diagonal, rows
    normalised to 1 (seed 000 §4.2.2: any ``w_ij > 0`` there)."""
    support = np.asarray(hears, bool) | np.eye(len(hears), dtype=bool)
    raw = np.where(support, 10.0 ** rng.uniform(-decades, 0, support.shape), 0.0)
    return raw / raw.sum(axis=1, keepdims=True)


def _uniform_bearings(rng: np.random.Generator, n: int) -> np.ndarray:
    angles = rng.uniform(0, 2 * np.pi) + 2 * np.pi * np.arange(n) / n
    return np.column_stack([np.cos(angles), np.sin(angles)])


def _solid(rng: np.random.Generator, draw: st.DrawFn) -> np.ndarray:
    from theory.tdoa.geometry.crb import platonic_solids

    solids = platonic_solids()
    return solids[draw(st.sampled_from(sorted(solids)))] @ orthonormal_matrix(rng, 3).T


@st.composite
def formations(
    draw: st.DrawFn, *, dim: int = 2, family: str = "general", max_agents: int = 12
) -> np.ndarray:
    """Unit directions (N, ``dim``) from a target to ``N ≥ 3`` receivers (seed 000 §4.3.1, seed
    003 Result 3): every formation, since only the bearings enter the CRB.

    ``family`` (:data:`FORMATION_FAMILIES`): ``general`` (random directions), ``uniform`` (a
    rotated uniform angular array in 2-D, a rotated Platonic solid in 3-D), ``union`` (two or
    three of those, rotated independently), ``degenerate`` (every direction on one line through
    the target in 2-D, in one plane in 3-D; directions may repeat). ``InvalidArgument`` for
    another ``dim`` or ``family``, or ``max_agents < 4``."""
    if dim not in (2, 3) or family not in FORMATION_FAMILIES or max_agents < 4:
        raise InvalidArgument(
            f"dim={dim!r}, family={family!r}, max_agents={max_agents}: expected dim 2 or 3, a "
            f"family of {FORMATION_FAMILIES}, max_agents ≥ 4"
        )
    rng = draw(generators())
    if family == "uniform":
        return (
            _uniform_bearings(rng, draw(st.integers(3, max_agents)))
            if dim == 2
            else _solid(rng, draw)
        )
    if family == "union":
        parts = draw(st.integers(2, 3))
        if dim == 2:
            return np.vstack(
                [_uniform_bearings(rng, draw(st.integers(3, 6))) for _ in range(parts)]
            )
        return np.vstack([_solid(rng, draw) for _ in range(parts)])
    n = draw(st.integers(3, max_agents))
    directions = rng.standard_normal((n, dim))
    if family == "degenerate":
        directions[:, 1 if dim == 2 else 2] = 0.0
        repeats = draw(st.integers(0, n - 1))
        directions[:repeats] = directions[n - 1]
        if dim == 3:
            directions = directions @ orthonormal_matrix(rng, 3).T
    return directions / np.linalg.norm(directions, axis=1, keepdims=True)
