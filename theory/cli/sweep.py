"""``trackcert sweep CASE --param PATH=SPEC … -o DIR``: a case judged and simulated over a grid.

A shell over :func:`theory.sweep.run.sweep_case` and :func:`theory.sweep.outputs.write_sweep`
(``docs/sweep.md``): writes ``DIR/sweep.csv``, ``DIR/sweep.json`` and ``DIR/sweep.png``, shows
a progress bar on a terminal (none under ``--json`` or when stdout is not a terminal) and
prints the counts by status and agreement (or, with ``--json``, the ``summary`` record).
Exit code (:mod:`theory.core.verdicts`, :attr:`theory.sweep.run.Sweep.verdict`): 1 some
point's simulation disagrees with its holding verdict, 3 none does but some point is
inconclusive, 0 otherwise; 2 bad input (including a grid with no valid point).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from theory.cli.common import (
    COMMAND_LINE,
    check_folder_output,
    console,
    json_option,
    print_json,
    progress_bar,
    reports_errors,
    scheduler_option,
    workers_option,
)
from theory.core.validation import check_count

__all__ = ["register"]

PARAM_HELP = (
    "PATH=SPEC, repeatable (the grid is the product). SPEC: FROM:TO integers FROM…TO−1 "
    "(half-open), FROM:TO:linN or FROM:TO:logN (N points, ends included), v1,v2,… or one value "
    "(e.g. k_gamma=1:400:log20, seed=0:50). PATH is a dotted path to a numeric case field "
    "(k_gamma, trackers.0.r_x, W.0.1) or seed."
)
LINK_HELP = (
    "PATH=EXPR, repeatable: set PATH at each point from a swept --param path SOURCE, EXPR one "
    "of SOURCE, -SOURCE, B*SOURCE, A+SOURCE, A-SOURCE, A+B*SOURCE, A-B*SOURCE "
    "(e.g. W.0.1=1-W.0.0 keeps a row of W stochastic). Adds no points."
)


def _print_summary(summary: dict, files: list[Path]) -> None:
    status = ", ".join(f"{n} {s}" for s, n in summary["status"].items())
    agreement = ", ".join(f"{n} {a}" for a, n in summary["agreement"].items())
    console.print(
        f"{summary['points']} points: {status}; simulation vs verdict: {agreement}",
        markup=False,
        highlight=False,
    )
    if summary["disagreeing_points"]:
        console.print(f"disagreeing points: {summary['disagreeing_points']}", markup=False)
    console.print(f"wrote {', '.join(str(f) for f in files)}", markup=False, highlight=False)


def register(app: typer.Typer) -> None:
    """Add the ``sweep`` command to ``app``."""

    @app.command("sweep")
    @reports_errors
    def sweep(
        case: str = typer.Argument(..., help="Case file or bundled case name."),
        param: Annotated[list[str] | None, typer.Option("--param", "-p", help=PARAM_HELP)] = None,
        link: Annotated[list[str] | None, typer.Option("--link", help=LINK_HELP)] = None,
        output: str = typer.Option(..., "-o", "--output", help="Folder for the sweep files."),
        workers: int = workers_option(),
        scheduler: str = scheduler_option(),
        steps: int = typer.Option(None, "--steps", min=1, help="Simulation steps per point."),
        simulate: bool = typer.Option(
            True, "--simulate/--no-simulate", help="Simulate each point (one run)."
        ),
        max_points: int = typer.Option(
            None, "--max-points", help="Largest grid accepted (default 100000)."
        ),
        as_json: bool = json_option("Print the summary as JSON."),
    ) -> None:
        """Judge and simulate CASE at every point of a parameter grid; write CSV, JSON, PNG."""
        from theory.sweep.grid import MAX_POINTS
        from theory.sweep.outputs import MARKER, write_sweep
        from theory.sweep.run import sweep_case

        check_folder_output(output, "-o/--output", MARKER)
        if steps is not None:
            check_count("steps", steps, "--steps", file=COMMAND_LINE)
        with progress_bar(0, "sweep", quiet=as_json) as advance:
            result = sweep_case(
                case,
                param or [],
                links=link or [],
                steps=steps,
                simulate=simulate,
                workers=workers,
                scheduler=scheduler,
                max_points=MAX_POINTS if max_points is None else max_points,
                progress=lambda done, total: advance(done, total=total),
            )
        files = write_sweep(result, Path(output))
        summary = result.to_json()["summary"]
        if as_json:
            print_json({"case": result.case, **summary, "files": [str(f) for f in files]})
        else:
            _print_summary(summary, files)
        raise typer.Exit(result.exit_code)
