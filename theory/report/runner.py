"""Run every claim on every case as tasks on the engine, in an order that finishes early, and
account for the time each check took.

:func:`run_claims` runs the claims of each case's kind on it, and the model claims (``kinds=()``)
once on no case (``"-"``), as :mod:`theory.report.tasks` on a
:class:`~theory.core.parallel.TaskRunner` (serially in this process by default). Every check's
seed derives from the report's seed, its id and its case, and the records are sorted afterwards,
so the result is the same whatever the workers and the order they finish in. A lost task becomes
``inconclusive`` records; drawn figures travel back as bytes and are written under the caller's
figure folder.

**Schedule.** A few checks cost tens of seconds and most cost milliseconds; handed out in report
order, a long task that comes late keeps one worker busy while the others idle (5–9 s later on
two cores, docs/parallel.md). So tasks are submitted longest first (Graham's LPT rule, within 4/3
of the best makespan) by *estimated* CPU seconds: the previous run's ``timings.json`` in the same
folder, else the bundled ``check_costs.json`` (``python -m benchmarks.bench_report
--write-costs``), else the claim's mean over the cases it was measured on, else
:data:`UNKNOWN_SECONDS`. Short checks of one claim travel in one batch (:func:`batches`) so one
worker pays their first-run cost. A missing or malformed estimate only makes the order worse.

**Timings.** Wall times differ between runs, so they stay out of ``report.json`` and go to
``timings.json`` (:func:`timings_document`): ``{"format", "workers", "scheduler",
"wall_seconds", "cpu_seconds", "parent_peak_rss", "worker_peak_rss", "checks": [{"id", "case",
"wall_seconds", "cpu_seconds", "worker", "started_seconds"}, …]}`` in check order
(``started_seconds`` after the run began, ``null`` for a lost task).
"""

from __future__ import annotations

import fnmatch
import json
import resource
import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from statistics import fmean
from typing import Any

from theory.core.case_file import Case
from theory.core.claims import Claim
from theory.core.errors import CaseError
from theory.core.expectations import Expectation, evaluate, observations_from
from theory.core.jsonable import canonical
from theory.core.parallel import Outcome, TaskRunner, engine
from theory.core.verdicts import Verdict, expectations_verdict
from theory.registry import all_claims
from theory.report.tasks import (
    MODEL_CASE,
    CheckOutput,
    CheckTask,
    Record,
    TaskOutput,
    failed_task,
    plan_tasks,
    process_name,
    run_batch,
)

__all__ = [
    "BATCH_SECONDS",
    "COSTS_FORMAT",
    "SMALL_SECONDS",
    "TIMINGS_FORMAT",
    "UNKNOWN_SECONDS",
    "Batch",
    "Estimates",
    "ProgressHook",
    "RunResult",
    "Timing",
    "batches",
    "bundled_costs_path",
    "costs_document",
    "load_estimates",
    "longest_first",
    "run_claims",
    "select_claims",
    "slowest",
    "timings_document",
    "write_timings",
]

ProgressHook = Callable[[int, str], None]
"""``progress(done, label)``: checks finished so far and the last one's ``"claim on case"``."""

TIMINGS_FORMAT = "trackcert-timings/1"
COSTS_FORMAT = "trackcert-check-costs/1"

UNKNOWN_SECONDS = 0.05
"""Estimate of a check nothing is known about (a new claim): about the median check."""

SMALL_SECONDS = 0.3
"""A one-claim task estimated under this many seconds is batched with others of its claim."""

BATCH_SECONDS = 1.0
"""The most a batch of short tasks is estimated to take (so the workers finish together)."""

Batch = tuple[CheckTask, ...]
"""Tasks run one after the other as one engine task (:func:`theory.report.tasks.run_batch`)."""


@dataclass(frozen=True)
class Timing:
    """One check's wall and CPU seconds, the ``host:pid`` that ran it (``""``: lost), that
    process's peak memory (bytes) and when it began after the run began (``None``: lost)."""

    claim: str
    case: str
    wall_seconds: float
    cpu_seconds: float
    worker: str
    peak_rss: int
    started: float | None = None


