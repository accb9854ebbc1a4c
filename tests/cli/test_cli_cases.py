"""``trackcert cases`` and the CLI's error handling."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases

runner = CliRunner()


def test_cases_lists_every_bundled_case() -> None:
    result = runner.invoke(app, ["cases", "--json"])
    assert result.exit_code == 0
    names = {row["name"] for row in json.loads(result.stdout)["cases"]}
    assert names == set(bundled_cases())


def test_cases_names_only() -> None:
    result = runner.invoke(app, ["cases", "--names"])
    assert result.exit_code == 0
    assert result.stdout.split() == sorted(bundled_cases())
