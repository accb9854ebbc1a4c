"""The report's unit of work on the task engine: some claims on one case, run where a worker is.

A :class:`CheckTask` is a small picklable payload — claim ids, the case, the report's seed, the time
limit — and :func:`run_task` runs it on a Dask worker (or in this process with ``--workers 1``):
it looks each claim up in the worker's own registry, runs it with its derived seed under the time
limit, and returns plain data (:class:`TaskOutput`): the records, the reason of a claim that does
not apply, the wall and CPU time of each check, the bytes of the figures the claims drew (so that
the report can be built on a machine that does not share the worker's disk), the independent
checker's verdict on each certificate document a claim returned
(:func:`theory.report.artifacts.check_document`: certificates are re-verified in parallel, not
after all the checks) and the worker's peak memory.

Claims of one case registered with ``shares_work`` share one task and one
:class:`~theory.core.claims.RunCache` (:func:`plan_tasks`), so that work they have in common (an
LMI solution, a simulation, Monte Carlo runs) is done once; every other check is a task of its own.
"""

from __future__ import annotations

import os
import resource
import socket
import tempfile
import time
import traceback
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from theory.core.case_file import Case
from theory.core.claims import (
    DOCUMENT_KEY,
    Claim,
    ClaimResult,
    Context,
    NotApplicable,
    RunCache,
)
from theory.registry import domains, get_claim
from theory.report.artifacts import check_document
from theory.report.canonical import canonical
from theory.report.records import MODEL_CASE, Record, derive_seed, paper_of, slug
from theory.report.time_limit import TimeLimitExceeded, time_limit

__all__ = [
    "CheckOutput",
    "CheckTask",
    "TaskOutput",
    "failed_task",
    "plan_tasks",
    "process_name",
    "run_batch",
    "run_task",
    "worker_modules",
]


@dataclass(frozen=True)
class CheckTask:
    """Claims to run, in order, on one case (``None``: the model claims' case ``-``).

    Attributes
    ----------
    claims : tuple of str
        Claim ids, looked up on the worker.
    case : Case or None
        The case.
    seed : int
        The report's seed (each claim gets :func:`~theory.report.records.derive_seed` of it).
    seconds : float or None
        Time limit of each check.
    figures : bool
        Whether claims that can draw should draw.
    """

    claims: tuple[str, ...]
    case: Case | None
    seed: int
    seconds: float | None
    figures: bool

    @property
    def case_name(self) -> str:
        """The case's name (``-`` for model claims)."""
        return MODEL_CASE if self.case is None else self.case.name


@dataclass(frozen=True)
class CheckOutput:
    """What one claim returned on the task's case.

    Attributes
    ----------
    claim, case : str
        Claim id and case name.
    records : tuple of Record
        Its results (figures named relative to the task's figure folder).
    not_applicable : str or None
        ``None`` when it returned results; else the reason it gave (``""``: none given).
    wall_seconds, cpu_seconds : float
        Wall and CPU (this process) time the check took.
    figures : dict of str to bytes
        The figures' content, by relative name ``<claim>/<case>/<file>``.
    certificate_checks : dict of str to dict
        The checker's verdict on each certificate document of the records, by the SHA-256 of
        the bytes checked (:func:`~theory.report.artifacts.check_document`).
    started : float or None
        When the check began (``time.time()`` where it ran); ``None`` if it never ran.
    """

    claim: str
    case: str
    records: tuple[Record, ...]
    not_applicable: str | None
    wall_seconds: float
    cpu_seconds: float
    figures: dict[str, bytes]
    certificate_checks: dict[str, dict[str, Any]] = field(default_factory=dict)
    started: float | None = None


@dataclass(frozen=True)
class TaskOutput:
    """A finished :class:`CheckTask`.

    Attributes
    ----------
    checks : tuple of CheckOutput
        One per claim of the task, in its order.
    worker : str
        ``host:pid`` of the process that ran it.
    peak_rss : int
        That process's peak resident memory so far, bytes.
    """

    checks: tuple[CheckOutput, ...]
    worker: str
    peak_rss: int


