"""Gain regions of the pursuit loop (seed 003, corrected Theorems 1–2): which gains work.

Over a user's box of (k_γ, k_c, K_p scale s, ε), :func:`gain_regions` splits the box into cells
and decides each exactly: **certified** (every point of the cell satisfies the corrected
conditions, shown by an ``iss-box`` certificate that ``proofs_check`` re-verifies), **refuted**
(a rational point of the cell where a condition fails exactly, or the whole cell), or
**undecided**. Certified cells carry an exact enclosure [lo, hi] of the analysis's ISS gain
g_e(1 + g_ξ) over the cell. How each condition depends on the box (docs/design.md, *Gain
regions*): with positive gains, K = diag(sK_p, k_γ) ≻ 0 iff K_p ≻ 0 and the graph conditions do not
involve the box at all, so they are decided once; ε enters only through ε₁ ≠ 0 (eq. (22)) and the
margin |ε₁|/‖ε‖ ≥ margin_tol of ``trackcert iss``; every rate and gain bound is monotone in
each gain, so each holds on a cell iff it holds at one corner. Optional requirements (a largest
ISS gain, a smallest decay rate) make the map a design answer: the corrected conditions alone hold
for every positive gain.
"""

from __future__ import annotations

import itertools
import math
import re
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from enum import StrEnum
from fractions import Fraction
from pathlib import Path
from typing import Any

from proofs_check.linalg import positive_definite
from theory.core.case_file import Case
from theory.core.errors import COMMAND_LINE, CaseError
from theory.core.exact import exact_decimal
from theory.core.tolerances import ISS_DIGITS, MARGIN_TOL
from theory.core.verdicts import Verdict
from theory.pursuit.case import Controller, PursuitSpec
from theory.pursuit.certificates import (
    LoopBounds,
    box_gain_below,
    box_witness,
    iss_box_certificate,
    loop_bounds,
)
from theory.pursuit.iss import ConditionStatus, exact_gain_matrix, iss_conditions, r_perp_gram

__all__ = [
    "Axis",
    "Cell",
    "CellStatus",
    "FailingCondition",
    "GainRegions",
    "default_box",
    "design_summary",
    "draw_gain_map",
    "gain_regions",
    "parse_box",
]

GAINS = ("K_p_scale", "k_gamma", "k_c")
"""Box paths that scale a gain (each must stay positive)."""
EPSILON = ("epsilon.0", "epsilon.1", "epsilon.2")
"""Box paths of ε's components, 0-based as in ``trackcert sweep`` (epsilon.0 is the paper's ε₁)."""
DELTA = "delta_full_rank"
DELTA_SOURCE = "seed 003 eq. (22), Remark 6 (corrected: needs ε₁ ≠ 0)"


class CellStatus(StrEnum):
    """What is known of a cell."""

    CERTIFIED = "certified"
    REFUTED = "refuted"
    UNDECIDED = "undecided"


@dataclass(frozen=True)
class Axis:
    """One side of the box: ``path`` from ``lo`` to ``hi`` (exact), split evenly or in log scale."""

    path: str
    lo: Fraction
    hi: Fraction
    log: bool = False

    def ends(self, n: int) -> list[Fraction]:
        """n + 1 increasing rationals from lo to hi: the initial grid along this side."""
        if not self.log:
            return [self.lo + (self.hi - self.lo) * k / n for k in range(n + 1)]
        ratio = float(self.hi / self.lo)
        ends = [self.lo]
        for k in range(1, n):
            ends.append(_inside(ends[-1], self.hi, float(self.lo) * ratio ** (k / n)))
        return [*ends, self.hi]

    def middle(self, lo: Fraction, hi: Fraction) -> Fraction:
        """A short rational strictly inside (lo, hi): the midpoint, or the geometric one."""
        return _inside(lo, hi, math.sqrt(float(lo) * float(hi))) if self.log else (lo + hi) / 2

    def share(self, lo: Fraction, hi: Fraction) -> float:
        """The part of this side that [lo, hi] covers (in log measure for a log side)."""
        if self.log:
            return math.log(float(hi / lo)) / math.log(float(self.hi / self.lo))
        return float((hi - lo) / (self.hi - self.lo))

    def to_json(self) -> dict[str, Any]:
        """``{"path", "lo", "hi", "scale"}`` (exact strings)."""
        scale = "log" if self.log else "lin"
        return {"path": self.path, "lo": str(self.lo), "hi": str(self.hi), "scale": scale}


