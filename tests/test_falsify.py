"""``trackcert falsify``: wrong paper wordings are refuted within the default budget, holding
wordings survive the CI profile's budget, counterexamples come back as ready-to-run case files
with their finding, and every registered claim is searched or marked as a fixed instance."""

from __future__ import annotations

import json

import numpy as np
import pytest
import yaml
from hypothesis import settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from theory.cli import app
from theory.consensus.properties import jointly_detectable, strongly_connected
from theory.core.claims import Finding, Property, Wording
from theory.falsify import DEFAULT_EXAMPLES, falsify, fixed_instances, unsearched_claims
from theory.kinds import parse_case
from theory.pursuit.properties import (
    PursuitExample,
    coordination_terms,
    phi_terms,
    pursuit_terms,
)
from theory.registry import all_claims, all_properties
from theory.strategies import TdoaScene
from theory.tdoa.observability.properties import (
    WeightedScene,
    analyze_weighted_scene,
    component_rank,
    scene_case,
)

runner = CliRunner()
PROPERTIES = all_properties()


WRONG = [p for p in PROPERTIES if not p.expected_to_hold]
HOLDING = [p for p in PROPERTIES if p.expected_to_hold]


@pytest.mark.parametrize("prop", WRONG, ids=[p.id for p in WRONG])
def test_default_budget_refutes_wrong_wordings(prop) -> None:
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
    assert result.found and result.finding == Finding.COUNTEREXAMPLE


@pytest.mark.parametrize("prop", HOLDING, ids=[p.id for p in HOLDING])
def test_holding_wordings_survive_the_profile_budget(prop) -> None:
    """The budget of the registered hypothesis profile (tests/conftest.py: 25 in CI)."""
    result = falsify(prop, examples=settings().max_examples, seed=0)
    assert not result.found and result.finding is None, result.case


@pytest.mark.parametrize("prop", WRONG, ids=[p.id for p in WRONG])
def test_counterexample_is_a_valid_deterministic_case(prop) -> None:
    first = falsify(prop, examples=DEFAULT_EXAMPLES, seed=3)
    again = falsify(prop, examples=DEFAULT_EXAMPLES, seed=3)
    assert first.found and first.case == again.case
    reloaded = yaml.safe_load(yaml.safe_dump(first.case))
    if "kind" in first.case:
        assert parse_case(reloaded).kind == first.case["kind"]
    else:  # a claim about the model alone: the record says how to rerun the search
        assert reloaded["claim"] == prop.claim and reloaded["example"]
        assert reloaded["rerun"] == f"trackcert falsify {prop.id} --seed 3 --examples 200"


@pytest.mark.parametrize("prop", [p for p in WRONG if p.to_case is scene_case], ids=lambda p: p.id)
def test_tdoa_counterexample_reloads_to_the_same_verdict(prop) -> None:
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=3)
    case = parse_case(yaml.safe_load(yaml.safe_dump(result.case)))
    scene = TdoaScene(case.spec.target[0], case.spec.agents[0], "reloaded")
    assert not prop.holds(scene)
    rank, conclusive = component_rank(scene)
    assert conclusive
    assert case.expect["observable"] == [rank == case.spec.dim] * case.spec.n_agents


@pytest.mark.parametrize("printed", ["paper", "paper75"])
def test_coordination_counterexample_reloads(printed: str) -> None:
    name = {"paper": "seed003.eq74/paper", "paper75": "seed003.eq75/paper"}[printed]
    prop = next(p for p in WRONG if p.id == name)
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
    case = parse_case(result.case)
    spec = case.spec
    example = result.counterexample
    assert len(spec.trackers) == example.laplacian.shape[0]
    assert (spec.laplacian == example.laplacian).all()
    assert [t.gamma0 for t in spec.trackers] == example.gamma.tolist()
    terms = coordination_terms(example)
    assert terms["v_dot"] > terms[printed] and terms["v_dot"] <= terms["corrected"] + 1e-9


def test_rank_sum_counterexample_reloads_to_the_same_verdict() -> None:
    prop = next(p for p in WRONG if p.id == "seed000.eq4.36.rank-sum/paper")
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=3)
    case = parse_case(yaml.safe_load(yaml.safe_dump(result.case)))
    spec = case.spec
    original = result.counterexample
    scene = TdoaScene(spec.target[0], spec.agents[0], "reloaded")
    reloaded = WeightedScene(scene, spec.weights[0], spec.weights_rule)
    assert np.allclose(reloaded.weights, original.weights, rtol=0, atol=1e-15)
    assert not prop.holds(reloaded)
    net = analyze_weighted_scene(reloaded)
    assert net.conclusive and net.network_rank < net.rank_sum
    assert case.expect["network_rank"] == net.network_rank
    assert case.expect["network_detectable"] == net.detectable


