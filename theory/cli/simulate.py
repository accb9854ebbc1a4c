"""``trackcert simulate CASE``: closed-loop simulation, data files and figures (DESIGN.md)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import typer
from rich.progress import Progress

from theory.case_file import load_case
from theory.cli.common import (
    EXIT_FAILS,
    console,
    error_console,
    print_json,
    reports_errors,
    to_jsonable,
)
from theory.errors import CaseError

__all__ = ["register"]


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command to ``app``."""

    @app.command("simulate")
    @reports_errors
    def simulate(
        case: str = typer.Argument(..., help="Case file or bundled case name (kind tdoa-sim)."),
        output: str = typer.Option(..., "-o", "--output", help="Folder for data and figures."),
        runs: int = typer.Option(1, "--runs", min=1, help="Monte Carlo runs."),
        seed: int = typer.Option(0, "--seed", help="Root seed (run i uses child i)."),
        workers: int = typer.Option(
            None, "--workers", min=1, help="Worker processes (default: all local cores)."
        ),
        figures: bool = typer.Option(True, "--figures/--no-figures", help="Write PNG figures."),
        as_json: bool = typer.Option(False, "--json", help="Print the summary as JSON."),
    ) -> None:
        """Simulate the closed loop; write runs.npz, CSV tables, PNG figures and summary.json."""
        from theory.sim.figures import write_figures
        from theory.sim.metrics import check_expectations, summarize_runs
        from theory.sim.outputs import write_data
        from theory.sim.runner import default_workers, monte_carlo

        loaded = load_case(case)
        if loaded.kind != "tdoa-sim":
            raise CaseError(
                "kind", "tdoa-sim (the kinds trackcert simulate runs)", loaded.kind, file=case
            )
        spec = loaded.spec
        workers = workers or default_workers()
        with Progress(console=error_console, transient=True) as progress:
            task = progress.add_task(f"simulating {loaded.name}", total=runs)
            results = monte_carlo(
                spec,
                runs=runs,
                seed=seed,
                workers=workers,
                progress=lambda done: progress.update(task, completed=done),
            )
        summary = summarize_runs(spec, results)
        error_bound = loaded.tolerances.get("error_bound", 10.0 * math.sqrt(spec.r))
        expectations = check_expectations(summary, loaded.expect, error_bound=error_bound)
        folder = Path(output)
        folder.mkdir(parents=True, exist_ok=True)
        files = write_data(results, summary, folder)
        if figures:
            files += write_figures(results, folder)
        report = {
            "case": loaded.name,
            "source": loaded.source,
            "kind": loaded.kind,
            "filter": spec.filter,
            "b": spec.b,
            "runs": runs,
            "seed": seed,
            "workers": min(workers, runs),
            "steps": spec.steps,
            "tolerances": {"error_bound": error_bound},
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


def _print_table(report: dict) -> None:
    from rich.table import Table

    table = Table(title=f"{report['case']} ({report['runs']} run(s), seed {report['seed']})")
    for column in ("agent", "final error (m)", "mean error (m)", "mean ‖P‖", "distance (m)"):
        table.add_column(column, justify="right")
    for agent in report["agents"]:
        table.add_row(
            str(agent["id"]),
            f"{agent['final_localization_error']:.3g}",
            f"{agent['mean_localization_error']:.3g}",
            f"{agent['mean_cov_norm']:.3g}",
            f"{agent['distance']:.1f}",
        )
    console.print(table)
    console.print(f"total distance {report['total_distance']:.1f} m; files in {report['files'][0]}")
