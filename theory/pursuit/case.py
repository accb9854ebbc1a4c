"""``kind: pursuit`` case files: trackers, S-T curves, gains and network (seed 003 §IV–VI).

Block fields::

    pursuit:
      dim: 2                        # 2 or 3
      controller: II                # I (eq. 49) or II (eq. 50): the analysed law, or
      # controller: {law: II, variant: published, inputs_min: [0, -0.4], inputs_max: [2, 0.4],
      #              gamma_ddot: [-0.001, 0.01]}   # as the authors' scripts run it (published.py)
      duration: 450                 # optional, simulated seconds (default 450)
      omega_bar: 0.05               # ω̄ (rad/s), eq. (18), (46)
      epsilon: [-0.5, 0]            # ε of eq. (19), dim numbers
      K_p: [0.4, 0.2]               # diagonal of K_p, or a dim × dim symmetric PD matrix
      k_gamma: 500                  # k_γ > 0, eq. (50b); required for controller II
      k_c: 0.2                      # k_c > 0, eq. (45); required when N > 1
      trackers:                     # one entry per tracker: path (15)/(16) parameters
        - {r_x: 30, r_y: 30, gamma0: 0}              # 3D also r_z > 0 and c ∉ {0, 1}
        - {r_x: 30, r_y: 30, gamma0: 2.0943951, initial: {position: [..], euler: [..], gamma: 0}}
      edges: [[2, 1], [3, 2], [1, 3]]   # directed, 1-based [s, r]: tracker s sends to tracker r
      # edges: [[2, 1, 0.5], [3, 2, 2], [1, 3]]  # optional weight a_rs > 0 per edge (default 1)
      target:                       # optional, see TargetMotion
        offset: [0, 0]
        velocity: [0, 0.3]
        amplitude: [20, 0]
        frequency: [0.01, 0]
        phase: [3.14159265, 0]
      dekf:                         # optional, for the simulation (Algorithm 2)
        Ts: 2                       # sampling period (s)
        sigma: 0.5                  # range noise standard deviation (m), eq. (10)
        V: 10                       # inverse measurement-noise weight V^[i]
        Q: [[...]]                  # 2·dim × 2·dim positive-definite process-noise weight
        weights: uniform            # or N × N row-stochastic fusion weights π^[i,j] (in-edges)
        edges: [[1, 2], ...]        # optional fusion graph (default: pursuit.edges)
        predict_every: 2            # optional prediction period (s) dividing Ts (default Ts);
                                    # Q is the process noise of one prediction
        x0: [[...], ...]            # optional initial estimates, N × 2·dim
        P0: [[...]]                 # optional initial covariance, 2·dim × 2·dim (or N of them)

The graph convention is the paper's: a_ij = 1 when tracker i receives from tracker j, and the
Laplacian is L = D_in − A (seed 003 §II-B). An edge ``[s, r, a]`` gives a_rs = a instead (any
a > 0: the weighted digraphs of Lemma 1's reference [28]; the paper's own class has a = 1); the
weight enters L, hence the coordination law (45), the ISS constants and the iss certificate, and
is read as the decimal written. ``dekf.edges`` are pairs (its fusion weights are ``weights``).
Conditions that decide the analysis (Δ of full row rank, strong connectivity) are *not* refused
here: ``trackcert iss`` reports them as failing conditions (exit 1). Only malformed data is
refused (:class:`~theory.core.errors.CaseError`, exit 2).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np

from theory.core.case_file import KindSpec
from theory.core.errors import CaseError
from theory.core.network import adjacency_from_edges, uniform_weights
from theory.core.validation import (
    check_keys,
    check_length,
    finite_matrix,
    finite_number,
    finite_vector,
    one_of,
    positive_definite,
    positive_number,
    require,
    row_stochastic,
)
from theory.pursuit.published import PublishedControl

__all__ = [
    "PURSUIT",
    "Controller",
    "DekfSettings",
    "PursuitSpec",
    "TargetMotion",
    "TrackerPath",
    "parse_pursuit",
]

FIELDS = (
    "dim",
    "controller",
    "duration",
    "omega_bar",
    "epsilon",
    "K_p",
    "k_gamma",
    "k_c",
    "trackers",
    "edges",
    "target",
    "dekf",
)
TRACKER_FIELDS_2D = ("r_x", "r_y", "gamma0", "initial")
TRACKER_FIELDS_3D = ("r_x", "r_y", "r_z", "c", "gamma0", "initial")
INITIAL_FIELDS = ("position", "euler", "gamma", "gamma_dot")
TARGET_FIELDS = ("offset", "velocity", "amplitude", "frequency", "phase")
DEKF_FIELDS = ("Ts", "sigma", "V", "Q", "weights", "edges", "predict_every", "x0", "P0")
CONTROLLER_FIELDS = ("law", "variant", "inputs_min", "inputs_max", "gamma_ddot")
VARIANTS = ("analysed", "published")
EXPECT_KEYS = (
    "iss",
    "delta_full_rank",
    "strongly_connected",
    "simulation_bounded",
    "runaways",
    "final_localization_error",
    "mean_pursuit_error",
)
EXPECT_RULES = {"final_localization_error": "within", "mean_pursuit_error": "within"}
TOLERANCE_KEYS = ("margin_tol", "weight_sum_tol", "runaway_factor")


class Controller(StrEnum):
    """The path-following law: Type I (eq. 49, γ̇ = ω_d) or Type II (eq. 50, γ̈ feedback)."""

    I = "I"
    II = "II"


@dataclass(frozen=True)
class TrackerPath:
    """The path r(γ) of one tracker, seed 003 eqs. (15)–(16) (``r_z``, ``c``: 3D only).

    ``initial`` optionally holds the simulation's initial ``position``, ``euler`` (yaw in 2D,
    roll-pitch-yaw in 3D), ``gamma`` and ``gamma_dot``.
    """

    r_x: float
    r_y: float
    r_z: float | None
    c: float | None
    gamma0: float
    initial: dict[str, Any]


@dataclass(frozen=True)
class TargetMotion:
    """q_k(t) = offset_k + velocity_k·t + amplitude_k·sin(frequency_k·t + phase_k) (Tables I–II).

    Each field has one entry per coordinate k (m, m/s, m, rad/s, rad); a missing key is zero.
    """

    offset: np.ndarray
    velocity: np.ndarray
    amplitude: np.ndarray
    frequency: np.ndarray
    phase: np.ndarray

    def position(self, t: float) -> np.ndarray:
        """q(t)."""
        return (
            self.offset
            + self.velocity * t
            + self.amplitude * np.sin(self.frequency * t + self.phase)
        )

    def velocity_at(self, t: float) -> np.ndarray:
        """q̇(t)."""
        return self.velocity + self.amplitude * self.frequency * np.cos(
            self.frequency * t + self.phase
        )


@dataclass(frozen=True, eq=False)
class DekfSettings:
    """Settings of the distributed EKF (seed 003 Algorithm 2) for the simulation.

    ``Ts`` sampling period (s), ``sigma`` range-noise deviation (m, eq. (10)), ``V`` inverse
    measurement-noise weight, ``Q`` process-noise weight (2·dim square) of one prediction,
    ``weights`` fusion weights π^[i,j] on the in-edges of the fusion graph; ``x0`` (N × 2·dim)
    and ``P0`` (N stacked covariances) are ``None`` for the simulation's defaults;
    ``predictions`` per ``Ts`` (1: Algorithm 2 as printed).
    """

    Ts: float
    sigma: float
    V: float
    Q: np.ndarray
    weights: np.ndarray
    x0: np.ndarray | None
    P0: np.ndarray | None
    predictions: int = 1


@dataclass(frozen=True, eq=False)
class PursuitSpec:
    """A validated cooperative-pursuit case (seed 003).

    ``K_p`` is the symmetric positive-definite position gain (dim × dim), ``k_gamma`` is set for
    controller II, ``k_c`` for N > 1; ``adjacency[i, j]``: tracker i receives from tracker j,
    ``edge_weights[i, j]`` its weight a_ij (``None``: every a_ij = 1);
    ``published`` the clamps of the authors' scripts when the case simulates their variant
    (:mod:`theory.pursuit.published`), ``duration`` the simulated seconds (``None``: default).
    """

    dim: int
    controller: Controller
    omega_bar: float
    epsilon: np.ndarray
    K_p: np.ndarray
    k_gamma: float | None
    k_c: float | None
    trackers: tuple[TrackerPath, ...]
    adjacency: np.ndarray
    target: TargetMotion | None
    dekf: DekfSettings | None
    published: PublishedControl | None = None
    duration: float | None = None
    edge_weights: np.ndarray | None = None

    @property
    def n_trackers(self) -> int:
        """Number of trackers N."""
        return len(self.trackers)

    @property
    def weighted_adjacency(self) -> np.ndarray:
        """A = [a_ij] (seed 003 §II-B): ``edge_weights``, or 1 on every edge (integers)."""
        return self.adjacency.astype(int) if self.edge_weights is None else self.edge_weights

    @property
    def laplacian(self) -> np.ndarray:
        """L = D_in − A (seed 003 §II-B): integer entries unless edges carry weights (exact
        rationals: :func:`theory.pursuit.model.exact_laplacian`)."""
        a = self.weighted_adjacency
        return np.diag(a.sum(axis=1)) - a


def parse_pursuit(block: Mapping[str, Any]) -> PursuitSpec:
    """Validate a ``pursuit:`` block (fields in the module docstring); CaseError names a bad one."""
    check_keys(block, FIELDS, "pursuit")
    dim = require(block, "dim", "pursuit")
    if dim not in (2, 3) or isinstance(dim, bool):
        raise CaseError("pursuit.dim", "2 or 3", dim)
    controller, published = _controller(require(block, "controller", "pursuit"), dim)
    omega_bar = finite_number(require(block, "omega_bar", "pursuit"), "pursuit.omega_bar")
    epsilon = finite_vector(require(block, "epsilon", "pursuit"), "pursuit.epsilon", length=dim)
    K_p = _gain_matrix(require(block, "K_p", "pursuit"), dim)
    trackers = _trackers(require(block, "trackers", "pursuit"), dim)
    n = len(trackers)
    k_gamma = _optional_gain(block, "k_gamma", required=controller == "II", why="controller II")
    k_c = _optional_gain(block, "k_c", required=n > 1, why="more than one tracker")
    adjacency, edge_weights = _weighted_adjacency(block.get("edges", []), n)
    target = _target(block["target"], dim) if "target" in block else None
    dekf = _dekf(block["dekf"], dim, adjacency) if "dekf" in block else None
    duration = (
        positive_number(block["duration"], "pursuit.duration") if "duration" in block else None
    )
    return PursuitSpec(
        dim, controller, omega_bar, epsilon, K_p, k_gamma, k_c, trackers, adjacency, target, dekf,
        published, duration, edge_weights,
    )  # fmt: skip


def _law(raw: object, field: str) -> Controller:
    return Controller(one_of(str(raw), [c.value for c in Controller], field))


def _controller(raw: object, dim: int) -> tuple[Controller, PublishedControl | None]:
    """The law and, for ``variant: published``, the scripts' clamps (module docstring)."""
    if not isinstance(raw, Mapping):
        return _law(raw, "pursuit.controller"), None
    prefix = "pursuit.controller"
    check_keys(raw, CONTROLLER_FIELDS, prefix)
    law = _law(require(raw, "law", prefix), f"{prefix}.law")
    variant = one_of(str(raw.get("variant", "analysed")), list(VARIANTS), f"{prefix}.variant")
    clamps = [key for key in CONTROLLER_FIELDS[2:] if key in raw]
    if variant == "analysed":
        if clamps:
            raise CaseError(
                f"{prefix}.{clamps[0]}", "no clamp with variant: analysed", raw[clamps[0]]
            )
        return law, None
    size = 2 if dim == 2 else 4
    bounds = {
        key: finite_vector(raw[key], f"{prefix}.{key}", length=size) if key in raw else None
        for key in ("inputs_min", "inputs_max")
    }
    low, high = bounds["inputs_min"], bounds["inputs_max"]
    if low is not None and high is not None and np.any(low > high):
        raise CaseError(f"{prefix}.inputs_max", "entries ≥ those of inputs_min", raw["inputs_max"])
    gamma_ddot = None
    if "gamma_ddot" in raw:
        gamma_ddot = tuple(finite_vector(raw["gamma_ddot"], f"{prefix}.gamma_ddot", length=2))
        if gamma_ddot[0] > gamma_ddot[1]:
            raise CaseError(f"{prefix}.gamma_ddot", "[min, max] with min ≤ max", raw["gamma_ddot"])
    return law, PublishedControl(low, high, gamma_ddot)


