"""Public hypothesis strategies for systems, networks, TDOA scenes and pursuit parameters.

Users import these in their own property tests (STYLE.md, *Adopt* 11)::

    from hypothesis import given
    from theory.strategies import tdoa_scenes

    @given(tdoa_scenes(dim=3, family="cone"))
    def test_cone_scenes_lose_rank(scene): ...

Names are plural nouns, bounds are keyword-only, conditioning is bounded, and impossible
arguments raise :class:`hypothesis.errors.InvalidArgument` with the offending value. The seed 003
strategies live in :mod:`theory.pursuit.strategies` and are re-exported here.
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx
import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.core.network import metropolis_weights, uniform_weights
from theory.pursuit.strategies import (
    PursuitParameters,
    TrackerState,
    pursuit_cases,
    pursuit_parameters,
    simulated_pursuit_blocks,
    simulated_pursuit_cases,
    tracker_states,
)

__all__ = [
    "SCENE_FAMILIES",
    "WEIGHT_KINDS",
    "DkfProblem",
    "PursuitParameters",
    "TdoaScene",
    "TrackerState",
    "digraph_laplacians",
    "dkf_problems",
    "is_connected",
    "networks",
    "pursuit_cases",
    "pursuit_parameters",
    "simulated_pursuit_blocks",
    "simulated_pursuit_cases",
    "state_space_pairs",
    "tdoa_scenes",
    "tracker_states",
    "weight_matrices",
]

SCENE_FAMILIES = ("general", "coplanar", "cone", "target-in-plane")
"""The ``family`` values of :func:`tdoa_scenes`."""
WEIGHT_KINDS = ("metropolis", "uniform", "random", "singular")
"""The ``kind`` values of :func:`weight_matrices`."""


@dataclass(frozen=True, eq=False)
class TdoaScene:
    """A target and receivers. ``family`` says which geometric family it was drawn from.

    Attributes
    ----------
    target : ndarray, shape (dim,)
        Target position.
    agents : ndarray, shape (N, dim)
        Receiver positions, one row per agent.
    family : str
        One of ``general``, ``coplanar``, ``cone``, ``target-in-plane`` (see
        :func:`tdoa_scenes`).
    """

    target: np.ndarray
    agents: np.ndarray
    family: str


@dataclass(frozen=True, eq=False)
class DkfProblem:
    """A consensus-filter problem (seed 000 ch. 5): system, per-agent measurements, weights,
    gains, and the seed that built them.

    Attributes
    ----------
    seed : int
        Seed of the ``numpy.random.Generator`` that drew everything else (a failing example is
        reproduced from it).
    A : ndarray, shape (n, n)
        State matrix.
    C : tuple of ndarray
        Measurement matrix ``C_i`` of each agent, shape (p_i, n) with ``p_i`` possibly 0.
    W : ndarray, shape (N, N)
        Row-stochastic consensus weights.
    L : tuple of ndarray
        Filter gain ``L_i`` of each agent, shape (n, p_i).
    """

    seed: int
    A: np.ndarray
    C: tuple[np.ndarray, ...]
    W: np.ndarray
    L: tuple[np.ndarray, ...]


def _check_range(name_low: str, low: int, name_high: str, high: int, floor: int) -> None:
    if low < floor:
        raise InvalidArgument(f"{name_low}={low} must be at least {floor}")
    if high < low:
        raise InvalidArgument(f"{name_high}={high} must be ≥ {name_low}={low}")


def _seeds() -> st.SearchStrategy[np.random.Generator]:
    return st.integers(0, 2**32 - 1).map(np.random.default_rng)


def _orthonormal(rng: np.random.Generator, n: int) -> np.ndarray:
    q, r = np.linalg.qr(rng.standard_normal((n, n)))
    return q * np.sign(np.diag(r))


@st.composite
def state_space_pairs(
    draw: st.DrawFn,
    *,
    min_states: int = 1,
    max_states: int = 4,
    min_outputs: int = 1,
    max_outputs: int = 2,
    spectral_radius: tuple[float, float] = (0.2, 1.5),
    max_condition: float = 10.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Pairs ``(A, C)`` with real eigenvalues of ``A`` in ``±spectral_radius`` and ``cond(V) ≤
    max_condition`` for its eigenvector matrix ``V`` (so eigenvalue tests are well posed).

    Parameters
    ----------
    min_states, max_states : int
        Bounds on ``n``.
    min_outputs, max_outputs : int
        Bounds on the rows of ``C`` (0 allowed).
    spectral_radius : (float, float)
        Eigenvalue magnitudes are drawn from this interval.
    max_condition : float
        Bound on the condition number of the eigenvector matrix (≥ 1).
    """
    _check_range("min_states", min_states, "max_states", max_states, 1)
    _check_range("min_outputs", min_outputs, "max_outputs", max_outputs, 0)
    low, high = spectral_radius
    if not 0 <= low <= high:
        raise InvalidArgument(f"spectral_radius={spectral_radius} must satisfy 0 ≤ low ≤ high")
    if max_condition < 1:
        raise InvalidArgument(f"max_condition={max_condition} must be ≥ 1")
    n = draw(st.integers(min_states, max_states))
    m = draw(st.integers(min_outputs, max_outputs))
    rng = draw(_seeds())
    magnitudes = rng.uniform(low, high, n) * rng.choice([-1.0, 1.0], n)
    singular = np.exp(rng.uniform(0, np.log(max_condition), n))
    V = _orthonormal(rng, n) @ np.diag(singular / singular.max()) @ _orthonormal(rng, n)
    A = V @ np.diag(magnitudes) @ np.linalg.inv(V)
    C = rng.standard_normal((m, n))
    return A, C