def test_singular_weights_break_the_rank_sum() -> None:
    """Uniform weights on a complete graph (W = J/N, rank 1) on a scene that localizes."""
    prop = next(p for p in WRONG if p.id == "seed000.eq4.36.rank-sum/paper")
    agents = np.array([[10.0, 0, 0], [0, 10, 0], [0, 0, 10], [-10, -10, -10]])
    scene = TdoaScene(np.zeros(3), agents, "general")
    example = WeightedScene(scene, np.full((4, 4), 0.25), "uniform")
    net = analyze_weighted_scene(example)
    assert net.conclusive and net.detectable and not net.observable
    assert not prop.holds(example) and net.network_rank < net.rank_sum


def test_eq71_counterexample_is_exact_equality() -> None:
    prop = next(p for p in WRONG if p.id == "seed003.eq71/paper")
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
    example = result.counterexample
    terms = phi_terms(example)
    assert terms["x_sq"] > 0 and terms["phi_sq"] == terms["mu_x_sq"]
    (tracker,) = parse_case(result.case).spec.trackers
    assert (tracker.r_x, tracker.r_y) == (example.r_x, example.r_y)


def test_eq72_counterexample_reloads() -> None:
    """The case carries the gains and the path; with the described state, (72) fails again
    while the region of (78) excludes the state."""
    prop = next(p for p in WRONG if p.id == "seed003.eq72/paper")
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
    found = result.counterexample
    reloaded = PursuitExample(parse_case(result.case), found.state, found.theta)
    assert not prop.holds(reloaded)
    terms = pursuit_terms(reloaded)
    assert terms["lambda_min"] < 1
    assert terms["e_norm"] < terms["c"] * terms["x_norm"] / (found.theta * terms["lambda_min"])


def test_cli_exit_codes_and_json() -> None:
    found = runner.invoke(app, ["falsify", "seed000.thm4.2.3/paper", "--json"])
    assert found.exit_code == 1
    record = json.loads(found.stdout)["results"][0]
    assert record["found"] and record["case"]["kind"] == "tdoa"
    clean = runner.invoke(app, ["falsify", "seed000.thm4.2.3/corrected", "--examples", "30"])
    assert clean.exit_code == 0 and "no counterexample in 30 examples" in clean.stdout
    listed = runner.invoke(app, ["falsify", "--list", "--json"])
    assert {p["id"] for p in json.loads(listed.stdout)["properties"]} == {p.id for p in PROPERTIES}
    bad = runner.invoke(app, ["falsify", "no.such.claim"])
    assert bad.exit_code == 2 and "Traceback" not in bad.output


def test_documented_cone_example_finds_the_counterexample() -> None:
    """The example of docs/property-based.md fails as the document says it does."""
    import re
    from pathlib import Path

    text = (Path(__file__).parent.parent / "docs" / "property-based.md").read_text()
    code = re.findall(r"```python\n(.*?)```", text, re.S)[0]
    namespace: dict = {}
    exec(code, namespace)
    with pytest.raises(AssertionError):
        namespace["test_non_coplanar_agents_localize"]()


def test_detectability_counterexample_is_a_connected_blind_agent() -> None:
    prop = next(p for p in WRONG if p.id == "seed000.sec5.2.detectability/paper")
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=1)
    problem = result.counterexample
    assert strongly_connected(problem) and jointly_detectable(problem)
    case = parse_case(result.case)
    assert case.kind == "dkf"
    assert any(c.shape[0] == 0 for c in problem.C), "a blind agent is what breaks S-detectability"


# ------------------------------------------------------------------------- coverage (issue 27)
def test_every_registered_claim_is_searched_or_a_fixed_instance() -> None:
    assert unsearched_claims() == []
    ids = {c.id for c in all_claims()}
    for mark in fixed_instances():
        assert mark.claim in ids and len(mark.reason) > 20, mark


def test_fixed_instances_are_listed_with_their_reason() -> None:
    listed = runner.invoke(app, ["falsify", "--list", "--json"])
    marks = json.loads(listed.stdout)["fixed_instances"]
    assert {m["claim"]: m["reason"] for m in marks} == {
        f.claim: f.reason for f in fixed_instances()
    }
    text = runner.invoke(app, ["falsify", "--list"]).stdout
    assert "fixed instance" in text and "seed000.ex5.1" in text


# ------------------------------------------------------------------- planted false claims
def _planted(statement: str, examples, holds, *, expected: bool = False) -> Property:
    return Property(
        "planted/paper", "planted", Wording.PAPER, statement, examples, holds,
        lambda example: {"name": "planted", "example": repr(example)}, expected,
    )  # fmt: skip