def _gain_matrix(raw: object, dim: int) -> np.ndarray:
    field = "pursuit.K_p"
    if isinstance(raw, list) and raw and not isinstance(raw[0], list):
        diagonal = finite_vector(raw, field, length=dim)
        if np.any(diagonal <= 0):
            raise CaseError(field, "positive diagonal entries (K_p ≻ 0)", raw)
        return np.diag(diagonal)
    matrix = finite_matrix(raw, field, rows=dim, cols=dim)
    return positive_definite(matrix, field)


def _optional_gain(block: Mapping[str, Any], key: str, *, required: bool, why: str) -> float | None:
    if key not in block:
        if required:
            raise CaseError(f"pursuit.{key}", f"a number > 0 (required with {why})", "nothing")
        return None
    return positive_number(block[key], f"pursuit.{key}")


def _trackers(raw: object, dim: int) -> tuple[TrackerPath, ...]:
    if not isinstance(raw, list) or not raw:
        raise CaseError("pursuit.trackers", "a non-empty list of tracker path parameters", raw)
    check_length(raw, "trackers", "pursuit.trackers")
    allowed = TRACKER_FIELDS_3D if dim == 3 else TRACKER_FIELDS_2D
    paths = []
    for index, entry in enumerate(raw):
        prefix = f"pursuit.trackers[{index + 1}]"
        check_keys(entry, allowed, prefix)
        r_x = positive_number(require(entry, "r_x", prefix), f"{prefix}.r_x")
        r_y = positive_number(require(entry, "r_y", prefix), f"{prefix}.r_y")
        r_z = c = None
        if dim == 3:
            r_z = positive_number(require(entry, "r_z", prefix), f"{prefix}.r_z")
            c = finite_number(require(entry, "c", prefix), f"{prefix}.c")
            if c in (0.0, 1.0):
                raise CaseError(f"{prefix}.c", "a real number other than 0 and 1 (eq. 15)", c)
        gamma0 = finite_number(entry.get("gamma0", 0.0), f"{prefix}.gamma0")
        initial = _initial(entry.get("initial", {}), dim, f"{prefix}.initial")
        paths.append(TrackerPath(r_x, r_y, r_z, c, gamma0, initial))
    return tuple(paths)


