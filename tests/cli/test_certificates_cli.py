"""``trackcert certify`` and ``trackcert check``: files, exit codes, JSON keys (DESIGN.md)."""

from __future__ import annotations

import json
from pathlib import Path

import yaml
from typer.testing import CliRunner

from theory.cli import app

runner = CliRunner()
DATA = Path(__file__).resolve().parents[1] / "data" / "certificates"


def test_certify_then_check(tmp_path: Path) -> None:
    out = tmp_path / "fig.json"
    result = runner.invoke(app, ["certify", "fig43-case-d", "-o", str(out)])
    assert result.exit_code == 0, result.output
    document = json.loads(out.read_text(encoding="utf-8"))
    assert document["format"] == "trackcert-certificate/1"
    assert document["kind"] == "bundle" and document["case"] == "fig43-case-d"
    assert {c["kind"] for c in document["certificates"]} == {"generic-rank"}
    checked = runner.invoke(app, ["check", str(out), "--json"])
    assert checked.exit_code == 0
    report = json.loads(checked.stdout)
    assert report["valid"] is True
    assert all(set(c) == {"name", "valid", "detail"} for c in report["checks"])
    assert not list(tmp_path.glob(".fig.json.*"))


def test_certify_json_prints_the_certificate() -> None:
    result = runner.invoke(app, ["certify", "fig43-case-d", "--json", "--seed", "3"])
    assert result.exit_code == 0
    document = json.loads(result.stdout)
    assert document["certificates"][0]["produced_by"]["seed"] == 3


def test_check_exit_codes_follow_the_checker() -> None:
    for folder, code in (("valid", 0), ("invalid", 1), ("malformed", 2)):
        for path in sorted((DATA / folder).glob("*.json"))[:2]:
            assert runner.invoke(app, ["check", str(path)]).exit_code == code, path


def test_nothing_is_written_when_no_certificate_can_be_made(tmp_path: Path) -> None:
    case = {
        "name": "mute",
        "kind": "tdoa",
        "tdoa": {
            "T": 1.0,
            "agents": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
            "target": [5, 5, 5],
            "edges": [],
        },
    }
    path = tmp_path / "mute.yaml"
    path.write_text(yaml.safe_dump(case), encoding="utf-8")
    out = tmp_path / "out.json"
    result = runner.invoke(app, ["certify", str(path), "-o", str(out)])
    assert result.exit_code == 3
    assert "no TDOA rows" in result.output
    assert not out.exists()


def test_unwritable_output_is_bad_input(tmp_path: Path) -> None:
    result = runner.invoke(app, ["certify", "fig43-case-d", "-o", str(tmp_path / "no" / "x.json")])
    assert result.exit_code == 2
    assert "--output" in result.output