@dataclass(frozen=True)
class RunResult:
    """Everything the claims returned, ready to be rendered.

    ``records`` are sorted by paper, claim id and case order; ``expectations`` has one entry per
    key of every case's ``expect`` block; ``not_applicable`` lists (claim, case, reason) of the
    claims that returned no result (the reason of their
    :class:`~theory.core.claims.NotApplicable`, or ``""``); ``claims`` are the claims run, by id;
    ``timings`` go to ``timings.json`` only; ``certificate_checks`` are the checker's verdicts on
    certificate documents, by SHA-256 of the bytes checked.
    """

    records: tuple[Record, ...]
    expectations: tuple[Expectation, ...]
    not_applicable: tuple[tuple[str, str, str], ...]
    cases: tuple[Case, ...]
    claims: tuple[Claim, ...]
    seed: int
    time_limit: float | None = None
    timings: tuple[Timing, ...] = ()
    certificate_checks: Mapping[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def all_expectations_met(self) -> bool:
        """Whether every expectation of every case is met."""
        return all(e.met for e in self.expectations)

    @property
    def verdict(self) -> Verdict:
        """The expectations' verdict (:func:`theory.core.verdicts.expectations_verdict`)."""
        return expectations_verdict(self.expectations)


def select_claims(claims: Sequence[Claim], patterns: Sequence[str]) -> list[Claim]:
    """The claims whose id matches one of the shell-style ``patterns`` (none: all of them)."""
    if not patterns:
        return list(claims)
    return [c for c in claims if any(fnmatch.fnmatchcase(c.id, p) for p in patterns)]


def run_claims(
    cases: Sequence[Case],
    *,
    seed: int = 0,
    claims: Sequence[Claim] | None = None,
    progress: ProgressHook | None = None,
    seconds: float | None = None,
    figure_dir: Path | None = None,
    runner: TaskRunner | None = None,
    estimates: Estimates | None = None,
) -> RunResult:
    """Run each claim on each case it applies to, and the model claims once.

    Parameters
    ----------
    cases : sequence of Case
        Validated cases with distinct names.
    seed : int
        The report's seed (each check's derives from it).
    claims : sequence of Claim, optional
        Default: every registered claim (:func:`theory.registry.all_claims`); a task looks each
        one up by id in its own process's registry.
    progress : callable, optional
        :data:`ProgressHook`, called as each task completes.
    seconds : float, optional
        CPU-time limit of each check (``None``: none).
    figure_dir : Path, optional
        Folder under which drawing checks put their figures (``None``: no figures).
    runner : TaskRunner, optional
        An open engine (:func:`theory.core.parallel.engine`); default: this process, serially.
    estimates : Estimates, optional
        Estimated costs: tasks are handed out longest first, short ones of a claim together
        (:func:`batches`); default: one by one in report order.

    Returns
    -------
    RunResult
        The same records, order and seeds whatever the runner and the estimates.
    """
    claims = sorted(all_claims() if claims is None else claims, key=lambda c: c.id)
    _check_distinct_names(cases)
    checks = [(c, None) for c in claims if not c.kinds] + [
        (c, case) for case in cases for c in claims if case.kind in c.kinds
    ]
    tasks = plan_tasks(checks, seed=seed, seconds=seconds, figures=figure_dir is not None)
    scheduled = [(t,) for t in tasks] if estimates is None else batches(tasks, estimates)
    began = time.time()
    with _opened(runner) as engine_runner:
        outputs = _run_tasks(engine_runner, scheduled, {c.id: c for c in claims}, progress)
    rows, skipped, timings = _collect(checks, cases, outputs, figure_dir, began)
    rows.sort(key=lambda row: (row[1].paper, row[1].id, row[0]))
    records = tuple(r for _, r in rows)
    return RunResult(
        records,
        _expectations(cases, records),
        tuple(skipped),
        tuple(cases),
        tuple(claims),
        seed,
        seconds,
        tuple(timings),
        {d: v for out in outputs for o in out.checks for d, v in o.certificate_checks.items()},
    )


def _collect(
    checks: list[tuple[Claim, Case | None]],
    cases: Sequence[Case],
    outputs: list[TaskOutput],
    figure_dir: Path | None,
    began: float,
) -> tuple[list[tuple[int, Record]], list[tuple[str, str, str]], list[Timing]]:
    """Records (with their case's position), not-applicable triples and timings, in check order."""
    by_check = {(o.claim, o.case): (o, out) for out in outputs for o in out.checks}
    order = {MODEL_CASE: -1} | {case.name: i for i, case in enumerate(cases)}
    rows: list[tuple[int, Record]] = []
    skipped: list[tuple[str, str, str]] = []
    timings: list[Timing] = []
    for claim, case in checks:
        name = MODEL_CASE if case is None else case.name
        check, task = by_check[(claim.id, name)]
        if check.not_applicable is not None:
            skipped.append((claim.id, name, check.not_applicable))
        rows.extend((order[name], r) for r in _with_figures(check, figure_dir))
        started = None if check.started is None else check.started - began
        timings.append(
            Timing(
                claim.id,
                name,
                check.wall_seconds,
                check.cpu_seconds,
                task.worker,
                task.peak_rss,
                started,
            )
        )
    return rows, skipped, timings


@contextmanager
def _opened(runner: TaskRunner | None) -> Iterator[TaskRunner]:
    if runner is not None:
        yield runner
        return
    with engine(1) as serial:
        yield serial


def _run_tasks(
    runner: TaskRunner,
    scheduled: list[Batch],
    claims: dict[str, Claim],
    progress: ProgressHook | None,
) -> list[TaskOutput]:
    """Every task's output; a lost batch's checks become inconclusive records."""
    outputs: list[TaskOutput] = []
    done = 0
    for outcome in runner.completed(run_batch, scheduled):
        batch = scheduled[outcome.index]
        outputs.extend(_outputs(batch, outcome, claims))
        done += sum(len(task.claims) for task in batch)
        if progress is not None:
            last = batch[-1]
            where = "model" if last.case is None else last.case_name
            progress(done, f"{last.claims[-1]} on {where}")
    return outputs


def _outputs(batch: Batch, outcome: Outcome, claims: dict[str, Claim]) -> list[TaskOutput]:
    """The batch's outputs, or each task's failure when the batch was lost or returned junk."""
    value = outcome.value
    if (
        outcome.error is None
        and isinstance(value, tuple)
        and len(value) == len(batch)
        and all(isinstance(output, TaskOutput) for output in value)
    ):
        return list(value)
    error = outcome.error or TypeError(f"the task returned a {type(value).__name__}")
    return [failed_task(task, claims, error) for task in batch]


def _with_figures(check: CheckOutput, figure_dir: Path | None) -> tuple[Record, ...]:
    """The check's records, their figures written under ``figure_dir`` and named by path there."""
    if figure_dir is None or not check.figures:
        return check.records
    for name, content in check.figures.items():
        target = figure_dir / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(content)
    return tuple(
        replace(r, result=replace(r.result, figures=tuple(str(figure_dir / f) for f in r.figures)))
        for r in check.records
    )


def _check_distinct_names(cases: Sequence[Case]) -> None:
    names = [case.name for case in cases]
    duplicated = sorted({n for n in names if names.count(n) > 1})
    if duplicated:
        raise CaseError("name", "distinct case names in one report", duplicated[0])


def _expectations(cases: Sequence[Case], records: Sequence[Record]) -> tuple[Expectation, ...]:
    verdicts: list[Expectation] = []
    for case in cases:
        observations = [
            found
            for r in records
            if r.case == case.name
            for found in observations_from(r.id, r.evidence, r.status)
        ]
        rules = case.expect_rules
        verdicts.extend(evaluate(case.name, canonical(case.expect), observations, rules))
    return tuple(verdicts)


# ---------------------------------------------------------------------------------- schedule
@dataclass(frozen=True)
class Estimates:
    """Estimated CPU seconds of checks by ``(claim id, case name)``, and each measured claim's
    mean over its cases (for a case it was not measured on)."""

    seconds: Mapping[tuple[str, str], float] = field(default_factory=dict)
    claim_means: Mapping[str, float] = field(default_factory=dict)

    @classmethod
    def of(cls, measured: Mapping[tuple[str, str], float]) -> Estimates:
        """Estimates from measured costs."""
        by_claim: dict[str, list[float]] = {}
        for (claim, _), seconds in measured.items():
            by_claim.setdefault(claim, []).append(seconds)
        return cls(dict(measured), {c: fmean(v) for c, v in by_claim.items()})

    def check(self, claim: str, case: str) -> float:
        """The estimated cost of ``claim`` on ``case``."""
        known = self.seconds.get((claim, case))
        if known is not None:
            return known
        return self.claim_means.get(claim, UNKNOWN_SECONDS)

    def task(self, task: CheckTask) -> float:
        """The estimated cost of a task: the sum over its checks."""
        return sum(self.check(claim, task.case_name) for claim in task.claims)


def batches(tasks: Sequence[CheckTask], estimates: Estimates) -> list[Batch]:
    """Every task once, in batches sorted by :func:`longest_first`: each task alone, but for a
    claim's short ones (under :data:`SMALL_SECONDS`), which travel together in report order up to
    :data:`BATCH_SECONDS` a batch.

    A claim's short checks cost more the first time a process runs them (imports inside
    functions, caches, solver set-up: +37 % on the checks under 0.05 s with two workers,
    docs/parallel.md); batched, one worker pays that once, and the engine handles a few dozen
    tasks instead of hundreds.
    """
    grouped: list[list[CheckTask]] = []
    filling: dict[str, int] = {}  # claim id → its batch still being filled
    for task in tasks:
        cost = estimates.task(task)
        if len(task.claims) > 1 or cost >= SMALL_SECONDS:
            grouped.append([task])
            continue
        claim = task.claims[0]
        open_batch = filling.get(claim)
        if open_batch is not None and _cost(grouped[open_batch], estimates) + cost <= BATCH_SECONDS:
            grouped[open_batch].append(task)
        else:
            filling[claim] = len(grouped)
            grouped.append([task])
    return longest_first([tuple(batch) for batch in grouped], estimates)


def longest_first(items: Sequence[Batch], estimates: Estimates) -> list[Batch]:
    """``items`` by decreasing estimated cost (ties keep their order)."""
    return sorted(items, key=lambda batch: -_cost(batch, estimates))


def _cost(batch: Sequence[CheckTask], estimates: Estimates) -> float:
    return sum(estimates.task(task) for task in batch)


def bundled_costs_path() -> Path:
    """The reference costs shipped with trackcert (``check_costs.json`` beside this module)."""
    return Path(__file__).with_name("check_costs.json")


def load_estimates(out_dir: Path | None = None) -> Estimates:
    """The bundled costs, overridden by the previous run's ``out_dir/timings.json`` (empty where
    neither can be read: every task is then estimated alike and report order is kept)."""
    measured = _costs(_read(bundled_costs_path()))
    if out_dir is not None:
        measured.update(_timings(_read(Path(out_dir) / "timings.json")))
    return Estimates.of(measured)


def costs_document(timings: Mapping[str, Any], source: str) -> dict[str, Any]:
    """The ``check_costs.json`` document ``{"format", "source", "seconds": {"claim on case":
    CPU seconds}}`` of a ``timings.json`` document (best from ``--workers 1``); ``source`` says
    what was measured, where and when."""
    seconds = _timings(timings)
    return {
        "format": COSTS_FORMAT,
        "source": source,
        "seconds": {f"{claim} on {case}": round(s, 3) for (claim, case), s in seconds.items()},
    }


def _read(path: Path) -> Any:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError):
        return None


