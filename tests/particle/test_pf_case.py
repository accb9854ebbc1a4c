"""``kind: pf`` case files, the Monte Carlo runner and ``trackcert pf``."""

from __future__ import annotations

import copy
import json
import subprocess
import sys

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases
from theory.core.errors import CaseError
from theory.kinds import load_case, parse_case
from theory.particle.experiments import (
    compare_variants,
    convergence_verdicts,
    monte_carlo,
    node_summary,
)

runner = CliRunner()
PF_CASES = ("pf-topology-a", "pf-topology-b", "pf-learning")


def _data(name: str = "pf-topology-b") -> dict:
    return yaml.safe_load(bundled_cases()[name].read_text())


@pytest.mark.parametrize("name", PF_CASES)
def test_bundled_pf_cases_load_with_the_thesis_settings(name: str):
    spec = load_case(name).spec
    assert spec.config.particles == 100 and spec.config.share == 10
    assert spec.steps == 100 and spec.runs == (100 if name == "pf-learning" else 50)
    assert spec.network.filters == (0, 3, 4)
    assert np.allclose(spec.network.nodes.mean(0), 0.0, atol=0.01)  # Fig. 3.5: centre at origin


def test_topologies_match_figs_3_2_and_3_3():
    a = load_case("pf-topology-a").spec.network.hears
    b = load_case("pf-topology-b").spec.network.hears
    neighbours = {i + 1: set(np.flatnonzero(a[i]) + 1) for i in (0, 3, 4)}
    assert neighbours == {1: {2, 3}, 4: {5}, 5: {4}}
    neighbours = {i + 1: set(np.flatnonzero(b[i]) + 1) for i in (0, 3, 4)}
    assert neighbours == {1: {2, 3, 4}, 4: {1, 5}, 5: {4}}


@pytest.mark.parametrize(
    ("path", "value", "field"),
    [
        (("pf", "share"), 50, "pf.share"),
        (("pf", "model"), "kalman", "pf.model"),
        (("pf", "target", "gamma"), 1.0, "pf.target.gamma"),
        (("pf", "filters"), [1, 1], "pf.filters"),
        (("pf", "edges"), [[1, 9]], "pf.edges[1]"),
        (("pf", "workspace"), [[5, 1], [0, 1]], "pf.workspace"),
        (("pf", "exchange_weights"), "mean", "pf.exchange_weights"),
        (("pf", "learning", "gamma_max"), 1.5, "pf.learning.gamma_max"),
        (("pf", "particle"), 3, "pf.particle"),
    ],
)
def test_bad_fields_are_named(path: tuple, value: object, field: str):
    data = copy.deepcopy(_data())
    block = data
    for key in path[:-1]:
        block = block.setdefault(key, {})
    block[path[-1]] = value
    with pytest.raises(CaseError) as error:
        parse_case(data, file="bad.yaml")
    assert error.value.field == field and error.value.file == "bad.yaml"


def _small(name: str, runs: int = 4):
    spec = load_case(name).spec
    return monte_carlo(spec, runs=runs, seed=5), spec


def test_monte_carlo_is_reproducible_and_pairs_paths_across_variants():
    (one, spec), (two, _) = _small("pf-topology-b"), _small("pf-topology-b")
    np.testing.assert_array_equal(one.errors, two.errors)
    first = monte_carlo(spec, runs=1, seed=5, snapshot_steps=(0, 3))
    np.testing.assert_array_equal(first.errors[0], one.errors[0])  # figures show run 0
    assert sorted(first.snapshots) == [0, 3] and first.snapshots[3].shape == (3, 100, 3)
    off = monte_carlo(spec, runs=4, seed=5, share=0)
    np.testing.assert_array_equal(one.paths, off.paths)
    assert not np.array_equal(one.errors, off.errors)
    low, high = spec.workspace[:, 0], spec.workspace[:, 1]
    assert np.all((one.paths[:, 0] >= low) & (one.paths[:, 0] <= high))