def _inside(lo: Fraction, hi: Fraction, x: float) -> Fraction:
    """The shortest decimal near ``x`` strictly inside (lo, hi) (their midpoint if none is)."""
    for digits in range(2, 18):
        q = Fraction(f"{x:.{digits}g}")
        if lo < q < hi:
            return q
    return (lo + hi) / 2


@dataclass(frozen=True)
class FailingCondition:
    """A condition that fails exactly at ``point`` of a cell (at every point if ``whole_cell``)."""

    name: str
    source: str
    point: dict[str, Fraction]
    whole_cell: bool
    detail: str

    def to_json(self) -> dict[str, Any]:
        """``{"name", "source", "point", "whole_cell", "detail"}`` (the point exact)."""
        point = {k: str(v) for k, v in self.point.items()}
        return {"name": self.name, "source": self.source, "point": point,
                "whole_cell": self.whole_cell, "detail": self.detail}  # fmt: skip


@dataclass(frozen=True)
class Cell:
    """One cell of the map: its box (one [lo, hi] per axis), status and the evidence for it.

    ``iss_gain`` is an exact enclosure of the analysis gain over the cell (certified cells, and
    undecided ones whose conditions hold but a requirement is undecided); ``reason`` says why a
    cell is undecided.
    """

    box: tuple[tuple[Fraction, Fraction], ...]
    status: CellStatus
    depth: int
    certificate: dict[str, Any] | None = None
    failing_condition: FailingCondition | None = None
    iss_gain: tuple[Fraction, Fraction] | None = None
    reason: str = ""

    def to_json(self, axes: Sequence[Axis]) -> dict[str, Any]:
        """The cell's JSON record (docs/design.md)."""
        out: dict[str, Any] = {
            "box": {a.path: [str(lo), str(hi)] for a, (lo, hi) in zip(axes, self.box, strict=True)},
            "status": self.status,
            "depth": self.depth,
        }
        if self.certificate is not None:
            out["certificate"] = self.certificate
        if self.failing_condition is not None:
            out["failing_condition"] = self.failing_condition.to_json()
        out["iss_gain"] = None if self.iss_gain is None else _interval(*self.iss_gain)
        if self.reason:
            out["reason"] = self.reason
        return out


@dataclass(frozen=True)
class GainRegions:
    """The answer of :func:`gain_regions`: the cells and how they were decided."""

    case: str
    axes: tuple[Axis, ...]
    fixed: dict[str, Fraction]
    cells: tuple[Cell, ...]
    requirements: dict[str, Fraction | None]
    settings: dict[str, Any]
    box_conditions: tuple[dict[str, Any], ...]
    tolerances: dict[str, float]

    def count(self, status: CellStatus) -> int:
        """How many cells have ``status``."""
        return sum(c.status == status for c in self.cells)

    @property
    def verdict(self) -> Verdict:
        """True if a cell is certified, False if every cell is refuted, else None."""
        if self.count(CellStatus.CERTIFIED):
            return True
        return False if self.count(CellStatus.REFUTED) == len(self.cells) else None

    @property
    def certificates(self) -> list[dict[str, Any]]:
        """The ``iss-box`` certificates of the certified cells, in cell order."""
        return [c.certificate for c in self.cells if c.certificate is not None]

    def share(self, status: CellStatus) -> float:
        """The part of the box's volume (log measure on log sides) in cells of ``status``."""
        return sum(
            math.prod(a.share(lo, hi) for a, (lo, hi) in zip(self.axes, c.box, strict=True))
            for c in self.cells
            if c.status == status
        )

    def gain_range(self) -> tuple[Fraction, Fraction] | None:
        """The smallest lower end and the largest upper end of the certified cells' gains."""
        gains = [c.iss_gain for c in self.cells if c.status == CellStatus.CERTIFIED]
        return (min(g[0] for g in gains), max(g[1] for g in gains)) if gains else None

    def to_json(self) -> dict[str, Any]:
        """``{"cells": [{"box", "status", "certificate" | "failing_condition", "iss_gain"}]}``."""
        span = self.gain_range()
        wanted = self.requirements
        return {
            "case": self.case,
            "parameters": [a.to_json() for a in self.axes],
            "fixed": {k: str(v) for k, v in self.fixed.items()},
            "requirements": {k: None if v is None else str(v) for k, v in wanted.items()},
            "settings": self.settings,
            "box_conditions": list(self.box_conditions),
            "counts": {s.value: self.count(s) for s in CellStatus},
            "volume_share": {s.value: self.share(s) for s in CellStatus},
            "iss_gain": None if span is None else _interval(*span),
            "verdict": self.verdict,
            "tolerances": self.tolerances,
            "cells": [c.to_json(self.axes) for c in self.cells],
        }


