"""Distributed TDOA observability of every agent of a network (seed 000 §4.2.2, Thm 4.2.3).

For each agent ``i`` the library reports the rank of ``O_i``, the block column of the networked
observability matrix (seed 000 eq. (4.36)) belonging to ``i``, decided *without* forming it:

    rank O_i = 2 · rank G_{R(i)},

where ``R(i)`` is the set of agents that receive agent ``i``'s information (``[W^l]_{ji} > 0`` for
some ``l``: the connected component for an undirected graph, the downstream reachable set for a
directed one) and ``G_{R(i)}`` stacks the position blocks of their TDOA Jacobians ``H_j``
(eqs. (4.7)–(4.10)). The proof (``docs/topology.md``) needs only ``T ≠ 0``, ``W ≥ 0`` and
``w_ii > 0``. The networked pair is detectable iff its eigenvalue 1 (the only one on the unit
circle) passes the PBH test, which for an undirected graph means every component's ``G`` has
rank ``d``; the full rank of ``O`` comes from the spectrum of ``W`` per component
(:mod:`~theory.tdoa.observability.spectral`), for components of more than
:data:`SPECTRAL_MAX_AGENTS` agents from the blind agents' invariant subspace and the inertia of
``W`` (:mod:`~theory.tdoa.observability.sparse_rank`), or, for weights that are not
symmetrizable, from the dense matrix of :mod:`~theory.tdoa.observability.network`.

Beside the exact verdict the paper's heuristic (a component of ≥ 4 non-coplanar agents; ≥ 3
non-collinear in 2-D) is reported with a one-line reason wherever the two disagree; receivers in a
common hyperplane are flagged ``mirror_ambiguous``; and a separate global-uniqueness check
(:mod:`~theory.tdoa.geometry.uniqueness`) looks for a second position with the same TDOAs.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

from theory.core.observability import RANK_TOL, RankResult, numeric_rank
from theory.core.sparse_weights import SparseWeights
from theory.core.tolerances import CLUSTER_TOL, INCONCLUSIVE_FACTOR, UNIQUENESS_TOL
from theory.core.validation import check_estimate
from theory.tdoa.case import TdoaSpec
from theory.tdoa.geometry.exact import (
    exact_affine_rank,
    exact_direction_rank,
    exact_mirror,
    rational_points,
    same_ray_pair,
)
from theory.tdoa.geometry.uniqueness import Uniqueness, tdoa_solutions
from theory.tdoa.model import cv_discrete, unit_directions
from theory.tdoa.observability.network import analyze_network
from theory.tdoa.observability.sparse_rank import sparse_network_rank
from theory.tdoa.observability.spectral import (
    eigenspace_defects,
    spectral_network_rank,
    symmetrizing_scale,
)

if TYPE_CHECKING:
    import networkx as nx

__all__ = [
    "DENSE_MAX_STATES",
    "SPECTRAL_MAX_AGENTS",
    "AgentVerdict",
    "NetworkVerdict",
    "TopologyResult",
    "analyze_topology",
    "check_topology_cost",
    "observed_values",
]


DENSE_MAX_STATES = 240
"""Largest component (in states 2·d·n) whose non-symmetrizable W is ranked densely."""

SPECTRAL_MAX_AGENTS = 500
"""Largest component whose symmetrizable W is ranked by its eigen-decomposition; larger ones
by the blind agents' invariant subspace and the inertia of W (:mod:`.sparse_rank`)."""


@dataclass(frozen=True)
class AgentVerdict:
    """What one agent can localize (1-based ``id`` and ``component`` as users see them).

    ``reach`` are the agents whose rows enter ``O_i`` (``R(i)``, one tuple shared by the agents of
    a reach set, ``reach_set`` its 1-based index in the record); ``rank`` is ``rank O_i`` at the
    actual geometry (``2d`` when ``observable``); ``sigma_min`` the smallest singular value of
    ``G_{R(i)}`` (zero-padded to ``d``) and ``margin`` how many times the rank decision clears
    ``rank_tol · σ_max``. ``heuristic_4_noncoplanar`` is the paper's condition and ``reason`` says
    why it and the exact verdict disagree. ``mirror_ambiguous``: the receivers lie in a hyperplane
    missing the target, whose reflection ``mirror_point`` has the same TDOAs. ``localizes``: every
    closed class upstream of ``i`` (agents hearing only among themselves whose information reaches
    ``i``) has a stacked Jacobian of rank ``d`` (undirected: the same as ``observable``)."""

    id: int
    component: int
    reach: tuple[int, ...]
    reach_set: int
    rank: int
    observable: bool
    sigma_min: float
    margin: float
    heuristic_4_noncoplanar: bool
    reason: str
    mirror_ambiguous: bool
    mirror_point: tuple[float, ...] | None
    uniqueness: Uniqueness
    localizes: bool