def test_summary_and_verdicts_follow_their_definitions():
    mc, spec = _small("pf-topology-a", runs=6)
    rows = node_summary(mc, spec)
    assert [r["id"] for r in rows] == [1, 4, 5]
    assert [r["measurements"] for r in rows] == [2, 1, 1]
    tail = mc.errors[:, 50:].mean(1)
    assert rows[0]["tail_error_median"] == pytest.approx(np.median(tail[:, 0]))
    verdicts = convergence_verdicts(
        mc.tail_errors, spec.network.filters, converge_tol=1e9, diverge_tol=2e9
    )
    assert set(verdicts.values()) == {"converges"}
    verdicts = convergence_verdicts(
        mc.tail_errors, spec.network.filters, converge_tol=0.0, diverge_tol=1e-12
    )
    assert set(verdicts.values()) == {"does not converge"}


def test_compare_variants_is_a_paired_z_test():
    mc, _ = _small("pf-topology-b")
    same = compare_variants(mc, mc, 1, improvement_tol=3.0)
    assert same.mean_difference == 0.0 and same.lower is False
    assert same.evidence()["verdict"] == "not lower"
    with pytest.raises(ValueError, match="metric"):
        compare_variants(mc, mc, 1, improvement_tol=3.0, metric="final")


def test_cli_pf_json_and_files(tmp_path):
    result = runner.invoke(
        app, ["pf", "pf-topology-b", "--runs", "3", "--seed", "1", "--json", "-o", str(tmp_path)]
    )
    report = json.loads(result.stdout)
    verdicts = {e["verdict"] for e in report["expectations"]}
    assert [e["key"] for e in report["expectations"]] == ["converges", "consensus_helps"]
    expected_code = 1 if "unmet" in verdicts else 3 if verdicts - {"met"} else 0
    assert result.exit_code == expected_code
    assert {c["id"] for c in report["claims"]} == {
        "seed002.sec3.convergence",
        "seed002.sec3.consensus",
        "seed002.sec3.measurements",
    }
    assert report["runs"] == 3 and report["seed"] == 1
    for agent in report["agents"]:
        assert {"id", "final_localization_error", "mean_localization_error"} <= set(agent)
    assert json.loads((tmp_path / "pf.json").read_text())["agents"] == report["agents"]
    for figure in report["figures"]:
        assert (tmp_path / figure.split("/")[-1]).stat().st_size > 0
    assert len(report["figures"]) == 2


def test_cli_pf_learning_writes_learned_pdfs(tmp_path):
    result = runner.invoke(app, ["pf", "pf-learning", "--runs", "2", "-o", str(tmp_path)])
    assert result.exit_code in (0, 1, 3), result.stdout
    assert (tmp_path / "pf-learning-learned-pdfs.png").is_file()
    assert "seed002.sec3.learning" in result.stdout


def test_cli_pf_refuses_other_kinds_and_bad_files(tmp_path):
    result = runner.invoke(app, ["pf", "fig43-case-d"])
    assert result.exit_code == 2 and "kind" in result.stderr
    bad = tmp_path / "bad.yaml"
    data = _data()
    data["pf"]["share"] = 60
    bad.write_text(yaml.safe_dump(data))
    result = runner.invoke(app, ["pf", str(bad), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and "pf.share" in result.stderr
    assert "Traceback" not in result.stderr and not (tmp_path / "out").exists()


def test_summary_table_has_a_row_per_variant_and_node():
    from theory.particle.experiments import VARIANTS, summary_table

    table = summary_table(runs=1, seed=3).splitlines()
    expected = sum(
        len(variants) * len(load_case(name).spec.network.filters)
        for name, variants in VARIANTS.items()
    )
    assert len(table) == 2 + expected
    assert all(line.count("|") == 10 for line in table)


def test_loading_a_pf_case_imports_neither_the_filter_nor_scipy_optimize():
    """The case module holds the scenario's data, so validating a case stays cheap."""
    script = (
        "import json, sys\n"
        "from theory.kinds import load_case\n"
        "load_case('pf-topology-b')\n"
        "heavy = ['theory.particle.filter', 'theory.particle.dcrw', 'scipy.optimize',"
        " 'scipy.stats']\n"
        "print(json.dumps([m for m in heavy if m in sys.modules]))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    )
    assert json.loads(done.stdout.strip().splitlines()[-1]) == []
