"""Off a terminal (CI, nohup, a notebook, a file) the long commands print plain progress lines:
one when the work starts, one every $TRACKCERT_PROGRESS_SECONDS, one when it ends."""

from __future__ import annotations

import re

import pytest
from typer.testing import CliRunner

from theory.cli import app

runner = CliRunner()  # its stderr is not a terminal

COMMANDS = {
    "simulate": (["simulate", "pursuit-table1-n1", "--steps", "300", "--runs", "2"],
                 "simulating pursuit-table1-n1"),
    "report": (["report", "fig43-case-d", "--only", "seed000.eq4.6"], "checking"),
    "sweep": (["sweep", "pursuit-table1-n1", "--param", "k_gamma=100,200", "--steps", "20"],
              "sweep"),
    "pf": (["pf", "pf-path3", "--runs", "2"], "pf pf-path3"),
}  # fmt: skip


@pytest.mark.parametrize("name", list(COMMANDS))
def test_lines_at_the_start_at_an_interval_and_at_the_end(tmp_path, monkeypatch, name) -> None:
    monkeypatch.setenv("TRACKCERT_PROGRESS_SECONDS", "0.05")
    args, label = COMMANDS[name]
    done = runner.invoke(app, [*args, "--workers", "1", "-o", str(tmp_path / "out"), "--json"])
    assert done.exit_code in (0, 3), done.output
    lines = [line for line in done.stderr.splitlines() if line.startswith(f"{label}")]
    assert re.fullmatch(rf"{label}: 0(/\d+)? done \(started\), 0s elapsed", lines[0]), lines
    assert re.match(rf"{label}: (\d+)/\1 done \(finished\), \d+s elapsed", lines[-1]), lines
    if name == "simulate":  # about a second of work: several lines between
        assert len(lines) > 3 and all(" done, " in line for line in lines[1:-1])


def test_a_bad_interval_is_bad_input(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("TRACKCERT_PROGRESS_SECONDS", "-1")
    done = runner.invoke(app, [*COMMANDS["simulate"][0], "-o", str(tmp_path / "o")])
    assert done.exit_code == 2
    assert "<environment>: field 'TRACKCERT_PROGRESS_SECONDS'" in done.stderr