def _interval(lo: Fraction, hi: Fraction) -> dict[str, Any]:
    """An exact interval and its approximation for reading."""
    return {"lo": str(lo), "hi": str(hi), "lo_approx": float(lo), "hi_approx": float(hi)}


# ---------------------------------------------------------------------------------------------
# the box


def _case_values(spec: PursuitSpec) -> dict[str, Fraction]:
    """The case's value of every path a box may vary (K_p_scale is 1: K_p as written)."""
    values = {"K_p_scale": Fraction(1)}
    if spec.controller == Controller.II:
        values["k_gamma"] = exact_decimal(spec.k_gamma)
    if spec.n_trackers > 1:
        values["k_c"] = exact_decimal(spec.k_c)
    for i, x in enumerate(spec.epsilon):
        values[f"epsilon.{i}"] = exact_decimal(x)
    return values


def _number(text: str, where: str) -> Fraction:
    """An exact number of ``--box``: 0 or a magnitude in [1e-300, 1e300] (floats must hold it)."""
    expected = "a decimal or a fraction such as 0.5, 1e-3 or 1/3, 0 or of magnitude 1e-300 … 1e300"
    if len(text) > 60 or re.search(r"[eE][+-]?\d{4}", text):
        raise CaseError(where, expected, text, file=COMMAND_LINE)
    try:
        value = Fraction(text.strip())
    except (ValueError, ZeroDivisionError):
        raise CaseError(where, expected, text, file=COMMAND_LINE) from None
    if value and not Fraction(1, 10**300) <= abs(value) <= 10**300:
        raise CaseError(where, expected, text, file=COMMAND_LINE)
    return value


def _require_pursuit(case: Case) -> None:
    if case.kind != "pursuit":
        raise CaseError("kind", "pursuit (trackcert design gains answers for seed 003 cases)",
                        case.kind, file=case.file)  # fmt: skip


def parse_box(case: Case, specs: Sequence[str]) -> tuple[Axis, ...]:
    """Axes from ``PATH=LO:HI`` or ``PATH=LO:HI:log`` texts (``--box``), checked against ``case``.

    PATH is ``k_gamma``, ``k_c``, ``K_p_scale`` or ``epsilon.I`` (0-based; ``pursuit.`` may
    prefix it); CaseError (field ``--box``) for an unknown path, a parameter the case lacks, a
    path given twice, LO ≥ HI, a gain with LO ≤ 0 or a log side with LO ≤ 0.
    """
    _require_pursuit(case)
    known = _case_values(case.spec)
    axes: list[Axis] = []
    for text in specs:
        path, sep, rest = text.partition("=")
        path = path.strip().removeprefix("pursuit.")
        parts = rest.split(":")
        if not sep or len(parts) not in (2, 3) or (len(parts) == 3 and parts[2] != "log"):
            raise CaseError("--box", "PATH=LO:HI or PATH=LO:HI:log", text, file=COMMAND_LINE)
        if path not in known:
            hint = "k_gamma needs controller II, k_c more than one tracker"
            expected = f"a path among {', '.join(known)}"
            raise CaseError("--box", expected, path, file=COMMAND_LINE, hint=hint)
        if any(a.path == path for a in axes):
            raise CaseError("--box", "each path once", text, file=COMMAND_LINE)
        lo, hi = (_number(x, f"--box {path}") for x in parts[:2])
        log = len(parts) == 3
        if not lo < hi:
            raise CaseError(f"--box {path}", "LO < HI", f"{lo}:{hi}", file=COMMAND_LINE)
        if (path in GAINS or log) and lo <= 0:
            why = "a gain of seed 003 must be positive" if path in GAINS else "a log side"
            raise CaseError(f"--box {path}", f"LO > 0 ({why})", f"{lo}:{hi}", file=COMMAND_LINE)
        axes.append(Axis(path, lo, hi, log))
    return tuple(axes)


