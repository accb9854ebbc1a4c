"""``trackcert simulate`` runs ``kind: pf`` cases exactly as ``trackcert pf`` does."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from theory.cli import app

runner = CliRunner()


def test_simulate_and_pf_agree_on_a_pf_case(tmp_path) -> None:
    args = ["pf-path3", "--runs", "1", "--seed", "5", "--json"]
    via_simulate = runner.invoke(app, ["simulate", *args, "-o", str(tmp_path / "a")])
    via_pf = runner.invoke(app, ["pf", *args, "-o", str(tmp_path / "b")])
    assert via_simulate.exit_code == via_pf.exit_code
    first, second = json.loads(via_simulate.stdout), json.loads(via_pf.stdout)
    assert first["seed"] == 5 and first["agents"] == second["agents"]
    assert {"id", "final_localization_error", "mean_localization_error"} <= set(first["agents"][0])
    assert (tmp_path / "a" / "pf.json").is_file()
