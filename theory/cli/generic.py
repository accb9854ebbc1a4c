"""``trackcert generic``: symbolic generic observability of one agent (seed 000 §4.2.1)."""

from __future__ import annotations

import typer

from theory.cli.common import EXIT_FAILS, print_json, reports_errors
from theory.core.errors import CaseError

__all__ = ["MAX_ROWS", "register"]

MAX_ROWS = {2: 8, 3: 4}
"""Largest ``--rows`` per dimension: C(32, 4) = 35960 and C(24, 6) = 134596 minors."""


def register(app: typer.Typer) -> None:
    """Add the ``generic`` command to ``app``."""

    @app.command("generic")
    @reports_errors
    def generic(
        dim: int = typer.Option(3, "--dim", help="Position dimension: 2 or 3."),
        rows: int = typer.Option(None, "--rows", help="Number of TDOA rows (default: dim)."),
        seed: int = typer.Option(0, "--seed", help="Seed of the random evaluation points."),
        fig43: str = typer.Option(
            None, "--fig43", help="Instead: the networked pair for Fig. 4.3 case a, b, c or d."
        ),
        weights: str = typer.Option(
            "metropolis", "--weights", help="With --fig43: metropolis or uniform."
        ),
        as_json: bool = typer.Option(False, "--json", help="Print JSON."),
    ) -> None:
        """Enumerate every minor of O = [H; HA; …] for one agent and print the derivation.

        Exit 0 when every check reproduces the statement (eq. 4.20, footnote 2, or all minors
        vanishing), 1 when a cross-check disagrees, 2 on bad options. With --fig43: exit 0 when
        the symbolic and exact ranks of every O_i agree and the pair is detectable.
        """
        if fig43 is not None:
            _fig43(fig43, weights, seed, as_json)
            return
        if dim not in (2, 3):
            raise CaseError("--dim", "2 or 3", dim, file="<command line>")
        rows = dim if rows is None else rows
        limit = MAX_ROWS[dim]
        if rows < 1 or rows > limit:
            raise CaseError(
                "--rows",
                f"an integer between 1 and {limit} for dim {dim} (all C(2·dim·rows, 2·dim) "
                "minors are enumerated; footnote 2 needs only rows = dim + 1)",
                rows,
                file="<command line>",
            )
        from theory.tdoa.generic_rank import single_agent_generic_rank  # sympy: imported on use

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
            typer.echo(result.markdown(), nl=False)  # raw markdown: no re-wrapping of tables
        if not ok:
            raise typer.Exit(EXIT_FAILS)


def _fig43(case: str, weights: str, seed: int, as_json: bool) -> None:
    """Print the Fig. 4.3 analysis: symbolic rank O_i, exact rank O, detectability."""
    from theory.tdoa.fig43 import FIG43_EDGES, fig43_analysis  # sympy: imported on use

    if case not in FIG43_EDGES:
        raise CaseError("--fig43", f"one of {sorted(FIG43_EDGES)}", case, file="<command line>")
    if weights not in ("metropolis", "uniform"):
        raise CaseError("--weights", "metropolis or uniform", weights, file="<command line>")
    result = fig43_analysis(case, rule=weights, seed=seed)
    ok = result["agree"] and result["detectable"]
    if as_json:
        print_json({**result, "holds": ok})
    else:
        exact = result["exact"]
        lines = [f"Fig. 4.3 case ({case}), {weights} weights, App. B.1 shared-λ Jacobians"]
        for agent, witness in enumerate(result["witnesses"], start=1):
            lines.append(
                f"  rank O_{agent} = {witness['rank']}: minor {witness['minor']} "
                f"(rows (power, agent, edge) {witness['rows']})"
            )
        lines += [
            f"  exact at a random point (seed {exact['seed']}): rank O = {exact['network_rank']}"
            f" of {exact['n_states']}; Σ rank O_i = {exact['rank_sum']}; P(wrong "
            f"rank-deficient verdict) ≤ {exact['error_bound']:.1e}",
            f"  rank O = Σ rank O_i (paper, after eq. 4.36): {result['rank_sum_claim_holds']}",
            f"  observable: {result['network_observable']}; detectable: {result['detectable']}",
        ]
        typer.echo("\n".join(lines))
    if not ok:
        raise typer.Exit(EXIT_FAILS)
