"""The ``trackcert`` command line: a thin layer over the library.

:data:`COMMANDS` lists every command with the module that defines it and its summary line. Each
module adds its commands to the application with ``register(app)``; it is imported only when one
of its commands runs (:class:`LazyCommands`), so ``trackcert simulate`` never imports what
``trackcert report`` needs. Exit codes (:mod:`theory.core.verdicts`): 0 the property holds, 1 it
does not, 2 bad input, 3 inconclusive.
"""

from __future__ import annotations

import importlib
from difflib import get_close_matches
from typing import Any, NamedTuple

import typer
from typer import _click
from typer.core import TyperCommand, TyperGroup
from typer.main import get_command_from_info, get_group_from_info

from theory.core.parallel import one_thread_pools

__all__ = ["COMMANDS", "CommandEntry", "LazyCommands", "app", "main"]


class CommandEntry(NamedTuple):
    """A command's module and the summary line ``trackcert --help`` lists."""

    module: str
    help: str


COMMANDS: dict[str, CommandEntry] = {
    "cases": CommandEntry("theory.cli.report", "List the bundled cases (name, kind, source)."),
    "certify": CommandEntry(
        "theory.cli.certify",
        "Write every certificate the case supports (a bundle), re-checked exactly.",
    ),
    "check": CommandEntry(
        "theory.cli.certify",
        "Re-verify a certificate exactly with proofs_check (0 valid, 1 invalid, 2 malformed).",
    ),
    "design": CommandEntry(
        "theory.cli.design",
        "Certified design answers: which parameters work, how far agents may drift, what may fail",
    ),
    "dkf": CommandEntry(
        "theory.cli.dkf",
        "S-detectability (LMI), Thm 5.2.10's conditions and the blind-set condition.",
    ),
    "falsify": CommandEntry(
        "theory.cli.falsify",
        "Run hypothesis against a claim; print the shrunk counterexample as a case file.",
    ),
    "generic": CommandEntry(
        "theory.cli.topology",
        "Enumerate every minor of O = [H; HA; …] for one agent and print the derivation.",
    ),
    "iss": CommandEntry(
        "theory.cli.iss", "ISS Lyapunov analysis of the pursuit/coordination loop (seed 003)."
    ),
    "pf": CommandEntry(
        "theory.cli.pf",
        "Run the distributed TDOA particle filter of seed 002 on a kind: pf case.",
    ),
    "report": CommandEntry(
        "theory.cli.report",
        "Run every registered check on every case; write index.html, report.md, report.json.",
    ),
    "schema": CommandEntry(
        "theory.cli.schema",
        "Print a case kind's JSON Schema, or write its reference page and schema file.",
    ),
    "simulate": CommandEntry(
        "theory.cli.simulate",
        "Simulate the closed loop; write runs.npz, CSV tables, PNG figures and summary.json.",
    ),
    "sweep": CommandEntry(
        "theory.cli.sweep",
        "Judge and simulate CASE at every point of a parameter grid; write CSV, JSON, PNG.",
    ),
    "topology": CommandEntry(
        "theory.cli.topology",
        "Distributed TDOA observability of every agent (seed 000 §4.2.2, Cor. 4.2.4).",
    ),
}
"""Command → its module and summary line, in the order ``trackcert --help`` lists them."""


class LazyCommands(TyperGroup):
    """The ``trackcert`` group: a command's module is imported when the command is needed.

    While the group's own help is written, commands not loaded yet are listed from
    :data:`COMMANDS` (name and summary) instead.
    """

    def __init__(self, **attrs: Any) -> None:
        super().__init__(**attrs)
        self._listing = False

    def list_commands(self, ctx: _click.Context) -> list[str]:
        """Every command of :data:`COMMANDS`, in its order."""
        return list(COMMANDS)

    def get_command(self, ctx: _click.Context, cmd_name: str) -> _click.Command | None:
        """The command ``cmd_name`` (its module imported on first use), ``None`` if unknown."""
        entry = COMMANDS.get(cmd_name)
        if entry is None or cmd_name in self.commands:
            return self.commands.get(cmd_name)
        if self._listing:
            return TyperCommand(name=cmd_name, help=entry.help)
        self._load(entry.module)
        return self.commands[cmd_name]

    def resolve_command(
        self, ctx: _click.Context, args: list[str]
    ) -> tuple[str | None, _click.Command | None, list[str]]:
        """The command named by ``args[0]``; an unknown name's error suggests close ones."""
        try:
            return super().resolve_command(ctx, args)
        except _click.exceptions.UsageError as error:
            matches = get_close_matches(args[0], list(COMMANDS)) if args else []
            if matches and self.suggest_commands:
                suggestions = ", ".join(f"{m!r}" for m in matches)
                error.message = f"{error.message.rstrip('.')}. Did you mean {suggestions}?"
            raise

    def format_help(self, ctx: _click.Context, formatter: _click.HelpFormatter) -> None:
        """The group's help, listing the commands from :data:`COMMANDS` (nothing imported)."""
        self._listing = True
        try:
            super().format_help(ctx, formatter)
        finally:
            self._listing = False

    def _load(self, module: str) -> None:
        registry = typer.Typer()
        importlib.import_module(module).register(registry)
        for info in registry.registered_commands:
            command = get_command_from_info(
                info, pretty_exceptions_short=True, rich_markup_mode=self.rich_markup_mode
            )
            self.add_command(command)
        for info in registry.registered_groups:  # a sub-application such as ``design``
            group = get_group_from_info(
                info,
                pretty_exceptions_short=True,
                suggest_commands=self.suggest_commands,
                rich_markup_mode=self.rich_markup_mode,
            )
            self.add_command(group, info.name)


app = typer.Typer(
    name="trackcert",
    cls=LazyCommands,
    help="Formal verification for distributed target localization and pursuit by robot networks.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)


def _print_version(requested: bool) -> None:
    if requested:
        from theory import __version__

        typer.echo(f"trackcert {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_print_version, is_eager=True, help="Print the version."
    ),
) -> None:
    """Formal verification for distributed target localization and pursuit by robot networks."""


def main() -> None:
    """Console-script entry point: one-thread BLAS pools (:func:`one_thread_pools`), then the
    command."""
    one_thread_pools()
    app()
