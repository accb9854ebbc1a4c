"""``trackcert sweep`` as a library call: the grid of a case's parameters, judged and simulated
point by point on the task engine (:mod:`theory.core.parallel`).

:func:`sweep_case` checks everything it can before running anything — the case loads, every
``--param`` parses and names a numeric field (or ``seed``), the grid stays below
``max_points`` — so bad input is exit 2 with nothing computed. The points then run as engine
tasks in batches (:data:`TASKS_PER_WORKER` tasks per worker, each a stride of the grid, so the
cost of expensive regions is spread), and the rows come back in grid order: the result is the
same whatever the number of workers, the batching or the order in which tasks finish.

The sweep's verdict (:attr:`Sweep.verdict`, exit code by :mod:`theory.core.verdicts`): a sweep
asks *where do the analysis and the simulation part?*, so a point whose verdict fails is a
finding, not a failure of the sweep. It is False (exit 1) when some point's simulation
disagrees with its holding verdict (a certified point whose simulation leaves the certified
bound: a counterexample to the theorem as implemented), None (exit 3) when no point disagrees
but some valid point is inconclusive (its verdict, or the comparison), True (exit 0) otherwise.
Invalid points are rows, not errors; a sweep with no valid point at all is bad input (exit 2).
"""

from __future__ import annotations

import functools
import math
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import yaml

from theory.core.case_file import resolve_case_path
from theory.core.engines import resolve_engine
from theory.core.errors import COMMAND_LINE, CaseError
from theory.core.jsonable import plain
from theory.core.parallel import engine
from theory.core.verdicts import Verdict, exit_code
from theory.kinds import SIMULATED, load_case
from theory.sweep.grid import (
    MAX_POINTS,
    Param,
    Target,
    check_size,
    grid_points,
    parse_link,
    parse_param,
    resolve_target,
)
from theory.sweep.points import (
    Agreement,
    PointStatus,
    Row,
    SweepSetup,
    analysis_for,
    evaluate_batch,
    point_modules,
)

__all__ = ["TASKS_PER_WORKER", "Sweep", "sweep_case"]

TASKS_PER_WORKER = 64
"""Engine tasks per worker: enough for the last tasks to balance, few enough that Dask's
per-task overhead (a few ms) stays small against a batch of points."""


@dataclass(frozen=True)
class Sweep:
    """The result of :func:`sweep_case`: the case's name, kind and file, the swept parameters in
    ``--param`` order (then the links), the ``settings`` (``steps``, ``simulate``,
    ``runs_per_point``, ``seed`` — ``None`` when swept —, ``seed_swept``, ``max_points``) and one
    row per point, in grid order."""

    case: str
    kind: str
    file: str
    params: tuple[Param, ...]
    settings: dict[str, Any]
    rows: tuple[Row, ...]

    @property
    def verdict(self) -> Verdict:
        """False if a point disagrees, None if one is inconclusive, else True (module docstring)."""
        valid = [r for r in self.rows if r.status != PointStatus.INVALID]
        if any(r.agreement == Agreement.DISAGREE for r in valid):
            return False
        undecided = (PointStatus.INCONCLUSIVE, Agreement.INCONCLUSIVE)
        if any(r.status in undecided or r.agreement in undecided for r in valid):
            return None
        return True

    @property
    def exit_code(self) -> int:
        """The exit code of :attr:`verdict`."""
        return exit_code(self.verdict)

    def sim_columns(self) -> list[str]:
        """The ``sim_*`` columns present in some row, in first-seen order."""
        seen: dict[str, None] = {}
        for row in self.rows:
            seen.update(dict.fromkeys(row.simulated))
        return list(seen)

    def columns(self) -> list[str]:
        """The ``sweep.csv`` header (``docs/sweep.md``)."""
        return [
            "point",
            *(p.path for p in self.params),
            "status",
            "exit_code",
            "margin",
            "tolerances",
            "sim_seed",
            *self.sim_columns(),
            "agreement",
            "message",
        ]

    def records(self) -> list[dict[str, Any]]:
        """One plain mapping per row, keyed by :meth:`columns` (tolerances as a mapping)."""
        sims = self.sim_columns()
        return [
            {
                "point": r.point,
                **{p.path: v for p, v in zip(self.params, r.values, strict=True)},
                "status": r.status,
                "exit_code": r.exit_code,
                "margin": r.margin,
                "tolerances": dict(r.tolerances),
                "sim_seed": r.sim_seed,
                **{k: r.simulated.get(k) for k in sims},
                "agreement": r.agreement,
                "message": r.message,
            }
            for r in self.rows
        ]

    def summary(self) -> dict[str, Any]:
        """Counts by status and by agreement, the verdict and the exit code."""
        return {
            "points": len(self.rows),
            "status": dict(sorted(Counter(r.status for r in self.rows).items())),
            "agreement": dict(sorted(Counter(r.agreement for r in self.rows).items())),
            "disagreeing_points": [
                r.point for r in self.rows if r.agreement == Agreement.DISAGREE
            ],
            "verdict": self.verdict,
            "exit_code": self.exit_code,
        }

    def to_json(self) -> dict[str, Any]:
        """The ``sweep.json`` record: case, params, settings, tolerances, summary, rows."""
        valid = [r for r in self.rows if r.status != PointStatus.INVALID]
        return plain(
            {
                "case": self.case,
                "kind": self.kind,
                "file": self.file,
                "params": [p.to_json() for p in self.params],
                "settings": self.settings,
                "tolerances": dict(valid[0].tolerances) if valid else {},
                "summary": self.summary(),
                "columns": self.columns(),
                "rows": self.records(),
            }
        )


