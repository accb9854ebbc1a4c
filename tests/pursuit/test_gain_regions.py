"""Gain regions of seed 003 (issue 25 item 2): cells against the exact point decisions.

The point decision is ``trackcert iss``'s (``iss_conditions``, exact), the ``iss`` certificate of
the point (re-checked by ``proofs_check``) and the analysis gain ``iss_bound(spec).gain`` of
docs/theory/pursuit-iss.md §5. A point of a certified cell must pass all three with its gain inside
the cell's enclosure; the failing point of a refuted cell must fail, and so must every point of a
cell refuted as a whole. Float comparisons (gains, rates) allow a relative 1e-9: the enclosures are
exact, the point's gain is a float.
"""

from __future__ import annotations

import itertools
import json
import math
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

import proofs_check
from theory.cli import app
from theory.core.errors import CaseError
from theory.kinds import load_case
from theory.pursuit.certificates import iss_certificate
from theory.pursuit.design import (
    Axis,
    CellStatus,
    default_box,
    design_summary,
    draw_gain_map,
    gain_regions,
    parse_box,
)
from theory.pursuit.iss import ConditionStatus, coordination_iss, iss_bound, iss_conditions
from theory.strategies import pursuit_cases

runner = CliRunner()
RTOL = 1e-9
"""Relative slack of a float point value against an exact enclosure end."""
BUNDLED = [
    "pursuit-table1-n1",
    "pursuit-table1-n3",
    "pursuit-table2-n1",
    "pursuit-table2-n3",
    "pursuit-not-strongly-connected",
    "pursuit-singular-epsilon",
]


def _short(x: float) -> Fraction:
    """``x`` at 3 significant digits (0 below 1e-290: ``--box`` takes magnitudes ≥ 1e-300)."""
    return Fraction(f"{x:.3g}") if abs(x) >= 1e-290 else Fraction(0)


@st.composite
def _side(draw: st.DrawFn, path: str, value: Fraction) -> str:
    """``PATH=LO:HI[:log]`` as a user writes it (decimals): gains around the case's value, ε
    components often across 0 and sometimes tiny."""
    if path.startswith("epsilon."):
        lo = _short(draw(st.floats(-2.0, 1.0)))
        hi = lo + _short(draw(st.floats(0.05, 3.0)))
        return f"{path}={float(lo)!r}:{float(hi)!r}"
    lo = _short(float(value) * 10 ** draw(st.floats(-2.0, 1.0)))
    hi = _short(float(lo) * 10 ** draw(st.floats(0.05, 3.0)))
    if lo >= hi:
        hi = lo * 2
    return f"{path}={float(lo)!r}:{float(hi)!r}{':log' if draw(st.booleans()) else ''}"


@st.composite
def problems(draw: st.DrawFn):
    """A case (bundled or random), a box of one or two sides, settings and requirements."""
    random_case = st.integers(1, 3).flatmap(lambda n: pursuit_cases(n_trackers=n))
    case = draw(st.one_of(st.sampled_from(BUNDLED).map(load_case), random_case))
    values = {"K_p_scale": Fraction(1)} | {
        p: v for p, v in _values(case).items() if p != "K_p_scale"
    }
    paths = draw(st.lists(st.sampled_from(sorted(values)), min_size=1, max_size=2, unique=True))
    specs = [draw(_side(p, values[p])) for p in paths]
    options = {"grid": draw(st.integers(1, 3)), "depth": draw(st.integers(0, 3)), "max_cells": 64}
    if draw(st.booleans()):
        options["max_gain"] = _short(_case_gain(case) * 10 ** draw(st.floats(-0.5, 1.0)))
    if draw(st.booleans()):
        options["min_rate"] = _short(_case_rate(case) * 10 ** draw(st.floats(-1.5, 0.3)))
    return case, parse_box(case, specs), options


def _values(case) -> dict[str, Fraction]:
    spec = case.spec
    out = {"K_p_scale": Fraction(1)}
    out |= {f"epsilon.{i}": Fraction(repr(float(x))) for i, x in enumerate(spec.epsilon)}
    if spec.controller == "II":
        out["k_gamma"] = Fraction(repr(spec.k_gamma))
    if spec.n_trackers > 1:
        out["k_c"] = Fraction(repr(spec.k_c))
    return out


def _case_gain(case) -> float:
    try:
        return iss_bound(case.spec).gain
    except ValueError:  # a condition fails: any requirement will do
        return 100.0


def _case_rate(case) -> float:
    return float(np.linalg.eigvalsh(case.spec.K_p)[0])


