"""The two TDOA case kinds: ``kind: tdoa`` (a scene) and ``kind: tdoa-sim`` (a closed loop).

``tdoa:`` block (seed 000 ch. 4)::

    T: 1.0                     # ping period (s), > 0; required (a physical quantity)
    dim: 3                     # 2 or 3; default: inferred from the coordinates
    agents: [[x, y, z], ...]   # N × dim, or a trajectory: steps × N × dim
    target: [x, y, z]          # dim, or a trajectory: steps × dim
    edges: [[1, 2], ...]       # 1-based pairs; or comm_range: 21 (strict "<")
    directed: false            # with edges: [s, r] means s sends to r
    weights: metropolis        # metropolis | uniform | an explicit N × N matrix

With an explicit matrix and neither ``edges`` nor ``comm_range``, the edges are read off the
matrix's support (directed if it is not symmetric).

``tdoa-sim:`` block (seed 000 §4.4 defaults in brackets)::

    agents: [[x, y, z], ...]     # initial positions, N × 3 (required)
    target: [17, -5, -15]        # initial target position (required)
    target_velocity: [0, 0, 0]   # initial target velocity [0]
    Q: 0.01                      # white-acceleration covariance: number (· I₃) or 3 × 3
    R: 1.0                       # TDOA noise variance r, R_i = r I_{|N_i|}
    T: 1.0                       # ping period (s) [1]
    tau: 0.1                     # consensus period (s); T/tau must be an integer [T]
    P0: 100                      # initial covariance: number (· I₆) or 6 × 6
    x0: [0, 0, 0, 0, 0, 0]       # initial estimate of every agent [0]
    b: 0                         # movement threshold: move iff ‖P_i‖ > b; .inf never moves
    edges: [[1, 2], ...]         # fixed undirected topology (1-based), or
    comm_range: 21               # distance rule "closer than comm_range" (re-evaluated each τ)
    weights: metropolis          # metropolis | uniform | explicit N × N (with edges only)
    filter: averaged             # averaged | decentralized | centralized
    linearize: estimate          # estimate (the EKF) | truth (linearized filter, for checks)
    steps: 100                   # number of pings after the first
    formation: cube              # cube | crown | explicit N × 3 offsets d_i
    formation_radius: 10         # circumradius of the cube / radius of the crown
    formation_height: 5          # half-height of the crown
    pole: 0.5                    # closed-loop pole −λ of the linearized agents (1/s)
    max_input: [2, 2, 2]         # actuator limits |u₁| (m/s³), |u₂|, |u₃| (rad/s²); .inf: none
    substeps: 2                  # Runge–Kutta steps per τ
    cov_norm: spectral           # spectral | frobenius: the norm ‖P_i‖ of the trigger

A tdoa-sim run can be checked against ``bounded_error`` (every agent's final localization error
below ``tolerances.error_bound``) and ``max_final_error``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum
from functools import cached_property
from typing import Any, TypeVar

import numpy as np

from theory.core.case_file import Case, KindSpec
from theory.core.errors import CaseError
from theory.core.network import adjacency_from_edges, pairs_within_range, weights_support
from theory.core.observability import RANK_TOL
from theory.core.sparse_weights import SparseWeights
from theory.core.tolerances import COINCIDENCE_TOL, INCONCLUSIVE_FACTOR, PERIOD_TOL
from theory.core.validation import (
    bounded_coordinates,
    check_count,
    check_estimate,
    check_keys,
    check_length,
    distinct_points,
    finite_array,
    finite_matrix,
    finite_vector,
    one_of,
    positive_definite,
    positive_int,
    positive_number,
    require,
    row_stochastic,
)

__all__ = [
    "TDOA",
    "TDOA_SIM",
    "CovNorm",
    "Filter",
    "Linearize",
    "TdoaSimSpec",
    "TdoaSpec",
    "WeightRule",
    "check_sim_work",
    "check_tdoa_expect",
    "parse_tdoa",
    "parse_tdoa_sim",
    "rank_tolerances",
    "scene_simulation",
]


E = TypeVar("E", bound=StrEnum)


class WeightRule(StrEnum):
    """How a scene's consensus weights are made."""

    METROPOLIS = "metropolis"
    UNIFORM = "uniform"
    EXPLICIT = "explicit"