def default_box(case: Case) -> tuple[Axis, ...]:
    """Two gains (k_γ or the K_p scale, and k_c; one gain for Type I with N = 1) from a tenth
    to ten times the case's values, in log scale."""
    _require_pursuit(case)
    values = _case_values(case.spec)
    first = "k_gamma" if "k_gamma" in values else "K_p_scale"
    second = "k_c" if "k_c" in values else ("K_p_scale" if first == "k_gamma" else None)
    paths = [p for p in (first, second) if p is not None]
    return tuple(Axis(p, values[p] / 10, values[p] * 10, log=True) for p in paths)


# ---------------------------------------------------------------------------------------------
# deciding one cell


@dataclass(frozen=True)
class _Problem:
    """Everything a cell's decision needs, computed once per box."""

    case: Case
    axes: tuple[Axis, ...]
    fixed: dict[str, Fraction]
    bounds: LoopBounds
    K_p: list[list[Fraction]]
    margin_tol: Fraction
    max_gain: Fraction | None
    min_rate: Fraction | None
    gain_rtol: Fraction | None
    gains: dict[tuple, tuple[Fraction, Fraction]] = field(default_factory=dict, compare=False)

    def gain(self, box: tuple) -> tuple[Fraction, Fraction]:
        """The exact enclosure [lo, hi] of the analysis gain over ``box`` (hi: the witness's)."""
        if box not in self.gains:
            kind_box = _kind_box(self.intervals(box))
            hi = box_witness(self.bounds, kind_box)["gain"]
            self.gains[box] = (box_gain_below(self.bounds, kind_box), hi)
        return self.gains[box]

    def intervals(self, box: tuple[tuple[Fraction, Fraction], ...]) -> dict[str, tuple]:
        """Every parameter's interval on the cell (unboxed ones: their case value)."""
        out = {k: (v, v) for k, v in self.fixed.items()}
        return out | {a.path: span for a, span in zip(self.axes, box, strict=True)}

    def corner(self, box: tuple, ends: dict[str, int]) -> dict[str, Fraction]:
        """The point of the cell at end ``ends[path]`` (0 lo, 1 hi; default lo) of each side."""
        return {a.path: span[ends.get(a.path, 0)] for a, span in zip(self.axes, box, strict=True)}


@dataclass(frozen=True)
class _Decision:
    """A cell's outcome, the sides a split may improve (empty: final) and, for a certified
    cell, the witness its certificate is made of once the cell is final."""

    cell: Cell
    split: tuple[str, ...] = field(default=())
    witness: tuple[dict, dict] | None = None


def _kind_box(spans: dict[str, tuple]) -> dict[str, tuple[Fraction, Fraction]]:
    """The cell in the names of kind ``iss-box``."""
    box = {"K_p_scale": spans["K_p_scale"], "epsilon_1": spans["epsilon.0"]}
    return box | {k: spans[k] for k in ("k_gamma", "k_c") if k in spans}


def _epsilon(problem: _Problem, box: tuple, depth: int) -> _Decision | None:
    """ε₁ ≠ 0 on the cell (eq. (22)) and |ε₁|/‖ε‖ ≥ margin_tol, or the decision against it."""
    spans = problem.intervals(box)
    lo, hi = spans["epsilon.0"]
    sides = tuple(a.path for a in problem.axes if a.path in EPSILON)
    if lo <= 0 <= hi:
        point = problem.corner(box, {})
        if "epsilon.0" in point:
            point["epsilon.0"] = Fraction(0)
        whole = lo == hi
        failing = FailingCondition(DELTA, DELTA_SOURCE, point, whole,
                                   "det(ΔΔᵀ) = 0 at ε₁ = 0: Δ̄ does not exist")  # fmt: skip
        cell = Cell(box, CellStatus.REFUTED, depth, failing_condition=failing)
        return _Decision(cell, () if whole else ("epsilon.0",))
    others = [spans[p] for p in EPSILON[1:] if p in spans]
    near, far = min(abs(lo), abs(hi)), max(abs(lo), abs(hi))
    widest = sum(max(a * a, b * b) for a, b in others)
    narrowest = sum(Fraction(0) if a <= 0 <= b else min(a * a, b * b) for a, b in others)
    tol2 = problem.margin_tol**2
    if near * near >= tol2 * (near * near + widest):
        return None
    whole = far * far < tol2 * (far * far + narrowest)
    where = "the whole" if whole else "part of the"
    reason = f"|ε₁|/‖ε‖ < margin_tol on {where} cell (trackcert iss: inconclusive there)"
    return _Decision(Cell(box, CellStatus.UNDECIDED, depth, reason=reason), () if whole else sides)