@st.composite
def networks(
    draw: st.DrawFn,
    *,
    min_agents: int = 2,
    max_agents: int = 8,
    connected: bool | None = True,
    directed: bool = False,
) -> np.ndarray:
    """Boolean "hears" matrices ``H[r, s]`` (no self-loops) of ``min_agents`` to ``max_agents``.

    Parameters
    ----------
    min_agents, max_agents : int
        Bounds on the number of agents (``1 ≤ min_agents ≤ max_agents``).
    connected : bool or None
        ``True`` gives (strongly, when directed) connected graphs, ``False`` gives graphs with at
        least two (weak) components (so at least 2 agents; needs ``max_agents ≥ 2``), ``None``
        either.
    directed : bool
        Whether ``H`` may be asymmetric; undirected graphs give symmetric ``H``.

    Returns
    -------
    SearchStrategy of ndarray of bool, shape (N, N)

    Raises
    ------
    InvalidArgument
        For impossible bounds.
    """
    _check_range("min_agents", min_agents, "max_agents", max_agents, 1)
    if connected is False and max_agents < 2:
        raise InvalidArgument("a disconnected network needs max_agents ≥ 2")
    low = 2 if connected is False else min_agents
    n = draw(st.integers(max(low, min_agents), max_agents))
    rng = draw(_seeds())
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
def digraph_laplacians(
    draw: st.DrawFn,
    *,
    min_agents: int = 2,
    max_agents: int = 7,
    max_extra_edges: int | None = None,
) -> np.ndarray:
    """Integer Laplacians ``L = D_in − A`` of strongly connected digraphs (seed 003 §II-B).

    The digraph is a random Hamiltonian cycle (so it is strongly connected) plus random edges;
    ``a_ij = 1`` means i receives from j.

    Parameters
    ----------
    min_agents, max_agents : int
        Bounds on the number of nodes ``n`` (``2 ≤ min_agents ≤ max_agents``).
    max_extra_edges : int, optional
        At most this many random edges beyond the cycle (default ``2n``; ``≥ 0``).

    Returns
    -------
    SearchStrategy of ndarray of int, shape (n, n)

    Raises
    ------
    InvalidArgument
        For impossible bounds.
    """
    _check_range("min_agents", min_agents, "max_agents", max_agents, 2)
    if max_extra_edges is not None and max_extra_edges < 0:
        raise InvalidArgument(f"max_extra_edges={max_extra_edges} must be ≥ 0")
    n = draw(st.integers(min_agents, max_agents))
    order = draw(st.permutations(range(n)))
    adjacency = np.zeros((n, n), dtype=int)
    for k in range(n):
        adjacency[order[k], order[(k + 1) % n]] = 1
    pairs = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1))
    extra = draw(st.lists(pairs, max_size=2 * n if max_extra_edges is None else max_extra_edges))
    for i, j in extra:
        if i != j:
            adjacency[i, j] = 1
    return np.diag(adjacency.sum(axis=1)) - adjacency


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
    """Row-stochastic ``W`` with positive diagonal on a drawn network.

    The network is drawn by :func:`networks` with ``min_agents``, ``max_agents``, ``directed``
    and ``connected``.

    Parameters
    ----------
    min_agents, max_agents : int
        Bounds on the number of agents.
    kind : str
        One of :data:`WEIGHT_KINDS`: ``metropolis`` (symmetric, doubly stochastic; undirected
        only), ``uniform``, ``random`` (positive random weights on the support), or ``singular``
        (uniform weights on a complete graph — singular on purpose: W = J/N has rank 1; needs
        ``min_agents ≥ 2``, and ``directed`` and ``connected`` are ignored).
    directed : bool
        Draw a directed network (not with ``metropolis``).
    connected : bool or None
        As for :func:`networks`.

    Returns
    -------
    SearchStrategy of ndarray, shape (N, N)

    Raises
    ------
    InvalidArgument
        For an unknown ``kind``, ``metropolis`` with ``directed``, or impossible bounds.
    """
    if kind not in WEIGHT_KINDS:
        raise InvalidArgument(f"kind={kind!r}; expected one of {WEIGHT_KINDS}")
    if kind == "metropolis" and directed:
        raise InvalidArgument("Metropolis weights need an undirected network (directed=False)")
    if kind == "singular":
        _check_range("min_agents", min_agents, "max_agents", max_agents, 2)
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
    rng = draw(_seeds())
    raw = np.where(hears | np.eye(len(hears), dtype=bool), rng.uniform(0.2, 1.0, hears.shape), 0.0)
    return raw / raw.sum(axis=1, keepdims=True)


