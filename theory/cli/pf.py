"""``trackcert pf CASE``: Monte Carlo runs of the distributed TDOA particle filter (seed 002 §3.3).

Prints the per-node error summary and the verdicts of every registered claim for ``kind: pf``
cases, and each key of the case's ``expect`` block with the value the claims observed (the
verdicts of :mod:`theory.report.expectations`, as ``trackcert report`` gives them); with
``-o DIR`` writes ``DIR/pf.json`` and the figures. Exit code 0 when every expectation is met, 1
when one is unmet, 3 when one is inconclusive.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import typer
from rich.table import Table

from theory.cli.common import (
    EXIT_FAILS,
    EXIT_HOLDS,
    EXIT_INCONCLUSIVE,
    console,
    print_json,
    reports_errors,
    to_jsonable,
)
from theory.core.case_file import Case, load_case
from theory.core.claims import all_claims, applicable_results
from theory.core.errors import CaseError

__all__ = ["register", "run_pf_case"]

SNAPSHOT_STEPS = (0, 5, 20)


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
    ) -> None:
        """Run the distributed TDOA particle filter of seed 002 on a ``kind: pf`` case."""
        raise typer.Exit(run_pf_case(load_case(case_name), runs, seed, out, as_json))


def run_pf_case(
    case: Case, runs: int | None, seed: int | None, out: str | None, as_json: bool
) -> int:
    """Run ``case`` (``kind: pf``), print the summary and return the exit code.

    Parameters
    ----------
    case : Case
        A loaded case; anything but ``kind: pf`` is refused.
    runs, seed : int or None
        Monte Carlo runs and base seed (``None``: the case's own).
    out : str or None
        Folder for ``pf.json`` and figures (``None``: write nothing).
    as_json : bool
        Print JSON instead of a table.

    Returns
    -------
    int
        1 when an expectation is unmet, 3 when one is inconclusive, 0 otherwise.
    """
    from theory.particle.experiments import monte_carlo, node_summary, shared_monte_carlo

    folder = None if out is None else Path(out)
    if case.kind != "pf":
        raise CaseError(
            "kind", "pf (this command runs particle-filter cases)", case.kind, file=case.file
        )
    spec = replace(
        case.spec, runs=runs or case.spec.runs, seed=case.spec.seed if seed is None else seed
    )
    case = replace(case, spec=spec)
    mc = shared_monte_carlo(spec)
    claims = [
        (claim.source, result)
        for claim in all_claims()
        if "pf" in claim.kinds
        for result in applicable_results(claim, case)
    ]
    figures = []
    if folder is not None:
        from theory.particle.figures import write_figures

        first = monte_carlo(spec, runs=1, snapshot_steps=SNAPSHOT_STEPS)  # = run 0 of mc
        figures = write_figures(replace(mc, snapshots=first.snapshots), spec, folder, case.name)
    report = {
        "case": case.name,
        "runs": spec.runs,
        "seed": spec.seed,
        "model": spec.model,
        "share": spec.config.share,
        "config": to_jsonable(vars(spec.config)),
        "agents": node_summary(mc, spec),
        "claims": [result.to_json(source) for source, result in claims],
        "expectations": _expectations(case, [result for _, result in claims]),
        "figures": figures,
    }
    if folder is not None:
        (folder / "pf.json").write_text(json.dumps(to_jsonable(report), indent=2) + "\n")
    if as_json:
        print_json(report)
    else:
        _print(report)
    verdicts = {e["verdict"] for e in report["expectations"]}
    if "unmet" in verdicts:
        return EXIT_FAILS
    if verdicts - {"met"}:
        return EXIT_INCONCLUSIVE
    return EXIT_HOLDS


def _expectations(case: Case, results: list) -> list[dict]:
    from theory.report.canonical import canonical
    from theory.report.expectations import EXPECTATIONS_KEY, evaluate

    observed = [
        (r.claim, canonical(r.evidence[EXPECTATIONS_KEY]), r.status)
        for r in results
        if EXPECTATIONS_KEY in r.evidence
    ]
    return [e.to_json() for e in evaluate(case.name, canonical(case.expect), observed)]


def _print(report: dict) -> None:
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
