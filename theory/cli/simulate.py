"""``trackcert simulate CASE``: closed-loop simulation, data files and figures (DESIGN.md).

A shell over :func:`theory.simulate.simulate_case` with the case kind's simulator
(:func:`theory.simulate.simulator_for`: ``kind: tdoa-sim`` in :mod:`theory.tdoa.sim_summary`,
``kind: dkf`` in :mod:`theory.consensus.dkf_report`); ``kind: pf`` cases are handed to
:func:`theory.cli.pf.run_pf_case`, as ``trackcert pf`` runs them. Interim: 2-D ``kind: pursuit``
cases (seed 003, :mod:`theory.pursuit.simulation`) still use the backend below until the pursuit
kind registers its simulator. Exit code (:mod:`theory.core.verdicts`): the expectations'
verdict, 0 all met (or none stated), 1 one unmet, 3 one inconclusive or unchecked.
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import Any

import typer
from rich.progress import Progress

from theory.cli.common import console, error_console, print_json, reports_errors
from theory.core.case_file import Case, load_case
from theory.core.errors import CaseError
from theory.core.verdicts import exit_code

__all__ = ["register"]

KINDS = ("tdoa-sim", "pursuit", "dkf", "pf")


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command to ``app``.

    Parameters
    ----------
    app : typer.Typer
        The application.
    """

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
        workers: int = typer.Option(
            None, "--workers", min=1, help="Worker processes (default: all local cores)."
        ),
        steps: int = typer.Option(
            None, "--steps", min=1, help="Override the number of steps (pings / 0.1 s steps)."
        ),
        figures: bool = typer.Option(True, "--figures/--no-figures", help="Write PNG figures."),
        as_json: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
    ) -> None:
        """Simulate the closed loop; write runs.npz, CSV tables, PNG figures and summary.json."""
        from theory.sim.runner import default_workers
        from theory.simulate import simulate_case, simulator_for

        loaded = load_case(case)
        if loaded.kind not in KINDS:
            raise CaseError(
                "kind", f"one of {list(KINDS)} (the kinds simulate runs)", loaded.kind, file=case
            )
        if loaded.kind == "pf":
            from theory.cli.pf import run_pf_case

            raise typer.Exit(run_pf_case(loaded, runs, seed, output, as_json))
        runs, seed = runs or 1, seed or 0
        chosen = (
            _interim_pursuit(loaded, steps)
            if loaded.kind == "pursuit"
            else simulator_for(loaded, steps)
        )
        workers = workers or default_workers()
        with Progress(console=error_console, transient=True) as progress:
            task = progress.add_task(f"simulating {loaded.name}", total=runs)
            simulation = simulate_case(
                loaded,
                chosen,
                folder=Path(output),
                runs=runs,
                seed=seed,
                workers=workers,
                figures=figures,
                progress=lambda done: progress.update(task, completed=done),
            )
        report = simulation.to_json()
        if as_json:
            print_json(report)
        else:
            _print_table(report)
        raise typer.Exit(exit_code(simulation.verdict))


def _interim_pursuit(case: Case, steps: int | None) -> Any:
    """The pursuit backend below as a :class:`theory.simulate.Simulator` (interim)."""
    from theory.simulate import Finished, Simulator

    spec, simulate_one, header = _pursuit_backend(case, steps)

    def finish(case: Case, spec: Any, results: list, folder: Path, figures: bool) -> Finished:
        summary, _, files = header["finish"](case, spec, results, folder, figures)
        return Finished(summary, files)

    return Simulator(spec, simulate_one, header["fields"], finish)


def _pursuit_backend(case: Case, steps: int | None) -> tuple[Any, Any, dict]:
    from theory.pursuit.simulation import (
        check_pursuit_case,
        default_steps,
        integration_step,
        run_pursuit_case,
    )

    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise error.in_file(case.file) from None
    steps = steps or default_steps(case.spec.dim)
    dt = integration_step(case.spec.dim)
    fields = {"controller": case.spec.controller, "dim": case.spec.dim, "steps": steps, "dt": dt}
    simulate_one = functools.partial(run_pursuit_case, steps=steps)
    return case.spec, simulate_one, {"fields": fields, "finish": _finish_pursuit}


def _finish_pursuit(case: Case, spec: Any, results: list, folder: Path, figures: bool):
    from theory.pursuit.simulation import (
        summarize_pursuit,
        write_pursuit_data,
        write_pursuit_figures,
    )

    summary = summarize_pursuit(spec, results)
    files = write_pursuit_data(results, summary, folder)
    if figures:
        files += write_pursuit_figures(results, folder)
    return summary, {}, files


def _print_table(report: dict) -> None:
    from rich.table import Table

    table = Table(title=f"{report['case']} ({report['runs']} run(s), seed {report['seed']})")
    columns = [key for key in report["agents"][0] if key != "id"]
    table.add_column("agent", justify="right")
    for column in columns:
        table.add_column(column.replace("_", " "), justify="right")
    for agent in report["agents"]:
        table.add_row(str(agent["id"]), *(_cell(agent[c]) for c in columns))
    console.print(table)
    console.print(f"files in {Path(report['files'][0]).parent}")


def _cell(value: Any) -> str:
    return f"{value:.3g}" if isinstance(value, float) else str(value)
