"""``kind: tdoa-sim`` case files: a closed-loop TDOA localization-and-tracking scenario.

Block fields (seed 000 §4.4 defaults in brackets)::

    tdoa-sim:
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

Expectations (``expect:``) a run can be checked against: ``bounded_error`` (every agent's final
localization error below ``tolerances.error_bound``), ``max_final_error``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.case_file import register_kind
from theory.core.errors import CaseError
from theory.core.limits import check_count, check_estimate, check_length
from theory.core.network import adjacency_from_edges
from theory.core.tolerances import PERIOD_TOL
from theory.core.validation import (
    bounded_coordinates,
    check_keys,
    finite_matrix,
    finite_vector,
    one_of,
    positive_definite,
    positive_int,
    positive_number,
    require,
    row_stochastic,
)
from theory.tdoa.filters import FILTERS
from theory.tdoa.formation import assign_offsets, crown_vertices, cube_vertices

__all__ = ["TdoaSimSpec", "check_sim_work", "parse_tdoa_sim"]

KIND = "tdoa-sim"
FIELDS = (
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
EXPECT_KEYS = ("bounded_error", "max_final_error")
TOLERANCE_KEYS = ("error_bound",)


@dataclass(frozen=True, eq=False)
class TdoaSimSpec:
    """A validated closed-loop TDOA scenario (see the module docstring for the fields).

    Attributes
    ----------
    agents : ndarray, shape (N, 3)
    target : ndarray, shape (6,)
        Initial target state ``[p; ṗ]``.
    Q : ndarray, shape (3, 3)
    r : float
    T, tau : float
    P0 : ndarray, shape (6, 6)
    x0 : ndarray, shape (6,)
    b : float
        ``math.inf`` for "never move".
    hears : ndarray of bool, shape (N, N) or None
        Fixed topology, or ``None`` with ``comm_range``.
    comm_range : float or None
    weights : str or ndarray
        ``"metropolis"``, ``"uniform"`` or an explicit matrix.
    filter : str
    linearize : str
        ``estimate`` (EKF) or ``truth`` (Jacobians at the true target: the covariance is the
        Riccati recursion of the linearized system, used to cross-check observability).
    steps : int
    offsets : ndarray, shape (N, 3)
        Formation offsets ``d_i`` of eq. (4.45).
    pole : float
    max_input : tuple of 3 floats
    substeps : int
    cov_norm : str
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
    weights: str | np.ndarray
    filter: str
    linearize: str
    steps: int
    offsets: np.ndarray
    pole: float
    max_input: tuple[float, float, float]
    substeps: int
    cov_norm: str

    @property
    def n_agents(self) -> int:
        """Number of agents ``N``."""
        return self.agents.shape[0]

    @property
    def rounds(self) -> int:
        """Consensus rounds per ping, ``T/τ``."""
        return round(self.T / self.tau)


def parse_tdoa_sim(block: Mapping[str, Any]) -> TdoaSimSpec:
    """Validate a ``tdoa-sim:`` block.

    Raises
    ------
    CaseError
        For any missing, unknown or invalid field, naming it.
    """
    check_keys(block, FIELDS, KIND)
    raw_agents = require(block, "agents", KIND)
    check_length(raw_agents, "agents", f"{KIND}.agents")
    agents = finite_matrix(raw_agents, f"{KIND}.agents", cols=3)
    n = bounded_coordinates(agents, f"{KIND}.agents").shape[0]
    if n < 2:
        raise CaseError(f"{KIND}.agents", "at least 2 agents", n)
    position = finite_vector(require(block, "target", KIND), f"{KIND}.target", length=3)
    bounded_coordinates(position, f"{KIND}.target")
    velocity = finite_vector(
        block.get("target_velocity", [0, 0, 0]), f"{KIND}.target_velocity", length=3
    )
    T = positive_number(block.get("T", 1.0), f"{KIND}.T")
    tau = positive_number(block.get("tau", T), f"{KIND}.tau")
    ratio = T / tau
    if (
        not math.isfinite(ratio)
        or ratio < 1 - PERIOD_TOL
        or abs(ratio - round(ratio)) > PERIOD_TOL * ratio
    ):
        raise CaseError(f"{KIND}.tau", "a period dividing T (T/tau a positive integer)", tau)
    hears, comm_range = _topology(block, n)
    steps = check_count(
        "steps", positive_int(block.get("steps", 100), f"{KIND}.steps"), f"{KIND}.steps"
    )
    substeps = positive_int(block.get("substeps", 2), f"{KIND}.substeps")
    check_sim_work(n, steps, round(ratio), substeps, f"{KIND}.steps")
    return TdoaSimSpec(
        agents=agents,
        target=np.concatenate([position, velocity]),
        Q=_covariance(block.get("Q", 0.01), 3, f"{KIND}.Q"),
        r=positive_number(block.get("R", 1.0), f"{KIND}.R"),
        T=T,
        tau=tau,
        P0=_covariance(block.get("P0", 100.0), 6, f"{KIND}.P0"),
        x0=finite_vector(block.get("x0", [0] * 6), f"{KIND}.x0", length=6),
        b=_threshold(block.get("b", 0.0)),
        hears=hears,
        comm_range=comm_range,
        weights=_weights(block.get("weights", "metropolis"), hears, n),
        filter=one_of(block.get("filter", "averaged"), FILTERS, f"{KIND}.filter"),
        linearize=one_of(
            block.get("linearize", "estimate"), ("estimate", "truth"), f"{KIND}.linearize"
        ),
        steps=steps,
        offsets=_offsets(block, agents),
        pole=positive_number(block.get("pole", 0.5), f"{KIND}.pole"),
        max_input=_limits(block.get("max_input", [2.0, 2.0, 2.0])),
        substeps=substeps,
        cov_norm=one_of(block.get("cov_norm", "spectral"), ("spectral", "frobenius"), "cov_norm"),
    )


