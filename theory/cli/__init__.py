"""The ``trackcert`` command line: a thin layer over the library (DESIGN.md, *CLI*).

Each command lives in its own module under ``theory/cli/`` and registers itself on an application
through a ``register(app)`` function; :func:`command_modules` finds them (every module of the
package but the shared helpers :data:`NOT_COMMANDS`). Each is a thin shell over one library
function. Exit codes (:mod:`theory.core.verdicts`): 0 the property holds, 1 it does not, 2 bad
input, 3 inconclusive.

Commands are loaded lazily (:class:`LazyCommands`): their names and help lines are read from the
command modules' source (:func:`command_index`, nothing imported), and a command's module is
imported only when that command runs, so ``trackcert simulate CASE`` never imports what
``trackcert report`` needs (sympy, hypothesis, jinja2, cvxpy) and ``trackcert --help`` imports
no command at all.
"""

from __future__ import annotations

import ast
import functools
import importlib
import pkgutil
from difflib import get_close_matches
from pathlib import Path
from typing import Any, NamedTuple

import typer
from typer import _click
from typer.core import TyperCommand, TyperGroup
from typer.main import get_command_from_info

__all__ = [
    "NOT_COMMANDS",
    "CommandEntry",
    "LazyCommands",
    "app",
    "command_index",
    "command_modules",
    "main",
]

NOT_COMMANDS = ("__main__", "common")
"""Modules of ``theory/cli/`` that define no command."""


def command_modules() -> tuple[str, ...]:
    """The command modules of ``theory/cli/``, sorted (found on disk, not listed by hand).

    Returns
    -------
    tuple of str
    """
    return tuple(
        f"{__name__}.{info.name}"
        for info in sorted(pkgutil.iter_modules(__path__), key=lambda i: i.name)
        if info.name not in NOT_COMMANDS
    )


class CommandEntry(NamedTuple):
    """A command as its module's source declares it: the module and the help text."""

    module: str
    help: str


@functools.cache
def command_index() -> dict[str, CommandEntry]:
    """Command name → its module and help, read from the command modules' source (no import).

    A command is a function decorated with ``@app.command("name")`` (or ``name=…``; without a
    name, typer's: the function name, lower case, ``_`` → ``-``); its help is the decorator's
    ``help=`` or the function's docstring. Order: modules sorted, commands as written.

    Returns
    -------
    dict

    Raises
    ------
    ValueError
        If a command module declares no command, or two declare one name.
    """
    index: dict[str, CommandEntry] = {}
    for module in command_modules():
        path = Path(__path__[0]) / f"{module.rpartition('.')[2]}.py"
        found = _declared_commands(path.read_text(encoding="utf-8"), module)
        if not found:
            raise ValueError(f"{module} declares no @app.command")
        for name, help_text in found:
            if name in index:
                raise ValueError(f"command {name!r} declared by {index[name].module} and {module}")
            index[name] = CommandEntry(module, help_text)
    return index


def _declared_commands(source: str, module: str) -> list[tuple[str, str]]:
    """(name, help) of every ``@….command(…)``-decorated function of ``source``."""
    found = []
    for node in ast.walk(ast.parse(source, filename=module)):
        if not isinstance(node, ast.FunctionDef):
            continue
        for decorator in node.decorator_list:
            if isinstance(decorator, ast.Call) and getattr(decorator.func, "attr", "") == "command":
                options = {k.arg: _constant(k.value) for k in decorator.keywords}
                name = _constant(decorator.args[0]) if decorator.args else options.get("name")
                name = name or node.name.lower().replace("_", "-")
                found.append((name, options.get("help") or ast.get_docstring(node) or ""))
    return found


def _constant(node: ast.expr) -> Any:
    return node.value if isinstance(node, ast.Constant) else None


class LazyCommands(TyperGroup):
    """The ``trackcert`` group: a command's module is imported when the command is needed.

    :meth:`get_command` imports the module declaring the command (:func:`command_index`), lets
    it ``register`` its commands on a fresh :class:`typer.Typer` and keeps the click commands
    built from them. While the group's own help is written, commands not loaded yet are listed
    from the index (name and help line) instead.
    """

    def __init__(self, **attrs: Any) -> None:
        super().__init__(**attrs)
        self._listing = False

    def list_commands(self, ctx: _click.Context) -> list[str]:
        """Every command of the index, in its order (``ctx``, click's context, is not used)."""
        return list(command_index())

    def get_command(self, ctx: _click.Context, cmd_name: str) -> _click.Command | None:
        """The command ``cmd_name`` (its module imported on first use), ``None`` if unknown.

        Parameters
        ----------
        ctx : click.Context
            The group's context (not used).
        cmd_name : str
            A command name.
        """
        entry = command_index().get(cmd_name)
        if entry is None or cmd_name in self.commands:
            return self.commands.get(cmd_name)
        if self._listing:
            return TyperCommand(name=cmd_name, help=entry.help)
        self._load(entry.module)
        return self.commands[cmd_name]

    def resolve_command(
        self, ctx: _click.Context, args: list[str]
    ) -> tuple[str | None, _click.Command | None, list[str]]:
        """The command named by ``args[0]``; an unknown name's error suggests close ones.

        Parameters
        ----------
        ctx : click.Context
            The group's context.
        args : list of str
            The command line after the group's options.
        """
        try:
            return super().resolve_command(ctx, args)
        except _click.exceptions.UsageError as error:
            matches = get_close_matches(args[0], list(command_index())) if args else []
            if matches and self.suggest_commands:
                suggestions = ", ".join(f"{m!r}" for m in matches)
                error.message = f"{error.message.rstrip('.')}. Did you mean {suggestions}?"
            raise

    def format_help(self, ctx: _click.Context, formatter: _click.HelpFormatter) -> None:
        """The group's help, listing the commands from the index (nothing imported).

        Parameters
        ----------
        ctx : click.Context
            The group's context.
        formatter : click.HelpFormatter
            Where the help goes (typer writes it with rich instead).
        """
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


app = typer.Typer(
    name="trackcert",
    cls=LazyCommands,
    help="Formal verification for distributed target localization and pursuit by robot networks.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)


@app.callback()
def _root() -> None:
    """Formal verification for distributed target localization and pursuit by robot networks."""


def main() -> None:
    """Console-script entry point."""
    app()
