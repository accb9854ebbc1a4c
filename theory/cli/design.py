"""``trackcert design …``: certified design answers, one subcommand per question (DESIGN.md).

Each subcommand is a shell over one library function: ``margin`` over
:func:`theory.tdoa.geometry.margin.tdoa_margin`, ``placement`` over
:func:`theory.tdoa.geometry.placement.tdoa_placement`, ``redundancy`` over the function of the
case's kind (:data:`REDUNDANCY`). What an engineer deploys is printed plainly (rounded); ``--json``
gives the contract keys and the certificates, exact. Exit codes (docs/cli.md): 0 answered (the
property holds), 1 the property fails at the stated design (e.g. an agent already unobservable),
2 bad input, 3 inconclusive (nothing certified).
"""

from __future__ import annotations

from collections.abc import Callable

import typer
from rich.table import Table

from theory.cli.common import case_argument, console, finish, json_option, reports_errors
from theory.core.case_file import Case
from theory.core.errors import CaseError
from theory.core.verdicts import exit_code
from theory.kinds import load_case
from theory.tdoa.design import Redundancy, tdoa_redundancy
from theory.tdoa.geometry.margin import NORM, Margin, tdoa_margin
from theory.tdoa.geometry.placement import Placement, tdoa_placement

__all__ = ["REDUNDANCY", "design_app", "register"]

design_app = typer.Typer(
    name="design",
    help="Certified design answers: how far agents may drift, where to put them, what may fail.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)

REDUNDANCY: dict[str, Callable[..., Redundancy]] = {"tdoa": tdoa_redundancy}
"""Case kind → its redundancy function (``links=True`` for links, ``False`` for agents)."""


def register(app: typer.Typer) -> None:
    """Add the ``design`` command group to ``app``.

    Parameters
    ----------
    app : typer.Typer
        The ``trackcert`` application.
    """
    app.add_typer(design_app, name="design")


def _case_of(name: str, kinds: tuple[str, ...]) -> Case:
    case = load_case(name)
    if case.kind not in kinds:
        raise CaseError(
            "kind", f"a case of kind {' or '.join(kinds)} for this question", case.kind, file=name
        )
    return case


@design_app.command("margin")
@reports_errors
def margin(
    case: str = case_argument("Case file path or bundled case name (kind tdoa)."),
    as_json: bool = json_option(),
    seed: int = typer.Option(0, "--seed", help="Seed of the witness search's random starts."),
    search: bool = typer.Option(True, "--search/--no-search", help="Search a witness (ρ̄)."),
) -> None:
    """How far agents and target may drift with every agent still observable (certified ρ)."""
    result = tdoa_margin(_case_of(case, ("tdoa",)), search=search, seed=seed)
    code = exit_code(result.verdict)
    data = {**result.to_json(), "exit_code": code}
    finish(data, code, as_json=as_json, show=lambda: _print_margin(result))


def _print_margin(result: Margin) -> None:
    table = Table(title=f"{result.case}: displacement margin per agent", caption=f"norm: {NORM}")
    for column in ("agent", "certified ρ", "witness ρ̄", "note"):
        table.add_column(column)
    for a in result.per_agent:
        upper = "-" if a.upper_bound is None else f"{a.upper_bound:.4g}"
        note = "unobservable already" if a.degenerate else ""
        table.add_row(str(a.id), f"{float(a.radius):.4g}", upper, note)
    console.print(table)
    upper = "none found" if result.upper_bound is None else f"{result.upper_bound:.4g}"
    exact = " (exact)" if result.exact else ""
    console.print(
        f"margin: certified ρ = {float(result.radius):.4g}{exact}, witness ρ̄ = {upper}",
        markup=False,
        style="bold",
    )
    if result.witness is not None:
        w = result.witness
        console.print(
            f"witness: step {w.step + 1}, agent {w.agent + 1} loses rank ({w.mechanism}); "
            f"largest move {w.size:.4g}",
            markup=False,
        )
    console.print(result.note, markup=False)


@design_app.command("placement")
@reports_errors
def placement(
    n_agents: int = typer.Argument(..., metavar="N", help="Number of agents."),
    comm_range: float = typer.Option(..., "--comm-range", help="Communication range R."),
    rho0: float = typer.Option(0.0, "--rho0", help="Least certified margin ρ₀."),
    dim: int = typer.Option(3, "--dim", help="2 or 3."),
    seed: int = typer.Option(0, "--seed", help="Seed of the random starting formations."),
    starts: int = typer.Option(6, "--starts", help="Starting formations of the search."),
    as_json: bool = json_option(),
) -> None:
    """N agents around a target: least Cramér–Rao trace with a certified margin ≥ ρ₀."""
    result = tdoa_placement(n_agents, comm_range, rho0=rho0, dim=dim, seed=seed, starts=starts)
    code = exit_code(result.verdict)
    data = {**result.to_json(), "exit_code": code}
    finish(data, code, as_json=as_json, show=lambda: _print_placement(result))


def _print_placement(result: Placement) -> None:
    best = result.best
    table = Table(title=f"{best.name}: agents around the target at the origin")
    for column in ("agent", *"xyz"[: result.dim]):
        table.add_column(column, justify="right")
    for i, position in enumerate(best.agents, start=1):
        table.add_row(str(i), *(f"{v:.4f}" for v in position))
    console.print(table)
    console.print(
        f"CRB trace {best.crb_trace:.6g} (bound d²/N² = {result.bound:.6g}); certified margin "
        f"ρ = {float(best.radius):.4g} ≥ ρ₀ = {result.rho0:g}; range {result.comm_range:g}",
        markup=False,
        style="bold",
    )
    for other in result.compared:
        console.print(
            f"  {other.name}: CRB trace {other.crb_trace:.6g}, certified margin "
            f"{float(other.radius):.4g}",
            markup=False,
        )


@design_app.command("redundancy")
@reports_errors
def redundancy(
    case: str = case_argument("Case file path or bundled case name."),
    links: bool = typer.Option(True, "--links/--agents", help="Remove links (default) or agents."),
    as_json: bool = json_option(),
) -> None:
    """The fewest links (or agents) whose loss breaks observability, and a certificate."""
    loaded = _case_of(case, tuple(REDUNDANCY))
    result = REDUNDANCY[loaded.kind](loaded, links=links)
    code = exit_code(result.verdict)
    data = {**result.to_json(), "exit_code": code}
    finish(data, code, as_json=as_json, show=lambda: _print_redundancy(result))


def _print_redundancy(result: Redundancy) -> None:
    shown = ", ".join(
        f"{item[0]}–{item[1]}" if isinstance(item, tuple) else str(item) for item in result.witness
    )
    bracket = "" if result.exact else f" (bracket: no set of fewer than {result.certified_below})"
    console.print(
        f"{result.case}: losing {result.k} {result.items}{bracket} breaks observability: "
        f"remove {shown or 'nothing'} (step {result.step + 1})",
        markup=False,
        style="bold",
    )
    console.print(result.reason, markup=False)
    console.print(
        f"every set of fewer than {result.certified_below} {result.items} keeps every agent "
        f"observable ({result.checked} sets checked exactly; {len(result.certificates)} "
        "certificates)",
        markup=False,
    )
    if result.note:
        console.print(result.note, markup=False)
