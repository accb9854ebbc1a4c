"""``trackcert falsify``: wrong paper wordings are refuted within the default budget, corrected
wordings survive it, and counterexamples come back as ready-to-run case files."""

from __future__ import annotations

import json

import pytest
import yaml
from typer.testing import CliRunner

from theory.case_file import parse_case
from theory.cli import app
from theory.falsifiable_dkf import jointly_detectable, strongly_connected
from theory.falsifiable_iss import coordination_terms
from theory.falsifiable_tdoa import component_rank, scene_case
from theory.falsify import DEFAULT_EXAMPLES, all_properties, falsify
from theory.strategies import TdoaScene

runner = CliRunner()
PROPERTIES = all_properties()


@pytest.mark.parametrize("prop", PROPERTIES, ids=[p.id for p in PROPERTIES])
def test_default_budget_separates_wrong_from_corrected(prop) -> None:
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
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


def test_coordination_counterexample_reloads() -> None:
    prop = next(p for p in WRONG if p.id == "seed003.eq74/paper")
    result = falsify(prop, examples=DEFAULT_EXAMPLES, seed=0)
    case = parse_case(result.case)
    spec = case.spec
    example = result.counterexample
    assert len(spec.trackers) == example.laplacian.shape[0]
    terms = coordination_terms(example)
    assert terms["v_dot"] > terms["paper"] and terms["v_dot"] <= terms["corrected"] + 1e-9


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
