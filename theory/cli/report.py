"""``trackcert report [CASES…] -o DIR``: every registered check on every case, as a report; and
``trackcert cases``, the bundled cases it runs on by default.

A shell over :func:`theory.report.render.build_report`; the exit code is the expectations'
verdict (:func:`theory.core.verdicts.command_verdict`: the report decides no property of its own).
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.table import Table

from theory.cli.common import (
    check_folder_output,
    console,
    print_json,
    progress_bar,
    reports_errors,
    scheduler_option,
    workers_option,
)
from theory.core.case_file import bundled_cases, resolve_case_path
from theory.core.claims import Status
from theory.core.expectations import ExpectationVerdict
from theory.core.jsonable import dumps
from theory.core.parallel import engine
from theory.core.verdicts import command_verdict, exit_code
from theory.kinds import load_case

if TYPE_CHECKING:  # the report's modules (jinja2 …) are imported when a report runs
    from theory.report.runner import RunResult

__all__ = ["DEFAULT_TIME_LIMIT", "register"]

DEFAULT_TIME_LIMIT = 300.0
"""CPU seconds one check (a claim on a case) may use by default: the slowest bundled one uses about
40 s, so only a runaway check meets it, however loaded the machine
(:class:`theory.report.tasks.time_limit`)."""


def register(app: typer.Typer) -> None:
    """Add the ``report`` and ``cases`` commands to ``app``."""

    @app.command("cases")
    @reports_errors
    def cases(
        kind: str = typer.Option(None, "--kind", help="Only cases of this kind."),
        as_json: bool = typer.Option(False, "--json", help="Print JSON."),
        names: bool = typer.Option(False, "--names", help="Print only the names, one a line."),
    ) -> None:
        """List the bundled cases (name, kind, source)."""
        rows = []
        for name, path in bundled_cases().items():
            case = load_case(path)
            if kind is None or case.kind == kind:
                rows.append(
                    {"name": name, "kind": case.kind, "source": case.source, "path": str(path)}
                )
        if names:
            console.print("\n".join(row["name"] for row in rows), markup=False, highlight=False)
            return
        if as_json:
            print_json({"cases": rows})
            return
        table = Table(title="bundled cases")
        for column in ("name", "kind", "source"):
            table.add_column(column)
        for row in rows:
            table.add_row(row["name"], row["kind"], row["source"])
        console.print(table)

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
                help="CPU seconds each check may use before it is recorded as inconclusive "
                "(0: no limit); CPU, not wall-clock, so a busy machine changes no verdict.",
            ),
        ] = DEFAULT_TIME_LIMIT,
        model_claims: Annotated[
            bool | None,
            typer.Option(
                "--model-claims/--no-model-claims",
                help="Also run the case-independent model claims (default: yes for the full "
                "bundled report or with --only, no when CASES are named).",
                show_default=False,
            ),
        ] = None,
        as_json: Annotated[
            bool, typer.Option("--json", help="Also print report.json to stdout.")
        ] = False,
        workers: int | None = workers_option(),
        scheduler: str | None = scheduler_option(),
    ) -> None:
        """Run every registered check on every case; write index.html, report.md, report.json.

        Exit 0 when every expectation of every case is met, 1 when one is unmet, 3 when one is
        inconclusive or unchecked (and none unmet), 2 on bad input, 4 on a fault (a failed
        write, no worker). CASES are case files or bundled names; --seed seeds every randomized
        check; --only keeps the claims whose id matches a pattern; --model-claims also runs the
        claims that need no case (by default when no CASES are named, or with --only; a report of
        named cases does only their work otherwise); --errata names the errata
        document; --time-limit bounds each check's CPU time; --json prints report.json; the
        folder is replaced whole, or left as it was; --workers and --scheduler
        say where the checks run (the report is the same whatever they say). The checks' times
        go to timings.json; the ten slowest are printed at the end.
        """
        from theory.report.render import MARKER

        check_folder_output(out, "-o/--out", MARKER)
        options = {"seed": seed, "seconds": time_limit or None, "errata_path": errata}
        paths = [resolve_case_path(c) for c in (cases or list(bundled_cases()))]
        models = model_claims if model_claims is not None else not cases or bool(only)
        selection = (only or [], models)
        run, document = _run(paths, out, selection, options, (workers, scheduler), as_json)
        if as_json:
            console.file.write(dumps(document))
        else:
            _print_summary(document, out)
            if not models:
                console.print(
                    "the case-independent model claims were not run (--model-claims runs them)",
                    markup=False,
                )
            _print_slowest(run)
        raise typer.Exit(exit_code(command_verdict(True, run.expectations)))


def _run(
    paths: list[Path],
    out: Path,
    selection: tuple[list[str], bool],
    options: dict[str, Any],
    where: tuple[int | None, str | None],
    quiet: bool,
) -> tuple[RunResult, dict]:
    """The report on the engine (``where`` = workers, scheduler) behind a progress bar, of the
    claims ``selection`` = (``--only`` patterns, whether the model claims run).

    The workers start first, in the background, while this process loads the case files
    ``paths`` and imports the claims (their forkserver imports the same modules: about 3 s that
    would otherwise come before the first check); a case name that names no file was refused
    before, without waiting for them."""
    from theory.report.render import build_report, check_count, choose_claims
    from theory.report.tasks import worker_modules

    with engine(*where, preload=worker_modules()) as runner:
        runner.start()
        loaded = [load_case(path) for path in paths]
        only, models = selection
        claims = [c for c in choose_claims(only) if models or c.kinds]
        with progress_bar(check_count(loaded, claims), "checking", quiet=quiet) as advance:
            return build_report(
                loaded, out, claims=claims, progress=advance, runner=runner, **options
            )


def _print_summary(document: dict, out: Path) -> None:
    """One row per claim with its results counted by status (every result is in the files)."""
    statuses = (Status.VERIFIED, Status.CORRECTED, Status.REFUTED, Status.INCONCLUSIVE)
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
    findings = Counter(r["finding"] for r in document["claims"] if r.get("finding"))
    if findings:
        found = ", ".join(f"{n} {finding}" for finding, n in sorted(findings.items()))
        console.print(f"findings of the non-verified results: {found}", markup=False)
    unmet = [e for e in document["expectations"] if e["verdict"] != ExpectationVerdict.MET]
    for e in unmet:
        console.print(f"{e['verdict']}: {e['case']} expect.{e['key']}", markup=False)
    counts = document["summary"]["expectations"]
    verdict = (
        "every expectation is met"
        if document["summary"]["all_expectations_met"]
        else ", ".join(f"{n} {v}" for v, n in counts.items() if n) + " expectation(s)"
    )
    wrote = f"wrote {out / 'index.html'}, report.md, report.json, timings.json"
    console.print(f"{verdict}; {wrote}", markup=False)


def _print_slowest(run: RunResult, count: int = 10) -> None:
    """The ``count`` slowest checks (wall and CPU seconds; all are in timings.json)."""
    from theory.report.runner import slowest

    table = Table(title=f"{count} slowest checks (all in timings.json)")
    for column, justify in (("claim", "left"), ("case", "left"), ("wall s", "right")):
        table.add_column(column, justify=justify, overflow="fold")
    table.add_column("CPU s", justify="right")
    for t in slowest(run.timings, count):
        table.add_row(t.claim, t.case, f"{t.wall_seconds:.2f}", f"{t.cpu_seconds:.2f}")
    console.print(table)