def _initial(raw: object, dim: int, prefix: str) -> dict[str, Any]:
    check_keys(raw, INITIAL_FIELDS, prefix)
    initial: dict[str, Any] = {}
    if "position" in raw:
        initial["position"] = finite_vector(raw["position"], f"{prefix}.position", length=dim)
    if "euler" in raw:
        length = 1 if dim == 2 else 3
        initial["euler"] = finite_vector(raw["euler"], f"{prefix}.euler", length=length)
    for key in ("gamma", "gamma_dot"):
        if key in raw:
            initial[key] = finite_number(raw[key], f"{prefix}.{key}")
    return initial


def _weighted_adjacency(raw: object, n: int) -> tuple[np.ndarray, np.ndarray | None]:
    """``pursuit.edges``: pairs ``[s, r]`` or triples ``[s, r, a]`` with a weight ``a > 0``;
    the adjacency and (when some edge has a weight) ``a_rs`` on every edge (1 where none)."""
    field = "pursuit.edges"
    if not isinstance(raw, list) or not all(isinstance(e, list) and len(e) in (2, 3) for e in raw):
        raise CaseError(
            field, "a list of directed pairs [s, r] or [s, r, weight] of 1-based tracker ids", raw
        )
    adjacency = _adjacency([e[:2] for e in raw], n)
    if all(len(e) == 2 for e in raw):
        return adjacency, None
    weights = adjacency.astype(float)
    for index, edge in enumerate(raw):
        if len(edge) == 3:
            s, r, a = edge
            weights[r - 1, s - 1] = positive_number(a, f"{field}[{index + 1}][3]")
    return adjacency, weights