def _costs(document: Any) -> dict[tuple[str, str], float]:
    """The costs of a ``check_costs.json`` document (nothing if it is not one)."""
    entries = _part(document, COSTS_FORMAT, "seconds", dict)
    pairs = ((key.partition(" on "), value) for key, value in entries.items())
    return _valid((claim, case, value) for (claim, _, case), value in pairs)


def _timings(document: Any) -> dict[tuple[str, str], float]:
    """The checks' CPU seconds of a ``timings.json`` document (nothing if it is not one)."""
    rows = (c for c in _part(document, TIMINGS_FORMAT, "checks", list) if isinstance(c, dict))
    return _valid((c.get("id"), c.get("case"), c.get("cpu_seconds")) for c in rows)


def _part(document: Any, tag: str, key: str, kind: type) -> Any:
    """``document[key]`` if ``document`` is of format ``tag`` and that is a ``kind``, else an
    empty ``kind``."""
    if isinstance(document, dict) and document.get("format") == tag:
        part = document.get(key)
        if isinstance(part, kind):
            return part
    return kind()


def _valid(rows: Iterable[tuple[Any, Any, Any]]) -> dict[tuple[str, str], float]:
    """The rows naming a claim and a case with a finite non-negative cost."""
    return {
        (claim, case): float(value)
        for claim, case, value in rows
        if isinstance(claim, str)
        and isinstance(case, str)
        and claim
        and case
        and isinstance(value, int | float)
        and not isinstance(value, bool)
        and 0 <= value < float("inf")
    }