class Filter(StrEnum):
    """The network filters of seed 000 §4.2 (``trackcert simulate``'s ``filter``)."""

    AVERAGED = "averaged"  # own update, then averaging with neighbours (§4.2.2)
    DECENTRALIZED = "decentralized"  # own update, never averaged (§4.2.1)
    CENTRALIZED = "centralized"  # one EKF on every agent's rows: the baseline


class Linearize(StrEnum):
    """Where a tdoa-sim filter evaluates its Jacobians."""

    ESTIMATE = "estimate"  # the EKF
    TRUTH = "truth"  # at the true target: the Riccati recursion of the linearized system


class CovNorm(StrEnum):
    """The norm ``‖P_i‖`` of the movement trigger."""

    SPECTRAL = "spectral"
    FROBENIUS = "frobenius"


FIELDS = ("T", "dim", "agents", "target", "edges", "comm_range", "directed", "weights")
EXPECT_KEYS = (
    "observable",
    "heuristic_4_noncoplanar",
    "mirror_ambiguous",
    "network_rank",
    "network_observable",
    "network_detectable",
    "first_failure_step",
    "unobservable_steps",
)
TOLERANCE_KEYS = ("rank_tol", "inconclusive_factor", "weight_sum_tol")


@dataclass(frozen=True, eq=False)
class TdoaSpec:
    """A validated TDOA scene; arrays have a leading axis of ``steps`` (1 when static).

    ``links[k]`` is the row-stochastic consensus matrix of step ``k`` held by its entries
    (``O(N + E)``; agent ``r`` receives from agent ``s`` iff ``w_rs > 0``, ``r ≠ s``);
    :attr:`hears` and :attr:`weights` are the same as dense ``steps × N × N`` arrays, made on
    first use; ``comm_range`` is the distance rule, if any.
    """

    T: float
    dim: int
    agents: np.ndarray
    target: np.ndarray
    links: tuple[SparseWeights, ...]
    weights_rule: WeightRule
    directed: bool
    comm_range: float | None

    @cached_property
    def hears(self) -> np.ndarray:
        """``hears[k, r, s]``: agent ``r`` receives from agent ``s`` at step ``k`` (dense; its
        memory, ``steps·N²`` bytes, is checked against the limit first)."""
        self._check_dense(1, "hears")
        return np.stack([links.hears() for links in self.links])

    @cached_property
    def weights(self) -> np.ndarray:
        """``weights[k]``: the consensus matrix ``W`` of step ``k`` (dense; ``8 B × steps·N²``,
        checked against the limit first)."""
        self._check_dense(8, "weights")
        return np.stack([links.dense() for links in self.links])

    def _check_dense(self, size: int, what: str) -> None:
        n, steps = self.n_agents, self.steps
        check_estimate(
            "memory_bytes",
            float(size) * steps * n * n,
            "tdoa.agents",
            f"{size} B × steps·N² for the dense {what} (N = {n} agents, {steps} steps)",
        )

    @property
    def n_agents(self) -> int:
        """Number of agents ``N``."""
        return self.agents.shape[1]

    @property
    def steps(self) -> int:
        """Number of time steps described (1 for a static scene)."""
        return self.agents.shape[0]

    def networks(self) -> list[tuple[int, ...]]:
        """The 0-based steps grouped by network (equal ``hears`` and ``W``), in order."""
        groups: dict[bytes, list[int]] = {}
        for k in range(self.steps):
            groups.setdefault(self.links[k].key(), []).append(k)
        return [tuple(steps) for steps in groups.values()]

    def at_step(self, k: int) -> TdoaSpec:
        """The static scene of step ``k``."""
        return dataclasses.replace(
            self,
            agents=self.agents[k : k + 1],
            target=self.target[k : k + 1],
            links=self.links[k : k + 1],
        )


def required_period(block: Mapping[str, Any], field: str) -> float:
    """The ping period ``T`` of a ``tdoa`` block: required, never defaulted silently."""
    if "T" not in block:
        hint = "The field is required (it is never defaulted); e.g. `T: 1.0`."
        raise CaseError(field, "the ping period in seconds, > 0", "nothing", hint=hint)
    return positive_number(block["T"], field)