def _targets(data: Any, kind: str, params: Sequence[Param], file: str) -> tuple[Target, ...]:
    targets = tuple(resolve_target(data, kind, p.path, file=file) for p in params)
    for target, param in zip(targets, params, strict=True):
        if target.is_seed and not all(isinstance(v, int) and v >= 0 for v in param.values):
            raise CaseError(
                "--param seed", "integers ≥ 0 (e.g. seed=0:50)", param.spec, file=COMMAND_LINE
            )
    return targets


def _batches(points: list[tuple[int, tuple]], tasks: int) -> list[list[tuple[int, tuple]]]:
    """``tasks`` strides of the grid (batch ``j`` holds points ``j, j + tasks, …``)."""
    return [points[j::tasks] for j in range(min(tasks, len(points)))]


def sweep_case(
    case: str,
    params: Sequence[str | Param],
    *,
    links: Sequence[str] = (),
    steps: int | None = None,
    simulate: bool = True,
    workers: int | None = None,
    scheduler: str | None = None,
    max_points: int = MAX_POINTS,
    progress: Callable[[int, int], None] | None = None,
) -> Sweep:
    """Sweep ``case`` (a file or bundled name) over the grid of ``params`` (``trackcert sweep``).

    Parameters
    ----------
    case : str
        A case file or bundled case name.
    params : sequence of str or Param
        ``PATH=SPEC`` texts (:func:`theory.sweep.grid.parse_param`) or parsed parameters.
    links : sequence of str
        ``PATH=EXPR`` texts (:func:`theory.sweep.grid.parse_link`): fields set at each point from
        a swept parameter's value (they follow the parameters in rows and columns).
    steps : int, optional
        Simulation steps per point (default: the kind's).
    simulate : bool
        Whether to simulate each point (kinds with a simulator).
    workers : int, optional
        Local worker processes (default all cores; 1 runs serially in this process).
    scheduler : str, optional
        Address of a Dask scheduler (default ``$TRACKCERT_SCHEDULER``).
    max_points : int
        The largest grid accepted (:data:`theory.sweep.grid.MAX_POINTS`).
    progress : callable, optional
        ``progress(done, total)`` in points, as tasks finish.

    Raises
    ------
    CaseError
        Bad case, ``--param``, ``--link``, ``--steps``, ``--max-points`` or ``--no-simulate``
        for a kind judged by its simulation, no point valid, or a ``$TRACKCERT_ENGINE`` naming
        no engine for a pursuit sweep (exit 2).
    """
    loaded = load_case(case)
    data = yaml.safe_load(resolve_case_path(case).read_text(encoding="utf-8"))
    swept = tuple(p if isinstance(p, Param) else parse_param(p) for p in params)
    parsed = swept + tuple(parse_link(text, swept) for text in links)
    total = check_size(parsed, max_points)
    _check_settings(loaded.kind, steps, simulate)
    targets = _targets(data, loaded.kind, parsed, loaded.file)
    setup = SweepSetup(data, loaded.file, targets, steps, simulate)
    points = list(enumerate(grid_points(parsed)))
    rows = _run(setup, points, workers, scheduler, progress)
    sweep = Sweep(loaded.name, loaded.kind, loaded.file, parsed, _settings(setup, max_points), rows)
    if all(r.status == PointStatus.INVALID for r in rows):
        raise CaseError(
            "--param",
            "a grid with at least one point the case loader accepts",
            rows[0].message,
            file=loaded.file,
            hint=f"all {total} points are invalid",
        )
    return sweep


def _check_settings(kind: str, steps: int | None, simulate: bool) -> None:
    if steps is not None and steps < 1:
        raise CaseError("--steps", "an integer ≥ 1", steps, file=COMMAND_LINE)
    if not simulate and analysis_for(kind) is None:
        raise CaseError(
            "--no-simulate",
            "a kind with an analysis verdict (pursuit, dkf, tdoa, pf)",
            f"kind {kind}, judged by its simulation",
            file=COMMAND_LINE,
        )
    if simulate and kind == "pursuit":
        resolve_engine()  # a bad $TRACKCERT_ENGINE is bad input, not a row per point


def _settings(setup: SweepSetup, max_points: int) -> dict[str, Any]:
    simulated = setup.simulate and setup.data["kind"] in SIMULATED
    swept_seed = any(t.is_seed for t in setup.targets)
    return {
        "steps": setup.steps,
        "simulate": simulated,
        "runs_per_point": 1 if simulated else 0,
        "seed": None if swept_seed else setup.seed,
        "seed_swept": swept_seed,
        "max_points": max_points,
    }


def _run(
    setup: SweepSetup,
    points: list[tuple[int, tuple]],
    workers: int | None,
    scheduler: str | None,
    progress: Callable[[int, int], None] | None,
) -> tuple[Row, ...]:
    total = len(points)
    with engine(workers, scheduler, preload=point_modules(setup.data["kind"])) as runner:
        batches = _batches(points, TASKS_PER_WORKER * runner.workers)
        per_task = total / len(batches)

        def advance(done: int) -> None:
            if progress is not None:
                progress(min(total, math.ceil(done * per_task)), total)

        results = runner.map(functools.partial(evaluate_batch, setup), batches, progress=advance)
    return tuple(sorted((row for batch in results for row in batch), key=lambda r: r.point))
