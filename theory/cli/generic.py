"""``trackcert generic``: symbolic generic observability of one agent (seed 000 §4.2.1)."""

from __future__ import annotations

import typer

from theory.cli.common import EXIT_FAILS, console, print_json, reports_errors
from theory.errors import CaseError
from theory.generic_rank import single_agent_generic_rank

__all__ = ["register"]


def register(app: typer.Typer) -> None:
    """Add the ``generic`` command to ``app``."""

    @app.command("generic")
    @reports_errors
    def generic(
        dim: int = typer.Option(3, "--dim", help="Position dimension: 2 or 3."),
        rows: int = typer.Option(None, "--rows", help="Number of TDOA rows (default: dim)."),
        seed: int = typer.Option(0, "--seed", help="Seed of the random evaluation points."),
        as_json: bool = typer.Option(False, "--json", help="Print JSON."),
    ) -> None:
        """Enumerate every minor of O = [H; HA; …] for one agent and print the derivation.

        Exit 0 when every check reproduces the statement (eq. 4.20, footnote 2, or all minors
        vanishing), 1 when a cross-check disagrees, 2 on bad options.
        """
        if dim not in (2, 3):
            raise CaseError("--dim", "2 or 3", dim, file="<command line>")
        rows = dim if rows is None else rows
        if rows < 1 or rows > 8:
            raise CaseError(
                "--rows",
                "an integer between 1 and 8 (C(2·dim·rows, 2·dim) minors are enumerated)",
                rows,
                file="<command line>",
            )
        result = single_agent_generic_rank(dim, rows, seed=seed)
        ok = (
            result.cross_check["all_agree"]
            and result.random_rank.rank == result.kronecker_rank
            and result.generically_full_rank == (rows >= dim)
            and result.closed_form_alpha in (None, True)
            and result.paper_factor_matches in (None, True)
        )
        if as_json:
            print_json({**result.to_json(), "derivation": result.markdown(), "holds": ok})
        else:
            console.print(result.markdown(), markup=False, highlight=False)
        if not ok:
            raise typer.Exit(EXIT_FAILS)
