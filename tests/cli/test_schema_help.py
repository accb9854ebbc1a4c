"""Help texts as users read them: no reStructuredText or Sphinx markup left in any command's
``--help`` (issue 26 item 6), and ``--version``."""

from __future__ import annotations

import re

import pytest
import typer
from typer.testing import CliRunner

from theory import __version__
from theory.cli import COMMANDS, app

runner = CliRunner()
LEFTOVER = re.compile(r"``|:(?:func|class|mod|meth|attr|data|doc|ref):`")


def _helps() -> list[list[str]]:
    """Every command, and every subcommand of a command group (``design``)."""
    group = typer.main.get_command(app)
    context = group.context_class(group)
    helps: list[list[str]] = [[]]
    for name in COMMANDS:
        helps.append([name])
        command = group.get_command(context, name)
        if hasattr(command, "list_commands"):  # a group (typer's own click)
            helps += [[name, sub] for sub in command.list_commands(context)]
    return helps


@pytest.mark.parametrize("command", _helps(), ids=lambda c: " ".join(c) or "trackcert")
def test_help_has_no_markup_leftovers(command: list[str]) -> None:
    result = runner.invoke(app, [*command, "--help"], env={"COLUMNS": "200"})
    assert result.exit_code == 0, result.output
    assert not LEFTOVER.findall(result.output), result.output


def test_version() -> None:
    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0 and result.stdout.strip() == f"trackcert {__version__}"