def parse_tdoa(block: Mapping[str, Any]) -> TdoaSpec:
    """Validate a ``tdoa:`` block; a :class:`CaseError` names any bad field."""
    check_keys(block, FIELDS, "tdoa")
    T = required_period(block, "tdoa.T")
    agents, target = _positions(block)
    dim = agents.shape[2]
    _check_distinct(agents, target)
    directed = block.get("directed", False)
    if not isinstance(directed, bool):
        raise CaseError("tdoa.directed", "true or false", directed)
    pairs, comm_range = _topology(block, agents, directed)
    _check_memory(pairs, agents.shape[1])
    links, rule = _weights(block.get("weights", "metropolis"), pairs, agents.shape[1], directed)
    return TdoaSpec(T, dim, agents, target, links, rule, directed, comm_range)


def _check_sizes(raw_agents: object, raw_target: object) -> None:
    """Refuse too many agents or steps before any entry is read (:mod:`theory.core.validation`)."""
    nested = isinstance(raw_agents, list) and raw_agents and isinstance(raw_agents[0], list)
    if nested and raw_agents[0] and isinstance(raw_agents[0][0], list):
        check_length(raw_agents, "steps", "tdoa.agents")
        check_length(raw_agents[0], "agents", "tdoa.agents[1]")
    else:
        check_length(raw_agents, "agents", "tdoa.agents")
    if isinstance(raw_target, list) and raw_target and isinstance(raw_target[0], list):
        check_length(raw_target, "steps", "tdoa.target")


def _check_memory(pairs: list[tuple[np.ndarray, np.ndarray]], n: int) -> None:
    """Refuse a scene whose links would exceed the memory budget: the parser keeps, per
    distinct network (a fixed network is one for every step), each link's two indices and
    weight (24 B) and each agent's self-weight (8 B). What a command computes beyond (the network
    rank of ``trackcert topology``) is estimated by that command."""
    distinct = {id(r): int(r.size) for r, _ in pairs}
    links = sum(distinct.values())
    check_estimate(
        "memory_bytes",
        24.0 * links + 8.0 * n * len(distinct),
        "tdoa.agents",
        f"24 B × E + 8 B × N per network for the links and weights (E = {links} links in all, "
        f"N = {n} agents, {len(distinct)} networks)",
    )


