"""``trackcert topology``: bundled cases meet their ``expect`` blocks, the documented JSON keys,
exit codes 0/1/2/3, and the registered claims."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases
from theory.core.claims import Status
from theory.kinds import load_case
from theory.registry import all_claims, get_claim
from theory.tdoa.observability.trajectory import analyze_trajectory, topology_report

runner = CliRunner()
TDOA_CASES = [name for name, path in bundled_cases().items() if load_case(path).kind == "tdoa"]
AGENT_KEYS = {
    "id",
    "component",
    "rank",
    "observable",
    "heuristic_4_noncoplanar",
    "sigma_min",
    "mirror_ambiguous",
}
TOP_KEYS = {"agents", "network_rank", "network_observable", "network_detectable"}


def invoke(*args: str):
    return runner.invoke(app, ["topology", *args])


@pytest.mark.parametrize("name", TDOA_CASES)
def test_bundled_case_meets_its_expect_block(name: str) -> None:
    case = load_case(name)
    assert case.expect, f"{name} has no expect block"
    report = topology_report(case)
    assert [e.verdict for e in report.expectations] == ["met"] * len(case.expect)
    assert case.source.strip()


@pytest.mark.parametrize("name", TDOA_CASES)
def test_json_has_the_design_keys_and_exit_code_follows_the_verdict(name: str) -> None:
    result = invoke(name, "--json")
    data = json.loads(result.stdout)
    assert TOP_KEYS <= set(data)
    assert all(AGENT_KEYS <= set(agent) for agent in data["agents"])
    assert data["expectations"]["met"]
    assert data["tolerances"]["rank_tol"] > 0
    assert result.exit_code == 0  # every bundled case's expectations are met (command_verdict)
    assert data["exit_code"] == result.exit_code


@pytest.mark.parametrize("name", TDOA_CASES)
def test_json_lists_components_and_reach_sets_once(name: str) -> None:
    """O(N) record: members listed once per component and per reach set, agents point at them;
    the reach set of agent i is R(i), which is its component when the network is undirected."""
    data = json.loads(invoke(name, "--json", "--no-network-rank").stdout)
    members, reach_sets = data["component_members"], data["reach_sets"]
    assert sorted(i for part in members for i in part) == [a["id"] for a in data["agents"]]
    for agent in data["agents"]:
        assert "reach" not in agent
        assert agent["id"] in members[agent["component"] - 1]
        reach = reach_sets[agent["reach_set"] - 1]
        assert agent["id"] in reach and set(reach) <= set(members[agent["component"] - 1])
    if data["information_flow"].startswith("undirected"):
        assert reach_sets == members


def test_network_rank_beyond_the_limits_is_refused_up_front_naming_the_option(
    tmp_path, monkeypatch
) -> None:
    """The estimate counts the eigen-decomposition of the largest component's W (10 n³ for
    n = 8 agents: 5,120) only when the rank is asked for."""
    monkeypatch.setenv("TRACKCERT_MAX_WORK", "5000")
    refused = invoke("seed000-sec44-ring", "--json")
    assert refused.exit_code == 2
    message = " ".join(refused.output.split())
    assert "--no-network-rank" in message and "TRACKCERT_MAX_WORK" in message
    assert "Traceback" not in refused.output
    skipped = invoke("seed000-sec44-ring", "--json", "--no-network-rank")
    assert skipped.exit_code == 0, skipped.output
    assert json.loads(skipped.stdout)["network_method"] == "skipped"
    monkeypatch.setenv("TRACKCERT_MAX_WORK", "5120")
    assert invoke("seed000-sec44-ring", "--json").exit_code == 0


@pytest.mark.parametrize("name", TDOA_CASES)
def test_without_an_expect_block_the_exit_code_follows_the_verdict(name: str, tmp_path) -> None:
    data = yaml.safe_load(bundled_cases()[name].read_text())
    data.pop("expect")
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump(data))
    result = invoke(str(path), "--json")
    trajectory = analyze_trajectory(load_case(name).spec)
    assert result.exit_code == (0 if trajectory.first_failure_step is None else 1), result.output
    assert json.loads(result.stdout)["exit_code"] == result.exit_code


def test_human_output_has_a_table_and_a_verdict_line() -> None:
    result = invoke("topology-coplanar-mirror")
    assert result.exit_code == 0
    assert "TDOA observability per agent" in result.stdout
    assert "HOLDS" in result.stdout
    assert "mirror image" in result.stdout
    assert "rank_tol" in result.stdout


def write_case(tmp_path: Path, block: dict, **header) -> str:
    data = {"name": "tmp", "source": "test", "kind": "tdoa", "tdoa": block, **header}
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump(data))
    return str(path)


BASE = {
    "T": 1.0,
    "target": [17, -5, -15],
    "agents": [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]],
    "edges": [[1, 2], [2, 3], [3, 4]],
}


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"agents": [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4]]}, "tdoa.agents"),
        ({"edges": [[1, 5]]}, "tdoa.edges[1]"),
        ({"target": [-7, 3, 5]}, "tdoa.target"),
        ({"weights": [[1, 0, 0, 0]] * 4}, "tdoa.weights"),
        ({"colour": "red"}, "tdoa.colour"),
    ],
)
def test_bad_input_exits_2_with_a_message_and_no_traceback(tmp_path, change, field) -> None:
    result = invoke(write_case(tmp_path, {**BASE, **change}))
    assert result.exit_code == 2
    assert field in result.stderr
    assert "case.yaml" in result.stderr
    assert "Traceback" not in result.stderr + result.stdout
    assert result.stdout == ""


@pytest.mark.parametrize(
    "option", [["--rank-tol", "0"], ["--rank-tol", "2"], ["--inconclusive-factor", "0.5"]]
)
def test_bad_tolerance_options_exit_2(option) -> None:
    result = invoke("fig43-case-d", *option)
    assert result.exit_code == 2
    assert option[0] in result.stderr and "Traceback" not in result.stderr


def test_missing_case_and_malformed_yaml_exit_2(tmp_path) -> None:
    assert invoke("no-such-case").exit_code == 2
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: [unclosed\n")
    result = invoke(str(bad))
    assert result.exit_code == 2 and "valid YAML" in result.stderr


def test_singular_value_inside_tolerance_exits_3(tmp_path) -> None:
    """The cone case nudged off the cone by 1e-8: σ_min ≈ 1e-9·σ_max, inside the tolerance."""
    block = {
        "T": 1.0,
        "target": [1, 2, -3],
        "agents": [[4, 2, 1], [1, 8, 5], [-8, 2, 9], [1, -10, 13 + 1e-8]],
        "edges": [[1, 2], [2, 3], [3, 4]],
    }
    result = invoke(write_case(tmp_path, block), "--json")
    assert result.exit_code == 3
    data = json.loads(result.stdout)
    assert data["verdict"].startswith("INCONCLUSIVE")
    assert not data["conclusive"] and data["inconclusive"]


def test_case_tolerances_are_used_and_cli_overrides_them(tmp_path) -> None:
    path = write_case(tmp_path, BASE, tolerances={"rank_tol": 1e-6})
    assert json.loads(invoke(path, "--json").stdout)["tolerances"]["rank_tol"] == 1e-6
    override = json.loads(invoke(path, "--json", "--rank-tol", "1e-8").stdout)
    assert override["tolerances"]["rank_tol"] == 1e-8


def test_time_varying_json_reports_every_step() -> None:
    data = json.loads(invoke("topology-distance-rule-split", "--json").stdout)
    block = data["time_varying"]
    assert len(block["steps"]) == load_case("topology-distance-rule-split").spec.steps
    assert block["first_failure_step"] == 10
    assert block["steps"][9]["unobservable_agents"] == list(range(1, 9))


def test_registered_claims_run_on_every_tdoa_case() -> None:
    ids = {c.id for c in all_claims()}
    assert {"seed000.thm4.2.3.heuristic", "seed000.thm4.2.3.network", "seed000.cor4.2.4"} <= ids
    for name in TDOA_CASES:
        case = load_case(name)
        for claim_id in ("seed000.thm4.2.3.heuristic", "seed000.thm4.2.3.network"):
            (result,) = get_claim(claim_id).run(case)
            assert result.status in set(Status) and result.case == name
            json.dumps(result.to_json())


def test_claim_statuses_follow_the_exact_verdicts() -> None:
    heuristic = get_claim("seed000.thm4.2.3.heuristic")
    network = get_claim("seed000.thm4.2.3.network")
    cor = get_claim("seed000.cor4.2.4")
    assert heuristic.run(load_case("fig43-case-d"))[0].status == "verified"
    assert heuristic.run(load_case("topology-coplanar-mirror"))[0].status == "corrected"
    assert heuristic.run(load_case("topology-cone-unobservable"))[0].status == "corrected"
    assert network.run(load_case("fig43-case-a"))[0].status == "corrected"
    assert network.run(load_case("topology-coplanar-mirror"))[0].status == "refuted"
    assert cor.run(load_case("fig43-case-d")) == []
    (result,) = cor.run(load_case("topology-distance-rule-21"))
    assert result.evidence["hypothesis_steps_where_some_agent_fails"] == []
