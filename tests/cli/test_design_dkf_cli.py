"""``trackcert design self-weight | weights | redundancy`` on dkf cases: the contract's JSON keys
(../shared/DESIGN.md), exit codes (0 answered, 1 the property fails, 2 bad input, no traceback),
the plain answer printed for reading."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from theory.cli import app

RUN = CliRunner()


def _json(*args: str) -> tuple[int, dict]:
    result = RUN.invoke(app, ["design", *args, "--json"])
    return result.exit_code, json.loads(result.stdout)


def test_self_weight_json_contract_on_example_1() -> None:
    code, data = _json("self-weight", "ch5-example-1-wg")
    assert code == 0 and {"agent", "supremum", "below", "at_or_above"} <= set(data)
    assert data["agent"] == [1, 2]
    assert {"exact", "value", "rational", "interval"} <= set(data["supremum"])
    assert data["supremum"]["rational"] == "1/4" and data["supremum"]["exact"] is True
    assert {"w", "certificate"} <= set(data["below"]) and {"w", "certificate"} <= set(
        data["at_or_above"]
    )


def test_self_weight_prints_the_exact_value_plainly() -> None:
    result = RUN.invoke(app, ["design", "self-weight", "ch5-example-2-wg", "--agent", "3"])
    assert result.exit_code == 0 and "4000000/11840481" in result.stdout
    assert "0.337824" in result.stdout


def test_self_weight_of_a_complex_largest_root_is_exact_and_both_certificates_check(
    tmp_path: Path,
) -> None:
    """Agent 1 blind to the rotation·scale block ``[[1, −1], [1, 1]]`` (``|λ|² = 2``): the
    supremum is exactly 1/2 (a bracket before), and ``trackcert check`` accepts both ends."""
    case = Path(__file__).resolve().parents[1] / "data" / "dkf" / "self-weight-complex-root.yaml"
    code, data = _json("self-weight", str(case), "--agent", "1")
    assert code == 0 and data["status"] == "exact" and data["supremum"]["rational"] == "1/2"
    for end in ("below", "at_or_above"):
        path = tmp_path / f"{end}.json"
        path.write_text(json.dumps(data[end]["certificate"]), encoding="utf-8")
        assert RUN.invoke(app, ["check", str(path)]).exit_code == 0
    assert data["at_or_above"]["certificate"]["kind"] == "self-weight-necessary-violated"


def test_self_weight_never_exits_1() -> None:
    code, data = _json("self-weight", "ch5-blind-cycle")
    assert code == 1 and data["status"] == "never"
    assert data["at_or_above"]["certificate"]["kind"] == "s-detectability-infeasible"


@pytest.mark.parametrize(
    "args",
    [
        ["ch5-example-1-wg", "--agent", "9"],
        ["ch5-example-1-wg", "--width", "0"],
        ["ch5-example-1-wg", "--link", "W.0.0=w"],
        ["ch5-example-1-wg", "--link", "W.0.0=w**2"],
        ["pursuit-table1-n3", "--agent", "1"],
    ],
)
def test_self_weight_bad_input_exits_2_without_traceback(args: list[str]) -> None:
    result = RUN.invoke(app, ["design", "self-weight", *args])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert "expected" in result.output


def test_weights_json_contract() -> None:
    code, data = _json("weights", "ch5-example-1-wg")
    assert code == 0 and {"W", "spectral_radius", "certificate", "compared"} <= set(data)
    assert {c["weights"] for c in data["compared"]} >= {"case", "uniform"}
    assert all({"weights", "spectral_radius"} <= set(c) for c in data["compared"])


def test_redundancy_for_dkf_json_contract_and_exit_codes() -> None:
    code, data = _json("redundancy", "ch5-example-2-wg", "--agents")
    assert code == 0 and (data["k"], data["certified_below"]) == (1, 1)
    assert {"k", "witness", "certified_below"} <= set(data)
    code, data = _json("redundancy", "ch5-example-1-wc")
    assert code == 1 and data["k"] == 0
