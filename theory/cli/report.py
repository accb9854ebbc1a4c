"""``trackcert report [CASES…] -o DIR``: every registered check on every case, as a report.

A shell over :func:`theory.report.build.build_report`; the exit code is the expectations' verdict
(:mod:`theory.core.verdicts`).
"""

from __future__ import annotations

import contextlib
from collections import Counter
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Annotated

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from theory.cli.common import check_output, console, error_console, reports_errors
from theory.core.case_file import bundled_cases, load_case
from theory.core.verdicts import exit_code
from theory.report.build import build_report, check_count, choose_claims
from theory.report.canonical import dumps
from theory.report.runner import MODEL_CASE

__all__ = ["DEFAULT_TIME_LIMIT", "register"]

DEFAULT_TIME_LIMIT = 300.0
"""Seconds one check (a claim on a case) may take by default: the slowest bundled one takes about
20 s on two cores, so only a runaway check meets it."""


def register(app: typer.Typer) -> None:
    """Add the ``report`` command to ``app``."""

    @app.command("report")
    @reports_errors
    def report(
        cases: Annotated[
            list[str] | None,
            typer.Argument(help="Case files or bundled case names (default: every bundled case)."),
        ] = None,
        out: Annotated[Path, typer.Option("-o", "--out", help="Report folder.")] = Path("report"),
        seed: Annotated[
            int, typer.Option("--seed", min=0, help="Seed for every randomized check.")
        ] = 0,
        only: Annotated[
            list[str] | None,
            typer.Option("--only", help="Run only claims whose id matches this pattern."),
        ] = None,
        errata: Annotated[
            Path | None,
            typer.Option("--errata", help="Errata document (default: docs/errata.md)."),
        ] = None,
        time_limit: Annotated[
            float,
            typer.Option(
                "--time-limit",
                min=0,
                help="Seconds each check may run before it is recorded as inconclusive "
                "(0: no limit).",
            ),
        ] = DEFAULT_TIME_LIMIT,
        as_json: Annotated[
            bool, typer.Option("--json", help="Also print report.json to stdout.")
        ] = False,
    ) -> None:
        """Run every registered check on every case; write index.html, report.md, report.json.

        Exit 0 when every expectation of every case is met, 1 when one is unmet, 3 when one is
        inconclusive or unchecked (and none unmet), 2 on bad input. CASES
        are case files or bundled names; --seed seeds every randomized check; --only keeps the
        claims whose id matches a pattern; --errata names the errata document; --time-limit
        bounds each check's wall time; --json prints report.json.
        """
        check_output(out, "-o/--out", folder=True)
        loaded = [load_case(c) for c in (cases or list(bundled_cases()))]
        claims = choose_claims(only or [])
        with _progress(check_count(loaded, claims)) as advance:
            run, document = build_report(
                loaded,
                out,
                claims=claims,
                seed=seed,
                seconds=time_limit or None,
                errata_path=errata,
                progress=advance,
            )
        if as_json:
            console.file.write(dumps(document))
        else:
            _print_summary(document, out)
        raise typer.Exit(exit_code(run.verdict))


@contextlib.contextmanager
def _progress(total: int) -> Iterator[Callable[[str, str], None]]:
    """A progress bar on stderr, and the hook advancing it before each check."""
    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
    )
    with Progress(*columns, console=error_console, transient=True) as progress:
        task = progress.add_task("checking", total=total)

        def advance(claim_id: str, case: str) -> None:
            where = "model" if case == MODEL_CASE else case
            progress.update(task, description=f"{claim_id} on {where}")
            progress.advance(task)

        yield advance


def _print_summary(document: dict, out: Path) -> None:
    """One row per claim with its results counted by status (every result is in the files)."""
    statuses = ("verified", "corrected", "refuted", "inconclusive")
    table = Table(title=f"trackcert report: {document['summary']['results']} results")
    table.add_column("claim", overflow="fold")
    for status in statuses:
        table.add_column(status, justify="right")
    counts: dict[str, Counter] = {}
    for r in document["claims"]:
        counts.setdefault(r["id"], Counter())[r["status"]] += 1
    for claim, seen in counts.items():
        table.add_row(claim, *(str(seen[s]) if seen[s] else "" for s in statuses))
    console.print(table)
    unmet = [e for e in document["expectations"] if e["verdict"] != "met"]
    for e in unmet:
        console.print(f"{e['verdict']}: {e['case']} expect.{e['key']}", markup=False)
    counts = document["summary"]["expectations"]
    verdict = (
        "every expectation is met"
        if document["summary"]["all_expectations_met"]
        else ", ".join(f"{n} {v}" for v, n in counts.items() if n) + " expectation(s)"
    )
    console.print(f"{verdict}; wrote {out / 'index.html'}, report.md, report.json", markup=False)
