"""``trackcert design …``: certified design answers, one subcommand per question.

Each subcommand is a shell over one library function: ``self-weight`` over
:func:`theory.consensus.design.self_weight_design` (0 some weight certified S-detectable, 1 none
at the family's smallest weight, 3 nothing certified), ``weights`` over
:func:`theory.consensus.weight_design.weight_design` (0 the designed weights certified, 3 not),
``gains`` over
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


def _dkf_redundancy(case: Case, *, links: bool) -> Any:
    """:func:`theory.consensus.redundancy.dkf_redundancy`, imported when asked for."""
    from theory.consensus.redundancy import dkf_redundancy

    return dkf_redundancy(case, links=links)


REDUNDANCY: dict[str, Callable[..., Any]] = {"tdoa": tdoa_redundancy, "dkf": _dkf_redundancy}
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
    show = _print_redundancy if isinstance(result, Redundancy) else _print_dkf_redundancy
    finish(data, code, as_json=as_json, show=lambda: show(result))


def _print_dkf_redundancy(result: Any) -> None:
    """The dkf redundancy answer, plainly."""
    shown = ", ".join(f"{x[0]}←{x[1]}" if isinstance(x, tuple) else str(x) for x in result.witness)
    if result.k is None:
        head = f"{result.case}: no loss of {result.items} found that breaks S-detectability"
    else:
        head = (
            f"{result.case}: losing {result.k} {result.items} breaks S-detectability: remove "
            f"{shown or 'nothing'}"
        )
    console.print(head, markup=False, style="bold")
    console.print(result.reason, markup=False)
    console.print(
        f"every set of fewer than {result.certified_below} {result.items} keeps S-detectability "
        f"({result.checked} sets decided exactly; {len(result.certificates)} certificates)",
        markup=False,
    )
    console.print(result.note, markup=False)


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


@design_app.command("self-weight")
@reports_errors
def self_weight(
    case: str = case_argument("Case file or bundled case name (kind: dkf)."),
    agent: Annotated[
        list[int] | None,
        typer.Option(
            "--agent",
            help="Agent (1-based) whose self-weight varies; repeat to vary "
            "several together. Default: the agents with the least exact bound.",
        ),
    ] = None,
    link: Annotated[
        list[str] | None,
        typer.Option(
            "--link",
            help="W.i.j=EXPR, EXPR affine in w (e.g. W.0.1=1-w), as sweep "
            "--link; repeat for each weight. Replaces --agent.",
        ),
    ] = None,
    width: str = typer.Option("0.0001", "--width", help="Width of a certified bracket."),
    as_json: bool = json_option(),
) -> None:
    """Supremum of a self-weight (or linked weights) keeping S-detectability, exact if possible."""
    from theory.consensus.design import self_weight_design

    loaded = _case_of(case, ("dkf",))
    agents = None if not agent else [a - 1 for a in agent]
    result = self_weight_design(
        loaded, agents=agents, links=tuple(link or ()), width=_positive(width, "--width")
    )
    code = exit_code(result.verdict)
    finish({**result.to_json(), "exit_code": code}, code, as_json=as_json,
           show=lambda: _print_self_weight(result))  # fmt: skip


def _print_self_weight(result: Any) -> None:
    """The supremum (exact value or bracket) and both certified ends, plainly."""
    sup = result.supremum
    who = f"agent(s) {', '.join(map(str, result.agents))}" if result.agents else result.family
    if sup is None:
        console.print(f"{result.case}: {who}: {result.status}", markup=False, style="bold")
    elif sup.exact:
        exact = str(sup.rational) if sup.rational is not None else (
            f"root of {' + '.join(f'{c}·w^{k}' for k, c in enumerate(sup.polynomial))} in "
            f"[{float(sup.interval[0]):.12g}, {float(sup.interval[1]):.12g}]"
        )  # fmt: skip
        console.print(
            f"{result.case}: {who}: S-detectable below w* = {sup.value:.6g} (exact: {exact})",
            markup=False, style="bold",
        )  # fmt: skip
    else:
        lo, hi = (float(x) for x in sup.interval)
        console.print(
            f"{result.case}: {who}: supremum in [{lo:.6g}, {hi:.6g}] ({result.status})",
            markup=False, style="bold",
        )  # fmt: skip
    for label, probe in (("certified S-detectable at", result.below),
                         ("refuted at", result.at_or_above)):  # fmt: skip
        if probe is not None:
            kind = probe.certificate["kind"] if probe.certificate else "no certificate"
            console.print(f"  {label} w = {probe.w} ({kind})", markup=False)
    if result.condition:
        console.print(f"  {result.condition}", markup=False)
    console.print(result.note, markup=False)


@design_app.command("weights")
@reports_errors
def weights(
    case: str = case_argument("Case file or bundled case name (kind: dkf)."),
    as_json: bool = json_option(),
) -> None:
    """Rational weights on the case's graph, certified S-detectable with a small r_σ(L)."""
    from theory.consensus.weight_design import weight_design

    result = weight_design(_case_of(case, ("dkf",)))
    code = exit_code(result.verdict)
    finish({**result.to_json(), "exit_code": code}, code, as_json=as_json,
           show=lambda: _print_weights(result))  # fmt: skip


def _print_weights(result: Any) -> None:
    """The designed and compared weights with their certified ρ, plainly."""
    table = Table(title=f"{result.case}: consensus weights and certified r_σ(L) < ρ")
    for column in ("weights", "certified ρ", "estimate", "W (rows)"):
        table.add_column(column)
    for entry in (result.designed, *result.compared):
        rho = "not certified" if entry.radius is None else f"{float(entry.radius):.4g}"
        rows = "; ".join(" ".join(f"{float(x):.3f}" for x in row) for row in entry.W)
        table.add_row(entry.name, rho, f"{entry.estimate:.4g}", rows)
    console.print(table)
    console.print(result.note, markup=False)