def check_sim_work(n: int, steps: int, rounds: int, substeps: int, field: str) -> None:
    """Refuse a run whose memory or work would exceed the limits (:mod:`theory.core.limits`).

    Each agent keeps a 6-state estimate, its 6 × 6 covariance and its 9-state kinematics
    (seed 000 §4.4), recorded at every ping: 51 floats (408 B) per agent and step. The work is
    one N × N consensus exchange per round and one Runge–Kutta step per substep, per ping.

    Parameters
    ----------
    n, steps, rounds, substeps : int
        Agents, pings, consensus rounds per ping (T/τ), Runge–Kutta steps per round.
    field : str
        The field (or option, such as ``--steps``) named when it is too much.

    Raises
    ------
    CaseError
        Naming ``field``, the estimate and the limit.
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
    return positive_number(value, f"{KIND}.b", allow_zero=True)


def _limits(value: object) -> tuple[float, float, float]:
    field = f"{KIND}.max_input"
    if not isinstance(value, list | tuple) or len(value) != 3:
        raise CaseError(field, "three limits [u1, u2, u3] (numbers or .inf)", value)
    return tuple(_positive_or_inf(v, f"{field}[{k + 1}]") for k, v in enumerate(value))


def _positive_or_inf(value: object, field: str) -> float:
    if isinstance(value, float) and math.isinf(value) and value > 0:
        return math.inf
    return positive_number(value, field)


def _topology(block: Mapping[str, Any], n: int) -> tuple[np.ndarray | None, float | None]:
    has_edges, has_range = "edges" in block, "comm_range" in block
    if has_edges == has_range:
        raise CaseError(f"{KIND}.edges", "exactly one of edges or comm_range", "both or neither")
    if has_range:
        return None, positive_number(block["comm_range"], f"{KIND}.comm_range")
    edges = finite_matrix(block["edges"], f"{KIND}.edges", cols=2, allow_empty_rows=True)
    if edges.size and (np.any(edges != np.round(edges)) or edges.min() < 1 or edges.max() > n):
        raise CaseError(f"{KIND}.edges", f"pairs of agent ids in 1..{n}", edges.tolist())
    if np.any(edges[:, 0] == edges[:, 1]):
        raise CaseError(f"{KIND}.edges", "pairs of distinct agents", edges.tolist())
    return adjacency_from_edges(n, edges.astype(int) - 1), None


def _weights(value: object, hears: np.ndarray | None, n: int) -> str | np.ndarray:
    field = f"{KIND}.weights"
    if isinstance(value, str):
        return one_of(value, ("metropolis", "uniform"), field)
    if hears is None:
        raise CaseError(field, "metropolis or uniform with comm_range", "an explicit matrix")
    matrix = finite_matrix(value, field, rows=n, cols=n)
    return row_stochastic(matrix, field, support=hears)


def _offsets(block: Mapping[str, Any], agents: np.ndarray) -> np.ndarray:
    shape = block.get("formation", "cube")
    n = agents.shape[0]
    radius = positive_number(block.get("formation_radius", 10.0), f"{KIND}.formation_radius")
    if shape == "cube":
        if n != 8:
            raise CaseError(f"{KIND}.formation", "explicit offsets unless N = 8 (cube)", shape)
        return assign_offsets(agents, cube_vertices(radius))
    if shape == "crown":
        height = positive_number(block.get("formation_height", 5.0), f"{KIND}.formation_height")
        return assign_offsets(agents, crown_vertices(n, radius, height))
    if isinstance(shape, str):
        raise CaseError(f"{KIND}.formation", "cube, crown or an N × 3 list of offsets", shape)
    return finite_matrix(shape, f"{KIND}.formation", rows=n, cols=3)


register_kind(
    KIND,
    parse_tdoa_sim,
    expect_keys=EXPECT_KEYS,
    tolerance_keys=TOLERANCE_KEYS,
    observe="theory.tdoa.sim_summary:observe_tdoa_sim",
    expect_rules={"max_final_error": "at_most"},
    simulate="theory.tdoa.sim_summary:tdoa_simulator",
)