def _at(case, point: dict[str, Fraction]):
    """The case's spec at ``point`` (floats, as a case file would hold them)."""
    spec = case.spec
    eps, scale, gains = spec.epsilon.copy(), 1.0, {}
    for path, x in point.items():
        if path == "K_p_scale":
            scale = float(x)
        elif path.startswith("epsilon."):
            eps[int(path.split(".")[1])] = float(x)
        else:
            gains[path] = float(x)
    return replace(spec, K_p=spec.K_p * scale, epsilon=eps, **gains)


def _inside(cell, axes, draw_fraction) -> dict[str, Fraction]:
    """A point of the cell: a float of each side read back as its shortest decimal."""
    point = {}
    for axis, (lo, hi) in zip(axes, cell.box, strict=True):
        x = Fraction(repr(float(lo + (hi - lo) * draw_fraction())))
        point[axis.path] = min(max(x, lo), hi)
    return point


def _rates(spec) -> list[float]:
    k_gamma = spec.k_gamma if spec.controller == "II" else math.inf
    K = np.diag([*np.linalg.eigvalsh(spec.K_p), k_gamma])
    rates = [float(np.min(np.diag(K)))]
    if spec.n_trackers > 1:
        rates.append(coordination_iss(spec).decay_rate)
    return rates


def _holds(regions, case, cell, point) -> None:
    """The point decision at a point of a certified cell."""
    spec = _at(case, point)
    statuses = {c.name: c.status for c in iss_conditions(spec, **_tol(regions))}
    assert set(statuses.values()) <= {ConditionStatus.HOLDS, ConditionStatus.NOT_APPLICABLE}
    assert proofs_check.check_certificate(iss_certificate(spec)).valid
    gain = iss_bound(spec).gain
    lo, hi = cell.iss_gain
    assert float(lo) * (1 - RTOL) <= gain <= float(hi) * (1 + RTOL), (gain, cell.iss_gain)
    wanted = regions.requirements
    if wanted["max_gain"] is not None:
        assert gain <= float(wanted["max_gain"]) * (1 + RTOL)
    if wanted["min_rate"] is not None:
        assert min(_rates(spec)) >= float(wanted["min_rate"]) * (1 - RTOL)


def _fails(regions, case, name: str, point) -> None:
    """The point decision at a failing point: the named condition or requirement fails."""
    spec = _at(case, point)
    if name == "decay_rate_at_least":
        assert min(_rates(spec)) < float(regions.requirements["min_rate"]) * (1 + RTOL)
    elif name == "iss_gain_at_most":
        assert iss_bound(spec).gain > float(regions.requirements["max_gain"]) * (1 - RTOL)
    else:
        statuses = {c.name: c.status for c in iss_conditions(spec, **_tol(regions))}
        assert statuses[name] == ConditionStatus.FAILS


def _tol(regions) -> dict[str, float]:
    return {"margin_tol": regions.tolerances["margin_tol"]}


@given(problem=problems(), data=st.data())
def test_cells_agree_with_the_exact_point_decision(problem, data) -> None:
    case, axes, options = problem
    regions = gain_regions(case, axes, **options)
    fraction = lambda: data.draw(st.floats(0.0, 1.0))  # noqa: E731
    by_status = {s: [c for c in regions.cells if c.status == s] for s in CellStatus}
    for cell in data.draw(st.lists(st.sampled_from(by_status[CellStatus.CERTIFIED]), max_size=2)
                          if by_status[CellStatus.CERTIFIED] else st.just([])):  # fmt: skip
        _holds(regions, case, cell, _inside(cell, axes, fraction))
    for cell in by_status[CellStatus.REFUTED][:3]:
        failing = cell.failing_condition
        spans = dict(zip((a.path for a in axes), cell.box, strict=True))
        assert all(spans[p][0] <= x <= spans[p][1] for p, x in failing.point.items() if p in spans)
        _fails(regions, case, failing.name, failing.point)
        if failing.whole_cell:
            _fails(regions, case, failing.name, _inside(cell, axes, fraction))
    assert all(c.reason for c in by_status[CellStatus.UNDECIDED])