def _adjacency(raw: object, n: int, field: str = "pursuit.edges") -> np.ndarray:
    if not isinstance(raw, list) or not all(isinstance(e, list) and len(e) == 2 for e in raw):
        raise CaseError(field, "a list of directed pairs [s, r] of 1-based tracker ids", raw)
    for index, (s, r) in enumerate(raw):
        for agent in (s, r):
            if isinstance(agent, bool) or not isinstance(agent, int) or not 1 <= agent <= n:
                raise CaseError(f"{field}[{index + 1}]", f"tracker ids between 1 and {n}", [s, r])
        if s == r:
            raise CaseError(
                f"{field}[{index + 1}]", "two different trackers (no self-loops)", [s, r]
            )
    if len({tuple(e) for e in raw}) != len(raw):
        raise CaseError(field, "each directed edge listed once", raw)
    edges = np.asarray(raw, dtype=int).reshape(-1, 2) - 1
    return adjacency_from_edges(n, edges, directed=True)


def _target(raw: object, dim: int) -> TargetMotion:
    check_keys(raw, TARGET_FIELDS, "pursuit.target")
    values = {
        key: finite_vector(raw[key], f"pursuit.target.{key}", length=dim)
        if key in raw
        else np.zeros(dim)
        for key in TARGET_FIELDS
    }
    return TargetMotion(**values)


