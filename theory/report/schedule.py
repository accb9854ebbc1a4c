"""How the report hands its tasks to the engine: longest first, short ones of a claim together.

A few checks cost tens of seconds (the particle filter's online learning, the pursuit and TDOA
closed loops) and most cost milliseconds. Handed to the workers in report order, a long task that
comes late keeps one worker busy while the others have nothing left: on two cores the report
finished 5–9 s later than with the longest tasks first (docs/parallel.md). So the tasks are
submitted longest first (Graham's LPT rule, within 4/3 of the best makespan), by *estimated*
cost: the CPU seconds each check took

1. in the previous run written to the same folder (its ``timings.json``), else
2. in the reference run bundled with trackcert (``check_costs.json`` beside this module,
   written by ``python -m benchmarks.bench_report --write-costs``), else
3. on average over the cases where the claim was measured, else :data:`UNKNOWN_SECONDS`.

Short checks of one claim are also batched into one engine task (:func:`batches`), so that one
worker, not every worker, pays the first run of their code.

The order changes when the work is done, never what it computes: every check is seeded from its
identity and the report is sorted afterwards (:mod:`theory.report.runner`), so ``report.json`` is
the same whatever the estimates say. A missing or malformed file of estimates is not an error;
it only leaves the order less good.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from statistics import fmean
from typing import Any

from theory.report.tasks import CheckTask
from theory.report.timings import FORMAT as TIMINGS_FORMAT

__all__ = [
    "BATCH_SECONDS",
    "COSTS_FORMAT",
    "SMALL_SECONDS",
    "UNKNOWN_SECONDS",
    "Batch",
    "Estimates",
    "batches",
    "bundled_costs_path",
    "costs_document",
    "load_estimates",
    "longest_first",
]

COSTS_FORMAT = "trackcert-check-costs/1"
"""Format tag of the bundled ``check_costs.json``."""

UNKNOWN_SECONDS = 0.05
"""Estimate of a check nothing is known about (a new claim): about the median check."""

SMALL_SECONDS = 0.3
"""A one-claim task estimated under this many seconds is batched with others of its claim."""

BATCH_SECONDS = 1.0
"""The most a batch of short tasks is estimated to take (keeps the last tasks short, so that
the workers finish together)."""

Batch = tuple[CheckTask, ...]
"""Tasks run one after the other as one engine task (:func:`theory.report.tasks.run_batch`)."""


@dataclass(frozen=True)
class Estimates:
    """Estimated CPU seconds of checks, by ``(claim id, case name)``.

    Attributes
    ----------
    seconds : mapping of (str, str) to float
        Measured costs.
    claim_means : mapping of str to float
        Each measured claim's mean cost over its cases (for a case it was not measured on).
    """

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
    """The engine's tasks, longest first: every task alone, but for the short ones of one claim,
    which travel together (up to :data:`BATCH_SECONDS` a batch).

    A claim's short checks (under :data:`SMALL_SECONDS` each, most of the report's) cost more the
    first time a process runs them (imports inside functions, caches, solver set-up: +37 % on the
    checks under 0.05 s with two workers, docs/parallel.md); together, one worker pays that once
    for them, and the engine handles a few dozen tasks instead of hundreds.

    Parameters
    ----------
    tasks : sequence of CheckTask
        The report's tasks (:func:`theory.report.tasks.plan_tasks`), in report order.
    estimates : Estimates
        Their costs.

    Returns
    -------
    list of tuple of CheckTask
        Every task once, in batches sorted by :func:`longest_first`; within a batch, report
        order.
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
    """``items`` sorted by decreasing estimated cost (the sum over their tasks; ties keep their
    order).

    Parameters
    ----------
    items : sequence of tuple of CheckTask
        Batches of tasks.
    estimates : Estimates
        Their costs.

    Returns
    -------
    list of tuple of CheckTask
    """
    return sorted(items, key=lambda batch: -_cost(batch, estimates))


def _cost(batch: Sequence[CheckTask], estimates: Estimates) -> float:
    return sum(estimates.task(task) for task in batch)


def bundled_costs_path() -> Path:
    """The reference costs shipped with trackcert (``check_costs.json`` beside this module)."""
    return Path(__file__).with_name("check_costs.json")


def load_estimates(out_dir: Path | None = None) -> Estimates:
    """The bundled reference costs, overridden by the previous run's ``out_dir/timings.json``.

    Parameters
    ----------
    out_dir : Path, optional
        The report folder about to be written.

    Returns
    -------
    Estimates
        Empty where neither file can be read (then every task is estimated alike and the
        report order is kept).
    """
    measured = _costs(_read(bundled_costs_path()))
    if out_dir is not None:
        measured.update(_timings(_read(Path(out_dir) / "timings.json")))
    return Estimates.of(measured)


def costs_document(timings: Mapping[str, Any], source: str) -> dict[str, Any]:
    """The ``check_costs.json`` document of a report's ``timings.json`` document.

    Parameters
    ----------
    timings : mapping
        A ``timings.json`` document (best from ``--workers 1``: no contention between checks).
    source : str
        What was measured, where and when (kept in the file).

    Returns
    -------
    dict
        ``{"format", "source", "seconds": {"claim on case": CPU seconds}}``.
    """
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
    """``document[key]`` when ``document`` is a mapping of format ``tag`` and that is a ``kind``,
    else an empty ``kind``."""
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
