"""``kind: tdoa`` case files: agents, target, network and weights (DESIGN.md, seed 000 ch. 4).

Block fields::

    tdoa:
      T: 1.0                     # ping period (s), > 0; required (a physical quantity)
      dim: 3                     # 2 or 3; default: inferred from the coordinates
      agents: [[x, y, z], ...]   # N × dim, or a trajectory: steps × N × dim
      target: [x, y, z]          # dim, or a trajectory: steps × dim
      edges: [[1, 2], ...]       # 1-based pairs; or comm_range: 21 (strict "<")
      directed: false            # with edges: [s, r] means s sends to r
      weights: metropolis        # metropolis | uniform | an explicit N × N matrix

With an explicit matrix and neither ``edges`` nor ``comm_range``, the edges are read off the
matrix's support (directed if it is not symmetric).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.case_file import register_kind
from theory.core.errors import CaseError
from theory.core.limits import check_estimate, check_length
from theory.core.network import (
    adjacency_from_edges,
    adjacency_from_range,
    metropolis_weights,
    uniform_weights,
    weights_support,
)
from theory.core.tolerances import COINCIDENCE_TOL
from theory.core.validation import (
    bounded_coordinates,
    check_keys,
    distinct_points,
    finite_array,
    finite_matrix,
    positive_number,
    require,
    row_stochastic,
)

__all__ = ["TdoaSpec", "check_tdoa_expect", "parse_tdoa", "required_period"]

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
    """A validated TDOA scene.

    Attributes
    ----------
    T : float
        Ping period.
    dim : int
        2 or 3.
    agents : ndarray, shape (steps, N, dim)
        Agent positions at each step (``steps = 1`` for a static scene).
    target : ndarray, shape (steps, dim)
        Target position at each step.
    hears : ndarray of bool, shape (steps, N, N)
        ``hears[k, r, s]``: agent ``r`` receives from agent ``s`` at step ``k``.
    weights : ndarray, shape (steps, N, N)
        Row-stochastic consensus matrix at each step.
    weights_rule : str
        ``metropolis``, ``uniform`` or ``explicit``.
    directed : bool
        Whether the communication graph may be directed.
    comm_range : float or None
        The distance rule, when the edges come from one.
    """

    T: float
    dim: int
    agents: np.ndarray
    target: np.ndarray
    hears: np.ndarray
    weights: np.ndarray
    weights_rule: str
    directed: bool
    comm_range: float | None

    @property
    def n_agents(self) -> int:
        """Number of agents ``N``."""
        return self.agents.shape[1]

    @property
    def steps(self) -> int:
        """Number of time steps described (1 for a static scene)."""
        return self.agents.shape[0]


def required_period(block: Mapping[str, Any], field: str) -> float:
    """The ping period ``T`` of a tdoa or tdoa-sim block: required, as a physical quantity is
    never defaulted silently.

    Parameters
    ----------
    block : Mapping
        The kind's block.
    field : str
        Its dotted name in messages (``tdoa.T``).

    Returns
    -------
    float

    Raises
    ------
    CaseError
        If ``T`` is missing or not a number > 0.
    """
    if "T" not in block:
        hint = "The field is required (it is never defaulted); e.g. `T: 1.0`."
        raise CaseError(field, "the ping period in seconds, > 0", "nothing", hint=hint)
    return positive_number(block["T"], field)


def parse_tdoa(block: Mapping[str, Any]) -> TdoaSpec:
    """Validate a ``tdoa:`` block (see the module docstring for the fields).

    Raises
    ------
    CaseError
        For any missing, unknown or invalid field, naming it.
    """
    check_keys(block, FIELDS, "tdoa")
    T = required_period(block, "tdoa.T")
    agents, target = _positions(block)
    dim = agents.shape[2]
    _check_distinct(agents, target)
    directed = block.get("directed", False)
    if not isinstance(directed, bool):
        raise CaseError("tdoa.directed", "true or false", directed)
    _check_memory(agents.shape[0], agents.shape[1], 0)
    hears, comm_range = _topology(block, agents, directed)
    _check_memory(*hears.shape[:2], int(hears.sum(axis=(1, 2)).max()))
    weights, rule = _weights(block.get("weights", "metropolis"), hears, directed)
    return TdoaSpec(T, dim, agents, target, hears, weights, rule, directed, comm_range)


def _check_sizes(raw_agents: object, raw_target: object) -> None:
    """Refuse too many agents or steps before any entry is read (:mod:`theory.core.limits`)."""
    nested = isinstance(raw_agents, list) and raw_agents and isinstance(raw_agents[0], list)
    if nested and raw_agents[0] and isinstance(raw_agents[0][0], list):
        check_length(raw_agents, "steps", "tdoa.agents")
        check_length(raw_agents[0], "agents", "tdoa.agents[1]")
    else:
        check_length(raw_agents, "agents", "tdoa.agents")
    if isinstance(raw_target, list) and raw_target and isinstance(raw_target[0], list):
        check_length(raw_target, "steps", "tdoa.target")


def _check_memory(steps: int, n: int, rows: int) -> None:
    """Refuse a scene whose arrays would exceed the memory budget (before they are made).

    ``O`` of seed 000 eq. (4.36) has ``6N·M`` rows and ``6N`` columns (``M`` TDOA rows, one
    per received link, known once the topology is); the parser itself keeps ``steps × N × N``
    links and weights.
    """
    estimate = 8.0 * (6 * n * rows) * (6 * n) + 9.0 * steps * n * n
    check_estimate(
        "memory_bytes",
        estimate,
        "tdoa.agents",
        f"8 B × 6N·M × 6N for O (N = {n} agents, M = {rows} TDOA rows) + 9 B × steps·N²",
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
    """Refuse coincident agents, or the target on an agent, at any step.

    Both use :func:`~theory.core.validation.distinct_points`'s rule: distance at most
    ``coincidence_tol`` times the points' own magnitude (seed 000 eq. (4.3) divides by it).
    """
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
) -> tuple[np.ndarray, float | None]:
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
        return np.stack(
            [adjacency_from_range(agents[k], comm_range) for k in range(steps)]
        ), comm_range
    if has_edges:
        edges = _edges(block["edges"], n)
        hears = adjacency_from_edges(n, edges, directed=directed)
        return np.broadcast_to(hears, (steps, n, n)).copy(), None
    if isinstance(block.get("weights"), list):
        matrix = finite_matrix(block["weights"], "tdoa.weights", rows=n, cols=n)
        return np.broadcast_to(weights_support(matrix), (steps, n, n)).copy(), None
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


def _weights(raw: object, hears: np.ndarray, directed: bool) -> tuple[np.ndarray, str]:
    if raw == "metropolis":
        if directed or not all(np.array_equal(h, h.T) for h in hears):
            raise CaseError(
                "tdoa.weights",
                "uniform or an explicit matrix for a directed network",
                "metropolis",
                hint="Metropolis weights are defined for undirected graphs.",
            )
        return np.stack([metropolis_weights(h) for h in hears]), "metropolis"
    if raw == "uniform":
        return np.stack([uniform_weights(h) for h in hears]), "uniform"
    if isinstance(raw, list):
        steps, n, _ = hears.shape
        if steps > 1 and not np.all(hears == hears[0]):
            raise CaseError(
                "tdoa.weights",
                "metropolis or uniform for a time-varying network",
                "an explicit matrix",
            )
        matrix = finite_matrix(raw, "tdoa.weights", rows=n, cols=n)
        row_stochastic(matrix, "tdoa.weights", support=hears[0])
        return np.broadcast_to(matrix, (steps, n, n)).copy(), "explicit"
    raise CaseError("tdoa.weights", "metropolis, uniform, or an N × N row-stochastic matrix", raw)


PER_AGENT_BOOLS = ("observable", "heuristic_4_noncoplanar", "mirror_ambiguous")
FLAGS = ("network_observable", "network_detectable")


def check_tdoa_expect(spec: TdoaSpec, expect: Mapping[str, Any]) -> None:
    """Validate the values of a tdoa case's ``expect`` block against ``spec``.

    Per-agent verdicts are lists of N booleans, network flags are booleans, ``network_rank``
    and ``first_failure_step`` are non-negative integers (or null: no failing step), and
    ``unobservable_steps`` is a list of N integers between 0 and the number of steps.

    Parameters
    ----------
    spec : TdoaSpec
        The validated scene (gives N and the number of steps).
    expect : mapping
        The case's ``expect`` block, keys already checked.

    Raises
    ------
    CaseError
        Naming the ``expect`` field, the expected form and what was found.
    """
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


register_kind(
    "tdoa",
    parse_tdoa,
    expect_keys=EXPECT_KEYS,
    tolerance_keys=TOLERANCE_KEYS,
    check_expect=check_tdoa_expect,
    observe="theory.tdoa.topology_report:observe_topology",
)