def plan_tasks(
    checks: Sequence[tuple[Claim, Case | None]],
    *,
    seed: int,
    seconds: float | None,
    figures: bool,
) -> list[CheckTask]:
    """The tasks running ``checks``: per case, one for the claims taking ``cache``, one per other.

    Parameters
    ----------
    checks : sequence of (Claim, Case or None)
        Every check of the report, in report order.
    seed : int
        The report's seed.
    seconds : float or None
        Time limit of each check.
    figures : bool
        Whether claims draw.

    Returns
    -------
    list of CheckTask
        The cache-sharing task of a case where its first such claim is, then the others in order.
    """
    tasks: list[CheckTask] = []
    sharing: dict[str, int] = {}
    for claim, case in checks:
        name = MODEL_CASE if case is None else case.name
        if claim.shares_work and name in sharing:
            task = tasks[sharing[name]]
            tasks[sharing[name]] = replace(task, claims=(*task.claims, claim.id))
            continue
        if claim.shares_work:
            sharing[name] = len(tasks)
        tasks.append(CheckTask((claim.id,), case, seed, seconds, figures))
    return tasks


def worker_modules() -> tuple[str, ...]:
    """The modules a worker imports to run any check: this one and every domain's registry,
    which imports its claims (the engine's ``preload``, :func:`theory.core.parallel.engine`)."""
    return (__name__, *(domain.__name__ for domain in domains()))


def run_task(task: CheckTask) -> TaskOutput:
    """Run every claim of ``task`` on its case, one :class:`RunCache` shared between them.

    Parameters
    ----------
    task : CheckTask
        The payload.

    Returns
    -------
    TaskOutput
        Never raises for a claim's failure: a check that raises (or runs past the time limit,
        or returns something malformed) is an ``inconclusive`` record of method ``none``.
    """
    cache = RunCache()
    with tempfile.TemporaryDirectory(prefix="trackcert-task-") as folder:
        root = Path(folder) if task.figures else None
        checks = tuple(_check(claim_id, task, cache, root) for claim_id in task.claims)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    return TaskOutput(checks, process_name(), peak)


def run_batch(batch: Sequence[CheckTask]) -> tuple[TaskOutput, ...]:
    """Run the tasks of ``batch`` one after the other, each as :func:`run_task` does (one engine
    task: the short checks of one claim travel together, :func:`theory.report.schedule.batches`).

    Parameters
    ----------
    batch : sequence of CheckTask
        The tasks.

    Returns
    -------
    tuple of TaskOutput
        One per task, in order.
    """
    return tuple(run_task(task) for task in batch)


def process_name() -> str:
    """``host:pid`` of this process (names the worker a check ran on)."""
    return f"{socket.gethostname()}:{os.getpid()}"


def failed_task(task: CheckTask, claims: dict[str, Claim], error: BaseException) -> TaskOutput:
    """The output of a task that never returned (its worker died, its payload did not pickle…).

    Parameters
    ----------
    task : CheckTask
        The task.
    claims : dict of str to Claim
        The report's claims by id.
    error : BaseException
        What the engine reported.

    Returns
    -------
    TaskOutput
        Every check of the task an ``inconclusive`` record saying why.
    """
    name = task.case_name
    outputs = []
    for claim_id in task.claims:
        claim = claims[claim_id]
        record = failure(claim, name, error, _recorded_seed(claim, task))
        outputs.append(CheckOutput(claim_id, name, (record,), None, 0.0, 0.0, {}))
    return TaskOutput(tuple(outputs), "", 0)