def _rates_hold(problem: _Problem, spans: dict[str, tuple], end: int) -> bool:
    """λ_min(K) ≥ min_rate and k_c a(L) ≥ min_rate at the lowest (0) or largest (1) gains."""
    rate = problem.min_rate
    s = spans["K_p_scale"][end]
    K = [[s * x for x in row] for row in problem.K_p]
    if "k_gamma" in spans:
        K = [[*row, Fraction(0)] for row in K] + [[Fraction(0)] * len(K) + [spans["k_gamma"][end]]]
    shifted = [[x - (rate if i == j else 0) for j, x in enumerate(row)] for i, row in enumerate(K)]
    if not positive_definite(shifted, semi=True).positive:
        return False
    if problem.bounds.r is None:
        return True
    gram = r_perp_gram(problem.case.spec.laplacian, problem.bounds.r, rate / spans["k_c"][end])
    return positive_definite(gram, semi=True).positive


def _rate_failure(problem: _Problem, box: tuple, depth: int) -> _Decision | None:
    """The decision against the cell when ``min_rate`` fails at its lowest gains (exact)."""
    spans = problem.intervals(box)
    if problem.min_rate is None or _rates_hold(problem, spans, 0):
        return None
    whole = not _rates_hold(problem, spans, 1)
    detail = f"the certified decay rate min(λ_min(K), k_c a(L)) < {problem.min_rate} here"
    failing = FailingCondition("decay_rate_at_least", "requirement --min-rate",
                               problem.corner(box, {}), whole, detail)  # fmt: skip
    cell = Cell(box, CellStatus.REFUTED, depth, failing_condition=failing)
    return _Decision(cell, () if whole else _gain_sides(problem))


def _gain_failure(problem: _Problem, box: tuple, depth: int, gain: tuple) -> _Decision | None:
    """The decision against the cell, or undecided, when its gain may exceed ``max_gain``.

    Refuted on the whole cell when the gain's exact lower end exceeds the limit, at a point when
    the lower end at a corner of lowest k_γ, k_c (either end of the K_p scale) does.
    """
    limit = problem.max_gain
    if limit is None or gain[1] <= limit:
        return None
    source = "requirement --max-gain"
    if gain[0] > limit:
        detail = f"the analysis gain is ≥ {float(gain[0]):.6g} > {limit} on the cell"
        failing = FailingCondition(
            "iss_gain_at_most", source, problem.corner(box, {}), True, detail
        )
        return _Decision(
            Cell(box, CellStatus.REFUTED, depth, failing_condition=failing, iss_gain=gain)
        )
    spans = problem.intervals(box)
    for s_end in (0, 1):
        point = problem.corner(box, {"K_p_scale": s_end})
        below = box_gain_below(
            problem.bounds, _kind_box(spans | {p: (x, x) for p, x in point.items()})
        )
        if below > limit:
            detail = f"the analysis gain at this point is ≥ {float(below):.6g} > {limit}"
            failing = FailingCondition("iss_gain_at_most", source, point, False, detail)
            cell = Cell(box, CellStatus.REFUTED, depth, failing_condition=failing, iss_gain=gain)
            return _Decision(cell, _gain_sides(problem))
    reason = f"the gain enclosure [{float(gain[0]):.6g}, {float(gain[1]):.6g}] contains {limit}"
    cell = Cell(box, CellStatus.UNDECIDED, depth, iss_gain=gain, reason=reason)
    return _Decision(cell, _gain_sides(problem))


def _gain_sides(problem: _Problem) -> tuple[str, ...]:
    return tuple(a.path for a in problem.axes if a.path in GAINS)


def _decide(problem: _Problem, box: tuple, depth: int) -> _Decision:
    """Certify, refute or leave undecided one cell (module docstring)."""
    decided = _epsilon(problem, box, depth) or _rate_failure(problem, box, depth)
    if decided is not None:
        return decided
    kind_box = _kind_box(problem.intervals(box))
    witness = box_witness(problem.bounds, kind_box, rate=problem.min_rate)
    gain = (problem.gain(box)[0], witness["gain"])
    decided = _gain_failure(problem, box, depth, gain)
    if decided is not None:
        return decided
    cell = Cell(box, CellStatus.CERTIFIED, depth, iss_gain=gain)
    loose = problem.gain_rtol is not None and gain[1] > gain[0] * (1 + problem.gain_rtol)
    return _Decision(cell, _gain_sides(problem) if loose else (), (kind_box, witness))


