"""``trackcert sweep``: files identical with 1 and 2 workers, exit codes, nothing written on bad
input."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from theory.cli import app

runner = CliRunner()

ARGS = ["pursuit-table1-n3", "--param", "k_gamma=1:400:log3", "--param", "seed=0:2", "--steps", "5"]


def sweep(*args: str):
    return runner.invoke(app, ["sweep", *args])


def test_identical_files_with_one_and_two_workers(tmp_path) -> None:
    """The points run on a 2-process LocalCluster give byte-identical CSV and JSON."""
    one = sweep(*ARGS, "--workers", "1", "-o", str(tmp_path / "one"), "--json")
    two = sweep(*ARGS, "--workers", "2", "-o", str(tmp_path / "two"), "--json")
    assert one.exit_code == two.exit_code == 0, one.output + two.output
    for name in ("sweep.csv", "sweep.json"):
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "two" / name).read_bytes()
    summary = json.loads(one.stdout)
    assert summary["points"] == 6 and summary["status"] == {"verified": 6}
    assert (tmp_path / "two" / "sweep.png").read_bytes()[:4] == b"\x89PNG"


def test_unknown_path_exit_2_nothing_written(tmp_path) -> None:
    result = sweep("pursuit-table1-n3", "--param", "k_gama=1:3", "-o", str(tmp_path / "out"))
    assert result.exit_code == 2
    assert "k_gama" in result.stderr and "k_gamma" in result.stderr
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


def test_bad_spec_exit_2_names_param(tmp_path) -> None:
    result = sweep("pursuit-table1-n3", "--param", "k_gamma=1:400:log", "-o", str(tmp_path))
    assert result.exit_code == 2
    assert "--param" in result.stderr and "k_gamma=1:400:log" in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_too_many_points_exit_2(tmp_path) -> None:
    args = [
        "pursuit-table1-n3",
        "-p",
        "k_gamma=1:400:log10",
        "-p",
        "seed=0:10",
        "-o",
        str(tmp_path),
    ]
    result = sweep(*args, "--max-points", "50")
    assert result.exit_code == 2
    assert "100 points" in result.stderr and "max-points" in result.stderr
