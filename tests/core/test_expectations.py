"""Expectations: a case's ``expect`` block judged against what observers and claims report, one
mechanism for every command and the report (``theory.core.expectations``), and the exit-code
policy on its verdicts (``theory.core.verdicts``)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.claims import Context, status_of
from theory.core.expectations import (
    EXPECTATIONS_KEY,
    UNDECIDED_KEY,
    Expectation,
    Observed,
    evaluate,
    judge,
    matches,
    observations_from,
)
from theory.core.verdicts import exit_code, expectations_verdict
from theory.kinds import load_case
from theory.registry import get_claim

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
        "got": 1.52,
        "met": True,
        "verdict": "met",
        "observations": [{"claim": "c1", "value": 1.52, "status": "verified", "matches": True}],
    }
    assert math.isclose(verdict.observations[0].value, 1.52)


@given(st.floats(-1e6, 1e6), st.floats(-1e6, 1e6))
def test_bound_rules_compare_as_their_names_say(bound: float, value: float) -> None:
    assert matches(bound, value, "at_most") is (value <= bound)
    assert matches(bound, value, "at_least") is (value >= bound)
    assert not matches(bound, True, "at_most")  # a boolean is not a number here


@given(st.floats(-1e6, 1e6), st.floats(0, 1e6), st.lists(st.floats(-1e6, 1e6), max_size=4))
def test_within_holds_exactly_when_every_value_lies_in_the_band(
    low: float, width: float, values: list[float]
) -> None:
    band = [low, low + width]
    inside = bool(values) and all(low <= v <= low + width for v in values)
    assert matches(band, values, "within") is inside
    if values:
        assert matches(band, values[0], "within") is (low <= values[0] <= low + width)
    assert not matches(band, True, "within") and not matches([low], low, "within")


def test_unknown_rule_is_refused() -> None:
    with pytest.raises(ValueError, match="rule"):
        matches(1.0, 1.0, "about")


def test_an_at_most_key_is_met_below_its_bound_and_unmet_above() -> None:
    rules = {"max_final_error": "at_most"}
    below, above = (
        evaluate(
            "k", {"max_final_error": 2.0}, [("sim", {"max_final_error": v}, "verified")], rules
        )
        for v in (1.3, 2.4)
    )
    assert [below[0].verdict, above[0].verdict] == ["met", "unmet"]
    assert below[0].to_json()["rule"] == "at_most"


def test_undecided_keys_are_inconclusive_and_the_others_keep_the_status() -> None:
    evidence = Observed({"a": True, "b": None}, frozenset({"b"})).evidence()
    assert evidence == {EXPECTATIONS_KEY: {"a": True, "b": None}, UNDECIDED_KEY: ["b"]}
    found = observations_from("obs", evidence, "verified")
    assert found == [("obs", {"a": True}, "verified"), ("obs", {"b": None}, "inconclusive")]
    verdicts = {e.key: e.verdict for e in evaluate("k", {"a": True, "b": False}, found)}
    assert verdicts == {"a": "met", "b": "inconclusive"}
    assert observations_from("obs", {"other": 1}, "verified") == []


@pytest.mark.parametrize(
    ("verdicts", "verdict", "code", "status"),
    [
        ((), True, 0, "verified"),
        (("met", "met"), True, 0, "verified"),
        (("met", "unmet", "inconclusive"), False, 1, "refuted"),
        (("met", "inconclusive"), None, 3, "inconclusive"),
        (("unchecked",), None, 3, "inconclusive"),
    ],
)
def test_one_exit_code_policy_on_expectation_verdicts(verdicts, verdict, code, status) -> None:
    judged = [Expectation("k", f"k{i}", True, (), v) for i, v in enumerate(verdicts)]
    assert expectations_verdict(judged) is verdict
    assert exit_code(verdict) == code and status_of(verdict) == status


def test_a_command_and_the_report_claim_judge_a_case_alike() -> None:
    """``trackcert topology``'s verdict records and ``case.expect.tdoa``'s status come from the
    same observer and the same judge."""
    from theory.tdoa.observability.trajectory import observe_topology, topology_report

    case = load_case("fig43-case-d")
    command = topology_report(case).expectations
    direct = judge(case, observe_topology(case, Context()), source="test")
    assert [e.verdict for e in command] == [e.verdict for e in direct] == ["met"] * len(case.expect)
    (result,) = get_claim("case.expect.tdoa").run(case)
    assert result.status == "verified"
    assert set(result.evidence[EXPECTATIONS_KEY]) == set(case.expect)


def test_the_report_claim_is_refuted_by_a_wrong_expectation() -> None:
    case = load_case("fig43-case-d")
    wrong = type(case)(**{**vars(case), "expect": {"observable": [False] * 4}})
    (result,) = get_claim("case.expect.tdoa").run(wrong)
    assert result.status == "refuted"
    assert "observable" in result.message
