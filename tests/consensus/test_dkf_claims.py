"""The ch. 5 claims in the registry: ids, sources, and the paper's examples reproduced."""

from __future__ import annotations

import pytest

from theory.core.claims import Status
from theory.kinds import load_case
from theory.registry import all_claims, get_claim

IDS = {
    "seed000.def5.2.4",
    "seed000.thm5.2.10",
    "seed000.thm5.2.10.blindset",
    "seed000.lem5.2.2",
    "seed000.lem5.2.3",
    "seed000.lemA.2.1",
    "seed000.fn5",
    "seed000.ex5.1",
    "seed000.ex5.2",
    "seed000.counterexample5.2",
}


def test_claims_registered_with_sources():
    claims = {c.id: c for c in all_claims()}
    assert IDS <= set(claims)
    for claim_id in IDS:
        assert claims[claim_id].source and claims[claim_id].statement


@pytest.mark.parametrize(
    "claim_id", ["seed000.ex5.1", "seed000.ex5.2", "seed000.counterexample5.2"]
)
def test_paper_examples_verified(claim_id):
    (result,) = get_claim(claim_id).run(None)
    assert result.status == "verified", result.evidence


def test_example_thresholds_equal_the_papers_bounds():
    (result,) = get_claim("seed000.ex5.1").run(None)
    joint = result.evidence["wg"]["lmi_thresholds"]["[1, 2]"]
    assert joint["equals_paper_bound"] and joint["supremum"]["rational"] == "1/4"
    assert joint["status"] == "exact" and joint["low"] < 0.25 == joint["high"]
    (result,) = get_claim("seed000.ex5.2").run(None)
    agent3 = result.evidence["wg"]["lmi_thresholds"]["[3]"]
    assert agent3["equals_paper_bound"] and agent3["supremum"]["rational"] == "4000000/11840481"


@pytest.mark.parametrize(
    "name",
    ["ch5-example-1-wg", "ch5-example-1-wc", "ch5-example-2-wb", "ch5-blind-cycle"],
)
def test_kind_claims_run_on_cases(name):
    case = load_case(name)
    for claim in all_claims():
        if "dkf" in claim.kinds:
            for result in claim.results(case):
                assert result.status in set(Status)
                assert result.status != "refuted", (claim.id, result.evidence)
