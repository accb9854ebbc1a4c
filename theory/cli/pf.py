"""``trackcert pf CASE``: Monte Carlo runs of the distributed TDOA particle filter (seed 002 §3.3).

A shell over :func:`theory.particle.report.pf_report`: prints the per-node error summary, the
verdicts of every registered claim for ``kind: pf`` cases, and each key of the case's ``expect``
block with the value the claims observed (judged by :mod:`theory.core.expectations`, as
``trackcert report`` judges it); with ``-o DIR`` the library writes ``DIR/pf.json`` and the
figures, replacing the folder whole. Exit code (:func:`theory.core.verdicts.command_verdict`: pf
decides no property of its own): 0 every expectation met (or none stated), 1 one unmet, 3 one
inconclusive or unchecked.
"""

from __future__ import annotations

import json
from pathlib import Path

import typer
from rich.table import Table

from theory.cli.common import (
    COMMAND_LINE,
    check_folder_output,
    console,
    print_json,
    progress_bar,
    reports_errors,
    scheduler_option,
    workers_option,
)
from theory.core.case_file import Case
from theory.core.verdicts import command_verdict, exit_code
from theory.kinds import load_case

__all__ = ["register", "run_pf_case"]


def register(app: typer.Typer) -> None:
    """Add the ``pf`` command to ``app``."""

    @app.command("pf")
    @reports_errors
    def pf(
        case_name: str = typer.Argument(..., metavar="CASE", help="Case file or bundled name."),
        runs: int = typer.Option(None, "--runs", min=1, help="Monte Carlo runs (case default)."),
        seed: int = typer.Option(None, "--seed", min=0, help="Base seed (case default)."),
        out: str = typer.Option(None, "-o", "--out", help="Folder for pf.json and figures."),
        as_json: bool = typer.Option(False, "--json", help="Print JSON."),
        workers: int = workers_option(),
        scheduler: str = scheduler_option(),
    ) -> None:
        """Run the distributed TDOA particle filter of seed 002 on a kind: pf case."""
        code = run_pf_case(
            load_case(case_name), runs, seed, out, as_json, workers=workers, scheduler=scheduler
        )
        raise typer.Exit(code)


def run_pf_case(
    case: Case,
    runs: int | None,
    seed: int | None,
    out: str | None,
    as_json: bool,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    figures: bool = True,
) -> int:
    """Print :func:`theory.particle.report.pf_report` of ``case`` (``runs``, ``seed``: ``None``
    for the case's own; ``out``: folder for ``pf.json`` and, when ``figures``, the figures) and
    return the expectations' exit code."""
    from theory.core.parallel import engine
    from theory.particle.case import check_pf_runs
    from theory.particle.report import MARKER, pf_report

    if out is not None:
        check_folder_output(out, "-o/--out", MARKER)
    if runs is not None:
        check_pf_runs(case, runs, "--runs", file=COMMAND_LINE)
    total = runs or getattr(case.spec, "runs", 1)
    with (
        engine(workers, scheduler) as runner,
        progress_bar(total, f"pf {case.name}", quiet=as_json) as advance,
    ):
        report = pf_report(
            case,
            runs=runs,
            seed=seed,
            out=None if out is None else Path(out),
            runner=runner,
            progress=advance,
            figures=figures,
        )
    record = report.to_json()
    if as_json:
        print_json(record)
    else:
        _print(record)
    return exit_code(command_verdict(True, report.expectations))


def _print(report: dict) -> None:
    from theory.core.consistency import describe

    table = Table(
        title=f"{report['case']}: {report['runs']} runs, seed {report['seed']}, "
        f"model {report['model']}, m = {report['share']}"
    )
    for column in (
        "node",
        "TDOA meas.",
        "mean E (m)",
        "final E (m)",
        "tail E mean ± sd",
        "tail E 10/50/90 %",
    ):
        table.add_column(column)
    for a in report["agents"]:
        table.add_row(
            str(a["id"]),
            str(a["measurements"]),
            f"{a['mean_localization_error']:.2f}",
            f"{a['final_localization_error']:.2f}",
            f"{a['tail_error_mean']:.2f} ± {a['tail_error_std']:.2f}",
            f"{a['tail_error_q10']:.2f} / {a['tail_error_median']:.2f} / {a['tail_error_q90']:.2f}",
        )
    console.print(table)
    for line in describe(report["metrics"]):
        console.print(line, markup=False)
    for claim in report["claims"]:
        console.print(f"{claim['id']}: {claim['status']} — {claim['message']}", markup=False)
    for e in report["expectations"]:
        found = ", ".join(json.dumps(o["value"]) for o in e["observations"]) or "nothing"
        console.print(
            f"expect {e['key']} = {json.dumps(e['expected'])}: {e['verdict']} (observed {found})",
            markup=False,
        )
    for figure in report["figures"]:
        console.print(f"figure: {figure}", markup=False)