def _directed_weights(rng: np.random.Generator, n: int, min_weight: float) -> np.ndarray:
    support = rng.random((n, n)) < rng.uniform(0.2, 1.0)
    np.fill_diagonal(support, True)
    raw = np.where(support, rng.uniform(min_weight, 1.0, (n, n)), 0.0)
    return raw / raw.sum(axis=1, keepdims=True)


def dkf_problems(
    *,
    min_states: int = 1,
    max_states: int = 3,
    min_agents: int = 1,
    max_agents: int = 4,
    max_rows: int = 2,
    a_bound: float = 1.5,
    gain_bound: float = 1.0,
    integer_data: bool = False,
) -> st.SearchStrategy[DkfProblem]:
    """Consensus-filter problems built from one drawn seed (a failing example is its seed).

    ``W`` is row-stochastic with a random directed support and weights ≥ 0.1 before
    normalisation.

    Parameters
    ----------
    min_states, max_states : int
        Bounds on the state dimension ``n`` (``1 ≤ min_states ≤ max_states``).
    min_agents, max_agents : int
        Bounds on the number of agents ``N`` (``1 ≤ min_agents ≤ max_agents``).
    max_rows : int
        Each ``C_i`` has 0 to ``max_rows`` rows (``≥ 0``).
    a_bound : float
        Bound on the magnitude of the entries of ``A`` (``> 0``).
    gain_bound : float
        Bound on the magnitude of the entries of the gains ``L_i`` (``≥ 0``).
    integer_data : bool
        Make the entries of ``A`` multiples of ``a_bound/2`` and those of ``C_i`` lie in
        {−1, 0, 1} (exact arithmetic stays small).

    Returns
    -------
    SearchStrategy of DkfProblem

    Raises
    ------
    InvalidArgument
        At call time, for impossible bounds.
    """
    _check_range("min_states", min_states, "max_states", max_states, 1)
    _check_range("min_agents", min_agents, "max_agents", max_agents, 1)
    if max_rows < 0 or not a_bound > 0 or not gain_bound >= 0:
        raise InvalidArgument(
            "need max_rows ≥ 0, a_bound > 0, gain_bound ≥ 0; "
            f"got {max_rows}, {a_bound}, {gain_bound}"
        )

    def build(seed: int) -> DkfProblem:
        rng = np.random.default_rng(seed)
        n = int(rng.integers(min_states, max_states + 1))
        N = int(rng.integers(min_agents, max_agents + 1))
        rows = [int(rng.integers(0, max_rows + 1)) for _ in range(N)]
        if integer_data:
            A = rng.integers(-2, 3, (n, n)).astype(float) / 2 * a_bound
            C = tuple(rng.integers(-1, 2, (p, n)).astype(float) for p in rows)
        else:
            A = rng.uniform(-a_bound, a_bound, (n, n))
            C = tuple(rng.uniform(-1, 1, (p, n)) for p in rows)
        W = _directed_weights(rng, N, 0.1)
        L = tuple(rng.uniform(-gain_bound, gain_bound, (n, p)) for p in rows)
        return DkfProblem(seed, A, C, W, L)

    return st.integers(0, 2**32 - 1).map(build)


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

    The degenerate families are exact up to floating-point rounding of the coordinates.

    Parameters
    ----------
    dim : int
        2 or 3.
    min_agents, max_agents : int
        Bounds on the number of receivers (``2 ≤ min_agents ≤ max_agents``).
    family : str
        One of :data:`SCENE_FAMILIES`: ``general`` (random points, receivers at least
        ``min_separation·scale`` from the target), ``coplanar`` (3D: receivers in a plane,
        target off it), ``cone`` (3D: receivers on a circular cone with apex at the target — the
        stacked TDOA Jacobian loses rank there), ``target-in-plane`` (3D: receivers and target in
        one plane).
    scale : float
        Length scale (``> 0``): the target is drawn in ``[−scale, scale]^dim`` and the receivers'
        offsets from it (in-plane offsets, for the planar families) are shorter than ``scale``.
    min_separation : float
        Those offsets are at least ``min_separation·scale`` long (``0 < min_separation < 1``).

    Returns
    -------
    SearchStrategy of TdoaScene

    Raises
    ------
    InvalidArgument
        For an unknown ``dim`` or ``family``, a 3D family with ``dim=2``, or impossible bounds.
    """
    if dim not in (2, 3):
        raise InvalidArgument(f"dim={dim}; expected 2 or 3")
    if family not in SCENE_FAMILIES:
        raise InvalidArgument(f"family={family!r}; expected one of {SCENE_FAMILIES}")
    if family != "general" and dim != 3:
        raise InvalidArgument(f"family={family!r} is a 3D family; use dim=3")
    _check_range("min_agents", min_agents, "max_agents", max_agents, 2)
    if not scale > 0 or not 0 < min_separation < 1:
        raise InvalidArgument(
            f"scale={scale} must be > 0 and min_separation={min_separation} in (0, 1)"
        )
    n = draw(st.integers(min_agents, max_agents))
    rng = draw(_seeds())
    target = rng.uniform(-scale, scale, dim)
    frame = _orthonormal(rng, dim)
    radii = rng.uniform(min_separation, 1.0, n) * scale
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    if family == "general":
        directions = rng.standard_normal((n, dim))
        offsets = directions / np.linalg.norm(directions, axis=1, keepdims=True) * radii[:, None]
    elif family == "cone":
        half_angle = rng.uniform(0.2, 1.3)
        local = np.column_stack(
            [
                np.full(n, np.cos(half_angle)),
                np.sin(half_angle) * np.cos(angles),
                np.sin(half_angle) * np.sin(angles),
            ]
        )
        offsets = (local @ frame.T) * radii[:, None]
    else:
        height = 0.0 if family == "target-in-plane" else rng.uniform(0.2, 1.0) * scale
        local = np.column_stack(
            [np.full(n, -height), radii * np.cos(angles), radii * np.sin(angles)]
        )
        offsets = local @ frame.T
    return TdoaScene(target, target + offsets, family)


def is_connected(hears: np.ndarray, *, strongly: bool = False) -> bool:
    """Whether the "hears" graph is (strongly) connected — used to test :func:`networks`.

    Parameters
    ----------
    hears : ndarray of bool, shape (N, N)
        ``hears[r, s]``: agent ``r`` receives from agent ``s``.
    strongly : bool
        Ask for strong connectivity; otherwise weak connectivity is enough.

    Returns
    -------
    bool
    """
    graph = nx.from_numpy_array(hears.T.astype(int), create_using=nx.DiGraph)
    return nx.is_strongly_connected(graph) if strongly else nx.is_weakly_connected(graph)
