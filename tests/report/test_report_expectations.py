"""Expectations: a case's ``expect`` block against the values claims report."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.expectations import evaluate, matches

json_values = st.recursive(
    st.none()
    | st.booleans()
    | st.integers(-(10**6), 10**6)
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(max_size=5),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=3), inner),
    max_leaves=12,
)


@given(json_values)
def test_every_value_matches_itself(value) -> None:
    assert matches(value, value)


@given(
    st.integers(-(10**9), 10**9).filter(lambda m: m % 10 != 0),
    st.integers(1, 6),
)
def test_floats_match_to_their_printed_digits(mantissa: int, digits: int) -> None:
    expected = float(f"{mantissa}e-{digits}")  # printed with exactly `digits` decimals
    unit = 10.0**-digits
    assert matches(expected, expected + 0.49 * unit)
    assert matches(expected, expected - 0.49 * unit)
    assert not matches(expected, expected + 0.51 * unit)
    assert not matches(expected, expected - 0.51 * unit)


@pytest.mark.parametrize(
    ("expected", "observed", "same"),
    [
        (0.975, 0.9754, True),
        (0.975, 0.9756, False),
        (1.026, 1.02649, True),
        (0.3378, 0.337851, False),
        (0.3378, 0.33784, True),
        (True, 1, False),
        (1, True, False),
        (6, 6, True),
        (6, 6.0, True),
        (6, 6.000001, False),
        ([True, False], [True, False], True),
        ([True, False], [True], False),
        ({"a": 1}, {"a": 1, "b": 2}, False),
        (None, None, True),
        (None, False, False),
        ("yes", "yes", True),
        (3, "3", False),
    ],
)
def test_matching_rules(expected, observed, same) -> None:
    assert matches(expected, observed) is same


def test_verdicts() -> None:
    expect = {"a": True, "b": 2, "c": [1, 2], "d": 0.5, "e": "x"}
    observations = [
        ("claim.one", {"a": True, "b": 3}, "verified"),
        ("claim.two", {"a": True, "c": [1, 2]}, "refuted"),
        ("claim.three", {"c": [9, 9], "d": 0.5}, "inconclusive"),
    ]
    verdicts = {e.key: e.verdict for e in evaluate("case", expect, observations)}
    assert verdicts == {
        "a": "met",
        "b": "unmet",
        "c": "met",
        "d": "inconclusive",
        "e": "unchecked",
    }


def test_expectation_json_lists_each_observation() -> None:
    (verdict,) = evaluate("k", {"x": 1.5}, [("c1", {"x": 1.52}, "verified")])
    assert verdict.to_json() == {
        "case": "k",
        "key": "x",
        "expected": 1.5,
        "observations": [{"claim": "c1", "value": 1.52, "status": "verified", "matches": True}],
        "verdict": "met",
    }
    assert math.isclose(verdict.observations[0].value, 1.52)
