"""``--link PATH=EXPR``: the affine forms of docs/sweep.md, refused forms, values at each point,
and seed 000 Example 1's self-weight sweep, which needs a link to stay row-stochastic."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.errors import CaseError
from theory.sweep.grid import check_size, grid_points, grid_size, parse_link, parse_param
from theory.sweep.run import sweep_case

SWEPT = (parse_param("w=0.2,0.25,0.3"), parse_param("seed=0:3"))


@pytest.mark.parametrize(
    ("expr", "offset", "factor"),
    [
        ("w", 0, 1),
        ("-w", 0, -1),
        ("2*w", 0, 2),
        ("1-w", 1, -1),
        ("1 - w", 1, -1),
        ("-0.5+w", -0.5, 1),
        ("1-2*w", 1, -2),
        ("3+1.5e-1*w", 3, 0.15),
    ],
)
def test_affine_forms(expr: str, offset: float, factor: float) -> None:
    link = parse_link(f"x.0={expr}", SWEPT)
    assert (link.source, link.offset, link.factor, link.scale) == ("w", offset, factor, "link")
    assert link.values == tuple(offset + factor * v for v in SWEPT[0].values)


@pytest.mark.parametrize(
    "text",
    ["x.0", "=1-w", "x.0=", "x..0=w", "x=w*2", "x=w+1", "x=1-w-w", "x=abs(w)", "x=2**w", "x=1-v"],
)
def test_other_forms_are_refused_naming_link(text: str) -> None:
    with pytest.raises(CaseError) as raised:
        parse_link(text, SWEPT)
    assert raised.value.field == "--link" and raised.value.file == "<command line>"


def test_a_link_cannot_follow_a_link() -> None:
    first = parse_link("x=1-w", SWEPT)
    with pytest.raises(CaseError, match="--link"):
        parse_link("y=2*x", (*SWEPT, first))


@given(st.integers(-5, 5), st.integers(-3, 3), st.sampled_from(["w", "seed"]))
def test_links_add_no_points_and_follow_their_source(offset: int, factor: int, source: str) -> None:
    sign = "-" if factor < 0 else "+"
    link = parse_link(f"x={offset}{sign}{abs(factor)}*{source}", SWEPT)
    params = (*SWEPT, link)
    assert grid_size(params) == grid_size(SWEPT) == check_size(params) == 9
    at = [p.path for p in SWEPT].index(source)
    for point, swept in zip(grid_points(params), grid_points(SWEPT), strict=True):
        assert point[:2] == swept
        assert point[2] == offset + factor * swept[at]
        assert isinstance(point[2], int) == isinstance(swept[at], int)


def test_a_path_set_twice_is_refused() -> None:
    with pytest.raises(CaseError, match="one --param or --link"):
        check_size((*SWEPT, parse_link("w=1-seed", SWEPT)))


def test_example_1_self_weight_sweep_crosses_one_quarter() -> None:
    """seed 000 Example 1 (A = 2I): S-detectable iff w₁₁ = w₂₂ < 1/r(A)² = 1/4 (Thm 5.2.10,
    docs/errata.md). Without the links every point would be an invalid W."""
    sweep = sweep_case(
        "ch5-example-1-wb",
        ["W.0.0=0.24,0.25,0.26"],
        links=["W.0.1=1-W.0.0", "W.1.1=W.0.0", "W.1.0=1-W.0.0"],
        simulate=False,
        workers=1,
    )
    assert [r.status for r in sweep.rows] == ["verified", "refuted", "refuted"]
    assert [r.values[1] for r in sweep.rows] == [0.76, 0.75, 0.74]
    assert sweep.columns()[1:5] == ["W.0.0", "W.0.1", "W.1.1", "W.1.0"]
    with pytest.raises(CaseError, match="row summing to 1"):
        sweep_case("ch5-example-1-wb", ["W.0.0=0.24,0.25"], simulate=False, workers=1)


def test_cli_link_sweep_and_bad_link_exit_2(tmp_path) -> None:
    from typer.testing import CliRunner

    from theory.cli import app

    args = ["sweep", "ch5-example-1-wb", "--param", "W.0.0=0.2,0.3", "--no-simulate", "--json"]
    links = ["--link", "W.0.1=1-W.0.0", "--link", "W.1.1=W.0.0", "--link", "W.1.0=1-W.0.0"]
    done = CliRunner().invoke(app, [*args, *links, "--workers", "1", "-o", str(tmp_path / "ok")])
    assert done.exit_code == 0, done.output
    header = (tmp_path / "ok" / "sweep.csv").read_text().splitlines()[0]
    assert header.startswith("point,W.0.0,W.0.1,W.1.1,W.1.0,status")
    bad = CliRunner().invoke(app, [*args, "--link", "W.0.1=1-w", "-o", str(tmp_path / "bad")])
    assert bad.exit_code == 2 and "--link" in bad.stderr and "Traceback" not in bad.output
    assert not (tmp_path / "bad").exists()
