"""One exit-code rule for every command (theory.core.verdicts.command_verdict, docs/cli.md):
when the command judged expectations of the case (the keys of its ``expect`` block it
observes), their verdict decides — all met 0, one unmet 1, otherwise 3; without any, the
property's verdict decides (0 holds, 1 fails, 3 inconclusive; 0 for a command that decides no
property of its own). Each command is run on one case three ways: as bundled, without its
``expect`` block, and with an expectation it observes turned false."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases

runner = CliRunner()


def _case(folder: Path, name: str, expect: dict | None) -> str:
    data = yaml.safe_load(bundled_cases()[name].read_text())
    data.pop("expect", None)
    if expect is not None:
        data["expect"] = expect
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return str(path)


# command, case, options, the property's exit code, an expectation it observes (met)
COMMANDS = [
    ("topology", "cone-agents-unobservable", (), 1, {"network_observable": False}),
    ("dkf", "ch5-example-1-wb", ("--no-self-weight",), 1, {"s_detectable": False}),
    ("dkf", "ch5-example-1-wg", ("--no-self-weight",), 0, {"s_detectable": True}),
    ("iss", "pursuit-singular-epsilon", (), 1, {"delta_full_rank": False}),
    ("iss", "pursuit-table1-n1", (), 0, {"iss": True}),
    ("simulate", "pursuit-table1-n1", ("--steps", "50", "--workers", "1", "-o", "{out}"), 0,
     {"simulation_bounded": True}),
    ("pf", "pf-path3", ("--runs", "4", "--workers", "1"), 0,
     {"converges": {1: True, 2: True, 3: True}}),
    ("report", "fig43-case-d", ("--only", "case.expect.tdoa", "--workers", "1", "-o", "{out}"), 0,
     {"network_observable": True}),
]  # fmt: skip


def _flip(expect: dict) -> dict:
    """Every boolean of ``expect`` negated (in nested mappings too)."""
    return {k: _flip(v) if isinstance(v, dict) else not v for k, v in expect.items()}


@pytest.mark.parametrize(
    ("command", "name", "options", "holds", "expect"),
    COMMANDS,
    ids=[f"{c[0]}-{c[1]}" for c in COMMANDS],
)
def test_the_expectations_decide_else_the_property(
    tmp_path, command, name, options, holds, expect
) -> None:
    def code(expected: dict | None, label: str) -> int:
        case = _case(tmp_path / label, name, expected)
        args = [a.replace("{out}", str(tmp_path / label / "out")) for a in options]
        done = runner.invoke(app, [command, case, *args])
        assert "Traceback" not in done.output
        return done.exit_code

    for label in ("none", "met", "unmet"):
        (tmp_path / label).mkdir()
    assert code(None, "none") == holds
    assert code(expect, "met") == 0
    assert code(_flip(expect), "unmet") == 1


def test_the_human_output_says_when_the_expectations_decided(tmp_path) -> None:
    done = runner.invoke(app, ["topology", "cone-agents-unobservable"])
    assert done.exit_code == 0
    assert "FAILS" in done.stdout
    assert "exit code 0: the case's expect block decides it" in done.stdout


def test_commands_without_a_case_decide_their_property() -> None:
    assert runner.invoke(app, ["generic", "--rows", "3"]).exit_code == 0
    assert runner.invoke(app, ["cases", "--names"]).exit_code == 0


@pytest.mark.parametrize("expect", [None, {"simulation_bounded": False}])
def test_sweep_judges_its_points_not_the_expect_block(tmp_path, expect) -> None:
    case = _case(tmp_path, "pursuit-table1-n1", expect)
    args = ["sweep", case, "--param", "k_gamma=100", "--steps", "20", "--workers", "1"]
    done = runner.invoke(app, [*args, "-o", str(tmp_path / "out")])
    assert done.exit_code == 0, done.output


def test_certify_judges_no_expectation_so_its_property_decides(tmp_path) -> None:
    """ch5-example-1-wb expects ``s_detectable: false`` (met), but certify observes nothing of
    the block: the S-detectability it is asked to certify fails, exit 1."""
    done = runner.invoke(app, ["certify", "ch5-example-1-wb", "-o", str(tmp_path / "c.json")])
    assert done.exit_code == 1 and done.stderr.startswith("does not hold:")
    assert not (tmp_path / "c.json").exists()


def test_epsilon_1_zero_is_the_same_verdict_from_iss_certify_and_simulate(tmp_path) -> None:
    """ε₁ = 0: a valid case on which Remark 6's hypothesis fails (Δ of seed 003 eq. (22) loses
    rank, the controller (26) does not exist; docs/errata.md). Not bad input: each command
    decides the property it is asked about is false, exit 1."""
    data = yaml.safe_load(bundled_cases()["pursuit-table1-n1"].read_text())
    data.pop("expect")
    data["pursuit"]["epsilon"] = [0, 0.5]
    case = tmp_path / "singular.yaml"
    case.write_text(yaml.safe_dump(data, sort_keys=False))
    runs = {
        "iss": ["iss", str(case)],
        "certify": ["certify", str(case), "-o", str(tmp_path / "c.json")],
        "simulate": ["simulate", str(case), "--steps", "20", "-o", str(tmp_path / "sim")],
    }
    for name, args in runs.items():
        done = runner.invoke(app, args)
        assert done.exit_code == 1, (name, done.output)
        assert "Traceback" not in done.output
    assert "ε₁ = 0" in done.stderr and "Remark 6" in done.stderr
    assert not (tmp_path / "c.json").exists() and not (tmp_path / "sim").exists()


def test_a_missing_ping_period_is_refused_naming_the_field(tmp_path) -> None:
    """``tdoa.T`` is a physical quantity: never silently 1 s (the bundled cases and the design
    example all state it)."""
    data = yaml.safe_load(bundled_cases()["fig43-case-d"].read_text())
    del data["tdoa"]["T"]
    case = tmp_path / "no-period.yaml"
    case.write_text(yaml.safe_dump(data, sort_keys=False))
    done = runner.invoke(app, ["topology", str(case)])
    assert done.exit_code == 2
    assert f"{case}: field 'tdoa.T': expected the ping period in seconds" in done.stderr
    for path in bundled_cases().values():
        data = yaml.safe_load(path.read_text())
        assert data["kind"] != "tdoa" or "T" in data["tdoa"], path.name
