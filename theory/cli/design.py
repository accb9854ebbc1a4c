"""``trackcert design …``: what will work, with certificates (issue 25); one subcommand each.

Each subcommand is a thin shell over one library function:

- ``gains CASE --box PATH=LO:HI …``: :func:`theory.pursuit.design.gain_regions`. Exit code: 0
  a cell of the box is certified, 1 every cell is refuted, 3 none is certified and some are
  undecided, 2 bad input.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Annotated, Any

import typer
from rich.table import Table

from theory.cli.common import case_argument, console, finish, json_option, reports_errors
from theory.core.errors import CaseError
from theory.core.verdicts import exit_code
from theory.kinds import load_case

__all__ = ["design_app", "register", "register_gains"]

BOX_HELP = (
    "PATH=LO:HI or PATH=LO:HI:log; PATH is k_gamma, k_c, K_p_scale or epsilon.I (0-based). "
    "Repeat for each side; default: k_gamma (or K_p_scale) × k_c from a tenth to ten times the "
    "case's values."
)

design_app = typer.Typer(
    name="design",
    help="Certified design answers: which parameters work, with certificates.",
    no_args_is_help=True,
)


def register(app: typer.Typer) -> None:
    """Add the ``design`` group (every subcommand registered below) to ``app``."""
    register_gains(design_app)
    app.add_typer(design_app, name="design")


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


def register_gains(design: typer.Typer) -> None:
    """Add ``gains`` (seed 003 gain regions) to the ``design`` group."""

    @design.command("gains")
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