def _positions(block: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    raw_agents = require(block, "agents", "tdoa")
    _check_sizes(raw_agents, block.get("target"))
    agents = finite_array(
        raw_agents,
        "tdoa.agents",
        "N points [x, y] or [x, y, z] (or steps × N points)",
        ndims=(2, 3),
    )
    agents = bounded_coordinates(agents, "tdoa.agents")
    agents = agents[None] if agents.ndim == 2 else agents
    dim = agents.shape[2]
    if "dim" in block and block["dim"] != dim:
        raise CaseError(
            "tdoa.dim", f"{dim} (the agents' coordinates have {dim} entries)", block["dim"]
        )
    if dim not in (2, 3):
        raise CaseError("tdoa.agents", "points with 2 or 3 coordinates", f"{dim} coordinates")
    raw_target = require(block, "target", "tdoa")
    expected = f"a point of {dim} coordinates (or steps × {dim})"
    target = finite_array(raw_target, "tdoa.target", expected, ndims=(1, 2))
    target = bounded_coordinates(target, "tdoa.target")
    target = target[None] if target.ndim == 1 else target
    if target.shape[1] != dim:
        raise CaseError("tdoa.target", expected, raw_target)
    steps = max(agents.shape[0], target.shape[0])
    for name, array in (("agents", agents), ("target", target)):
        if array.shape[0] not in (1, steps):
            raise CaseError(
                f"tdoa.{name}", f"{steps} time steps (as the other trajectory)", array.shape[0]
            )
    return np.broadcast_to(agents, (steps, *agents.shape[1:])).copy(), np.broadcast_to(
        target, (steps, dim)
    ).copy()


def _check_distinct(agents: np.ndarray, target: np.ndarray) -> None:
    """Refuse coincident agents, or the target on an agent, at any step (within
    ``coincidence_tol`` of the points' magnitude: seed 000 eq. (4.3) divides by the distance)."""
    static = agents.shape[0] == 1
    for k in range(agents.shape[0]):
        where = "" if static else f" at step {k + 1}"
        distinct_points(agents[k], "tdoa.agents", where=where)
        to_target = np.linalg.norm(agents[k] - target[k], axis=1)
        size = np.maximum(1.0, np.maximum(np.abs(agents[k]).max(axis=1), np.abs(target[k]).max()))
        close = np.flatnonzero(to_target <= COINCIDENCE_TOL * size)
        if close.size:
            raise CaseError(
                "tdoa.target",
                f"a position not on agent {close[0] + 1}{where} (TDOA is undefined there)",
                target[k].tolist(),
            )


def _topology(
    block: Mapping[str, Any], agents: np.ndarray, directed: bool
) -> tuple[list[tuple[np.ndarray, np.ndarray]], float | None]:
    """Each step's links ``(receiver, sender)`` (0-based, both directions of an undirected
    link), and the distance rule if there is one."""
    steps, n, _ = agents.shape
    has_edges, has_range = "edges" in block, "comm_range" in block
    if has_edges and has_range:
        raise CaseError("tdoa.edges", "either edges or comm_range, not both", "both")
    if has_range:
        if directed:
            raise CaseError(
                "tdoa.directed", "false with comm_range (the distance rule is symmetric)", True
            )
        comm_range = positive_number(block["comm_range"], "tdoa.comm_range")
        pairs = []
        for k in range(steps):
            i, j = pairs_within_range(agents[k], comm_range)
            pairs.append((np.concatenate([i, j]), np.concatenate([j, i])))
            _check_memory(pairs, n)
        return pairs, comm_range
    if has_edges:
        edges = _edges(block["edges"], n)
        receiver, sender = np.nonzero(adjacency_from_edges(n, edges, directed=directed))
        return [(receiver, sender)] * steps, None
    if isinstance(block.get("weights"), list):
        matrix = finite_matrix(block["weights"], "tdoa.weights", rows=n, cols=n)
        return [np.nonzero(weights_support(matrix))] * steps, None
    raise CaseError(
        "tdoa.edges",
        "edges (1-based pairs), comm_range, or an explicit weights matrix",
        "none of them",
    )


def _edges(raw: object, n: int) -> np.ndarray:
    if raw == []:
        return np.zeros((0, 2), dtype=int)
    if not isinstance(raw, list) or not all(isinstance(e, list) and len(e) == 2 for e in raw):
        raise CaseError("tdoa.edges", "a list of pairs [i, j] of 1-based agent ids", raw)
    for index, (i, j) in enumerate(raw):
        for agent in (i, j):
            if isinstance(agent, bool) or not isinstance(agent, int) or not 1 <= agent <= n:
                raise CaseError(f"tdoa.edges[{index + 1}]", f"agent ids between 1 and {n}", [i, j])
        if i == j:
            raise CaseError(
                f"tdoa.edges[{index + 1}]", "two different agents (no self-loops)", [i, j]
            )
    return np.asarray(raw, dtype=int) - 1


def _weights(
    raw: object, pairs: list[tuple[np.ndarray, np.ndarray]], n: int, directed: bool
) -> tuple[tuple[SparseWeights, ...], WeightRule]:
    """Each step's consensus weights on its links (``pairs``), by rule or explicit."""
    if raw in (WeightRule.METROPOLIS, WeightRule.UNIFORM):
        made: dict[int, SparseWeights] = {}  # a fixed network: one object for every step
        for r, s in pairs:
            if id(r) not in made:
                made[id(r)] = SparseWeights.named(n, r, s, str(raw))
        steps = tuple(made[id(r)] for r, _ in pairs)
        if raw == WeightRule.METROPOLIS and (directed or not all(w.symmetric() for w in steps)):
            raise CaseError(
                "tdoa.weights",
                "uniform or an explicit matrix for a directed network",
                "metropolis",
                hint="Metropolis weights are defined for undirected graphs.",
            )
        return steps, WeightRule(raw)
    if isinstance(raw, list):
        if len(pairs) > 1 and not all(_same(p, pairs[0]) for p in pairs):
            raise CaseError(
                "tdoa.weights",
                "metropolis or uniform for a time-varying network",
                "an explicit matrix",
            )
        matrix = finite_matrix(raw, "tdoa.weights", rows=n, cols=n)
        support = np.zeros((n, n), dtype=bool)
        support[pairs[0]] = True
        row_stochastic(matrix, "tdoa.weights", support=support)
        return (SparseWeights.from_dense(matrix),) * len(pairs), WeightRule.EXPLICIT
    raise CaseError("tdoa.weights", "metropolis, uniform, or an N × N row-stochastic matrix", raw)


def _same(a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray]) -> bool:
    """Whether two steps have the same set of links."""
    return set(zip(*(x.tolist() for x in a), strict=True)) == set(
        zip(*(x.tolist() for x in b), strict=True)
    )