# ---------------------------------------------------------------------------------------------
# the map


def _halves(problem: _Problem, box: tuple, k: int) -> list[tuple]:
    """The two halves of ``box`` along side ``k``."""
    lo, hi = box[k]
    middle = problem.axes[k].middle(lo, hi)
    return [(*box[:k], (lo, middle), *box[k + 1 :]), (*box[:k], (middle, hi), *box[k + 1 :])]


def _split(problem: _Problem, decision: _Decision) -> list[tuple]:
    """The halves of the cell along a side of ``decision.split``: for gains, the side whose
    halves have the narrowest gain enclosures (a side the gain does not depend on is never
    chosen first); otherwise, or on a tie, the side the cell covers most of."""
    box = decision.cell.box
    gains = decision.split[0] in GAINS

    def priority(k: int) -> tuple[Fraction, float]:
        halves = _halves(problem, box, k) if gains else []
        spread = max((problem.gain(h)[1] - problem.gain(h)[0] for h in halves), default=0)
        return Fraction(spread), -problem.axes[k].share(*box[k])

    sides = [k for k, a in enumerate(problem.axes) if a.path in decision.split]
    return _halves(problem, box, min(sides, key=priority))


def _whole_box(case: Case, axes: tuple[Axis, ...], margin_tol: float) -> tuple[list, Cell | None]:
    """The conditions no box parameter changes (all but ε's when ε is boxed), and the cell of the
    whole box if one of them does not hold."""
    boxed = any(a.path in EPSILON for a in axes)
    conditions = iss_conditions(case.spec, margin_tol=margin_tol)
    conditions = [c for c in conditions if not (boxed and c.name == DELTA)]
    records = [c.to_json(margin_tol) for c in conditions]
    box = tuple((a.lo, a.hi) for a in axes)
    point = {a.path: a.lo for a in axes}
    for c in conditions:
        if c.status == ConditionStatus.FAILS:
            failing = FailingCondition(c.name, c.source, point, True, c.detail)
            return records, Cell(box, CellStatus.REFUTED, 0, failing_condition=failing)
    for c in conditions:
        if c.status == ConditionStatus.INCONCLUSIVE:
            return records, Cell(box, CellStatus.UNDECIDED, 0, reason=f"{c.name}: {c.detail}")
    return records, None


def gain_regions(
    case: Case,
    axes: Sequence[Axis],
    *,
    grid: int = 4,
    depth: int = 6,
    max_cells: int = 1024,
    max_gain: Fraction | None = None,
    min_rate: Fraction | None = None,
    gain_rtol: Fraction | None = None,
    margin_tol: float | None = None,
) -> GainRegions:
    """Certified, refuted and undecided cells of the corrected seed 003 conditions over a box.

    The box (``axes``, :func:`parse_box`) is cut into ``grid`` cells per side; a cell that a
    split may decide (undecided, refuted at one point only, or certified with a gain enclosure
    wider than ``gain_rtol``) is halved (:func:`_split`), breadth first, at most ``depth`` times
    and while the map has fewer than ``max_cells`` cells. ``max_gain`` and
    ``min_rate`` are optional requirements on the analysis's ISS gain g_e(1 + g_ξ) and decay rates
    (λ_min(K), k_c a(L)). ``margin_tol`` as in ``trackcert iss`` (the case's, else the default).
    CaseError for a case of another kind or settings out of range.
    """
    _require_pursuit(case)
    axes = tuple(axes)
    if margin_tol is None:
        margin_tol = case.tolerances.get("margin_tol", MARGIN_TOL)
    tol = float(margin_tol)
    options = {
        "margin_tol": tol,
        "max_gain": max_gain,
        "min_rate": min_rate,
        "gain_rtol": gain_rtol,
    }
    _check_settings(axes, grid, depth, max_cells, options)
    values = _case_values(case.spec)
    fixed = {k: v for k, v in values.items() if k not in {a.path for a in axes}}
    records, whole = _whole_box(case, axes, tol)
    settings = {"grid": grid, "depth": depth, "max_cells": max_cells,
                "gain_rtol": None if gain_rtol is None else str(gain_rtol)}  # fmt: skip
    requirements = {"max_gain": max_gain, "min_rate": min_rate}
    tolerances = {"margin_tol": tol, "iss_digits": float(ISS_DIGITS)}
    regions = GainRegions(
        case.name, axes, fixed, (), requirements, settings, tuple(records), tolerances
    )
    if whole is not None:
        return replace(regions, cells=(whole,))
    problem = _Problem(
        case, axes, fixed, loop_bounds(case.spec), exact_gain_matrix(case.spec.K_p),
        exact_decimal(tol), max_gain, min_rate, gain_rtol,
    )  # fmt: skip
    return replace(regions, cells=_cells(problem, grid, depth, max_cells))


