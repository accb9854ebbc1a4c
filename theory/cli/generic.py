"""``trackcert generic``: symbolic generic observability of one agent (seed 000 §4.2.1).

A shell over :func:`theory.tdoa.observability.single_agent.generic_report` and
:func:`theory.tdoa.observability.fig43.fig43_report`; exit code (:mod:`theory.core.verdicts`) 0
when the derivation reproduces the statement, 1 when a check disagrees, 2 on bad options.
"""

from __future__ import annotations

import typer

from theory.cli.common import print_json, reports_errors
from theory.core.verdicts import exit_code
from theory.tdoa.observability.fig43 import fig43_report
from theory.tdoa.observability.single_agent import GenericReport, generic_report

__all__ = ["register"]


def register(app: typer.Typer) -> None:
    """Add the ``generic`` command to ``app``.

    Parameters
    ----------
    app : typer.Typer
        The ``trackcert`` application.
    """

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
            report = fig43_report(fig43, weights=weights, seed=seed)
            _show_fig43(report, fig43, weights, as_json)
        else:
            report = generic_report(dim, rows, seed=seed)
            result = report.result
            if as_json:
                print_json(
                    {**result.to_json(), "derivation": result.markdown(), "holds": report.holds}
                )
            else:
                typer.echo(result.markdown(), nl=False)  # raw markdown: no re-wrapping of tables
        raise typer.Exit(exit_code(report.holds))


def _show_fig43(report: GenericReport, case: str, weights: str, as_json: bool) -> None:
    """Print the Fig. 4.3 analysis: symbolic rank O_i, exact rank O, detectability."""
    result = report.result
    if as_json:
        print_json({**result, "holds": report.holds})
        return
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
