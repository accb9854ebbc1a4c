"""The public API (``import trackcert``) over plain objects and cases.

No second code path: every function builds the case the loader builds and calls the library
function its command calls, so its ``to_json()`` equals the command's ``--json`` output on the
case file ``to_case()`` writes; and that file reloads to the same result (round trip).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings
from typer.testing import CliRunner

import theory
import trackcert
from theory.cli import app
from theory.core.errors import CaseError
from trackcert.strategies import networks, tdoa_scenes

FIG43_D = np.array([[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]])
TARGET = [17, -5, -15]

EX1 = {  # seed 000 §5.3 Example 1 with W_g
    "A": 2 * np.eye(2),
    "C": [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)],
    "W": np.array([[0.24, 0.76, 0], [0.76, 0.24, 0], [0, 0, 1]]),
    "Q": 0.1 * np.eye(2),
    "R": [0.1 * np.eye(1), 0.1 * np.eye(1), 0.1 * np.eye(2)],
}


def cli_json(*args: str) -> dict:
    result = CliRunner().invoke(app, [*args, "--json"])
    assert result.exit_code in (0, 1, 3), result.output
    return json.loads(result.stdout)


def test_topology_of_arrays_and_a_graph_is_the_command_on_the_saved_case(tmp_path) -> None:
    result = trackcert.topology(FIG43_D, TARGET, nx.path_graph(4), name="fig43-d")
    path = tmp_path / "case.yaml"
    data = result.to_case(path)
    assert data["tdoa"]["edges"] == [[1, 2], [2, 3], [3, 4]]  # 0-based nodes, 1-based ids
    assert result.to_json() == cli_json("topology", str(path))
    assert result.verdict is True and result.exit_code == 0
    assert result.to_json()["agents"] == cli_json("topology", "fig43-case-d")["agents"]


def test_a_graph_an_edge_list_and_a_digraph_of_both_directions_agree() -> None:
    graph = nx.Graph([(0, 1), (2, 3)])
    by_graph = trackcert.topology(FIG43_D, TARGET, graph)
    by_list = trackcert.topology(FIG43_D, TARGET, [(0, 1), (2, 3)])
    by_digraph = trackcert.topology(FIG43_D, TARGET, graph.to_directed(), weights="uniform")
    assert by_graph.to_json() == by_list.to_json()
    assert [a["component"] for a in by_graph.agents] == [1, 1, 2, 2]
    assert by_graph.verdict is False  # two agents cannot localize a 3-D target
    assert [a["id"] for a in by_graph.agents] == [1, 2, 3, 4]
    assert by_digraph.to_case()["tdoa"]["directed"] is True
    assert [a["observable"] for a in by_digraph.agents] == [
        a["observable"] for a in by_graph.agents
    ]


def test_topology_takes_comm_range_and_explicit_weights() -> None:
    W = np.array([[0.5, 0.5, 0, 0], [0.5, 0.25, 0.25, 0], [0, 0.25, 0.5, 0.25], [0, 0, 0.25, 0.75]])
    explicit = trackcert.topology(FIG43_D, TARGET, weights=W)
    assert explicit.to_case()["tdoa"]["weights"] == W.tolist()
    assert explicit.verdict is True
    far = trackcert.topology(FIG43_D, TARGET, comm_range=1.0)
    assert far.verdict is False  # nobody hears anybody


@settings(max_examples=10, deadline=None)
@given(scene=tdoa_scenes(dim=3), hears=networks(min_agents=4, max_agents=4))
def test_any_scene_round_trips_through_its_case_file(tmp_path_factory, scene, hears) -> None:
    agents = scene.agents[:4] if len(scene.agents) >= 4 else scene.agents
    graph = nx.Graph(nx.from_numpy_array(hears[: len(agents), : len(agents)].astype(int)))
    result = trackcert.topology(agents, scene.target, graph)
    path = tmp_path_factory.mktemp("case") / "scene.yaml"
    result.to_case(path)
    again = trackcert.topology(trackcert.load_case(path))
    assert again.to_json() == result.to_json()
    assert again.verdict == result.verdict


def test_dkf_of_matrices_and_of_a_state_space_is_the_command(tmp_path) -> None:
    import control  # 1.5 s of import: only the state-space tests need it

    result = trackcert.dkf(**EX1, self_weight=False)
    system = control.ss(EX1["A"], np.zeros((2, 1)), np.eye(2), 0, dt=True)
    by_system = trackcert.dkf(system, [[0], [1], [0, 1]], EX1["W"], EX1["Q"], 0.1 * np.eye(2),
                              self_weight=False)  # fmt: skip
    assert by_system.to_json() == result.to_json()
    assert result.verdict is True and result.margin > 0
    assert trackcert.check(result.certificate).verdict is True  # the exact witness
    path = tmp_path / "dkf.yaml"
    result.to_case(path)
    assert result.to_json() == cli_json("dkf", str(path), "--no-self-weight")


def test_dkf_refutes_with_an_infeasibility_certificate() -> None:
    W_b = np.array([[0.26, 0.74, 0], [0.74, 0.26, 0], [0, 0, 1]])
    result = trackcert.dkf(**{**EX1, "W": W_b}, self_weight=False)
    assert result.verdict is False and result.exit_code == 1
    assert result.certificate["kind"] == "s-detectability-infeasible"
    assert trackcert.check(result.certificate).verdict is True


def test_dkf_refuses_a_continuous_state_space_and_a_bad_output() -> None:
    import control

    continuous = control.ss(EX1["A"], np.zeros((2, 1)), np.eye(2), 0)
    with pytest.raises(ValueError, match="discrete-time"):
        trackcert.dkf(continuous, [[0], [1], [0, 1]], EX1["W"], EX1["Q"], 0.1 * np.eye(2))
    system = control.ss(EX1["A"], np.zeros((2, 1)), np.eye(2), 0, dt=1.0)
    with pytest.raises(ValueError, match=r"outputs\[2\]: 5"):
        trackcert.dkf(system, [[0], [1], [5]], EX1["W"], EX1["Q"], 0.1 * np.eye(2))


def test_invalid_matrices_name_the_case_field() -> None:
    with pytest.raises(CaseError, match=r"dkf\.W"):
        trackcert.dkf(**{**EX1, "W": np.ones((3, 3))})
    with pytest.raises(CaseError, match=r"tdoa\.target"):
        trackcert.topology(FIG43_D, [1, 2], nx.path_graph(4))


def test_iss_of_keywords_of_a_block_and_of_the_case_agree(tmp_path) -> None:
    bundled = trackcert.iss("pursuit-table1-n3")
    block = bundled.to_case()["pursuit"]
    by_keywords = trackcert.iss(name="pursuit-table1-n3", **block)
    by_block = trackcert.iss(block, name="pursuit-table1-n3")
    assert by_keywords.conditions == bundled.conditions == by_block.conditions
    assert bundled.to_json() == cli_json("iss", "pursuit-table1-n3")
    assert bundled.verdict is True
    failing = trackcert.iss("pursuit-singular-epsilon")
    assert failing.verdict is False
    assert "delta_full_rank" in failing.summary()


def test_tolerance_keywords_go_into_the_case() -> None:
    result = trackcert.iss("pursuit-table1-n1", margin_tol=1e-6)
    assert result.to_case()["tolerances"]["margin_tol"] == 1e-6
    assert result.tolerances["margin_tol"] == 1e-6
    tight = trackcert.topology(FIG43_D, TARGET, nx.path_graph(4), inconclusive_factor=1e12)
    assert tight.verdict is None  # the margin 5e7 is now inside the band
    assert "inconclusive_factor" in tight.to_case()["tolerances"]


def test_simulate_runs_the_scene_as_checked_and_is_the_command(tmp_path) -> None:
    scene = trackcert.topology(FIG43_D, TARGET, nx.path_graph(4), name="fig43-d")
    sim = trackcert.simulate(scene, steps=5, folder=tmp_path / "api", figures=False)
    case = sim.to_case(tmp_path / "sim.yaml")
    assert case["kind"] == "tdoa-sim" and case["tdoa-sim"]["b"] == float("inf")
    assert len(sim.agents) == 4 and sim.verdict is True
    args = ["simulate", str(tmp_path / "sim.yaml"), "--steps", "5", "--workers", "1"]
    cli = cli_json(*args, "--no-figures", "-o", str(tmp_path / "cli"))
    api = json.loads((tmp_path / "api" / "summary.json").read_text())
    assert api == sim.to_json()
    assert {k: v for k, v in cli.items() if k != "files"} == {
        k: v for k, v in api.items() if k != "files"
    }


def test_simulate_writes_figures_into_a_kept_folder_by_default() -> None:
    sim = trackcert.simulate("pursuit-table1-n1", steps=20)
    assert sim.figures and all(f.is_file() for f in sim.figures)
    assert sim.to_json()["steps"] == 20


def test_pf_is_the_command_and_simulate_routes_pf_cases() -> None:
    result = trackcert.pf("pf-path3", runs=2)
    assert result.to_json() == cli_json("pf", "pf-path3", "--runs", "2", "--workers", "1")
    assert trackcert.simulate("pf-path3", runs=2).to_json() == result.to_json()
    assert result.verdict is True and len(result.agents) == 3
    with pytest.raises(CaseError, match="runs"):
        trackcert.pf("pf-path3", runs=0)


def test_certify_check_and_a_tampered_certificate(tmp_path) -> None:
    scene = trackcert.topology(FIG43_D, TARGET, nx.path_graph(4))
    certificate = trackcert.certify(scene)
    assert certificate.verdict is True and {c["kind"] for c in certificate.certificates} == {
        "generic-rank"
    }
    written = certificate.write(tmp_path / "cert.json")
    assert trackcert.check(written).verdict is True
    assert trackcert.check(certificate).to_json()["valid"] is True
    tampered = json.loads(json.dumps(certificate.certificate))
    tampered["certificates"][0]["witness"]["minor"] = "1"  # the minor's value, restated
    verdict = trackcert.check(tampered)
    assert verdict.verdict is False and "INVALID" in verdict.summary()


def test_certify_says_why_there_is_nothing_to_certify() -> None:
    refuted = trackcert.certify("pursuit-singular-epsilon")
    assert refuted.verdict is False and refuted.certificate is None
    assert "fails" in refuted.reason
    with pytest.raises(ValueError, match="nothing to check"):
        trackcert.check(refuted)
    with pytest.raises(ValueError, match="no certificate"):
        refuted.write("unused.json")


def test_a_result_is_plain_in_a_console_and_a_table_in_jupyter() -> None:
    result = trackcert.topology("cone-agents-unobservable")
    assert repr(result).startswith("<TopologyResult cone-agents-unobservable: FAILS")
    page = result._repr_html_()
    assert page.count("<tr>") == 1 + 4  # the header and one row per agent
    assert "FAILS" in page and "rank_tol" in page
    for other in (trackcert.iss("pursuit-table1-n1"), trackcert.check(
        trackcert.certify("fig43-case-d").certificate
    )):  # fmt: skip
        assert "<table>" in other._repr_html_() and "\n" not in repr(other)


def test_every_result_reports_the_protocol() -> None:
    result = trackcert.topology("fig43-case-d")
    assert result.margin == min(a["margin"] for a in result.agents)
    assert result.tolerances["rank_tol"] > 0
    assert "agents" in result.evidence and "case" not in result.evidence
    assert result.expectations and all(e["verdict"] == "met" for e in result.expectations)
    assert result.certificates == () and result.certificate is None


def test_a_case_excludes_plain_objects_and_unknown_keywords_raise() -> None:
    with pytest.raises(TypeError, match="target"):
        trackcert.topology("fig43-case-d", TARGET)
    with pytest.raises(TypeError, match="W"):
        trackcert.dkf("ch5-example-1-wg", W=EX1["W"])
    with pytest.raises(TypeError, match="unknown fields"):
        trackcert.iss(k_gama=3)
    with pytest.raises(TypeError, match="config or fields"):
        trackcert.iss("pursuit-table1-n1", k_gamma=3)
    with pytest.raises(TypeError, match="name"):  # the case has its own
        trackcert.iss("pursuit-table1-n1", name="mine")
    with pytest.raises(ValueError, match="node 4"):
        trackcert.topology(FIG43_D, TARGET, nx.path_graph(8))
    with pytest.raises(ValueError, match="self-loop"):
        trackcert.topology(FIG43_D, TARGET, [(0, 0), (0, 1)])
    with pytest.raises(TypeError, match="expected a case"):
        trackcert.simulate(42)


def test_to_case_needs_the_case_data() -> None:
    from theory.kinds import parse_case

    in_memory = parse_case(trackcert.iss("pursuit-table1-n1").to_case())
    with pytest.raises(ValueError, match="no case file data"):
        trackcert.iss(in_memory).to_case()
    with pytest.raises(ValueError, match="tolerances"):
        trackcert.iss(in_memory, margin_tol=1e-6)


def test_import_is_light_and_versions_agree() -> None:
    heavy = "{'numpy', 'control', 'theory.kinds'}"
    code = f"import sys, trackcert; print(sorted({heavy} & set(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
    from importlib.metadata import version

    assert trackcert.__version__ == theory.__version__ == version("trackcert")
    result = CliRunner().invoke(app, ["--version"])
    assert result.exit_code == 0 and result.stdout.strip() == f"trackcert {theory.__version__}"


def test_pf_refuses_another_kind_before_any_run() -> None:
    with pytest.raises(CaseError, match="field 'kind': expected pf"):
        trackcert.pf("seed002-fig32-split", runs=4)
    result = CliRunner().invoke(app, ["pf", "seed002-fig32-split", "--runs", "4"])
    assert result.exit_code == 2 and "expected pf" in result.output  # was a traceback


def test_simulate_of_a_pf_case_draws_figures_only_when_asked(tmp_path) -> None:
    """``figures=False`` writes ``pf.json`` and no PNG, as ``simulate --no-figures`` does."""
    bare = trackcert.simulate("pf-path3", runs=1, folder=tmp_path / "bare", figures=False)
    assert (tmp_path / "bare" / "pf.json").is_file()
    assert not list((tmp_path / "bare").glob("*.png")) and bare.to_json()["figures"] == []
    drawn = trackcert.simulate("pf-path3", runs=1, folder=tmp_path / "drawn")
    written = sorted(p.name for p in (tmp_path / "drawn").glob("*.png"))
    assert written and written == sorted(Path(f).name for f in drawn.to_json()["figures"])