def _cells(problem: _Problem, grid: int, depth: int, max_cells: int) -> tuple[Cell, ...]:
    """Decide the grid's cells and split the ones a split may decide (breadth first)."""
    sides = [list(itertools.pairwise(a.ends(grid))) for a in problem.axes]
    queue = deque((box, 0) for box in _product(sides))
    done, count = [], len(queue)
    while queue:
        box, level = queue.popleft()
        decision = _decide(problem, box, level)
        if decision.split and level < depth and count < max_cells:
            queue.extend((half, level + 1) for half in _split(problem, decision))
            count += 1
            continue
        done.append(_final(problem, decision, level < depth))
    return tuple(sorted(done, key=lambda c: c.box))


def _final(problem: _Problem, decision: _Decision, deeper: bool) -> Cell:
    """The cell as it stays: a certified one gets its certificate, an undecided one says why it
    was not split further."""
    cell = decision.cell
    if decision.witness is not None:
        box, witness = decision.witness
        certificate = iss_box_certificate(problem.bounds, box, witness, case=problem.case.name)
        return replace(cell, certificate=certificate)
    if cell.status != CellStatus.UNDECIDED or not decision.split:
        return cell
    why = "the cell budget (max_cells) is spent" if deeper else "the depth limit is reached"
    return replace(cell, reason=f"{cell.reason}; {why}")


def _product(sides: list[list[tuple]]) -> list[tuple]:
    boxes: list[tuple] = [()]
    for side in sides:
        boxes = [(*box, span) for box in boxes for span in side]
    return boxes


def _check_settings(axes: tuple, grid: int, depth: int, max_cells: int, options: dict) -> None:
    """CaseError (of the command line) for settings out of range."""

    def refuse(name: str, expected: str, got: object) -> None:
        raise CaseError(name, expected, got, file=COMMAND_LINE)

    if not axes:
        refuse("--box", "at least one PATH=LO:HI", "none")
    if not 1 <= grid <= 64:
        refuse("--grid", "an integer from 1 to 64", grid)
    if not 0 <= depth <= 40:
        refuse("--depth", "an integer from 0 to 40", depth)
    if grid ** len(axes) > max_cells:
        refuse("--max-cells", f"at least the grid's {grid ** len(axes)} cells", max_cells)
    for name, value in options.items():
        if value is not None and not value > 0:
            refuse(f"--{name.replace('_', '-')}", "a number > 0", value)


# ---------------------------------------------------------------------------------------------
# the report's design section and the map figure


def design_summary(case: Case) -> dict[str, Any]:
    """The report's design section for a pursuit case: what the gains change, and a small map.

    A 4 × 4 map of :func:`default_box` (no splits), the certified gain enclosure at the case's
    own gains, and the infimum of the analysis gain over all gains: ‖K_p‖/λ_min(K_p), since
    c♯/λ_min(K) ≥ s‖K_p‖/(sλ_min(K_p)), approached as k_γ, k_c → ∞ with s = k_γ/λ_min(K_p).
    """
    axes = default_box(case)
    regions = gain_regions(case, axes, grid=4, depth=0)
    out: dict[str, Any] = {
        "depends_on": {
            "k_gamma": "λ_min(K) = min(sλ_min(K_p), k_γ): decay rate and gain (Type II)",
            "K_p_scale": "λ_min(K) and c♯ = √(s²‖K_p‖² + 1 + μ_r): decay rate and gain",
            "k_c": "α = k_c a(L): coordination rate and g_ξ = b/(√r_min α) (N > 1)",
            "epsilon": "only ε₁ ≠ 0 (eq. (22)); the gains do not depend on ε",
        },
        "box_conditions": list(regions.box_conditions),
        "map": {k: v for k, v in regions.to_json().items() if k not in ("cells", "box_conditions")},
    }
    unsettled = (ConditionStatus.FAILS, ConditionStatus.INCONCLUSIVE)
    if any(c["status"] in unsettled for c in regions.box_conditions):
        return out
    bounds = loop_bounds(case.spec)
    values = _case_values(case.spec)
    spans = _kind_box({k: (v, v) for k, v in values.items()})
    at_case = box_witness(bounds, spans)["gain"]
    out["gain_at_case"] = _interval(box_gain_below(bounds, spans), at_case)
    condition = (bounds.norm_p[0] / bounds.lambda_p[1], bounds.norm_p[1] / bounds.lambda_p[0])
    out["gain_infimum"] = _interval(*condition) | {
        "value": "‖K_p‖/λ_min(K_p)",
        "approached": "k_γ, k_c → ∞ with K_p scaled by k_γ/λ_min(K_p) (Type I: scale → ∞)",
    }
    return out