@dataclass(frozen=True)
class NetworkVerdict:
    """The networked pair ``(W ⊗ A, D_H)`` (seed 000 eqs. (4.24), (4.36)).

    ``rank`` (summed over components) and ``observable`` are ``None`` when no method applies
    (``note`` says why); ``detectable`` (PBH at the eigenvalue 1) is always computed. ``method``
    says how the rank was decided (``spectral``/``dense`` per component, or ``skipped``);
    ``margin`` is the least factor by which a deciding singular value clears
    ``rank_tol · σ_max``."""

    rank: int | None
    n_states: int
    observable: bool | None
    detectable: bool
    unobservable_eigenvalues: tuple[complex, ...] | None
    method: str
    margin: float
    note: str = ""


@dataclass(frozen=True)
class TopologyResult:
    """Per-agent and network verdicts of one TDOA scene at 1-based ``step``, with the tolerances
    used and one line per decision within ``inconclusive_factor`` of its threshold."""

    step: int
    dim: int
    agents: tuple[AgentVerdict, ...]
    network: NetworkVerdict
    information_flow: str
    tolerances: dict[str, float] = field(default_factory=dict)
    inconclusive: tuple[str, ...] = ()

    @property
    def conclusive(self) -> bool:
        """Whether every deciding singular value clears its tolerance."""
        return not self.inconclusive

    @property
    def every_agent_localizes(self) -> bool:
        """Every agent's distributed filter can converge (undirected: the pair is detectable)."""
        return all(agent.localizes for agent in self.agents)

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert topology --json`` record of the step (plus evidence fields).

        ``O(N)``: each component's members and each reach set are listed once, at the top
        (``component_members``, ``reach_sets``); an agent names its ``component`` and
        ``reach_set`` by 1-based index.
        """
        net = self.network
        return {
            "step": self.step,
            "dim": self.dim,
            "agents": [_agent_json(a) for a in self.agents],
            "component_members": _members(self.agents, lambda a: a.component),
            "reach_sets": _reach_sets(self.agents),
            "network_rank": net.rank,
            "network_states": net.n_states,
            "network_observable": net.observable,
            "network_detectable": net.detectable,
            "unobservable_eigenvalues": (
                None if net.unobservable_eigenvalues is None else list(net.unobservable_eigenvalues)
            ),
            "network_method": net.method,
            "network_margin": net.margin,
            "network_note": net.note,
            "network_conclusive": net.margin >= self.tolerances["inconclusive_factor"],
            "information_flow": self.information_flow,
            "tolerances": dict(self.tolerances),
            "conclusive": self.conclusive,
            "inconclusive": list(self.inconclusive),
        }


def analyze_topology(
    spec: TdoaSpec,
    step: int = 0,
    *,
    rank_tol: float = RANK_TOL,
    inconclusive_factor: float = INCONCLUSIVE_FACTOR,
    uniqueness_tol: float = UNIQUENESS_TOL,
    cluster_tol: float = CLUSTER_TOL,
    network_rank: bool = True,
) -> TopologyResult:
    """Decide, for every agent, whether it can localize the target at 0-based ``step``.

    Every per-agent rank, the paper's coplanarity heuristic and the mirror ambiguity are decided in
    exact arithmetic on the coordinates as written (:mod:`~theory.tdoa.geometry.exact`); the float
    singular values are reported beside them. A rank full exactly but within
    ``inconclusive_factor`` of ``rank_tol · σ_max`` in floats makes the result inconclusive; so
    does a float-only decision (directed detectability, the network rank) inside its band.
    ``network_rank=False`` skips the rank of the whole ``O`` (cubic in a component's size); the
    per-agent verdicts and detectability, linear in ``N + E``, are always computed. Seed 000
    §4.2.2, eqs. (4.24), (4.36), Thm 4.2.3; seed 001."""
    tol = {"rank_tol": rank_tol, "inconclusive_factor": inconclusive_factor}
    scene = _scene(spec, step)
    doubts: list[str] = []
    groups = _agent_groups(scene, tol, uniqueness_tol, doubts)
    agents = _agent_verdicts(scene, groups, tol, doubts)
    detectable = _detectability(scene, groups, tol, doubts)
    network = (
        _network_verdict(spec, scene, detectable, tol, cluster_tol)
        if network_rank
        else _skipped_network(spec, detectable)
    )
    flow = _UNDIRECTED_FLOW if scene.symmetric else _DIRECTED_FLOW
    tolerances = {**tol, "uniqueness_tol": uniqueness_tol, "cluster_tol": cluster_tol}
    return TopologyResult(step + 1, spec.dim, agents, network, flow, tolerances, tuple(doubts))


def check_topology_cost(spec: TdoaSpec, *, network_rank: bool = True) -> None:
    """Refuse, before any work, a scene whose analysis exceeds the limits ``memory_bytes`` or
    ``work`` (:mod:`theory.core.validation`), counting what it will compute.

    The per-agent verdicts and detectability keep the TDOA rows: ``M`` rows of ``d`` floats and
    two indices, ``8(d + 2)·M`` bytes (twice, for the rows grouped by component). The network
    rank adds, per component of ``n ≤`` :data:`SPECTRAL_MAX_AGENTS` agents, an
    eigen-decomposition of its ``W`` (:mod:`~theory.tdoa.observability.spectral`): about
    ``3·8·n²`` bytes and ``10·n³`` operations for the largest such component of any step;
    larger components are ranked by :mod:`~theory.tdoa.observability.sparse_rank`, whose
    blind-agent matrices are checked against the limit when their size is known. Each
    refusal names ``--no-network-rank``, which skips that part.
    """
    rows = max(links.count for links in spec.links)
    memory = 16.0 * (spec.dim + 2) * rows
    what = f"16 B × (d + 2)·M, M = {rows} TDOA rows"
    check_estimate("memory_bytes", memory, "tdoa.agents", what)
    if not network_rank:
        return
    sizes = np.concatenate([np.bincount(w.component_labels()) for w in spec.links])
    largest = int(sizes[sizes <= SPECTRAL_MAX_AGENTS].max(initial=0))
    skip = (
        "Pass --no-network-rank for every agent's verdict and the detectability without the "
        "rank of the whole networked O (those are linear in N + E)."
    )
    check_estimate(
        "memory_bytes",
        memory + 24.0 * largest**2,
        "tdoa.agents",
        f"{what} + 24 B × n², n = {largest} in the largest component ranked by eigenvalues",
        alternative=skip,
    )
    check_estimate(
        "work",
        10.0 * largest**3,
        "tdoa.agents",
        f"10 n³ to diagonalize W, n = {largest} in the largest component ranked by eigenvalues",
        alternative=skip,
    )


_UNDIRECTED_FLOW = "undirected: O_i sees agent i's connected component"
_DIRECTED_FLOW = (
    "directed: O_i sees the agents reachable from i along information flow (j hears … hears "
    "i); components shown are weakly connected"
)


def _skipped_network(spec: TdoaSpec, detectable: tuple[bool, float]) -> NetworkVerdict:
    """The network verdict without its rank (``network_rank=False``): detectability only."""
    return NetworkVerdict(
        None,
        2 * spec.dim * spec.n_agents,
        None,
        detectable[0],
        None,
        "skipped",
        detectable[1],
        "network rank not requested",
    )


def observed_values(result: TopologyResult) -> dict[str, Any]:
    """What ``result`` says for each static key a tdoa case's ``expect`` block may name."""
    got = result.to_json()
    return {
        "observable": [a["observable"] for a in got["agents"]],
        "heuristic_4_noncoplanar": [a["heuristic_4_noncoplanar"] for a in got["agents"]],
        "mirror_ambiguous": [a["mirror_ambiguous"] for a in got["agents"]],
        "network_rank": got["network_rank"],
        "network_observable": got["network_observable"],
        "network_detectable": got["network_detectable"],
    }


@dataclass(frozen=True)
class _Rows:
    """All TDOA rows of a scene: row ``k`` is ``g_{agent[k]} − g_{other[k]}``."""

    agent: np.ndarray
    other: np.ndarray
    vectors: np.ndarray


@dataclass(frozen=True)
class _Scene:
    """One step of a scene, with everything the verdicts share (rows, components, rationals)."""

    spec: TdoaSpec
    positions: np.ndarray
    target: np.ndarray
    W: SparseWeights
    rows: _Rows
    parts: list[list[int]]
    component_of: np.ndarray
    part_rows: list[np.ndarray]
    symmetric: bool
    exact_positions: list[list[Fraction]]
    exact_target: list[Fraction]

    @property
    def dim(self) -> int:
        return self.positions.shape[1]


@dataclass(frozen=True)
class _RankDecision:
    """The rank of a stacked TDOA Jacobian: exact, with the float SVD beside it.

    ``rank`` is the exact rank (:func:`~theory.tdoa.geometry.exact.exact_direction_rank`);
    ``doubt`` says why the verdict is inconclusive (full rank exactly, but the float singular
    value within ``inconclusive_factor`` of ``rank_tol · σ_max``), ``None`` when it is not.
    """

    rank: int
    numeric: RankResult
    doubt: str | None

    @property
    def margin(self) -> float:
        """∞ when settled (exactly rank-deficient, or full and well-conditioned)."""
        return float("inf") if self.doubt is None else self.numeric.margin


@dataclass(frozen=True)
class _Group:
    reach: tuple[int, ...]
    decision: _RankDecision
    sigma_min: float
    heuristic: bool
    mirror: tuple[float, ...] | None
    uniqueness: Uniqueness
    reason: str
    dim: int

    def for_agent(
        self, agent: int, component: int, reach_set: int, localizes: bool
    ) -> AgentVerdict:
        rank = 2 * self.decision.rank
        return AgentVerdict(
            agent + 1,
            component,
            self.reach,
            reach_set,
            rank,
            rank == 2 * self.dim,
            self.sigma_min,
            self.decision.numeric.margin,
            self.heuristic,
            self.reason,
            self.mirror is not None,
            self.mirror,
            self.uniqueness,
            localizes,
        )


def _scene(spec: TdoaSpec, step: int) -> _Scene:
    """The shared data of step ``step``: TDOA rows, components, exact coordinates."""
    positions, target, W = spec.agents[step], spec.target[step], spec.links[step]
    rows = _tdoa_rows(positions, target, W)
    parts, component_of = _components(W)
    return _Scene(
        spec,
        positions,
        target,
        W,
        rows,
        parts,
        component_of,
        _rows_by_part(rows, component_of, len(parts)),
        W.symmetric(),
        rational_points(positions),
        rational_points([target])[0],
    )


def _agent_groups(
    scene: _Scene, tol: dict[str, float], uniqueness_tol: float, doubts: list[str]
) -> list[tuple[list[int], _Group]]:
    """Agents sharing a reach set ``R(i)`` (a component, or a strongly connected class) and the
    verdict on their stacked Jacobian."""
    reach_groups = [(p, p) for p in scene.parts] if scene.symmetric else _reach_groups(scene.W)
    out = []
    for members, reach in reach_groups:
        k = int(scene.component_of[members[0]])
        selected = (
            scene.part_rows[k]
            if scene.symmetric
            else np.flatnonzero(np.isin(scene.rows.agent, reach))
        )
        group = _group_verdict(scene, selected, reach, scene.parts[k], tol, uniqueness_tol)
        if group.decision.doubt:
            doubts.append(group.decision.doubt)
        out.append((members, group))
    return out


def _agent_verdicts(
    scene: _Scene,
    groups: list[tuple[list[int], _Group]],
    tol: dict[str, float],
    doubts: list[str],
) -> tuple[AgentVerdict, ...]:
    """Each agent's verdict; ``localizes`` from the closed classes upstream of it."""
    if scene.symmetric:
        leaders = {i: [g.decision] for members, g in groups for i in members}
    else:
        leaders = _upstream_leaders(scene, tol, doubts)
    agents: list[AgentVerdict | None] = [None] * scene.spec.n_agents
    for index, (members, group) in enumerate(groups, start=1):
        for i in members:
            ok = all(decision.rank == scene.dim for decision in leaders[i])
            agents[i] = group.for_agent(i, int(scene.component_of[i]) + 1, index, ok)
    return tuple(agents)  # type: ignore[arg-type]


def _detectability(
    scene: _Scene,
    groups: list[tuple[list[int], _Group]],
    tol: dict[str, float],
    doubts: list[str],
) -> tuple[bool, float]:
    """PBH at the eigenvalue 1 (seed 000 eq. (4.24)): exact per component when undirected."""
    if scene.symmetric:
        decisions = [g.decision for _, g in groups]
        return (
            all(d.rank == scene.dim for d in decisions),
            min((d.margin for d in decisions), default=float("inf")),
        )
    detectable = _directed_detectable(scene.W, scene.rows, tol["rank_tol"])
    if detectable[1] < tol["inconclusive_factor"]:
        doubts.append(f"detectability: a singular value within a factor {detectable[1]:.3g}")
    return detectable


def _tdoa_rows(positions: np.ndarray, target: np.ndarray, W: SparseWeights) -> _Rows:
    units = unit_directions(target, positions)
    agent, other = W.receiver, W.sender
    return _Rows(agent, other, units[agent] - units[other])


def _components(W: SparseWeights) -> tuple[list[list[int]], np.ndarray]:
    """Weakly connected components ordered by first agent, and each agent's component index.

    The partition of :func:`theory.core.network.components`, in ``O((N + E) log N)``.
    """
    labels = W.component_labels()
    roots, component_of = np.unique(labels, return_inverse=True)  # roots: first agents, sorted
    order = np.argsort(component_of, kind="stable")
    pieces = np.split(order, np.cumsum(np.bincount(component_of, minlength=len(roots)))[:-1])
    return [piece.tolist() for piece in pieces], component_of


def _condensation(W: SparseWeights) -> nx.DiGraph:
    """The strongly connected classes of the information flow (``s → r`` when ``r`` hears ``s``)."""
    import networkx as nx  # directed networks only

    flow = nx.DiGraph()
    flow.add_nodes_from(range(W.n))
    flow.add_edges_from(zip(W.sender.tolist(), W.receiver.tolist(), strict=True))
    return nx.condensation(flow)


def _reach_groups(W: SparseWeights) -> list[tuple[list[int], list[int]]]:
    """Agents of a directed network sharing one reach set ``R(i)``: strongly connected classes."""
    import networkx as nx

    condensed = _condensation(W)
    groups = []
    for node in condensed.nodes:
        members = sorted(condensed.nodes[node]["members"])
        reach = set(members)
        for later in nx.descendants(condensed, node):
            reach |= condensed.nodes[later]["members"]
        groups.append((members, sorted(reach)))
    return sorted(groups, key=lambda g: g[0][0])


def _decide_rank(
    scene: _Scene, stacked: np.ndarray, points: list[int], tol: dict[str, float], who: str
) -> _RankDecision:
    """Exact rank of the stacked rows over the connected set ``points``, float SVD beside it.

    The rows ``u_r − u_s`` connect ``points`` (the receivers and the agents they hear), so their
    rank is ``dim aff{u_j : j ∈ points}``, decided exactly. An exactly deficient rank settles the
    verdict whatever the floats say; a full one is conclusive only when the float singular value
    clears ``inconclusive_factor · rank_tol · σ_max`` (otherwise the geometry is ill-conditioned:
    a relative perturbation of the data of that size loses the rank).
    """
    dim = scene.dim
    numeric = numeric_rank(stacked, rank_tol=tol["rank_tol"]) if stacked.size else _empty(dim)
    if not stacked.size:
        return _RankDecision(0, numeric, None)
    exact = exact_direction_rank(scene.exact_target, [scene.exact_positions[j] for j in points])
    if exact < dim or (numeric.rank == dim and numeric.margin >= tol["inconclusive_factor"]):
        return _RankDecision(exact, numeric, None)
    sigma = numeric.singular_values[dim - 1] if len(numeric.singular_values) >= dim else 0.0
    return _RankDecision(
        exact,
        numeric,
        f"agents {who}: the stacked Jacobian has full rank {dim} in exact arithmetic (the "
        f"coordinates as written) but is ill-conditioned: σ_{dim} = {sigma:.3g} is within a "
        f"factor {numeric.margin:.3g} of rank_tol·σ_max = {numeric.threshold:.3g} (float rank "
        f"{numeric.rank})",
    )


def _group_verdict(
    scene: _Scene,
    inside: np.ndarray,
    reach: list[int],
    part: list[int],
    tol: dict[str, float],
    uniqueness_tol: float,
) -> _Group:
    dim, rows = scene.dim, scene.rows
    receivers = sorted(set(reach) | set(rows.other[inside].tolist()))
    decision = _decide_rank(scene, rows.vectors[inside], receivers, tol, _ids(reach))
    sigma = np.zeros(dim)
    values = decision.numeric.singular_values
    sigma[: min(dim, len(values))] = values[:dim]
    mirror = exact_mirror([scene.exact_positions[j] for j in receivers], scene.exact_target)[1]
    heuristic = (
        len(part) >= dim + 1 and exact_affine_rank([scene.exact_positions[j] for j in part]) == dim
    )
    exact = decision.rank == dim
    uniqueness = (
        tdoa_solutions(
            scene.positions[receivers], scene.target, rank_tol=tol["rank_tol"], tol=uniqueness_tol
        )
        if exact
        else Uniqueness(False, (), dim - decision.rank, "not even locally observable")
    )
    mirror_point = None if mirror is None else tuple(float(v) for v in mirror)
    reason = (
        ""
        if exact == heuristic
        else _disagreement(scene, exact, receivers, part, decision.rank, mirror_point, reach)
    )
    return _Group(
        tuple(j + 1 for j in reach),
        decision,
        float(sigma[-1]),
        heuristic,
        mirror_point,
        uniqueness,
        reason,
        dim,
    )


def _empty(dim: int) -> RankResult:
    return RankResult(0, (0.0,) * dim, 0.0, RANK_TOL, float("inf"))


def _disagreement(
    scene: _Scene,
    exact: bool,
    receivers: list[int],
    part: list[int],
    rank: int,
    mirror: tuple[float, ...] | None,
    reach: list[int],
) -> str:
    dim = scene.dim
    flat = "coplanar" if dim == 3 else "collinear"
    if exact:
        return (
            f"the agents are {flat} but the target is off their "
            f"{'plane' if dim == 3 else 'line'}: the Jacobian has full rank (locally "
            f"observable), yet the mirror image {_fmt(mirror)} gives the same TDOAs"
        )
    if set(reach) != set(part):
        return (
            f"directed network: only agents {_ids(reach)} receive this agent's information, "
            f"and their TDOA rows have rank {rank} < {dim}"
        )
    same = same_ray_pair(scene.exact_target, [scene.exact_positions[j] for j in receivers])
    if same:
        a, b = receivers[same[0]] + 1, receivers[same[1]] + 1
        return f"agents {a} and {b} lie on one ray from the target: rank {rank} < {dim}"
    where = "a circular cone with apex at the target" if dim == 3 else "two rays from the target"
    return (
        f"the agents are not {flat}, but the directions from the target to them are affinely "
        f"dependent (the receivers lie on {where}): stacked Jacobian rank {rank} < {dim}"
    )


def _network_verdict(
    spec: TdoaSpec,
    scene: _Scene,
    detectable: tuple[bool, float],
    tol: dict[str, float],
    cluster_tol: float,
) -> NetworkVerdict:
    dim, n = spec.dim, spec.n_agents
    rank, eigenvalues, methods, notes = 0, [], set(), []
    margin = detectable[1]
    for part, selected in zip(scene.parts, scene.part_rows, strict=True):
        piece = _component_rank(spec, scene.W, scene.rows, part, selected, tol, cluster_tol)
        if piece is None:
            notes.append(
                f"component {_ids(part)}: W is not symmetrizable and has "
                f"{2 * dim * len(part)} > {DENSE_MAX_STATES} states, or the factorization "
                "counting dim ker W failed its backward-error check; rank not computed"
            )
            rank = None
            continue
        part_rank, part_eigs, method, part_margin = piece
        methods.add(method)
        margin = min(margin, part_margin)
        if rank is not None:
            rank += part_rank
        eigenvalues += part_eigs
    observable = None if rank is None else rank == 2 * dim * n
    return NetworkVerdict(
        rank,
        2 * dim * n,
        observable,
        detectable[0],
        None if rank is None else tuple(eigenvalues),
        " + ".join(sorted(methods)) + " (per component; O is block-diagonal over components)",
        float(margin),
        "; ".join(notes),
    )


def _upstream_leaders(
    scene: _Scene, tol: dict[str, float], doubts: list[str]
) -> dict[int, list[_RankDecision]]:
    """For each agent, the stacked-Jacobian ranks of the closed classes upstream of it.

    A closed class hears only its own members, so its error dynamics are autonomous and it can
    localize iff its own stacked Jacobian has rank ``d``; every other agent's error is driven by
    the closed classes upstream of it through ``W_TT ⊗ A``, which is stable (``ρ(W_TT) < 1``).
    """
    import networkx as nx

    condensed = _condensation(scene.W)
    ranks = {}
    for node in condensed:
        if condensed.in_degree(node) == 0:
            members = sorted(condensed.nodes[node]["members"])
            stacked = scene.rows.vectors[np.isin(scene.rows.agent, members)]
            ranks[node] = _decide_rank(
                scene, stacked, members, tol, f"closed class {_ids(members)}"
            )
            if ranks[node].doubt:
                doubts.append(ranks[node].doubt)
    mapping = condensed.graph["mapping"]
    upstream: dict[int, list[_RankDecision]] = {}
    for agent in range(scene.W.n):
        node = mapping[agent]
        above = nx.ancestors(condensed, node) | {node}
        upstream[agent] = [ranks[c] for c in sorted(above) if c in ranks]
    return upstream


def _rows_by_part(rows: _Rows, component_of: np.ndarray, count: int) -> list[np.ndarray]:
    """Row indices of each component, in one sort (linear-time grouping)."""
    labels = component_of[rows.agent]
    order = np.argsort(labels, kind="stable")
    bounds = np.searchsorted(labels[order], np.arange(count + 1))
    return [order[bounds[k] : bounds[k + 1]] for k in range(count)]


def _directed_detectable(W: SparseWeights, rows: _Rows, rank_tol: float) -> tuple[bool, float]:
    """PBH at the eigenvalue 1 of ``W ⊗ A`` (the only one with ``|λ| ≥ 1``).

    Its eigenvectors are the absorption probabilities of the closed classes (agents that hear
    only among themselves); for an undirected graph they are the component indicators and the
    test reduces to "every component's stacked Jacobian has rank d".
    """
    basis = _unit_eigenvectors(W)
    defects, margin = eigenspace_defects([basis], rows.agent, rows.vectors, rank_tol=rank_tol)
    return defects[0] == 0, margin


def _unit_eigenvectors(W: SparseWeights) -> np.ndarray:
    """Right eigenvectors of a row-stochastic ``W`` (``w_ii > 0``) for eigenvalue 1."""
    import networkx as nx

    graph = nx.DiGraph(zip(W.receiver.tolist(), W.sender.tolist(), strict=True))
    graph.add_nodes_from(range(W.n))
    condensed = nx.condensation(graph)
    closed = [
        sorted(condensed.nodes[c]["members"]) for c in condensed if condensed.out_degree(c) == 0
    ]
    in_closed = np.zeros(W.n, dtype=bool)
    for members in closed:
        in_closed[members] = True
    transient = np.flatnonzero(~in_closed)
    basis = np.zeros((W.n, len(closed)))
    for k, members in enumerate(closed):
        basis[members, k] = 1.0
        if transient.size:
            rhs = W.block(transient, members).sum(axis=1)
            lhs = np.eye(transient.size) - W.block(transient)
            basis[transient, k] = np.linalg.solve(lhs, rhs)
    return basis


def _component_rank(
    spec: TdoaSpec,
    W: SparseWeights,
    rows: _Rows,
    part: list[int],
    selected: np.ndarray,
    tol: dict[str, float],
    cluster_tol: float,
) -> tuple[int, list[complex], str, float] | None:
    local = np.full(W.n, -1)
    local[part] = np.arange(len(part))
    W_part = W.restrict(part)
    scale = symmetrizing_scale(W_part)
    if scale is not None and len(part) > SPECTRAL_MAX_AGENTS:
        result = sparse_network_rank(
            W_part,
            local[rows.agent[selected]],
            rows.vectors[selected],
            scale=scale,
            rank_tol=tol["rank_tol"],
            cluster_tol=cluster_tol,
            inconclusive_factor=tol["inconclusive_factor"],
        )
        if result is None:
            return None
        eigs = [complex(v) for v in result.unobservable_eigenvalues]
        return result.rank, eigs, "sparse", result.margin
    if scale is not None:
        result = spectral_network_rank(
            W_part.dense(),
            local[rows.agent[selected]],
            rows.vectors[selected],
            scale=scale,
            rank_tol=tol["rank_tol"],
            cluster_tol=cluster_tol,
        )
        eigs = [complex(v) for v in result.unobservable_eigenvalues]
        return result.rank, eigs, "spectral", result.margin
    if 2 * spec.dim * len(part) > DENSE_MAX_STATES:
        return None
    return _dense_rank(spec, W_part.dense(), rows, part, tol["rank_tol"])


def _dense_rank(
    spec: TdoaSpec,
    W_part: np.ndarray,
    rows: _Rows,
    part: list[int],
    rank_tol: float,
) -> tuple[int, list[complex], str, float]:
    A, _ = cv_discrete(spec.T, spec.dim)
    blocks = []
    for j in part:
        vectors = rows.vectors[rows.agent == j]
        blocks.append(np.hstack([vectors, np.zeros_like(vectors)]))
    result = analyze_network(A, W_part, blocks, rank_tol=rank_tol)
    eigs = [complex(v) for v in result.unobservable_eigenvalues]
    return result.network_rank, eigs, "dense", float(result.margin)


def _agent_json(agent: AgentVerdict) -> dict[str, Any]:
    unique = agent.uniqueness
    return {
        "id": agent.id,
        "component": agent.component,
        "rank": agent.rank,
        "observable": agent.observable,
        "localizes": agent.localizes,
        "heuristic_4_noncoplanar": agent.heuristic_4_noncoplanar,
        "sigma_min": agent.sigma_min,
        "mirror_ambiguous": agent.mirror_ambiguous,
        "mirror_point": agent.mirror_point,
        "reach_set": agent.reach_set,
        "margin": agent.margin,
        "agrees_with_heuristic": not agent.reason,
        "reason": agent.reason,
        "unique_solution": unique.unique,
        "other_solutions": [list(p) for p in unique.solutions],
        "uniqueness_note": unique.note,
        "uniqueness_method": unique.method,
    }


def _members(agents: tuple[AgentVerdict, ...], index: Any) -> list[list[int]]:
    """The 1-based ids of the agents with ``index(agent)`` = 1, 2, …, in one pass."""
    listed: list[list[int]] = []
    for agent in agents:
        k = index(agent)
        listed.extend([] for _ in range(k - len(listed)))
        listed[k - 1].append(agent.id)
    return listed


def _reach_sets(agents: tuple[AgentVerdict, ...]) -> list[list[int]]:
    """Each reach set ``R(i)`` once (1-based ids), in ``reach_set`` order."""
    sets: dict[int, list[int]] = {}
    for agent in agents:
        if agent.reach_set not in sets:
            sets[agent.reach_set] = list(agent.reach)
    return [sets[k] for k in sorted(sets)]


def _ids(agents: list[int] | tuple[int, ...]) -> str:
    return "{" + ", ".join(str(a + 1) for a in agents) + "}"


def _fmt(point: tuple[float, ...] | None) -> str:
    return "-" if point is None else "[" + ", ".join(f"{v:.4g}" for v in point) + "]"
