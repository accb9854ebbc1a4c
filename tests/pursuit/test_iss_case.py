"""``kind: pursuit`` case files and ``trackcert iss`` (exit codes, JSON keys), seed 003."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases
from theory.core.errors import CaseError
from theory.kinds import load_case, parse_case

runner = CliRunner()

PURSUIT_CASES = sorted(name for name in bundled_cases() if name.startswith("pursuit-"))
HOLDING = ["pursuit-table1-n1", "pursuit-table1-n3", "pursuit-table2-n1", "pursuit-table2-n3"]
FAILING = ["pursuit-not-strongly-connected", "pursuit-singular-epsilon"]


def _data(name: str) -> dict:
    return yaml.safe_load(Path(bundled_cases()[name]).read_text(encoding="utf-8"))


def test_bundled_pursuit_cases_cover_tables_and_failures() -> None:
    assert set(HOLDING + FAILING) <= set(PURSUIT_CASES)


@pytest.mark.parametrize("name", PURSUIT_CASES)
def test_bundled_cases_load_and_cite_a_source(name: str) -> None:
    case = load_case(name)
    assert case.kind == "pursuit"
    assert "seed 003" in case.source


def test_table1_ring_is_the_stated_directed_ring() -> None:
    spec = load_case("pursuit-table1-n3").spec
    # 1 <- 2 <- 3 <- 1: tracker 1 hears 2, 2 hears 3, 3 hears 1 (a_ij = 1 iff i hears j)
    expected = np.array([[0, 1, 0], [0, 0, 1], [1, 0, 0]], dtype=bool)
    assert np.array_equal(spec.adjacency, expected)
    assert np.array_equal(spec.laplacian, np.eye(3, dtype=int) - expected.astype(int))
    assert np.allclose(spec.dekf.weights.sum(axis=1), 1.0)


def test_target_motion_matches_table1() -> None:
    target = load_case("pursuit-table1-n1").spec.target
    t = 37.0
    assert np.allclose(target.position(t), [20 * np.sin(0.01 * t + np.pi), 0.3 * t])
    assert np.allclose(target.velocity_at(t), [0.2 * np.cos(0.01 * t + np.pi), 0.3])


BAD_EDITS = [
    (("dim",), 4, "pursuit.dim"),
    (("controller",), "III", "pursuit.controller"),
    (("epsilon",), [1.0], "pursuit.epsilon"),
    (("K_p",), [0.4, -0.2], "pursuit.K_p"),
    (("K_p",), [[1, 2], [2, 1]], "pursuit.K_p"),
    (("k_gamma",), 0, "pursuit.k_gamma"),
    (("k_c",), -1, "pursuit.k_c"),
    (("edges",), [[1, 1]], "pursuit.edges[1]"),
    (("edges",), [[1, 4]], "pursuit.edges[1]"),
    (("edges",), [[2, 1], [2, 1]], "pursuit.edges"),
    (("trackers", 0, "r_x"), 0, "pursuit.trackers[1].r_x"),
    (("trackers", 0, "r_z"), 5, "pursuit.trackers[1]"),
    (("omega_bar",), "fast", "pursuit.omega_bar"),
    (("dekf", "weights"), [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "pursuit.dekf.weights"),
    (("dekf", "Q"), [[1, 0], [0, 1]], "pursuit.dekf.Q"),
    (("dekf", "Ts"), -2, "pursuit.dekf.Ts"),
    (("target", "speed"), [0, 1], "pursuit.target"),
]


@pytest.mark.parametrize(("path", "value", "field"), BAD_EDITS)
def test_bad_input_names_the_field(path: tuple, value: object, field: str) -> None:
    data = copy.deepcopy(_data("pursuit-table1-n3"))
    block = data["pursuit"]
    for key in path[:-1]:
        block = block[key]
    block[path[-1]] = value
    with pytest.raises(CaseError) as error:
        parse_case(data)
    assert error.value.field.startswith(field)


def test_three_d_needs_c_not_one() -> None:
    data = copy.deepcopy(_data("pursuit-table2-n1"))
    data["pursuit"]["trackers"][0]["c"] = 1
    with pytest.raises(CaseError, match="other than 0 and 1"):
        parse_case(data)


def test_missing_k_c_with_several_trackers() -> None:
    data = copy.deepcopy(_data("pursuit-table1-n3"))
    del data["pursuit"]["k_c"]
    with pytest.raises(CaseError, match="k_c"):
        parse_case(data)


@pytest.mark.parametrize("name", HOLDING)
def test_iss_holds_on_table_cases(name: str) -> None:
    result = runner.invoke(app, ["iss", name, "--json"])
    assert result.exit_code == 0, result.output
    record = json.loads(result.stdout)
    for key in ("controller", "lyapunov", "decay_rate", "iss_gain", "conditions"):
        assert key in record
    assert record["controller"] == "II"
    assert all(c["status"] in ("holds", "not-applicable") for c in record["conditions"])
    assert record["decay_rate"]["pursuit"] == pytest.approx(0.2)
    assert record["expectations"] and all(e["met"] for e in record["expectations"])
    # simulation_bounded is the simulation's to observe (seed003.thm2.sim-trajectories), not iss's
    assert "simulation_bounded" in load_case(name).expect
    assert "simulation_bounded" not in {e["key"] for e in record["expectations"]}


@pytest.mark.parametrize(
    ("name", "condition"),
    [
        ("pursuit-not-strongly-connected", "graph_strongly_connected"),
        ("pursuit-singular-epsilon", "delta_full_rank"),
    ],
)
def test_iss_fails_with_exit_1(name: str, condition: str, tmp_path: Path) -> None:
    """The condition fails: exit 1 without the case's ``expect`` block, 0 with it (it expects
    exactly that; docs/cli.md, Exit codes)."""
    result = runner.invoke(app, ["iss", name, "--json"])
    assert result.exit_code == 0
    data = copy.deepcopy(_data(name))
    data.pop("expect")
    bare = tmp_path / "bare.yaml"
    bare.write_text(yaml.safe_dump(data))
    assert runner.invoke(app, ["iss", str(bare)]).exit_code == 1
    record = json.loads(result.stdout)
    statuses = {c["name"]: c["status"] for c in record["conditions"]}
    assert statuses[condition] == "fails"
    expected = load_case(name).expect
    assert record["holds"] is expected["iss"]
    assert all(e["met"] for e in record["expectations"])


def test_iss_inconclusive_margin_exits_3(tmp_path: Path) -> None:
    data = copy.deepcopy(_data("pursuit-table1-n1"))
    data["pursuit"]["epsilon"] = [1e-12, 0.5]
    path = tmp_path / "tiny.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    result = runner.invoke(app, ["iss", str(path), "--json", "--margin-tol", "1e-9"])
    assert result.exit_code == 3
    record = json.loads(result.stdout)
    delta = next(c for c in record["conditions"] if c["name"] == "delta_full_rank")
    assert delta["status"] == "inconclusive" and delta["tolerance"] == 1e-9


def test_iss_bad_input_exit_2(tmp_path: Path) -> None:
    assert runner.invoke(app, ["iss", "fig43-case-d"]).exit_code == 2
    path = tmp_path / "bad.yaml"
    path.write_text("name: x\nkind: pursuit\npursuit: {dim: 2}\n", encoding="utf-8")
    result = runner.invoke(app, ["iss", str(path)])
    assert result.exit_code == 2
    assert "pursuit.controller" in result.output
    assert "Traceback" not in result.output


def test_table_text_output() -> None:
    result = runner.invoke(app, ["iss", "pursuit-table2-n3"])
    assert result.exit_code == 0
    assert "seed003.thm2" in result.stdout and "holds" in result.stdout


def test_spanning_tree_graph_is_corrected_not_refuted() -> None:
    """Lemma 3 needs less than strong connectivity: a rooted tree 1 → 2 → 3 still coordinates."""
    from theory.registry import get_claim

    data = copy.deepcopy(_data("pursuit-table1-n3"))
    data["pursuit"]["edges"] = [[1, 2], [2, 3]]
    del data["pursuit"]["dekf"]
    case = parse_case(data)
    (result,) = get_claim("seed003.lem3").run(case)
    assert result.status == "corrected"
    assert result.evidence["zero_eigenvalue_simple"] and not result.evidence["strongly_connected"]
    assert result.evidence["spectral_rate"] > 0
    no_tree = load_case("pursuit-not-strongly-connected")
    (result,) = get_claim("seed003.lem3").run(no_tree)
    assert result.status == "refuted"


def test_table_measurement_weights_contradict_the_text() -> None:
    """Erratum: the text sets V = 1/σ; Table I has σ = 0.5, V = 10; Table II prints V = σ = 1."""
    for name, expected_v in (("pursuit-table1-n1", 10.0), ("pursuit-table2-n1", 1.0)):
        dekf = load_case(name).spec.dekf
        assert dekf.sigma == 0.5 and dekf.V == expected_v
        assert dekf.V not in (1 / dekf.sigma, 1 / dekf.sigma**2, dekf.sigma)