def _dekf(raw: object, dim: int, adjacency: np.ndarray) -> DekfSettings:
    prefix = "pursuit.dekf"
    check_keys(raw, DEKF_FIELDS, prefix)
    n, size = adjacency.shape[0], 2 * dim
    Ts = positive_number(require(raw, "Ts", prefix), f"{prefix}.Ts")
    sigma = positive_number(require(raw, "sigma", prefix), f"{prefix}.sigma")
    V = positive_number(require(raw, "V", prefix), f"{prefix}.V")
    Q = positive_definite(
        finite_matrix(require(raw, "Q", prefix), f"{prefix}.Q", rows=size, cols=size), f"{prefix}.Q"
    )
    graph = _adjacency(raw["edges"], n, f"{prefix}.edges") if "edges" in raw else adjacency
    weights_raw = raw.get("weights", "uniform")
    if weights_raw == "uniform":
        weights = uniform_weights(graph)
    else:
        weights = finite_matrix(weights_raw, f"{prefix}.weights", rows=n, cols=n)
        row_stochastic(weights, f"{prefix}.weights", support=graph)
    predictions = _predictions(raw, Ts, prefix)
    x0 = None
    if "x0" in raw:
        x0 = finite_matrix(raw["x0"], f"{prefix}.x0", rows=n, cols=size)
    P0 = _initial_covariances(raw["P0"], n, size, f"{prefix}.P0") if "P0" in raw else None
    return DekfSettings(Ts, sigma, V, Q, weights, x0, P0, predictions)


def _predictions(raw: Mapping[str, Any], Ts: float, prefix: str) -> int:
    """Predictions per ``Ts`` from ``predict_every`` (s), which must divide ``Ts``."""
    if "predict_every" not in raw:
        return 1
    period = positive_number(raw["predict_every"], f"{prefix}.predict_every")
    count = round(Ts / period)
    if count < 1 or abs(count * period - Ts) > 1e-9 * Ts:
        raise CaseError(f"{prefix}.predict_every", f"a period dividing Ts = {Ts:g} s", period)
    return count


def _initial_covariances(raw: object, n: int, size: int, field: str) -> np.ndarray:
    stacked = isinstance(raw, list) and raw and isinstance(raw[0], list) and raw[0]
    if stacked and isinstance(raw[0][0], list):
        if len(raw) != n:
            raise CaseError(field, f"one {size} × {size} matrix or a list of {n} of them", raw)
        return np.stack(
            [
                positive_definite(
                    finite_matrix(m, f"{field}[{i + 1}]", rows=size, cols=size), f"{field}[{i + 1}]"
                )
                for i, m in enumerate(raw)
            ]
        )
    matrix = positive_definite(finite_matrix(raw, field, rows=size, cols=size), field)
    return np.broadcast_to(matrix, (n, size, size)).copy()


PURSUIT = KindSpec(
    "pursuit",
    parse_pursuit,
    expect_keys=EXPECT_KEYS,
    tolerance_keys=TOLERANCE_KEYS,
    expect_rules=EXPECT_RULES,
)
"""The ``pursuit`` case kind."""
