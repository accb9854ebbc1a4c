"""Seed 002's PF claims report what they observe for the case's ``expect`` block."""

from __future__ import annotations

import copy
import json
import math
from dataclasses import replace

import numpy as np
import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases
from theory.core.claims import Context
from theory.core.errors import CaseError
from theory.core.expectations import EXPECTATIONS_KEY, evaluate
from theory.core.jsonable import canonical
from theory.kinds import load_case, parse_case
from theory.particle.case import PARAM_NAMES
from theory.particle.experiments import learned_bias
from theory.registry import all_claims, get_claim

runner = CliRunner()
PF_CASES = tuple(name for name, path in bundled_cases().items() if name.startswith("pf-"))


def _small(name: str, runs: int = 4, **expect):
    """The bundled case with ``runs`` Monte Carlo runs (and ``expect`` entries replaced)."""
    case = load_case(name)
    return replace(case, spec=replace(case.spec, runs=runs), expect={**case.expect, **expect})


def _results(case):
    return [r for claim in all_claims() if case.kind in claim.kinds for r in claim.run(case)]


def _node_value(status: str, node: int):
    return {"verified": node, "refuted": False, "inconclusive": None}[status]


@pytest.mark.parametrize("name", [n for n in PF_CASES if load_case(n).kind == "pf"])
def test_every_pf_expectation_is_observed(name: str):
    """No key of a bundled pf case is left ``unchecked`` (the report's exit code 0 needs it)."""
    case = _small(name)
    observed = [
        (r.claim, canonical(r.evidence[EXPECTATIONS_KEY]), r.status)
        for r in _results(case)
        if EXPECTATIONS_KEY in r.evidence
    ]
    verdicts = evaluate(case.name, canonical(case.expect), observed)
    assert [e.key for e in verdicts if e.verdict == "unchecked"] == []


@pytest.mark.parametrize("name", ["pf-topology-b", "pf-learning"])
def test_node_valued_keys_follow_the_claims_status(name: str):
    """``consensus_helps`` / ``learned_beats_gaussian``: the node when verified, false when
    refuted, null when inconclusive; ``converges`` repeats each node's verdict."""
    case = _small(name, runs=3)
    for result in _results(case):
        values = result.evidence.get(EXPECTATIONS_KEY, {})
        for key in ("consensus_helps", "learned_beats_gaussian"):
            if key in values:
                assert values[key] == _node_value(result.status, case.expect[key])
        if "converges" in values:
            verdicts = {"converges": True, "does not converge": False, "inconclusive": None}
            assert values["converges"] == {
                k: verdicts[v] for k, v in result.evidence["found"].items()
            }


def test_learned_pdfs_keys_agree_with_the_bias_test():
    """``learned_pdfs_centre`` holds exactly when ``learned_biased`` lists no parameter."""
    case = _small("pf-learning", runs=3, learned_pdfs_centre=5, learned_biased={5: []})
    (result,) = [r for r in _results(case) if r.claim == "seed002.fig3.6"]
    values = result.evidence[EXPECTATIONS_KEY]
    (node,) = result.evidence["nodes"]
    biased = [p for p in PARAM_NAMES if node["z"][p] > 3.0]
    assert values["learned_biased"] == {5: biased}
    assert values["learned_pdfs_centre"] == (False if biased else 5)
    expected = "refuted" if "mu" in biased else "corrected" if biased else "verified"
    assert result.status == expected


@given(
    st.lists(
        st.tuples(
            st.floats(-math.pi, math.pi),
            st.floats(0, 0.95),
            st.floats(0.5, 5),
            st.floats(0.5, 10),
        ),
        min_size=2,
        max_size=30,
    ),
    st.floats(-3, 3),
)
def test_learned_bias_is_the_offset_of_the_mean(rows, shift):
    """Shifting every fit by ``c`` shifts the bias by ``c`` (μ: as an angle, modulo 2π)."""
    fits = np.array(rows)
    truth = np.array([0.3, 0.7, 2.0, 3.0])
    bias, se = learned_bias(fits.copy(), truth)
    shifted, se_shifted = learned_bias(fits + shift, truth)
    np.testing.assert_allclose(shifted[1:], bias[1:] + shift, atol=1e-9)
    np.testing.assert_allclose(se_shifted, se, atol=1e-9)
    turned = np.angle(np.exp(1j * (shifted[0] - bias[0] - shift)))
    resultant = abs(np.mean(np.exp(1j * fits[:, 0])))
    if resultant > 1e-6:  # the circular mean exists
        assert abs(turned) < 1e-6


def test_learned_bias_wraps_the_turning_angle():
    fits = np.array([[math.pi - 0.1, 0.5, 2, 3], [-math.pi + 0.1, 0.5, 2, 3]])
    bias, _ = learned_bias(fits, np.array([math.pi, 0.5, 2, 3]))
    assert bias[0] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(
    ("key", "value", "field"),
    [
        ("converges", {1: "yes"}, "expect.converges.1"),
        ("converges", {2: True}, "expect.converges.2"),
        ("converges", [True], "expect.converges"),
        ("consensus_helps", 2, "expect.consensus_helps"),
        ("consensus_helps", True, "expect.consensus_helps"),
        ("learned_pdfs_centre", "5", "expect.learned_pdfs_centre"),
        ("learned_biased", {5: ["lambda", "gamma"]}, "expect.learned_biased.5"),
        ("learned_biased", {5: ["sigma"]}, "expect.learned_biased.5"),
        ("learned_biased", {3: []}, "expect.learned_biased.3"),
        ("learned_biased", {}, "expect.learned_biased"),
    ],
)
def test_bad_expectations_are_named(key: str, value: object, field: str):
    data = copy.deepcopy(yaml.safe_load(bundled_cases()["pf-topology-b"].read_text()))
    data["expect"] = {key: value}
    with pytest.raises(CaseError) as error:
        parse_case(data, file="bad.yaml")
    assert error.value.field == field


def test_cli_pf_exit_code_follows_the_expectations(tmp_path):
    """The paper's Fig. 3.6 wording as an expectation: unmet where a parameter is biased."""
    data = yaml.safe_load(bundled_cases()["pf-learning"].read_text())
    data["expect"] = {"learned_pdfs_centre": 5}
    path = tmp_path / "paper.yaml"
    path.write_text(yaml.safe_dump(data))
    result = runner.invoke(app, ["pf", str(path), "--runs", "3", "--json"])
    report = json.loads(result.stdout)
    (entry,) = report["expectations"]
    assert entry["key"] == "learned_pdfs_centre"
    code = {"met": 0, "unmet": 1, "inconclusive": 3}[entry["verdict"]]
    assert result.exit_code == code
    (claim,) = [c for c in report["claims"] if c["id"] == "seed002.fig3.6"]
    assert (entry["verdict"] == "met") == (claim["status"] == "verified")


def test_the_convergence_claim_draws_the_error_curves(tmp_path):
    case = _small("pf-topology-a", runs=2)
    (result,) = get_claim("seed002.sec3.convergence").run(case, Context(figure_dir=tmp_path))
    assert result.figures == (str(tmp_path / "errors.png"),)
    assert (tmp_path / "errors.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
