"""``trackcert cases``: list the bundled cases."""

from __future__ import annotations

import typer
from rich.table import Table

from theory.cli.common import console, print_json, reports_errors
from theory.core.case_file import bundled_cases
from theory.kinds import load_case

__all__ = ["register"]


def register(app: typer.Typer) -> None:
    """Add the ``cases`` command to ``app``."""

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
