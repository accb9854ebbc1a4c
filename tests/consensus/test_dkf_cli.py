"""``trackcert dkf``: DESIGN.md keys, exit codes 0/1/2/3, no traceback on bad input."""

from __future__ import annotations

import json

import pytest
import yaml
from typer.testing import CliRunner

from theory.cli import app

KEYS = {
    "spectral_radius_B",
    "spectral_radius_L",
    "s_detectable",
    "source_components",
    "self_weight_bounds",
    "self_weight_ok",
    "max_self_weight",
}


def run(*args: str):
    return CliRunner().invoke(app, ["dkf", *args])


@pytest.mark.parametrize(
    ("case", "detectable"),
    [("ch5-example-1-wg", True), ("ch5-example-1-wb", False), ("ch5-blind-cycle", False)],
)
def test_exit_codes_and_keys(case, detectable):
    """Each case expects its verdict, so every one exits 0 (docs/cli.md, Exit codes: the
    expectations decide; tests/cli/test_exit_codes.py covers the code without them)."""
    result = run(case, "--json", "--no-self-weight")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert KEYS <= set(data)
    assert data["s_detectable"] is detectable
    for component in data["source_components"]:
        assert set(component) == {"agents", "detectable"}
    assert {c["status"] for c in data["claims"]} <= {
        "verified",
        "refuted",
        "corrected",
        "inconclusive",
    }


def test_counterexample_prints_paper_digits():
    data = json.loads(run("ch5-counterexample", "--json", "--no-self-weight").stdout)
    assert round(data["spectral_radius_B"], 3) == 0.975
    assert round(data["spectral_radius_L"], 3) == 1.026
    assert data["gains_source"] == "case"


def test_bad_input_exits_2_without_traceback(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(
        yaml.safe_dump(
            {
                "name": "bad",
                "kind": "dkf",
                "dkf": {"A": [[1]], "C": [[[1]]], "W": [[1]], "Q": [[-1]], "R": [[[1]]]},
            }
        )
    )
    result = run(str(bad))
    assert result.exit_code == 2
    assert "dkf.Q" in result.output and "Traceback" not in result.output


def _write(tmp_path, block, **extra):
    case = tmp_path / "edge.yaml"
    case.write_text(yaml.safe_dump({"name": "edge", "kind": "dkf", "dkf": block, **extra}))
    return str(case)


def test_unreachable_lmi_margin_leaves_the_exact_route(tmp_path):
    """``lmi_margin = 10`` rules the LMI witness out, yet A = 2 with a blind agent of self-weight
    0.2 (4 · 0.2 < 1) is certified by the projection gains' exact Lyapunov tuple: exit 0."""
    block = {"A": [[2]], "C": [[], [[1]]], "W": [[0.2, 0.8], [0, 1]], "Q": [[1]], "R": [[], [[1]]]}
    result = run(
        _write(tmp_path, block, tolerances={"lmi_margin": 10.0}), "--json", "--no-self-weight"
    )
    assert result.exit_code == 0, result.output
    detail = json.loads(result.stdout)["s_detectability"]
    assert "exact Lyapunov tuple" in detail["certificate_route"]


def test_no_exact_certificate_gives_inconclusive_exit_3(tmp_path):
    """A golden-ratio A (irrational eigenvectors) watched by one agent without sensor is not
    S-detectable, but no rational Farkas witness exists this way: inconclusive, exit 3."""
    block = {"A": [[1.2, 1.2], [1.2, 0]], "C": [[]], "W": [[1]], "Q": [[1, 0], [0, 1]], "R": [[]]}
    result = run(_write(tmp_path, block), "--json", "--no-self-weight")
    assert result.exit_code == 3, result.output
    assert json.loads(result.stdout)["s_detectable"] is None


@pytest.mark.parametrize(
    "case",
    [
        "ch5-example-1-wg",
        "ch5-example-1-wc",
        "ch5-example-1-wb",
        "ch5-example-2-wg",
        "ch5-example-2-wb",
        "ch5-counterexample",
        "ch5-blind-cycle",
    ],
)
def test_bundled_case_expectations_met(case):
    data = json.loads(run(case, "--json", "--no-self-weight").stdout)
    assert data["expectations"], "each bundled ch5 case states what it expects"
    assert all(e["met"] for e in data["expectations"]), data["expectations"]
