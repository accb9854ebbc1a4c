"""``trackcert dkf CASE``: S-detectability and necessary conditions of a consensus Kalman filter.

A shell over :func:`theory.consensus.analysis.dkf_report`. Exit code
(:func:`theory.core.verdicts.command_verdict`): the verdict of the case's expectations this
command observes when the case states any; otherwise the property's: 0 S-detectable (witness
verified), 1 not (certificate verified), 3 inconclusive (the LMI decision is near its boundary or
the solver failed: the output says which); 2 bad input.
"""

from __future__ import annotations

import typer
from rich.table import Table

from theory.cli.common import case_argument, console, finish, json_option, reports_errors
from theory.core.verdicts import command_verdict, exit_code
from theory.kinds import load_case
from theory.registry import claims_for

__all__ = ["register"]


def register(app: typer.Typer) -> None:
    """Add the ``dkf`` command to ``app``."""

    @app.command("dkf")
    @reports_errors
    def dkf(
        case: str = case_argument(),
        as_json: bool = json_option(),
        solver: str = typer.Option("CLARABEL", "--solver", help="CLARABEL or SCS."),
        self_weight: bool = typer.Option(
            True, "--self-weight/--no-self-weight", help="Bisect each agent's largest self-weight."
        ),
    ) -> None:
        """S-detectability (LMI), Thm 5.2.10's conditions and the blind-set condition."""
        from theory.consensus.analysis import dkf_report  # cvxpy: imported on use

        loaded = load_case(case)
        report = dkf_report(
            loaded, claims_for(loaded), search_self_weight=self_weight, solver=solver
        )
        data = report.to_json()
        code = exit_code(command_verdict(report.verdict, report.expectations))
        verdicts = (report.verdict, report.expectations)
        finish(data, code, as_json=as_json, show=lambda: _print_table(data), verdicts=verdicts)


def _print_table(data: dict) -> None:
    detail = data["s_detectability"]
    verdict = {True: "yes", False: "no", None: "inconclusive"}[data["s_detectable"]]
    console.print(f"case {data['case']} ({data['order']}): S-detectable: {verdict}", markup=False)
    console.print(f"  {detail['reason']}", markup=False, highlight=False)
    console.print(
        f"  r(B) = {data['spectral_radius_B']}, r(L) = {data['spectral_radius_L']} "
        f"(gains: {data['gains_source']})",
        markup=False,
    )
    table = Table(title="necessary conditions")
    for column in ("condition", "agents", "value", "ok"):
        table.add_column(column)
    for s in data["source_components"]:
        table.add_row("source component detectable", str(s["agents"]), "", str(s["detectable"]))
    for b in data["self_weight_bounds"]:
        table.add_row(
            "w_ii < 1/r(A_iᵘ)²",
            str([b["agent"]]),
            f"{b['w_ii']:g} vs {b['bound']:.6g}",
            str(b["ok"]),
        )
    for b in data["blind_sets"]:
        table.add_row("|λ|² r(W_SS) < 1", str(b["agents"]), f"{b['value']:.6g}", str(b["ok"]))
    console.print(table)
    for claim in data["claims"]:
        console.print(f"  {claim['id']}: {claim['status']}", markup=False)
    for e in data["expectations"]:
        console.print(
            f"  expect {e['key']} = {e['expected']}: {e['verdict']} (got {e['got']})",
            markup=False,
        )
