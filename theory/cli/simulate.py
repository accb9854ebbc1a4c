"""``trackcert simulate CASE``: closed-loop simulation, data files and figures (docs/simulation.md).

A shell over :func:`theory.sim.simulate.simulate_case` with the case kind's simulator
(:func:`theory.kinds.simulator_for`: ``kind: tdoa-sim`` in
:mod:`theory.tdoa.estimation.simulation`, ``kind: dkf`` in :mod:`theory.consensus.kalman_filter`,
``kind: pursuit`` in :mod:`theory.pursuit.simulation`); ``kind: pf`` cases are handed to
:func:`theory.cli.pf.run_pf_case`, as ``trackcert pf`` runs them. Exit code
(:func:`theory.core.verdicts.command_verdict`: simulate decides no property of its own): the
expectations' verdict, 0 all met (or none stated), 1 one unmet, 3 one inconclusive or unchecked;
1 too when the case's controller does not exist (``PropertyFails``, e.g. ε₁ = 0 in seed 003).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import typer

from theory.cli.common import (
    COMMAND_LINE,
    check_folder_output,
    console,
    error_console,
    print_json,
    progress_bar,
    reports_errors,
    scheduler_option,
    workers_option,
)
from theory.core.errors import CaseError
from theory.core.validation import check_count
from theory.core.verdicts import command_verdict, exit_code
from theory.kinds import load_case

__all__ = ["check_options", "register"]

KINDS = ("tdoa-sim", "pursuit", "dkf", "pf")


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command to ``app``."""

    @app.command("simulate")
    @reports_errors
    def simulate(
        case: str = typer.Argument(
            ..., help="Case file or bundled case (tdoa-sim, pursuit, dkf or pf)."
        ),
        output: str = typer.Option(..., "-o", "--output", help="Folder for data and figures."),
        runs: int = typer.Option(
            None, "--runs", min=1, help="Monte Carlo runs (default 1; pf cases: the case's)."
        ),
        seed: int = typer.Option(
            None, "--seed", help="Root seed, run i uses child i (default 0; pf cases: the case's)."
        ),
        workers: int = workers_option(),
        scheduler: str = scheduler_option(),
        steps: int = typer.Option(
            None, "--steps", min=1, help="Override the number of steps (pings / 0.1 s steps)."
        ),
        figures: bool = typer.Option(True, "--figures/--no-figures", help="Write PNG figures."),
        as_json: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
    ) -> None:
        """Simulate the closed loop; write runs.npz, CSV tables, PNG figures and summary.json."""
        from theory.core.parallel import default_workers
        from theory.kinds import simulator_for
        from theory.sim.simulate import MARKER, simulate_case

        check_options(runs, steps)
        loaded = load_case(case)
        if loaded.kind not in KINDS:
            raise CaseError(
                "kind", f"one of {list(KINDS)} (the kinds simulate runs)", loaded.kind, file=case
            )
        if loaded.kind == "pf":
            from theory.cli.pf import run_pf_case

            code = run_pf_case(
                loaded,
                runs,
                seed,
                output,
                as_json,
                workers=workers,
                scheduler=scheduler,
                figures=figures,
            )
            raise typer.Exit(code)
        check_folder_output(output, "-o/--output", MARKER)
        runs, seed = runs or 1, seed or 0
        chosen = simulator_for(loaded, steps, runs)
        workers = workers or default_workers()
        with progress_bar(runs, f"simulating {loaded.name}", quiet=as_json) as advance:
            simulation = simulate_case(
                loaded,
                chosen,
                folder=Path(output),
                runs=runs,
                seed=seed,
                workers=workers,
                scheduler=scheduler,
                figures=figures,
                progress=advance,
            )
        report = simulation.to_json()
        for warning in report.get("warnings", []):
            error_console.print(f"warning: {warning}", markup=False)
        if as_json:
            print_json(report)
        else:
            _print_table(report)
        raise typer.Exit(exit_code(command_verdict(True, simulation.expectations)))


def check_options(runs: int | None, steps: int | None) -> None:
    """Refuse ``--runs`` or ``--steps`` above their limits before any work
    (:mod:`theory.core.validation`)."""
    for name, value in (("runs", runs), ("steps", steps)):
        if value is not None:
            check_count(name, value, f"--{name}", file=COMMAND_LINE)


def _print_table(report: dict) -> None:
    from rich.table import Table

    from theory.core.consistency import describe

    table = Table(title=f"{report['case']} ({report['runs']} run(s), seed {report['seed']})")
    columns = [key for key in report["agents"][0] if key != "id"]
    table.add_column("agent", justify="right")
    for column in columns:
        table.add_column(column.replace("_", " "), justify="right")
    for agent in report["agents"]:
        table.add_row(str(agent["id"]), *(_cell(agent[c]) for c in columns))
    console.print(table)
    for line in describe(report["metrics"]):
        console.print(line, markup=False)
    console.print(f"files in {Path(report['files'][0]).parent}")


def _cell(value: Any) -> str:
    return f"{value:.3g}" if isinstance(value, float) else str(value)
