"""``trackcert iss CASE``: ISS Lyapunov analysis of the pursuit/coordination loop (seed 003).

A shell over :func:`theory.pursuit.iss.iss_report`. Exit code
(:func:`theory.core.verdicts.command_verdict`): the verdict of the case's expectations this
command observes when the case states any; otherwise the property's: 0 every condition holds, 1 a
condition fails (e.g. ε₁ = 0 so ΔΔᵀ is singular, or a graph without the strong connectivity
Lemma 3 needs), 3 a margin lies inside ``margin_tol`` (inconclusive; the output says which
condition); 2 bad input.
"""

from __future__ import annotations

from typing import Any

import typer
from rich.table import Table

from theory.cli.common import case_argument, console, finish, json_option, reports_errors
from theory.core.verdicts import command_verdict, exit_code
from theory.kinds import load_case

__all__ = ["register"]


def _print_table(report: Any) -> None:
    record = report.record
    console.print(
        f"{record['case']}: Type {record['controller']}, {record['dim']}D, "
        f"N = {record['n_trackers']}",
        markup=False,
        highlight=False,
    )
    table = Table(title="conditions")
    for column in ("condition", "status", "value", "margin", "source"):
        table.add_column(column)
    for c in record["conditions"]:
        margin = "" if c["margin"] is None else f"{c['margin']:.3g}"
        table.add_row(c["name"], c["status"], str(c["value"]), margin, c["source"])
    console.print(table)
    rates, gains = record["decay_rate"], record["iss_gain"]
    console.print(
        f"decay rates: pursuit {rates['pursuit']}, coordination {rates['coordination']}\n"
        f"ISS gains: pursuit {gains['pursuit']}, coordination {gains['coordination']}, "
        f"cascade {gains['cascade']}\nscope: {record['scope']}",
        markup=False,
        highlight=False,
    )
    claims = Table(title="claims")
    for column in ("id", "status", "finding", "message"):
        claims.add_column(column)
    for claim in record["claims"]:
        claims.add_row(claim["id"], claim["status"], claim["finding"] or "", claim["message"])
    console.print(claims)
    for e in report.expectations:
        console.print(f"expectation {e.describe()}", markup=False, highlight=False)


def register(app: typer.Typer) -> None:
    """Add the ``iss`` command to ``app``."""

    @app.command("iss")
    @reports_errors
    def iss(
        case: str = case_argument("Case file or bundled case name (kind: pursuit)."),
        as_json: bool = json_option(),
        margin_tol: float = typer.Option(
            None, "--margin-tol", help="Relative margin under which a condition is inconclusive."
        ),
    ) -> None:
        """ISS Lyapunov analysis of the pursuit/coordination loop (seed 003)."""
        from theory.pursuit.iss import iss_report  # sympy/scipy: imported on use

        report = iss_report(load_case(case), margin_tol=margin_tol)
        code = exit_code(command_verdict(report.verdict, report.expectations))
        finish(
            report.to_json(),
            code,
            as_json=as_json,
            show=lambda: _print_table(report),
            verdicts=(report.verdict, report.expectations),
        )
