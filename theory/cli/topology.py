"""``trackcert topology CASE``: distributed TDOA observability of every agent (DESIGN.md).

A shell over :func:`theory.tdoa.observability.trajectory.topology_report`. Exit code
(:func:`theory.core.verdicts.command_verdict`): the verdict of the case's expectations this
command observes when the case states any; otherwise the property's: 0 every agent can localize
the target at every step, 1 some agent cannot, 3 inconclusive (a deciding singular value lies
within ``inconclusive_factor`` of its threshold, or a linear-algebra routine failed); 2 bad input.
"""

from __future__ import annotations

import typer
from rich.table import Table

from theory.cli.common import case_argument, console, finish, json_option, reports_errors
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
    """Add the ``topology`` command to ``app``.

    Parameters
    ----------
    app : typer.Typer
        The ``trackcert`` application.
    """

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