PER_AGENT_BOOLS = ("observable", "heuristic_4_noncoplanar", "mirror_ambiguous")
FLAGS = ("network_observable", "network_detectable")


def check_tdoa_expect(spec: TdoaSpec, expect: Mapping[str, Any]) -> None:
    """Validate a tdoa ``expect`` block's values against ``spec`` (N agents, the steps)."""
    n = spec.n_agents
    for key, value in expect.items():
        field = f"expect.{key}"
        if key in PER_AGENT_BOOLS and not _list_of(value, bool, n):
            raise CaseError(field, f"a list of {n} true/false values, one per agent", value)
        if key in FLAGS and not isinstance(value, bool):
            raise CaseError(field, "true or false", value)
        if key == "network_rank" and not _count(value):
            raise CaseError(field, "a non-negative integer", value)
        if key == "first_failure_step" and value is not None and not _count(value):
            raise CaseError(field, "a step number (integer) or null", value)
        if key == "unobservable_steps" and not (
            _list_of(value, int, n) and all(0 <= v <= spec.steps for v in value)
        ):
            raise CaseError(field, f"a list of {n} step counts between 0 and {spec.steps}", value)


def _count(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= 0


def _list_of(value: object, kind: type, length: int) -> bool:
    ok = isinstance(value, list) and len(value) == length
    return ok and all(
        isinstance(v, kind) and (kind is bool or not isinstance(v, bool)) for v in value
    )


def rank_tolerances(case: Case) -> dict[str, float]:
    """The case's ``rank_tol`` and ``inconclusive_factor`` (the tolerance table's otherwise)."""
    return {
        "rank_tol": case.tolerances.get("rank_tol", RANK_TOL),
        "inconclusive_factor": case.tolerances.get("inconclusive_factor", INCONCLUSIVE_FACTOR),
    }


TDOA = KindSpec(
    "tdoa",
    parse_tdoa,
    expect_keys=EXPECT_KEYS,
    tolerance_keys=TOLERANCE_KEYS,
    check_expect=check_tdoa_expect,
)
"""The ``tdoa`` case kind."""


SIM = "tdoa-sim"
SIM_FIELDS = (
    "agents",
    "target",
    "target_velocity",
    "Q",
    "R",
    "T",
    "tau",
    "P0",
    "x0",
    "b",
    "edges",
    "comm_range",
    "weights",
    "filter",
    "linearize",
    "steps",
    "formation",
    "formation_radius",
    "formation_height",
    "pole",
    "max_input",
    "substeps",
    "cov_norm",
)


@dataclass(frozen=True, eq=False)
class TdoaSimSpec:
    """A validated closed-loop TDOA scenario (fields in the module docstring).

    ``target`` is the initial state ``[p; ṗ]``; ``b`` is ``math.inf`` for "never move";
    ``hears`` is ``None`` with ``comm_range``; ``weights`` a rule name or an explicit matrix;
    ``offsets`` the formation offsets ``d_i`` of seed 000 eq. (4.45).
    """

    agents: np.ndarray
    target: np.ndarray
    Q: np.ndarray
    r: float
    T: float
    tau: float
    P0: np.ndarray
    x0: np.ndarray
    b: float
    hears: np.ndarray | None
    comm_range: float | None
    weights: WeightRule | np.ndarray
    filter: Filter
    linearize: Linearize
    steps: int
    offsets: np.ndarray
    pole: float
    max_input: tuple[float, float, float]
    substeps: int
    cov_norm: CovNorm

    @property
    def n_agents(self) -> int:
        """Number of agents ``N``."""
        return self.agents.shape[0]

    @property
    def rounds(self) -> int:
        """Consensus rounds per ping, ``T/τ``."""
        return round(self.T / self.tau)


def parse_tdoa_sim(block: Mapping[str, Any]) -> TdoaSimSpec:
    """Validate a ``tdoa-sim:`` block; a :class:`CaseError` names any bad field."""
    check_keys(block, SIM_FIELDS, SIM)
    raw_agents = require(block, "agents", SIM)
    check_length(raw_agents, "agents", f"{SIM}.agents")
    agents = finite_matrix(raw_agents, f"{SIM}.agents", cols=3)
    n = bounded_coordinates(agents, f"{SIM}.agents").shape[0]
    if n < 2:
        raise CaseError(f"{SIM}.agents", "at least 2 agents", n)
    position = finite_vector(require(block, "target", SIM), f"{SIM}.target", length=3)
    bounded_coordinates(position, f"{SIM}.target")
    velocity = finite_vector(
        block.get("target_velocity", [0, 0, 0]), f"{SIM}.target_velocity", length=3
    )
    T = positive_number(block.get("T", 1.0), f"{SIM}.T")
    tau = positive_number(block.get("tau", T), f"{SIM}.tau")
    ratio = T / tau
    if (
        not math.isfinite(ratio)
        or ratio < 1 - PERIOD_TOL
        or abs(ratio - round(ratio)) > PERIOD_TOL * ratio
    ):
        raise CaseError(f"{SIM}.tau", "a period dividing T (T/tau a positive integer)", tau)
    hears, comm_range = _sim_topology(block, n)
    steps = check_count(
        "steps", positive_int(block.get("steps", 100), f"{SIM}.steps"), f"{SIM}.steps"
    )
    substeps = positive_int(block.get("substeps", 2), f"{SIM}.substeps")
    check_sim_work(n, steps, round(ratio), substeps, f"{SIM}.steps")
    return TdoaSimSpec(
        agents=agents,
        target=np.concatenate([position, velocity]),
        Q=_covariance(block.get("Q", 0.01), 3, f"{SIM}.Q"),
        r=positive_number(block.get("R", 1.0), f"{SIM}.R"),
        T=T,
        tau=tau,
        P0=_covariance(block.get("P0", 100.0), 6, f"{SIM}.P0"),
        x0=finite_vector(block.get("x0", [0] * 6), f"{SIM}.x0", length=6),
        b=_threshold(block.get("b", 0.0)),
        hears=hears,
        comm_range=comm_range,
        weights=_sim_weights(block.get("weights", "metropolis"), hears, n),
        filter=_member(Filter, block.get("filter", "averaged"), f"{SIM}.filter"),
        linearize=_member(Linearize, block.get("linearize", "estimate"), f"{SIM}.linearize"),
        steps=steps,
        offsets=_offsets(block, agents),
        pole=positive_number(block.get("pole", 0.5), f"{SIM}.pole"),
        max_input=_limits(block.get("max_input", [2.0, 2.0, 2.0])),
        substeps=substeps,
        cov_norm=_member(CovNorm, block.get("cov_norm", "spectral"), "cov_norm"),
    )


def _member(vocabulary: type[E], value: object, field: str, allowed: tuple[str, ...] = ()) -> E:
    """``value`` as a member of ``vocabulary`` (restricted to ``allowed``), else a CaseError."""
    return vocabulary(one_of(value, allowed or tuple(m.value for m in vocabulary), field))


def check_sim_work(n: int, steps: int, rounds: int, substeps: int, field: str) -> None:
    """Refuse a run whose memory or work exceeds :mod:`theory.core.validation`, naming ``field``.

    Per agent and ping: a 6-state estimate, its 6 × 6 covariance and the 9-state kinematics
    (51 floats, 408 B); per ping: one N × N exchange per round and one RK4 step per substep.
    """
    check_estimate("memory_bytes", 408.0 * n * (steps + 1), field, f"408 B × {n} agents × steps")
    work = float(steps + 1) * rounds * (n * n + substeps * n)
    check_estimate("work", work, field, f"steps × {rounds} rounds × (N² + {substeps} substeps × N)")


def _covariance(value: object, size: int, field: str) -> np.ndarray:
    if isinstance(value, int | float) and not isinstance(value, bool):
        return positive_number(value, field) * np.eye(size)
    return positive_definite(finite_matrix(value, field, rows=size, cols=size), field)


def _threshold(value: object) -> float:
    if isinstance(value, str) and value.strip().lower() in ("inf", ".inf", "infinity"):
        return math.inf
    if isinstance(value, float) and math.isinf(value) and value > 0:
        return math.inf
    return positive_number(value, f"{SIM}.b", allow_zero=True)


def _limits(value: object) -> tuple[float, float, float]:
    field = f"{SIM}.max_input"
    if not isinstance(value, list | tuple) or len(value) != 3:
        raise CaseError(field, "three limits [u1, u2, u3] (numbers or .inf)", value)
    return tuple(_positive_or_inf(v, f"{field}[{k + 1}]") for k, v in enumerate(value))


def _positive_or_inf(value: object, field: str) -> float:
    if isinstance(value, float) and math.isinf(value) and value > 0:
        return math.inf
    return positive_number(value, field)


def _sim_topology(block: Mapping[str, Any], n: int) -> tuple[np.ndarray | None, float | None]:
    has_edges, has_range = "edges" in block, "comm_range" in block
    if has_edges == has_range:
        raise CaseError(f"{SIM}.edges", "exactly one of edges or comm_range", "both or neither")
    if has_range:
        return None, positive_number(block["comm_range"], f"{SIM}.comm_range")
    edges = finite_matrix(block["edges"], f"{SIM}.edges", cols=2, allow_empty_rows=True)
    if edges.size and (np.any(edges != np.round(edges)) or edges.min() < 1 or edges.max() > n):
        raise CaseError(f"{SIM}.edges", f"pairs of agent ids in 1..{n}", edges.tolist())
    if np.any(edges[:, 0] == edges[:, 1]):
        raise CaseError(f"{SIM}.edges", "pairs of distinct agents", edges.tolist())
    return adjacency_from_edges(n, edges.astype(int) - 1), None


def _sim_weights(value: object, hears: np.ndarray | None, n: int) -> WeightRule | np.ndarray:
    field = f"{SIM}.weights"
    if isinstance(value, str):
        return _member(WeightRule, value, field, ("metropolis", "uniform"))
    if hears is None:
        raise CaseError(field, "metropolis or uniform with comm_range", "an explicit matrix")
    matrix = finite_matrix(value, field, rows=n, cols=n)
    return row_stochastic(matrix, field, support=hears)


def _offsets(block: Mapping[str, Any], agents: np.ndarray) -> np.ndarray:
    from theory.tdoa.estimation.agents import assign_offsets, crown_vertices, cube_vertices

    shape = block.get("formation", "cube")
    n = agents.shape[0]
    radius = positive_number(block.get("formation_radius", 10.0), f"{SIM}.formation_radius")
    if shape == "cube":
        if n != 8:
            raise CaseError(f"{SIM}.formation", "explicit offsets unless N = 8 (cube)", shape)
        return assign_offsets(agents, cube_vertices(radius))
    if shape == "crown":
        height = positive_number(block.get("formation_height", 5.0), f"{SIM}.formation_height")
        return assign_offsets(agents, crown_vertices(n, radius, height))
    if isinstance(shape, str):
        raise CaseError(f"{SIM}.formation", "cube, crown or an N × 3 list of offsets", shape)
    return finite_matrix(shape, f"{SIM}.formation", rows=n, cols=3)


TDOA_SIM = KindSpec(
    SIM,
    parse_tdoa_sim,
    expect_keys=("bounded_error", "max_final_error"),
    tolerance_keys=("error_bound",),
    expect_rules={"max_final_error": "at_most"},
)
"""The ``tdoa-sim`` case kind."""


def scene_simulation(spec: TdoaSpec) -> dict[str, Any]:
    """The ``tdoa-sim`` block that runs a static 3-D ``tdoa`` scene as checked: the agents hold
    their positions (``b: .inf``, the formation their own offsets from the centroid), the target
    starts at rest where the scene puts it, the network and weights are the scene's (seed 000
    §4.2.2, §4.4); a :class:`CaseError` for a moving, 2-D or directed scene."""
    if spec.steps > 1:
        raise CaseError("tdoa.agents", "a static scene to simulate", f"{spec.steps} time steps")
    if spec.dim != 3:
        raise CaseError("tdoa.agents", "3-D positions (tdoa-sim is 3-D)", f"{spec.dim}-D points")
    if spec.directed:
        raise CaseError("tdoa.directed", "false (tdoa-sim runs undirected networks)", True)
    agents = spec.agents[0]
    block: dict[str, Any] = {
        "agents": agents.tolist(),
        "target": spec.target[0].tolist(),
        "T": spec.T,
        "b": math.inf,
        "formation": (agents - agents.mean(axis=0)).tolist(),
    }
    explicit = spec.weights_rule is WeightRule.EXPLICIT
    if spec.comm_range is not None and not explicit:
        block["comm_range"] = spec.comm_range
    else:
        links = spec.links[0]
        upper = links.receiver < links.sender
        block["edges"] = (np.column_stack([links.receiver, links.sender])[upper] + 1).tolist()
    block["weights"] = spec.weights[0].tolist() if explicit else spec.weights_rule.value
    return block
