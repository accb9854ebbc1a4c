"""``trackcert design …``: certified design answers, one subcommand per question.

Each subcommand is a shell over one library function: ``gains`` over
:func:`theory.pursuit.design.gain_regions` (0 a cell of the box is certified, 1 every cell is
refuted, 3 none certified and some undecided), ``margin`` over
:func:`theory.tdoa.geometry.margin.tdoa_margin`, ``placement`` over
:func:`theory.tdoa.geometry.placement.tdoa_placement`, ``redundancy`` over the function of the
case's kind (:data:`REDUNDANCY`). What an engineer deploys is printed plainly (rounded); ``--json``
gives the contract keys and the certificates, exact. Exit codes (docs/cli.md): 0 answered (the
property holds), 1 the property fails at the stated design (e.g. an agent already unobservable),
2 bad input, 3 inconclusive (nothing certified).
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Annotated, Any

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
    help="Certified design answers: which parameters work, how far agents may drift, what may fail",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)

BOX_HELP = (
    "PATH=LO:HI or PATH=LO:HI:log; PATH is k_gamma, k_c, K_p_scale or epsilon.I (0-based). "
    "Repeat for each side; default: k_gamma (or K_p_scale) × k_c from a tenth to ten times the "
    "case's values."
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


def _positive(text: str | None, option: str) -> Fraction | None:
    if text is None:
        return None
    try:
        value = Fraction(text.strip())
    except (ValueError, ZeroDivisionError):
        raise CaseError(
            option, "a decimal or a fraction > 0", text, file="<command line>"
        ) from None
    if value <= 0:
        raise CaseError(option, "a number > 0", text, file="<command line>")
    return value


def _print_gains(regions: Any) -> None:
    from theory.pursuit.design import CellStatus

    sides = ", ".join(
        f"{a.path} ∈ [{float(a.lo):.4g}, {float(a.hi):.4g}]{' (log)' if a.log else ''}"
        for a in regions.axes
    )
    console.print(f"{regions.case}: gain regions over {sides}", markup=False, highlight=False)
    counts = ", ".join(
        f"{regions.count(s)} {s} ({100 * regions.share(s):.1f} % of the box)" for s in CellStatus
    )
    console.print(counts, markup=False, highlight=False)
    certified = [c for c in regions.cells if c.status == CellStatus.CERTIFIED]
    if certified:
        best = min(certified, key=lambda c: c.iss_gain[1])
        box = ", ".join(
            f"{a.path} ∈ [{float(lo):.4g}, {float(hi):.4g}]"
            for a, (lo, hi) in zip(regions.axes, best.box, strict=True)
        )
        console.print(
            f"smallest certified ISS gain: ≤ {float(best.iss_gain[1]):.4g} for {box} "
            f"(exact bounds and the iss-box certificate in --json)",
            markup=False,
            highlight=False,
        )
    table = Table(title="cells")
    for column in (*(a.path for a in regions.axes), "status", "ISS gain", "why"):
        table.add_column(column)
    for cell in regions.cells[:40]:
        spans = [f"{float(lo):.4g} – {float(hi):.4g}" for lo, hi in cell.box]
        gain = "" if cell.iss_gain is None else "{:.4g} – {:.4g}".format(*map(float, cell.iss_gain))
        why = cell.reason
        if cell.failing_condition is not None:
            scope = "whole cell" if cell.failing_condition.whole_cell else "at a point"
            why = f"{cell.failing_condition.name} fails ({scope})"
        table.add_row(*spans, cell.status, gain, why)
    console.print(table)
    if len(regions.cells) > 40:
        console.print(f"… {len(regions.cells) - 40} more cells (--json lists every one)")


@design_app.command("gains")
@reports_errors
def gains(
    case: str = case_argument("Case file or bundled case name (kind: pursuit)."),
    box: Annotated[list[str] | None, typer.Option("--box", help=BOX_HELP)] = None,
    grid: int = typer.Option(4, "--grid", help="Initial cells per side."),
    depth: int = typer.Option(6, "--depth", help="Most halvings of an initial cell."),
    max_cells: int = typer.Option(1024, "--max-cells", help="Most cells in the map."),
    max_gain: str = typer.Option(None, "--max-gain", help="Require ISS gain ≤ this."),
    min_rate: str = typer.Option(None, "--min-rate", help="Require decay rates ≥ this."),
    gain_rtol: str = typer.Option(
        None, "--gain-rtol", help="Split certified cells until hi ≤ lo·(1 + this)."
    ),
    margin_tol: float = typer.Option(
        None, "--margin-tol", help="|ε₁|/‖ε‖ below this is undecided (as trackcert iss)."
    ),
    as_json: bool = json_option(),
) -> None:
    """Certified, refuted and undecided cells of seed 003's ISS conditions over a gain box."""
    from theory.pursuit.design import default_box, gain_regions, parse_box

    loaded = load_case(case)
    axes = parse_box(loaded, box) if box else default_box(loaded)
    regions = gain_regions(
        loaded,
        axes,
        grid=grid,
        depth=depth,
        max_cells=max_cells,
        max_gain=_positive(max_gain, "--max-gain"),
        min_rate=_positive(min_rate, "--min-rate"),
        gain_rtol=_positive(gain_rtol, "--gain-rtol"),
        margin_tol=margin_tol,
    )
    code = exit_code(regions.verdict)
    finish(regions.to_json(), code, as_json=as_json, show=lambda: _print_gains(regions))