def draw_gain_map(regions: GainRegions, path: Path) -> Path:
    """The map of a one- or two-sided box: certified cells coloured by their ISS gain (upper end
    of the enclosure, log scale), refuted cells hatched (red: on the whole cell, orange: at a
    point of it), undecided cells grey.

    ValueError for a box of more than two sides.
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import LogNorm
    from matplotlib.patches import Patch, Rectangle

    from theory.sim.outputs import new_figure, save_figure

    axes = regions.axes
    if len(axes) > 2:
        raise ValueError(f"draw_gain_map draws one or two sides, not {len(axes)}")
    fig, ax = new_figure(figsize=(6.4, 5.2 if len(axes) == 2 else 2.8))
    span = regions.gain_range()
    norm = None
    if span is not None:
        low, high = float(span[0]), float(span[1])
        middle = math.sqrt(low * high)
        norm = LogNorm(min(low, middle / 1.05), max(high, middle * 1.05))
    colours = colormaps["viridis"]
    for cell in regions.cells:
        (x0, x1), (y0, y1) = cell.box[0], (cell.box[1] if len(axes) == 2 else (0, 1))
        style = _CELL_STYLES[_style_key(cell)]
        if cell.status == CellStatus.CERTIFIED:
            style = style | {"facecolor": colours(norm(float(cell.iss_gain[1])))}
        ax.add_patch(Rectangle((float(x0), float(y0)), float(x1 - x0), float(y1 - y0), **style))
    _frame(ax, axes)
    if norm is not None:
        bar = fig.colorbar(ScalarMappable(norm=norm, cmap=colours), ax=ax)
        bar.set_label("ISS gain (certified upper end)")
    handles = [Patch(label=k, **v) for k, v in _CELL_STYLES.items() if k != "certified"]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3,
              fontsize=7, frameon=False)  # fmt: skip
    counts = ", ".join(f"{regions.count(s)} {s}" for s in CellStatus)
    ax.set_title(f"{regions.case}: {counts}", fontsize=9)
    return save_figure(fig, path)


_CELL_STYLES: dict[str, dict[str, Any]] = {
    "certified": {"edgecolor": "white", "linewidth": 0.4},
    "refuted (whole cell)": {"facecolor": "#f4a6a6", "edgecolor": "#b22222", "hatch": "///"},
    "refuted (at a point)": {"facecolor": "#fbd9b5", "edgecolor": "#d2691e", "hatch": ".."},
    "undecided": {"facecolor": "#c8c8c8", "edgecolor": "white", "linewidth": 0.4},
}
"""How :func:`draw_gain_map` draws each kind of cell."""


def _style_key(cell: Cell) -> str:
    if cell.status != CellStatus.REFUTED:
        return str(cell.status)
    return f"refuted ({'whole cell' if cell.failing_condition.whole_cell else 'at a point'})"


def _frame(ax: Any, axes: tuple[Axis, ...]) -> None:
    ax.set_xlim(float(axes[0].lo), float(axes[0].hi))
    ax.set_xscale("log" if axes[0].log else "linear")
    ax.set_xlabel(axes[0].path)
    if len(axes) == 2:
        ax.set_ylim(float(axes[1].lo), float(axes[1].hi))
        ax.set_yscale("log" if axes[1].log else "linear")
        ax.set_ylabel(axes[1].path)
    else:
        ax.set_ylim(0, 1)
        ax.set_yticks([])
