"""``trackcert report`` as one library call: choose the claims, run them, write the folder.

:func:`build_report` runs :func:`theory.report.runner.run_claims` on the caller's task engine
(:func:`theory.core.parallel.engine`, preloading :func:`theory.report.tasks.worker_modules`;
default: serially in this process) with figures drawn in a temporary folder, then writes the report
with :func:`theory.report.render.write_report` and the checks' times with
:func:`theory.report.timings.write_timings` into a staging folder that replaces the report folder
whole (:func:`theory.core.atomic_output.replaced_folder`): a failure or a signal leaves the old
report as it was. The command only shows progress and a summary and exits with the expectations'
verdict (:mod:`theory.core.verdicts`).
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from theory.core.atomic_output import check_replaceable, recover, replaced_folder
from theory.core.case_file import Case
from theory.core.claims import Claim
from theory.core.errors import CaseError
from theory.core.parallel import TaskRunner
from theory.registry import all_claims
from theory.report.render import write_report
from theory.report.runner import ProgressHook, RunResult, run_claims, select_claims
from theory.report.schedule import load_estimates
from theory.report.timings import timings_document, write_timings

__all__ = ["MARKER", "build_report", "check_count", "choose_claims"]

MARKER = "report.json"
"""The file every report folder has: a folder without it is not replaced (unless empty)."""


def choose_claims(patterns: Sequence[str] = ()) -> list[Claim]:
    """The registered claims matching ``patterns`` (all of them when none is given).

    Parameters
    ----------
    patterns : sequence of str
        Shell-style patterns of claim ids (``--only``).

    Returns
    -------
    list of Claim

    Raises
    ------
    CaseError
        If patterns are given and none matches a registered claim (the hint lists them).
    """
    registered = all_claims()
    claims = select_claims(registered, patterns)
    if patterns and not claims:
        known = "Registered claims: " + ", ".join(c.id for c in registered)
        raise CaseError(
            "--only",
            "a pattern matching a registered claim id",
            list(patterns),
            file="<command line>",
            hint=known,
        )
    return claims


def check_count(cases: Sequence[Case], claims: Sequence[Claim]) -> int:
    """How many checks :func:`build_report` runs: each model claim once, each claim per case.

    Parameters
    ----------
    cases : sequence of Case
        The cases.
    claims : sequence of Claim
        The claims.

    Returns
    -------
    int
    """
    return sum(1 for c in claims if not c.kinds) + sum(
        1 for case in cases for c in claims if case.kind in c.kinds
    )


def build_report(
    cases: Sequence[Case],
    out_dir: Path,
    *,
    claims: Sequence[Claim] | None = None,
    seed: int = 0,
    seconds: float | None = None,
    errata_path: Path | None = None,
    progress: ProgressHook | None = None,
    runner: TaskRunner | None = None,
) -> tuple[RunResult, dict[str, Any]]:
    """Run every claim on every case; write ``index.html``, ``report.md``, ``report.json`` and
    ``timings.json``.

    Parameters
    ----------
    cases : sequence of Case
        The cases (distinct names).
    out_dir : Path
        The report folder.
    claims : sequence of Claim, optional
        Default: every registered claim.
    seed : int
        Seed of every randomized check (:func:`theory.report.runner.derive_seed`).
    seconds : float, optional
        Time limit of each check (``None``: none).
    errata_path : Path, optional
        The errata document (default ``docs/errata.md``).
    progress : callable, optional
        ``progress(done, label)`` as checks complete (:data:`~theory.report.runner.ProgressHook`).
    runner : TaskRunner, optional
        An open engine to run the checks on (default: serially in this process).

    Returns
    -------
    (RunResult, dict)
        What the claims returned, and the ``report.json`` document.

    Raises
    ------
    CaseError
        If ``errata_path`` is not a readable file, the folder is not a report folder
        (:func:`theory.core.atomic_output.replaceable_problem`) or the engine's scheduler cannot
        be reached.
    OutputError
        If writing fails (the folder is left as it was).
    """
    if errata_path is not None and not Path(errata_path).is_file():
        raise CaseError(
            "--errata", "a readable Markdown file", str(errata_path), file="<command line>"
        )
    recover(out_dir)  # a report killed while swapping folders: its old folder comes back first
    check_replaceable(out_dir, MARKER)
    with tempfile.TemporaryDirectory(prefix="trackcert-figures-") as figures:
        started = time.perf_counter()
        run = run_claims(
            cases,
            seed=seed,
            claims=claims,
            progress=progress,
            seconds=seconds,
            figure_dir=Path(figures),
            runner=runner,
            estimates=load_estimates(Path(out_dir)),
        )
        wall = time.perf_counter() - started
        timings = timings_document(
            run,
            wall_seconds=wall,
            workers=1 if runner is None else runner.size,
            scheduler=None if runner is None else runner.scheduler,
        )
        with replaced_folder(out_dir, MARKER) as staging:
            document = write_report(run, staging, errata_path=errata_path)
            write_timings(timings, staging)
    return run, document
