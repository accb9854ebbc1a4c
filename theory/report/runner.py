"""Run every registered claim on every case, as tasks on the engine, never letting one check stop
the others.

:func:`run_claims` is the report's engine: for each case it runs the claims registered for the
case's kind, and it runs the model claims (``kinds=()``) once, on no case (case ``"-"``). The checks
run as tasks (:mod:`theory.report.tasks`) on a :class:`~theory.core.parallel.TaskRunner`: serially
in this process by default, on Dask workers when the caller opens an engine with more. Every
exception a check raises, every malformed answer it returns, and every task the engine loses
becomes a :class:`Record` with status ``inconclusive``, method ``"none"`` and the error in its
message and evidence, so the report always completes. Each check's
:class:`~theory.core.claims.Context` carries a seed derived from the report's seed, its id and the
case name (:func:`derive_seed`), so reruns are identical whatever the number of workers or the
order in which they finish; claims registered with ``shares_work`` share one
:class:`~theory.core.claims.RunCache` per case; with a figure folder, a check draws into a fresh
sub-folder ``<claim>/<case>`` (returning the paths in ``figures``), and the figures travel back
from the worker as bytes and are written under the caller's folder. With a time
limit (:mod:`theory.report.time_limit`), a check still running when it expires becomes an
``inconclusive`` record saying so, and the report goes on with the next one.
"""

from __future__ import annotations

import fnmatch
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from theory.core.case_file import Case
from theory.core.claims import Claim
from theory.core.errors import CaseError
from theory.core.expectations import Expectation, evaluate, observations_from
from theory.core.parallel import Outcome, TaskRunner, engine
from theory.core.verdicts import expectations_verdict
from theory.registry import all_claims
from theory.report.canonical import canonical
from theory.report.records import MODEL_CASE, RESULT_FIELDS, Record, derive_seed, paper_of, slug
from theory.report.schedule import Batch, Estimates, batches
from theory.report.tasks import (
    CheckOutput,
    TaskOutput,
    failed_task,
    plan_tasks,
    run_batch,
)

__all__ = [
    "MODEL_CASE",
    "RESULT_FIELDS",
    "ProgressHook",
    "Record",
    "RunResult",
    "Timing",
    "derive_seed",
    "paper_of",
    "run_claims",
    "select_claims",
    "slug",
]

ProgressHook = Callable[[int, str], None]
"""``progress(done, label)``: ``done`` checks finished so far, ``label`` the last one's
``"claim on case"`` (called as each task completes)."""


@dataclass(frozen=True)
class Timing:
    """How long one check took, and where it ran.

    Attributes
    ----------
    claim, case : str
        The check.
    wall_seconds, cpu_seconds : float
        Wall time, and CPU time of the process that ran it.
    worker : str
        ``host:pid`` of that process (``""`` when its task was lost).
    peak_rss : int
        Peak resident memory of that process when the task ended, bytes.
    started : float or None
        When it began, in seconds after the run began (clocks of the report's machine and the
        worker's; ``None`` when its task was lost).
    """

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

    Attributes
    ----------
    records : tuple of Record
        Sorted by paper, claim id, case order.
    expectations : tuple of Expectation
        One per key of every case's ``expect`` block.
    not_applicable : tuple of (claim id, case name, reason)
        Claims that returned no result for a case (they do not apply to it); ``reason`` is the
        message of the :class:`~theory.core.claims.NotApplicable` the check raised, or ``""`` when
        it
        returned an empty list.
    cases : tuple of Case
        The cases, in the order given.
    claims : tuple of Claim
        The claims that were run, sorted by id.
    seed : int
        The report's seed.
    time_limit : float or None
        Seconds allowed to each check (``None``: no limit).
    timings : tuple of Timing
        Wall and CPU time of each check, in check order (not part of ``report.json``: they differ
        from run to run; :mod:`theory.report.timings` writes them to ``timings.json``).
    certificate_checks : dict of str to dict
        The independent checker's verdicts on the certificate documents, given where their
        claims ran, by the SHA-256 of the bytes checked (see
        :func:`theory.report.artifacts.prechecked`).
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
        """Whether every expectation of every case is met (the report's exit code 0)."""
        return all(e.verdict == "met" for e in self.expectations)

    @property
    def verdict(self) -> bool | None:
        """The expectations' verdict: False if one is unmet, True if all are met, else None
        (:func:`theory.core.verdicts.expectations_verdict`; the report's exit code)."""
        return expectations_verdict(self.expectations)


def select_claims(claims: Sequence[Claim], patterns: Sequence[str]) -> list[Claim]:
    """The claims whose id matches one of ``patterns``.

    Parameters
    ----------
    claims : sequence of Claim
        Candidates.
    patterns : sequence of str
        Shell-style patterns (``seed000.*``); none given selects every claim.

    Returns
    -------
    list of Claim
    """
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
        Validated cases (their names must be distinct).
    seed : int
        The report's seed; each claim accepting ``seed`` gets :func:`derive_seed` of it.
    claims : sequence of Claim, optional
        Defaults to every registered claim (:func:`theory.registry.all_claims`); workers
        look each one up by id in their own registry.
    progress : callable, optional
        ``progress(done, label)`` as each task completes (:data:`ProgressHook`).
    seconds : float, optional
        Time limit of each check (one claim on one case); ``None``: none.
    figure_dir : Path, optional
        Folder under which claims accepting ``figure_dir`` draw (``None``: no figures).
    runner : TaskRunner, optional
        An open engine (:func:`theory.core.parallel.engine`); default: this process, serially.
    estimates : Estimates, optional
        Estimated costs of the checks: the tasks are handed to the engine longest first, the
        short ones of a claim together (:func:`theory.report.schedule.batches`); default: one
        by one in report order.

    Returns
    -------
    RunResult
        Identical (records, order, seeds) whatever the runner and the estimates.
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
    """Records (with their case's position), not-applicable pairs and timings (started
    ``began`` = ``time.time()`` when the run began), in check order."""
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
