"""``--param PATH=SPEC``: the spec forms of docs/sweep.md, the grid's order and its size limit."""

from __future__ import annotations

import itertools
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.errors import CaseError
from theory.sweep.grid import check_size, grid_points, parse_param, parse_spec

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False).filter(lambda x: abs(x) > 1e-6)
positive = st.floats(min_value=1e-6, max_value=1e6, allow_nan=False)


@given(st.integers(-1000, 1000), st.integers(1, 200))
def test_integer_range_is_half_open(start: int, length: int) -> None:
    """``a:b`` is ``range(a, b)``: b itself is not swept."""
    scale, values = parse_spec(f"{start}:{start + length}")
    assert scale == "range"
    assert values == tuple(range(start, start + length))
    assert all(isinstance(v, int) for v in values)


@given(finite, finite, st.integers(2, 60))
def test_linear_spec_includes_both_ends_evenly(a: float, b: float, n: int) -> None:
    if a == b:
        return
    scale, values = parse_spec(f"{a!r}:{b!r}:lin{n}")
    assert scale == "lin" and len(values) == n
    assert values[0] == a and values[-1] == b
    steps = [y - x for x, y in itertools.pairwise(values)]
    assert all(
        math.isclose(s, (b - a) / (n - 1), rel_tol=1e-6, abs_tol=1e-9 * abs(b - a)) for s in steps
    )


@given(positive, positive, st.integers(2, 60))
def test_log_spec_is_geometric(a: float, b: float, n: int) -> None:
    if a == b:
        return
    scale, values = parse_spec(f"{a!r}:{b!r}:log{n}")
    assert scale == "log" and len(values) == n
    assert values[0] == a and values[-1] == b
    ratio = (b / a) ** (1 / (n - 1))
    for x, y in itertools.pairwise(values):
        assert math.isclose(y / x, ratio, rel_tol=1e-9)


@given(st.lists(st.one_of(st.integers(-(10**6), 10**6), finite), min_size=1, max_size=8))
def test_explicit_list_round_trips_in_order(items: list) -> None:
    scale, values = parse_spec(",".join(repr(v) for v in items))
    assert scale == ("value" if len(items) == 1 else "list")
    assert values == tuple(items)
    assert [type(v) for v in values] == [type(v) for v in items]


def test_the_issue_example_reads_naturally() -> None:
    k_gamma, seed = parse_param("k_gamma=1:400:log20"), parse_param("seed=0:50")
    assert (k_gamma.path, k_gamma.scale, len(k_gamma.values)) == ("k_gamma", "log", 20)
    assert k_gamma.values[0] == 1 and k_gamma.values[-1] == 400
    assert seed.values == tuple(range(50))
    assert parse_param("w=0.2,0.24,0.25").values == (0.2, 0.24, 0.25)
    assert parse_param("W.0.1 = 0.5").path == "W.0.1"


@pytest.mark.parametrize(
    "text",
    [
        "k_gamma",
        "=1:2",
        "k_gamma=",
        "k_gamma=1:2:3",
        "k_gamma=1:400:log1",
        "k_gamma=0:400:log5",
        "k_gamma=1.5:3",
        "k_gamma=5:5",
        "k_gamma=3:1",
        "k_gamma=1:2:3:4",
        "k_gamma=abc",
        "k_gamma=1,,2",
        "k_gamma=nan",
        "a..b=1",
        "k_gamma=2:2:lin3",
    ],
)
def test_bad_specs_name_param_the_forms_and_the_text(text: str) -> None:
    with pytest.raises(CaseError) as caught:
        parse_param(text)
    error = caught.value
    assert error.field == "--param"
    assert "FROM:TO:logN" in error.expected
    assert error.got == text


def test_grid_is_the_product_first_param_slowest() -> None:
    params = [parse_param("a=1,2"), parse_param("b=0:3")]
    assert list(grid_points(params)) == [(1, 0), (1, 1), (1, 2), (2, 0), (2, 1), (2, 2)]
    assert check_size(params) == 6


def test_size_limit_is_checked_before_expanding() -> None:
    params = [parse_param("a=0:1000"), parse_param("b=0:1000")]
    with pytest.raises(CaseError, match="max-points"):
        check_size(params)
    assert check_size(params, max_points=10**6) == 10**6


@pytest.mark.parametrize(
    ("params", "field"),
    [([], "--param"), (["a=1", "a=2"], "--param")],
)
def test_no_param_or_a_repeated_path_is_refused(params: list[str], field: str) -> None:
    with pytest.raises(CaseError) as caught:
        check_size([parse_param(p) for p in params])
    assert caught.value.field == field


def test_max_points_must_be_positive() -> None:
    with pytest.raises(CaseError) as caught:
        check_size([parse_param("a=1")], max_points=0)
    assert caught.value.field == "--max-points"
