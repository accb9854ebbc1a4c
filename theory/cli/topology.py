"""TDOA observability commands: ``trackcert topology CASE`` (every agent of a network, seed 000
§4.2.2) and ``trackcert generic`` (one agent, symbolically, §4.2.1); guide: docs/topology.md.

``topology`` is a shell over :func:`theory.tdoa.observability.trajectory.topology_report`. Exit
code (:func:`theory.core.verdicts.command_verdict`): the verdict of the case's expectations this
command observes when the case states any; otherwise the property's: 0 every agent can localize
the target at every step, 1 some agent cannot, 3 inconclusive (a deciding singular value lies
within ``inconclusive_factor`` of its threshold, or a linear-algebra routine failed); 2 bad input.
``generic`` is a shell over :func:`theory.tdoa.observability.single_agent.generic_report` and
:func:`theory.tdoa.observability.fig43.fig43_report`: 0 when the derivation reproduces the
statement, 1 when a check disagrees, 2 on bad options.
"""

from __future__ import annotations

from typing import Any

import typer
from rich.table import Table

from theory.cli.common import (
    case_argument,
    console,
    finish,
    json_option,
    print_json,
    reports_errors,
)
from theory.core.case_file import Case
from theory.core.verdicts import command_verdict, exit_code
from theory.kinds import load_case
from theory.tdoa.observability.topology import TopologyResult
from theory.tdoa.observability.trajectory import (
    TopologyReport,
    TrajectoryResult,
    topology_report,
)

__all__ = ["register"]


def register(app: typer.Typer) -> None:
    """Add the ``topology`` and ``generic`` commands to ``app``."""

    @app.command("topology")
    @reports_errors
    def topology(
        case: str = case_argument("Case file path or bundled case name."),
        as_json: bool = json_option(),
        rank_tol: float = typer.Option(None, "--rank-tol", help="Relative rank tolerance."),
        inconclusive_factor: float = typer.Option(
            None, "--inconclusive-factor", help="Margin below which a verdict is unsure."
        ),
        network_rank: bool = typer.Option(
            True, "--network-rank/--no-network-rank", help="Rank the whole networked pair."
        ),
    ) -> None:
        """Distributed TDOA observability of every agent (seed 000 §4.2.2, Cor. 4.2.4)."""
        report = topology_report(
            load_case(case),
            network_rank=network_rank,
            rank_tol=rank_tol,
            inconclusive_factor=inconclusive_factor,
        )
        code = exit_code(command_verdict(report.verdict, report.expectations))
        finish(
            {**report.to_json(), "exit_code": code},
            code,
            as_json=as_json,
            show=lambda: _print_human(report),
            verdicts=(report.verdict, report.expectations),
        )

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
        from theory.tdoa.observability.fig43 import fig43_report  # sympy: imported on use
        from theory.tdoa.observability.single_agent import generic_report

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


def _show_fig43(report: Any, case: str, weights: str, as_json: bool) -> None:
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


def _print_human(report: TopologyReport) -> None:
    case, result = report.case, report.result
    first = result.steps[0]
    console.print(_agent_table(case, first))
    net = first.network
    rank = "not computed" if net.rank is None else f"{net.rank}/{net.n_states}"
    console.print(
        f"network (W⊗A, D_H): rank {rank}, observable {net.observable}, detectable "
        f"{net.detectable}; unobservable eigenvalues {_eigs(net.unobservable_eigenvalues)}",
        markup=False,
    )
    console.print(f"information flow: {first.information_flow}", markup=False)
    reasons: dict[str, list[int]] = {}
    for agent in first.agents:
        if agent.reason:
            reasons.setdefault(agent.reason, []).append(agent.id)
    for reason, ids in reasons.items():
        console.print(f"heuristic ≠ exact for agents {ids}: {reason}", markup=False)
    if len(result.steps) > 1:
        console.print(_steps_table(result))
        console.print(
            f"time-varying: {len(result.steps)} steps; first failure step "
            f"{result.first_failure_step}; steps unobservable per agent "
            f"{list(result.unobservable_steps)}",
            markup=False,
        )
    console.print(f"tolerances: {first.tolerances}", markup=False)
    if report.expectations:
        unmet = [e.describe() for e in report.expectations if not e.met]
        met = "met" if not unmet else "NOT met: " + "; ".join(unmet)
        console.print(f"expectations: {met}", markup=False)
    console.print(report.sentence(), markup=False, style="bold")


def _agent_table(case: Case, step: TopologyResult) -> Table:
    title = f"{case.name}: TDOA observability per agent" + (
        f" (step {step.step})" if case.spec.steps > 1 else ""
    )
    heuristic = "≥ 4 non-coplanar" if step.dim == 3 else "≥ 3 non-collinear"
    caption = (
        f"rank = rank O_i (full: {2 * step.dim}); obs = O_i full rank; loc = the agent's "
        f"distributed filter can converge; heur = paper's {heuristic} connected agents"
    )
    table = Table(title=title, caption=caption)
    for column in ("id", "comp", "rank", "σ_min", "obs", "loc", "heur", "mirror", "unique"):
        table.add_column(column, no_wrap=True)
    yes = {True: "yes", False: "NO", None: "?"}
    for a in step.agents:
        table.add_row(
            str(a.id),
            str(a.component),
            str(a.rank),
            f"{a.sigma_min:.3g}",
            yes[a.observable],
            yes[a.localizes],
            yes[a.heuristic_4_noncoplanar],
            "yes" if a.mirror_ambiguous else "no",
            yes[a.uniqueness.unique],
        )
    return table


def _steps_table(result: TrajectoryResult) -> Table:
    table = Table(title="verdict at every step (Cor. 4.2.4)")
    for column in ("step", "comp", "rank O", "cannot localize", "heuristic fails"):
        table.add_column(column, no_wrap=column in ("step", "comp", "rank O"))
    for step in result.steps:
        rank = "-" if step.network.rank is None else f"{step.network.rank}/{step.network.n_states}"
        table.add_row(
            str(step.step),
            str(len({a.component for a in step.agents})),
            rank,
            _agents([a.id for a in step.agents if not a.localizes], len(step.agents)),
            _agents([a.id for a in step.agents if not a.heuristic_4_noncoplanar], len(step.agents)),
        )
    return table


def _agents(ids: list[int], total: int) -> str:
    return "-" if not ids else "all" if len(ids) == total else ", ".join(map(str, ids))


def _eigs(values: tuple[complex, ...] | None) -> str:
    if values is None:
        return "not computed"
    if not values:
        return "none"
    return "[" + ", ".join(_complex(v) for v in values) + "]"


def _complex(value: complex) -> str:
    return f"{value.real:.4g}" if value.imag == 0 else f"{value.real:.4g}{value.imag:+.4g}j"