def _check(claim_id: str, task: CheckTask, cache: RunCache, root: Path | None) -> CheckOutput:
    name = task.case_name
    began, started, cpu = time.time(), time.perf_counter(), time.process_time()
    try:
        claim = get_claim(claim_id)
    except KeyError as error:
        missing = Claim(claim_id, "", "", (), lambda case, ctx: [])
        record = failure(missing, name, error, None)
        return CheckOutput(claim_id, name, (record,), None, 0.0, 0.0, {})
    folder = None if root is None else root / slug(claim.id) / slug(name)
    try:
        records = _run_one(claim, task, cache, folder)
        reason = None if records else ""
    except NotApplicable as why:
        records, reason = [], str(why)
    wall, cpu = time.perf_counter() - started, time.process_time() - cpu
    records, figures = _ship_figures(records, root)
    verdicts = dict(
        check_document(r.evidence[DOCUMENT_KEY])
        for r in records
        if isinstance(r.evidence.get(DOCUMENT_KEY), dict)
    )
    return CheckOutput(claim_id, name, tuple(records), reason, wall, cpu, figures, verdicts, began)


def _recorded_seed(claim: Claim, task: CheckTask) -> int | None:
    """The claim's derived seed, recorded for a ``seeded`` claim only."""
    return derive_seed(task.seed, claim.id, task.case_name) if claim.seeded else None


def _run_one(claim: Claim, task: CheckTask, cache: RunCache, folder: Path | None) -> list[Record]:
    name = task.case_name
    seed = _recorded_seed(claim, task)
    ctx = Context(cache, derive_seed(task.seed, claim.id, name), folder)
    try:
        with time_limit(task.seconds):
            results = claim.run(task.case, ctx)
        return [_record(claim, name, result, seed) for result in results]
    except NotApplicable:
        raise
    except (Exception, SystemExit, TimeLimitExceeded) as error:  # one check never stops the report
        return [failure(claim, name, error, seed)]


def _ship_figures(
    records: list[Record], root: Path | None
) -> tuple[list[Record], dict[str, bytes]]:
    """The records with figures named relative to ``root``, and those files' bytes."""
    if root is None:
        return records, {}
    figures: dict[str, bytes] = {}
    shipped = []
    for record in records:
        names = []
        for path in map(Path, record.figures):
            name = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.name
            if path.is_file():
                figures[name] = path.read_bytes()
            names.append(name)
        shipped.append(replace(record, result=replace(record.result, figures=tuple(names))))
    return shipped, figures


def _record(claim: Claim, case: str, result: ClaimResult, seed: int | None) -> Record:
    evidence = canonical(result.evidence, "evidence")
    if not isinstance(evidence, dict):
        raise TypeError(f"evidence is a {type(result.evidence).__name__}, not a mapping")
    plain = replace(
        result,
        claim=claim.id,
        case=case,
        evidence=evidence,
        margin=canonical(result.margin, "margin"),
        tolerance=canonical(dict(result.tolerance), "tolerance"),
        figures=tuple(str(f) for f in result.figures),
    )
    return _wrap(claim, plain, seed)


def _wrap(claim: Claim, result: ClaimResult, seed: int | None) -> Record:
    paper = paper_of(claim.id, claim.source)
    return Record(result, claim.source, claim.statement, paper, seed)


def failure(claim: Claim, case: str, error: BaseException, seed: int | None) -> Record:
    """An ``inconclusive`` record of method ``none`` saying why ``claim`` gave no result.

    Parameters
    ----------
    claim : Claim
        The claim.
    case : str
        The case name.
    error : BaseException
        What it raised (a :class:`TimeLimitExceeded` says so plainly).
    seed : int or None
        Its derived seed.

    Returns
    -------
    Record
    """
    kind = type(error).__name__
    message = (
        str(error)
        if isinstance(error, TimeLimitExceeded)
        else f"the check failed to run: {kind}: {error}"
    )
    evidence = {"error": {"type": kind, "message": str(error), "where": _where(error)}}
    result = ClaimResult(
        "inconclusive", "none", evidence, message=message, claim=claim.id, case=case
    )
    return _wrap(claim, result, seed)


def _where(error: BaseException) -> str:
    """``file:line in function`` of the innermost frame, the file relative to the package root."""
    frames = traceback.extract_tb(error.__traceback__)
    if not frames:
        return ""
    frame = frames[-1]
    root = Path(__file__).resolve().parents[2]
    path = Path(frame.filename).resolve()
    shown = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.name
    return f"{shown}:{frame.lineno} in {frame.name}"