@given(problem=problems())
def test_the_cells_tile_the_box_and_each_certificate_is_its_cell(problem) -> None:
    case, axes, options = problem
    regions = gain_regions(case, axes, **options)
    assert sum(regions.share(s) for s in CellStatus) == pytest.approx(1, rel=1e-9)
    if not any(a.log for a in axes):
        volume = sum(math.prod(hi - lo for lo, hi in c.box) for c in regions.cells)
        assert volume == math.prod(a.hi - a.lo for a in axes)  # exact
    names = {"epsilon.0": "epsilon_1"}
    for cell in regions.cells:
        if cell.certificate is None:
            continue
        box = cell.certificate["claim"]["box"]
        for axis, (lo, hi) in zip(axes, cell.box, strict=True):
            if axis.path in (*names, "K_p_scale", "k_gamma", "k_c"):
                assert box[names.get(axis.path, axis.path)] == [str(lo), str(hi)]
        assert proofs_check.check_certificate(cell.certificate).valid


def test_table1_max_gain_boundary_is_where_the_closed_form_puts_it() -> None:
    """Table I, N = 3 (docs/theory/pursuit-iss.md §3–§5): λ = 0.2, a(L) = 3/2, b/√r_min = 1, so
    the gain is g_e(1 + 1/(1.5 k_c)) for every k_γ ≥ 0.2: it stays ≤ 1000 iff k_c ≥ k_c*."""
    case = load_case("pursuit-table1-n3")
    axes = parse_box(case, ["k_gamma=1:1000:log", "k_c=0.01:10:log"])
    regions = gain_regions(case, axes, max_gain=Fraction(1000), depth=8, max_cells=4096)
    g_e = iss_bound(case.spec).constants["g_e"]
    k_star = g_e / (1.5 * (1000 - g_e))
    for cell in regions.cells:
        (_, _), (k_lo, k_hi) = cell.box
        if cell.status == CellStatus.CERTIFIED:
            assert float(k_lo) >= k_star * (1 - RTOL)
        elif cell.failing_condition.whole_cell:
            assert float(k_hi) < k_star
    whole = [c.failing_condition and c.failing_condition.whole_cell for c in regions.cells]
    straddling = [
        c for c, w in zip(regions.cells, whole, strict=True)
        if c.status != CellStatus.CERTIFIED and not w
    ]  # fmt: skip
    assert all(float(c.box[1][0]) <= k_star <= float(c.box[1][1]) for c in straddling)
    assert regions.share(CellStatus.CERTIFIED) > 0.6  # the boundary is resolved to ~1/256


def test_epsilon_one_zero_is_refuted_exactly_and_nowhere_else() -> None:
    case = load_case("pursuit-table1-n3")
    regions = gain_regions(case, parse_box(case, ["epsilon.0=-1:1"]), grid=4, depth=5)
    refuted = [c for c in regions.cells if c.status == CellStatus.REFUTED]
    assert refuted and all(c.box[0][0] <= 0 <= c.box[0][1] for c in refuted)
    assert all(c.failing_condition.point == {"epsilon.0": 0} for c in refuted)
    assert not any(c.failing_condition.whole_cell for c in refuted)
    assert regions.count(CellStatus.CERTIFIED) == len(regions.cells) - len(refuted)


def test_a_box_of_epsilon_inside_margin_tol_is_undecided_as_trackcert_iss_is() -> None:
    """ε = (−0.5, y) with y ≥ 10¹²: |ε₁|/‖ε‖ < 10⁻⁹ = margin_tol, inconclusive in trackcert iss."""
    case = load_case("pursuit-table1-n3")
    regions = gain_regions(case, parse_box(case, ["epsilon.1=1e12:2e12"]))
    assert {c.status for c in regions.cells} == {CellStatus.UNDECIDED}
    assert regions.verdict is None
    spec = _at(case, {"epsilon.1": Fraction(15 * 10**11)})
    statuses = {c.name: c.status for c in iss_conditions(spec)}
    assert statuses["delta_full_rank"] == ConditionStatus.INCONCLUSIVE


def test_a_failing_graph_refutes_the_whole_box_in_one_cell() -> None:
    case = load_case("pursuit-not-strongly-connected")
    regions = gain_regions(case, default_box(case))
    (cell,) = regions.cells
    assert cell.status == CellStatus.REFUTED and cell.failing_condition.whole_cell
    assert cell.failing_condition.name == "graph_strongly_connected"
    assert regions.verdict is False


def test_the_summary_gives_the_case_gain_and_the_condition_number_floor() -> None:
    """Table I: gain 650.4 at the case's gains (§5); floor ‖K_p‖/λ_min(K_p) = 0.4/0.2 = 2."""
    case = load_case("pursuit-table1-n3")
    summary = design_summary(case)
    at_case, floor = summary["gain_at_case"], summary["gain_infimum"]
    gain = iss_bound(case.spec).gain
    assert round(gain, 1) == 650.4
    assert at_case["lo_approx"] * (1 - RTOL) <= gain <= at_case["hi_approx"] * (1 + RTOL)
    assert Fraction(floor["lo"]) <= 2 <= Fraction(floor["hi"])
    assert summary["map"]["counts"]["certified"] == 16


