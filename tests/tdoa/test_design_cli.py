"""``trackcert design margin | placement | redundancy`` on tdoa: the DESIGN.md JSON keys, what is
printed for an engineer, exit codes 0/1/2/3, and certificates that ``trackcert check`` accepts."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from theory.cli import COMMANDS, app

runner = CliRunner()


def design(*args: str):
    return runner.invoke(app, ["design", *args])


def test_design_is_a_listed_command_group() -> None:
    assert "design" in COMMANDS
    result = design("--help")
    assert result.exit_code == 0
    for sub in ("margin", "placement", "redundancy"):
        assert sub in result.output


def test_margin_json_keys_and_certificates_check(tmp_path: Path) -> None:
    result = design("margin", "fig43-case-a", "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert {"radius", "exact", "witness_displacement", "per_agent"} <= set(data)
    assert {"id", "radius"} <= set(data["per_agent"][0])
    assert 0 < data["radius"] <= data["upper_bound"]
    assert data["witness_displacement"]["mechanism"] == "cone"
    path = tmp_path / "margin.json"
    cert = {"format": "trackcert-certificate/1", "kind": "bundle"}
    cert["certificates"] = data["certificates"]
    path.write_text(json.dumps(cert), encoding="utf-8")
    assert runner.invoke(app, ["check", str(path)]).exit_code == 0


def test_margin_prints_the_radius_per_agent() -> None:
    result = design("margin", "seed000-sec44-ring")
    assert result.exit_code == 0
    assert "certified ρ = 0.5185" in result.output
    assert "witness ρ̄" in result.output


def test_degenerate_margin_exits_1() -> None:
    result = design("margin", "cone-agents-unobservable", "--json")
    assert result.exit_code == 1
    data = json.loads(result.output)
    assert (data["radius"], data["exact"], data["upper_bound"]) == (0.0, True, 0.0)


@pytest.mark.parametrize(
    ("args", "code", "k"),
    [
        (("seed000-sec44-ring",), 0, 2),
        (("seed000-sec44-ring", "--agents"), 0, 2),
        (("cone-agents-unobservable",), 1, 0),
    ],
)
def test_redundancy(args: tuple[str, ...], code: int, k: int) -> None:
    result = design("redundancy", *args, "--json")
    assert result.exit_code == code, result.output
    data = json.loads(result.output)
    assert {"k", "witness", "certified_below"} <= set(data)
    assert data["k"] == data["certified_below"] == k


def test_placement_json_keys() -> None:
    result = design("placement", "6", "--comm-range", "21", "--rho0", "1", "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert {"agents", "crb_trace", "radius", "compared"} <= set(data)
    assert {"formation", "crb_trace"} <= set(data["compared"][0])
    assert len(data["agents"]) == 6 and data["radius"] >= 1


@pytest.mark.parametrize(
    ("args", "code"),
    [
        (("margin", "ch5-example-1-wg"), 2),  # a dkf case: no displacement margin
        (("placement", "3", "--comm-range", "21"), 2),  # fewer than d + 1 agents
        (("placement", "8", "--comm-range", "21", "--rho0", "5"), 3),  # none found
        (("redundancy", "pursuit-table1-n1"), 2),
    ],
)
def test_exit_codes(args: tuple[str, ...], code: int) -> None:
    result = design(*args)
    assert result.exit_code == code, result.output
