"""``trackcert topology CASE``: distributed TDOA observability of every agent (DESIGN.md).

Exit codes: 0 every agent can localize the target at every step (the networked pair is
detectable), 1 some agent cannot, 2 bad input, 3 inconclusive (a deciding singular value lies
within ``inconclusive_factor`` of its threshold, or a linear-algebra routine failed).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import typer
from rich.table import Table

from theory.cli.common import (
    EXIT_HOLDS,
    EXIT_INCONCLUSIVE,
    case_argument,
    console,
    finish,
    json_option,
    reports_errors,
    verdict_exit_code,
)
from theory.core.case_file import Case, load_case
from theory.core.errors import CaseError, SolverError
from theory.tdoa.time_varying import (
    TrajectoryResult,
    analyze_trajectory,
    check_trajectory_expectations,
)
from theory.tdoa.topology import TopologyResult, check_expectations

__all__ = ["register", "run_topology"]


def run_topology(case: Case, *, network_rank: bool = True, **tolerances: float) -> TrajectoryResult:
    """Analyze a ``kind: tdoa`` case at every step with the case's tolerances (overridable).

    Parameters
    ----------
    case : Case
        A loaded case.
    network_rank : bool
        ``False`` skips the rank of the whole networked matrix (cubic in the largest component);
        per-agent verdicts and detectability are always computed.
    **tolerances : float
        ``rank_tol`` / ``inconclusive_factor`` overriding the case's (``None`` = keep).

    Returns
    -------
    TrajectoryResult

    Raises
    ------
    CaseError
        If the case is not ``kind: tdoa``.
    SolverError
        If a linear-algebra routine fails (reported as inconclusive).
    """
    if case.kind != "tdoa":
        raise CaseError("kind", "tdoa (trackcert topology checks TDOA cases)", case.kind)
    chosen = {k: v for k, v in case.tolerances.items() if k in ("rank_tol", "inconclusive_factor")}
    chosen.update({k: v for k, v in tolerances.items() if v is not None})
    if not 0 < chosen.get("rank_tol", 0.5) < 1:
        raise CaseError("--rank-tol", "a relative tolerance in (0, 1)", chosen["rank_tol"])
    if chosen.get("inconclusive_factor", 1.0) < 1:
        raise CaseError("--inconclusive-factor", "a factor ≥ 1", chosen["inconclusive_factor"])
    try:
        return analyze_trajectory(case.spec, network_rank=network_rank, **chosen)
    except np.linalg.LinAlgError as error:
        raise SolverError(f"linear algebra failed: {error}") from None


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
        loaded = load_case(case)
        result = run_topology(
            loaded,
            network_rank=network_rank,
            rank_tol=rank_tol,
            inconclusive_factor=inconclusive_factor,
        )
        first = result.steps[0]
        mismatches = check_expectations(first, loaded.expect) + check_trajectory_expectations(
            result, loaded.expect
        )
        code = _exit_code(result)
        finish(
            _json(loaded, result, mismatches, code),
            code,
            as_json=as_json,
            show=lambda: _print_human(loaded, result, mismatches, code),
        )


def _exit_code(result: TrajectoryResult) -> int:
    return verdict_exit_code(result.first_failure_step is None if result.conclusive else None)


def _verdict(result: TrajectoryResult, code: int) -> str:
    if code == EXIT_INCONCLUSIVE:
        reasons = [r for s in result.steps for r in s.inconclusive]
        return "INCONCLUSIVE: " + reasons[0]
    if code == EXIT_HOLDS:
        steps = f" at all {len(result.steps)} steps" if len(result.steps) > 1 else ""
        ambiguous = [a.id for a in result.steps[0].agents if a.uniqueness.unique is False]
        caveat = (
            f" (locally; for agents {ambiguous} another position has the same TDOAs)"
            if ambiguous
            else ""
        )
        return f"HOLDS: every agent can localize the target{steps}{caveat}"
    step = result.steps[result.first_failure_step - 1]
    failing = [a.id for a in step.agents if not a.localizes]
    where = f" (first at step {step.step})" if len(result.steps) > 1 else ""
    why = (
        "; the networked pair is detectable, but a closed class upstream of them (agents that "
        "hear only each other) cannot localize on its own"
        if step.network.detectable
        else ""
    )
    return f"FAILS: agents {failing} cannot localize the target{where}{why}"


def _json(case: Case, result: TrajectoryResult, mismatches: list[str], code: int) -> dict[str, Any]:
    data: dict[str, Any] = {"case": case.name, "source": case.source}
    data.update(result.steps[0].to_json())
    if len(result.steps) > 1:
        data["time_varying"] = result.to_json()
    data["expectations"] = {"met": not mismatches, "mismatches": mismatches}
    data["verdict"] = _verdict(result, code)
    data["exit_code"] = code
    return data


def _print_human(case: Case, result: TrajectoryResult, mismatches: list[str], code: int) -> None:
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
    if case.expect:
        met = "met" if not mismatches else "NOT met: " + "; ".join(mismatches)
        console.print(f"expectations: {met}", markup=False)
    console.print(_verdict(result, code), markup=False, style="bold")


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