def test_the_gain_never_goes_below_the_condition_number_of_k_p() -> None:
    """g_e ≥ s‖K_p‖/(sλ_min(K_p)) whatever the gains: a box of huge gains stays just above 2."""
    case = load_case("pursuit-table1-n3")
    sides = ["k_gamma=1e6:1e9:log", "k_c=1e6:1e9:log", "K_p_scale=1e6:1.001e6"]
    axes = parse_box(case, sides)
    lo, hi = gain_regions(case, axes, grid=2, depth=0).gain_range()
    assert 2 <= lo and float(hi) < 2.01


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ("k_c=1:2", "--box"),  # one tracker: no k_c
        ("k_gamma=0:2", "--box k_gamma"),
        ("k_gamma=2:1", "--box k_gamma"),
        ("k_gamma=1:2:lin", "--box"),
        ("epsilon.2=1:2", "--box"),
        ("K_p_scale=x:2", "--box K_p_scale"),
        ("epsilon.0=-1:1:log", "--box epsilon.0"),
        ("k_gamma=1e99999:1e100000", "--box k_gamma"),  # refused before 10^99999 is built
        ("k_gamma=1e-301:1", "--box k_gamma"),
    ],
)
def test_bad_boxes_name_the_option(text: str, field: str) -> None:
    with pytest.raises(CaseError) as error:
        parse_box(load_case("pursuit-table1-n1"), [text])
    assert error.value.field == field


def test_the_cli_prints_json_with_the_contract_keys_and_a_checkable_certificate(tmp_path) -> None:
    args = ["design", "gains", "pursuit-table2-n3", "--box", "k_c=0.05:0.5", "--json"]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    record = json.loads(result.stdout)
    for cell in record["cells"]:
        assert {"box", "status", "iss_gain"} <= set(cell)
        assert ("certificate" in cell) == (cell["status"] == "certified")
    path = tmp_path / "cell.json"
    path.write_text(json.dumps(record["cells"][0]["certificate"]), encoding="utf-8")
    checked = runner.invoke(app, ["check", str(path)])
    assert checked.exit_code == 0, checked.output


@pytest.mark.parametrize(
    ("args", "code"),
    [
        (["pursuit-table1-n3"], 0),
        (["pursuit-not-strongly-connected"], 1),
        (["pursuit-table1-n3", "--max-gain", "1.5"], 1),  # below ‖K_p‖/λ_min(K_p) = 2
        (["pursuit-table1-n3", "--box", "epsilon.1=1e12:2e12"], 3),
        (["pursuit-table1-n3", "--box", "k_c=0:1"], 2),
        (["ch5-example-1-wg"], 2),
    ],
)
def test_exit_codes(args: list[str], code: int) -> None:
    result = runner.invoke(app, ["design", "gains", *args])
    assert result.exit_code == code, result.output
    if code == 2:
        assert "error:" in result.output and "Traceback" not in result.output


@pytest.mark.parametrize("sides", [["k_c=0.01:10:log"], ["k_gamma=0.01:10:log", "K_p_scale=0.1:3"]])
def test_the_map_is_drawn_for_one_or_two_sides(tmp_path: Path, sides: list[str]) -> None:
    case = load_case("pursuit-table1-n3" if len(sides) == 1 else "pursuit-table1-n1")
    regions = gain_regions(case, parse_box(case, sides), max_gain=Fraction(300), depth=3)
    path = draw_gain_map(regions, tmp_path / "map.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_map_refuses_three_sides(tmp_path: Path) -> None:
    case = load_case("pursuit-table1-n3")
    axes = parse_box(case, ["k_c=1:2", "k_gamma=1:2", "K_p_scale=1:2"])
    with pytest.raises(ValueError, match="one or two sides"):
        draw_gain_map(gain_regions(case, axes, grid=1, depth=0), tmp_path / "map.png")


def test_log_sides_split_at_short_rationals_inside() -> None:
    axis = Axis("k_gamma", Fraction(1), Fraction(1000), log=True)
    ends = axis.ends(3)
    assert ends[0] == 1 and ends[-1] == 1000 and all(a < b for a, b in itertools.pairwise(ends))
    assert all(len(str(x)) <= 4 for x in ends)
    assert 1 < axis.middle(Fraction(1), Fraction(2)) < 2