def test_planted_false_claim_yields_a_shrunk_counterexample() -> None:
    """ "Every row-stochastic W with w_ii > 0 is symmetric" is false; the smallest
    counterexample has two agents."""
    from theory.tdoa.properties import stochastic_networks

    prop = _planted(
        "every row-stochastic W with a positive diagonal is symmetric",
        stochastic_networks(),
        lambda W: bool(np.allclose(W, W.T)),
    )
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
    assert result.found and result.finding == Finding.COUNTEREXAMPLE
    W = result.counterexample
    assert W.shape == (2, 2) and not np.allclose(W, W.T)
    assert np.allclose(W.sum(axis=1), 1) and (np.diag(W) > 0).all()


def test_planted_bound_without_the_noise_term_is_refuted_inside_the_hypotheses() -> None:
    """Lemma A.1.1 with the μ term dropped is false; the counterexample meets (A.9)–(A.10)."""
    from fractions import Fraction

    from theory.tdoa.properties import lemma_a11_holds, linear_processes

    def no_noise(k, *, v_min, v_max, mu, alpha, mean_square_0):
        return Fraction(v_max) / v_min * mean_square_0 * (1 - alpha) ** k

    prop = _planted("(A.11) without μ", linear_processes(), lambda p: lemma_a11_holds(p, no_noise))
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
    assert result.found and result.finding == Finding.COUNTEREXAMPLE
    assert not lemma_a11_holds(result.counterexample, no_noise)


def test_planted_true_claim_has_no_finding() -> None:
    prop = _planted("x² ≥ 0", st.integers(-100, 100), lambda x: x * x >= 0, expected=True)
    result = falsify(prop, examples=50, seed=0)
    assert not result.found and result.finding is None and result.case is None


def test_cli_shows_the_finding() -> None:
    shown = runner.invoke(app, ["falsify", "seed000.lemA.1.1/paper", "--workers", "1"])
    assert shown.exit_code == 1
    assert "finding: counterexample to the paper wording" in shown.stdout
    assert "trackcert falsify seed000.lemA.1.1/paper --seed 0 --examples 200" in shown.stdout
    found = runner.invoke(app, ["falsify", "seed000.lemA.1.1", "--json", "--workers", "1"])
    record = json.loads(found.stdout)
    findings = {r["wording"]: r["finding"] for r in record["results"]}
    assert findings == {"paper": "counterexample", "corrected": None}


# ----------------------------------------------------------------- findings on claim results
def test_a_theorem_whose_hypotheses_fail_is_not_a_counterexample() -> None:
    """seed003.thm2 on a graph that is not strongly connected: status stays ``refuted`` (backward
    compatible), the finding says the theorem is silent (issue 27 part 3)."""
    from theory.kinds import load_case
    from theory.registry import get_claim

    case = load_case("pursuit-not-strongly-connected")
    (result,) = get_claim("seed003.thm2").run(case)
    assert result.status == "refuted" and result.finding == Finding.HYPOTHESES_UNMET
    assert result.to_json()["finding"] == "hypotheses-unmet"


def test_findings_default_from_the_status() -> None:
    from theory.core.claims import Claim, ClaimResult, Method, Status

    def check(case, ctx):
        return [ClaimResult(s, Method.EXACT) for s in Status]

    model = Claim("x", "src", "statement", (), check).run(None)
    assert [r.finding for r in model] == [None, "counterexample", "counterexample", None]
    with pytest.raises(ValueError, match="verified result finds nothing"):
        ClaimResult(Status.VERIFIED, Method.EXACT, finding=Finding.COUNTEREXAMPLE)


def test_report_records_carry_the_finding() -> None:
    from theory.core.claims import ClaimResult, Method, Status
    from theory.report.tasks import RESULT_FIELDS, Record

    result = ClaimResult(Status.REFUTED, Method.EXACT, finding=Finding.PROPERTY_FAILS)
    record = Record(result, "src", "statement", "000")
    assert "finding" in RESULT_FIELDS and record.finding == Finding.PROPERTY_FAILS
    assert record.to_json()["finding"] == "property-fails"


def test_iss_shows_the_finding_of_each_claim() -> None:
    shown = runner.invoke(app, ["iss", "pursuit-not-strongly-connected"])
    assert "hypotheses-unmet" in shown.stdout
    record = json.loads(
        runner.invoke(app, ["iss", "pursuit-not-strongly-connected", "--json"]).stdout
    )
    findings = {c["id"]: c["finding"] for c in record["claims"]}
    assert findings["seed003.thm2"] == findings["seed003.lem3"] == "hypotheses-unmet"
