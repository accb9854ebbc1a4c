"""``trackcert simulate CASE``: closed-loop simulation, data files and figures (DESIGN.md).

Runs ``kind: tdoa-sim`` cases (seed 000 ch. 4, :mod:`theory.tdoa.scenario`), 2-D
``kind: pursuit`` cases (seed 003, :mod:`theory.pursuit.simulation`) and ``kind: dkf`` cases
(seed 000 ch. 5, :mod:`theory.consensus.simulation`); ``kind: pf`` cases (seed 002) are handed to
:func:`theory.cli.pf.run_pf_case`, as ``trackcert pf`` runs them.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
from pathlib import Path
from typing import Any

import typer
from rich.progress import Progress

from theory.cli.common import (
    EXIT_FAILS,
    console,
    error_console,
    print_json,
    reports_errors,
    to_jsonable,
)
from theory.core.case_file import Case, load_case
from theory.core.errors import CaseError

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
        from theory.sim.runner import default_workers, monte_carlo

        loaded = load_case(case)
        if loaded.kind not in KINDS:
            raise CaseError(
                "kind", f"one of {list(KINDS)} (the kinds simulate runs)", loaded.kind, file=case
            )
        if loaded.kind == "pf":
            from theory.cli.pf import run_pf_case

            raise typer.Exit(run_pf_case(loaded, runs, seed, output, as_json))
        runs, seed = runs or 1, seed or 0
        backend = {"tdoa-sim": _tdoa_backend, "pursuit": _pursuit_backend, "dkf": _dkf_backend}[
            loaded.kind
        ]
        spec, simulate_one, header = backend(loaded, steps)
        workers = workers or default_workers()
        with Progress(console=error_console, transient=True) as progress:
            task = progress.add_task(f"simulating {loaded.name}", total=runs)
            results = monte_carlo(
                spec,
                runs=runs,
                seed=seed,
                workers=workers,
                progress=lambda done: progress.update(task, completed=done),
                simulate=simulate_one,
            )
        folder = Path(output)
        folder.mkdir(parents=True, exist_ok=True)
        summary, expectations, files = header["finish"](loaded, spec, results, folder, figures)
        report = {
            "case": loaded.name,
            "source": loaded.source,
            "kind": loaded.kind,
            **header["fields"],
            "runs": runs,
            "seed": seed,
            "workers": min(workers, runs),
            **summary,
            "expectations": expectations,
            "files": [str(f) for f in files],
        }
        (folder / "summary.json").write_text(json.dumps(to_jsonable(report), indent=2))
        if as_json:
            print_json(report)
        else:
            _print_table(report)
        if not all(e["met"] for e in expectations.values()):
            raise typer.Exit(EXIT_FAILS)


def _tdoa_backend(case: Case, steps: int | None) -> tuple[Any, Any, dict]:
    from theory.tdoa.scenario import run_tdoa_scenario

    spec = case.spec if steps is None else dataclasses.replace(case.spec, steps=steps)
    fields = {"filter": spec.filter, "b": spec.b, "steps": spec.steps}
    return spec, run_tdoa_scenario, {"fields": fields, "finish": _finish_tdoa}


def _finish_tdoa(case: Case, spec: Any, results: list, folder: Path, figures: bool):
    from theory.sim.figures import write_figures
    from theory.sim.outputs import write_data
    from theory.tdoa.metrics import check_expectations, summarize_runs

    summary = summarize_runs(spec, results)
    error_bound = case.tolerances.get("error_bound", 10.0 * math.sqrt(spec.r))
    expectations = check_expectations(summary, case.expect, error_bound=error_bound)
    files = write_data(results, summary, folder)
    if figures:
        files += write_figures(results, folder)
    return {"tolerances": {"error_bound": error_bound}, **summary}, expectations, files


def _pursuit_backend(case: Case, steps: int | None) -> tuple[Any, Any, dict]:
    from theory.pursuit.simulation import (
        RECORD_INTERVAL,
        check_pursuit_case,
        default_steps,
        run_pursuit_case,
    )

    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise error.in_file(case.file) from None
    steps = steps or default_steps()
    fields = {
        "controller": case.spec.controller,
        "dim": case.spec.dim,
        "steps": steps,
        "dt": RECORD_INTERVAL,
    }
    simulate_one = functools.partial(run_pursuit_case, steps=steps)
    return case.spec, simulate_one, {"fields": fields, "finish": _finish_pursuit}


def _finish_pursuit(case: Case, spec: Any, results: list, folder: Path, figures: bool):
    from theory.pursuit.simulation import (
        pursuit_expectations,
        summarize_pursuit,
        write_pursuit_data,
        write_pursuit_figures,
    )

    summary = summarize_pursuit(spec, results)
    files = write_pursuit_data(results, summary, folder)
    if figures:
        files += write_pursuit_figures(results, folder)
    for stopped in summary["stopped_at"]:
        if stopped is not None:
            error_console.print(f"warning: a run's integration stopped at t = {stopped:g} s")
    return summary, pursuit_expectations(case, summary), files


def _dkf_backend(case: Case, steps: int | None) -> tuple[Any, Any, dict]:
    from theory.consensus.simulation import DEFAULT_STEPS, run_dkf_case

    steps = steps or DEFAULT_STEPS
    fields = {"order": case.spec.order, "steps": steps}
    simulate_one = functools.partial(run_dkf_case, steps=steps)
    return case.spec, simulate_one, {"fields": fields, "finish": _finish_dkf}


def _finish_dkf(case: Case, spec: Any, results: list, folder: Path, figures: bool):
    from theory.consensus.simulation import summarize_dkf, write_dkf_data

    summary = summarize_dkf(spec, results)
    return summary, {}, write_dkf_data(results, summary, folder)


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