# ----------------------------------------------------------------------------------- timings
def slowest(timings: Sequence[Timing], count: int = 10) -> list[Timing]:
    """The ``count`` checks of longest wall time, slowest first (ties: report order)."""
    return sorted(timings, key=lambda t: -t.wall_seconds)[:count]


def timings_document(
    run: RunResult, *, wall_seconds: float, workers: int, scheduler: str | None
) -> dict[str, Any]:
    """The ``timings.json`` document of ``run`` (module docstring): the whole run's wall seconds,
    the local workers used (1: serial) and the scheduler's address, if one was used."""
    workers_rss: dict[str, int] = {}
    for t in run.timings:
        if t.worker and t.worker != process_name():
            workers_rss[t.worker] = max(workers_rss.get(t.worker, 0), t.peak_rss)
    return {
        "format": TIMINGS_FORMAT,
        "workers": workers,
        "scheduler": scheduler,
        "wall_seconds": round(wall_seconds, 3),
        "cpu_seconds": round(sum(t.cpu_seconds for t in run.timings), 3),
        "parent_peak_rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
        "worker_peak_rss": dict(sorted(workers_rss.items())),
        "checks": [
            {
                "id": t.claim,
                "case": t.case,
                "wall_seconds": round(t.wall_seconds, 4),
                "cpu_seconds": round(t.cpu_seconds, 4),
                "worker": t.worker,
                "started_seconds": None if t.started is None else round(t.started, 3),
            }
            for t in run.timings
        ],
    }


def write_timings(document: dict[str, Any], out_dir: Path) -> Path:
    """Write ``document`` as ``out_dir/timings.json``."""
    path = Path(out_dir) / "timings.json"
    path.write_text(json.dumps(document, indent=1) + "\n", encoding="utf-8")
    return path
