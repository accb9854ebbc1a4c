"""Registered claims of seed 000 §4.2 and the bundled TDOA cases' expectations."""

from __future__ import annotations

import json

import numpy as np
import pytest

from theory.core.case_file import bundled_cases
from theory.core.claims import Status
from theory.kinds import load_case
from theory.registry import all_claims, get_claim
from theory.tdoa.observability.fig43 import evaluate_tdoa_step

IDS = {
    "seed000.eq4.20": "verified",
    "seed000.sec4.2.1.two-rows": "verified",
    "seed000.sec4.2.1.planar": "verified",
    "seed000.sec4.2.1.coplanar": "corrected",
    "seed000.thm4.2.3": "corrected",
    "seed000.eq4.36.rank-sum": "refuted",
    "seed000.fn2": "verified",
}
TDOA_CASES = [name for name, path in bundled_cases().items() if load_case(path).kind == "tdoa"]
STATIC_UNDIRECTED = [
    name
    for name in TDOA_CASES
    if load_case(name).spec.steps == 1
    and np.array_equal(load_case(name).spec.hears[0], load_case(name).spec.hears[0].T)
]
"""Cases the per-component analysis covers (time-varying and directed ones: trackcert topology)."""


def test_claims_are_registered_with_sources() -> None:
    claims = {c.id: c for c in all_claims()}
    assert set(IDS) <= set(claims)
    assert all(claims[i].source.startswith("seed 000") for i in IDS)


@pytest.mark.parametrize("claim_id", [i for i in IDS if i != "seed000.fn2"])
def test_model_claims_reach_the_documented_verdict(claim_id: str) -> None:
    (result,) = get_claim(claim_id).run(None)
    assert result.status == IDS[claim_id] and result.case == "-"
    json.dumps(result.to_json(get_claim(claim_id).source))


@pytest.mark.slow
def test_footnote_2_claim() -> None:
    (result,) = get_claim("seed000.fn2").run(None)
    assert result.status == "verified" and len(result.evidence["witnesses"]) == 4


@pytest.mark.parametrize("name", TDOA_CASES)
def test_case_claims_return_closed_vocabulary_json(name: str) -> None:
    case = load_case(name)
    for claim in all_claims():
        if "tdoa" in claim.kinds:
            for result in claim.run(case):
                assert result.status in set(Status) and result.case == case.name
                json.dumps(result.to_json(claim.source))


@pytest.mark.parametrize("name", STATIC_UNDIRECTED)
def test_bundled_case_expectations_hold(name: str) -> None:
    """The expectations written in each bundled case are what the analysis finds."""
    case = load_case(name)
    step = evaluate_tdoa_step(case, 0)
    net = step.network
    assert net.conclusive
    n = 2 * case.spec.dim
    of_agent = {i: k for k, part in enumerate(step.components) for i in part}
    found = {
        "observable": [r == n for r in net.agent_ranks],
        "network_rank": net.network_rank,
        "network_observable": net.observable,
        "network_detectable": net.detectable,
        "heuristic_4_noncoplanar": [
            step.geometry[of_agent[i]].heuristic_4_noncoplanar for i in range(case.spec.n_agents)
        ],
        "mirror_ambiguous": [
            step.geometry[of_agent[i]].mirror_ambiguous for i in range(case.spec.n_agents)
        ],
    }
    for key, expected in case.expect.items():
        assert found[key] == expected, key
    exact_full = [r == case.spec.dim for r in step.exact_ranks]
    assert [g.full_rank for g in step.geometry] == exact_full
    assert np.all(
        np.array(found["observable"])
        == np.array([exact_full[of_agent[i]] for i in range(case.spec.n_agents)])
    )
