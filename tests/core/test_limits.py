"""The limits table: one limit per request, checked before allocating, raised by its variable."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases
from theory.core.errors import CaseError
from theory.core.validation import LIMITS, check_count, check_estimate, limit
from theory.kinds import parse_case

DOCS = Path(__file__).resolve().parents[2] / "docs" / "cli.md"


def bundled(name: str) -> dict:
    return yaml.safe_load(bundled_cases()[name].read_text(encoding="utf-8"))


def test_every_limit_is_documented_with_its_variable() -> None:
    text = DOCS.read_text(encoding="utf-8")
    for entry in LIMITS.values():
        assert f"| `{entry.name}` |" in text and f"`{entry.env}`" in text, entry.name


@given(st.integers(1, 10**6), st.integers(0, 2 * 10**6))
def test_check_count_refuses_exactly_above_the_limit(bound: int, value: int) -> None:
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("TRACKCERT_MAX_RUNS", str(bound))
        if value <= bound:
            assert check_count("runs", value, "pf.runs") == value
        else:
            with pytest.raises(CaseError) as info:
                check_count("runs", value, "pf.runs")
            message = str(info.value)
            assert info.value.field == "pf.runs"
            assert f"at most {bound:,} runs" in message and "TRACKCERT_MAX_RUNS" in message


@pytest.mark.parametrize("raw", ["", "  "])
def test_an_empty_variable_means_the_default(raw: str, monkeypatch) -> None:
    monkeypatch.setenv("TRACKCERT_MAX_AGENTS", raw)
    assert limit("agents") == LIMITS["agents"].default


@pytest.mark.parametrize("raw", ["0", "-3", "many", "1e6", "9" * 40])
def test_a_bad_variable_is_bad_input(raw: str, monkeypatch) -> None:
    monkeypatch.setenv("TRACKCERT_MAX_AGENTS", raw)
    with pytest.raises(CaseError) as info:
        limit("agents")
    assert info.value.field == "TRACKCERT_MAX_AGENTS" and info.value.file == "<environment>"


def test_estimates_name_their_formula() -> None:
    with pytest.raises(CaseError, match=r"8 B × stuff") as info:
        check_estimate("memory_bytes", 1e30, "tdoa.agents", "8 B × stuff")
    assert info.value.field == "tdoa.agents"


def test_raising_a_limit_admits_the_case(monkeypatch) -> None:
    data = bundled("pf-path3")
    monkeypatch.setenv("TRACKCERT_MAX_RUNS", "49")
    with pytest.raises(CaseError, match="TRACKCERT_MAX_RUNS") as info:
        parse_case(data)
    assert info.value.field == "pf.runs"
    monkeypatch.setenv("TRACKCERT_MAX_RUNS", "50")
    assert parse_case(data).spec.runs == 50


def test_option_and_field_share_the_limit(monkeypatch) -> None:
    """``--runs`` is checked against the same ``runs`` limit as ``pf.runs``."""
    monkeypatch.setenv("TRACKCERT_MAX_RUNS", "60")
    result = CliRunner().invoke(app, ["pf", "pf-path3", "--runs", "61"])
    assert result.exit_code == 2
    assert "field '--runs'" in result.output and "at most 60 runs" in result.output


def test_pf_memory_estimate_blames_what_takes_most(monkeypatch) -> None:
    data = bundled("pf-path3")  # 3 filters, 50 steps, 50 runs
    data["pf"]["particles"] = 10_000
    need = 128 * 3 * 10_000 + 16 * 3 * 51 * 50
    monkeypatch.setenv("TRACKCERT_MAX_MEMORY_BYTES", str(need - 1))
    with pytest.raises(CaseError, match="128 B × 3 filters × 10,000 particles") as info:
        parse_case(data)
    assert info.value.field == "pf.particles"
    monkeypatch.setenv("TRACKCERT_MAX_MEMORY_BYTES", str(need))
    parse_case(data)
    data["pf"].update(particles=100, runs=10_000)  # now the error records dominate
    monkeypatch.setenv("TRACKCERT_MAX_MEMORY_BYTES", str(128 * 3 * 100 + 16 * 3 * 51 * 10_000 - 1))
    with pytest.raises(CaseError) as info:
        parse_case(data)
    assert info.value.field == "pf.runs"


def test_pf_work_counts_exchange_rounds(monkeypatch) -> None:
    data = bundled("pf-path3")
    data["pf"]["exchange_rounds"] = 10**6
    with pytest.raises(CaseError, match="limit 'work'") as info:
        parse_case(data)
    assert info.value.field == "pf.runs"


def test_dense_tdoa_scene_is_refused_by_its_memory_estimate(monkeypatch) -> None:
    """The parser counts what it keeps: per link two indices and a weight, per agent a self-
    weight, 24 B × E + 8 B × N (E = 999,000 links here: every pair, both directions)."""
    agents = [[float(i % 10), float(i // 10 % 10), float(i // 100)] for i in range(1000)]
    data = {
        "name": "dense",
        "kind": "tdoa",
        "tdoa": {"T": 1, "agents": agents, "target": [0.5, 0.5, 0.5], "comm_range": 100},
    }
    needed = 24 * 999_000 + 8 * 1000
    monkeypatch.setenv("TRACKCERT_MAX_MEMORY_BYTES", str(needed - 1))
    with pytest.raises(CaseError, match=r"2\.4e\+07 bytes \(24 B × E \+ 8 B × N") as info:
        parse_case(data)
    assert info.value.field == "tdoa.agents"
    monkeypatch.setenv("TRACKCERT_MAX_MEMORY_BYTES", str(needed))
    spec = parse_case(data).spec
    assert spec.n_agents == 1000 and spec.links[0].count == 999_000
    monkeypatch.setenv("TRACKCERT_MAX_MEMORY_BYTES", str(8 * 1000**2 - 1))
    with pytest.raises(CaseError, match=r"8 B × steps·N² for the dense weights"):
        spec.weights  # noqa: B018  (the dense W, 8 MB, is checked when made)


def test_dkf_dimension_is_checked_before_the_matrices() -> None:
    data = bundled("ch5-example-1-wb")
    n = 200
    data["dkf"]["W"] = [[1.0 if i == j else 0.0 for j in range(n)] for i in range(n)]
    with pytest.raises(CaseError, match="limit 'dkf_dimension'") as info:
        parse_case(data)
    assert info.value.field == "dkf.W"


def test_trackers_are_counted_before_they_are_read() -> None:
    data = bundled("pursuit-table1-n1")
    data["pursuit"]["trackers"] = [None] * 100_000  # refused before any entry is validated
    with pytest.raises(CaseError, match="TRACKCERT_MAX_TRACKERS") as info:
        parse_case(data)
    assert info.value.field == "pursuit.trackers"


@pytest.mark.parametrize(
    ("kind_case", "block", "key"),
    [("sim-ch4-fixed-b0", "tdoa-sim", "steps"), ("pf-path3", "pf", "steps")],
)
def test_steps_fields_use_the_steps_limit(kind_case: str, block: str, key: str) -> None:
    data = copy.deepcopy(bundled(kind_case))
    data[block][key] = LIMITS["steps"].default + 1
    with pytest.raises(CaseError, match="TRACKCERT_MAX_STEPS") as info:
        parse_case(data)
    assert info.value.field == f"{block}.{key}"


def test_sim_consensus_rounds_count_as_work() -> None:
    data = bundled("sim-ch4-fixed-b0")
    data["tdoa-sim"]["T"] = 1.0
    data["tdoa-sim"]["tau"] = 1e-12  # T/tau = 10^12 consensus rounds per ping
    with pytest.raises(CaseError, match="limit 'work'"):
        parse_case(data)
