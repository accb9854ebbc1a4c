"""``trackcert falsify``: wrong paper wordings are refuted within the default budget, corrected
wordings survive it, and counterexamples come back as ready-to-run case files."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest
import yaml
from hypothesis import settings
from typer.testing import CliRunner

from theory.cli import app
from theory.consensus.properties import jointly_detectable, strongly_connected
from theory.falsify import DEFAULT_EXAMPLES, falsify
from theory.kinds import parse_case
from theory.pursuit.properties import (
    PursuitExample,
    coordination_terms,
    phi_terms,
    pursuit_terms,
)
from theory.registry import all_properties
from theory.strategies import TdoaScene
from theory.tdoa.observability.properties import (
    WeightedScene,
    analyze_weighted_scene,
    component_rank,
    scene_case,
)

runner = CliRunner()
PROPERTIES = all_properties()
SURVIVAL_BUDGET = (
    settings.default.max_examples
    if os.environ.get("CI")
    else max(DEFAULT_EXAMPLES, settings.default.max_examples)
)
"""The search a corrected wording must survive: the ci profile's bounded budget (conftest.py; a
search of the default budget of a property that holds costs minutes), else at least the command's
default budget. A wrong wording must always fall within the default budget."""


@pytest.mark.parametrize("prop", PROPERTIES, ids=[p.id for p in PROPERTIES])
def test_default_budget_separates_wrong_from_corrected(prop) -> None:
    budget = SURVIVAL_BUDGET if prop.expected_to_hold else DEFAULT_EXAMPLES
    result = falsify(prop, examples=budget, seed=0)
    assert result.found == (not prop.expected_to_hold), result.case


WRONG = [p for p in PROPERTIES if not p.expected_to_hold]


@pytest.mark.parametrize("prop", WRONG, ids=[p.id for p in WRONG])
def test_counterexample_is_a_valid_deterministic_case(prop) -> None:
    first = falsify(prop, examples=DEFAULT_EXAMPLES, seed=3)
    again = falsify(prop, examples=DEFAULT_EXAMPLES, seed=3)
    assert first.found and first.case == again.case
    case = parse_case(yaml.safe_load(yaml.safe_dump(first.case)))
    assert case.kind == first.case["kind"]


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
