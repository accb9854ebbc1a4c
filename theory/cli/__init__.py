"""The ``trackcert`` command line: a thin layer over the library (DESIGN.md, *CLI*).

Each command lives in its own module under ``theory/cli/`` and registers itself on :data:`app`
through a ``register(app)`` function; :func:`command_modules` finds them (every module of the
package but the shared helpers :data:`NOT_COMMANDS`). Each is a thin shell over one library
function. Exit codes (:mod:`theory.core.verdicts`): 0 the property holds, 1 it does not, 2 bad
input, 3 inconclusive.
"""

from __future__ import annotations

import importlib
import pkgutil

import typer

__all__ = ["NOT_COMMANDS", "app", "command_modules", "main"]

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


app = typer.Typer(
    name="trackcert",
    help="Formal verification for distributed target localization and pursuit by robot networks.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)


@app.callback()
def _root() -> None:
    """Formal verification for distributed target localization and pursuit by robot networks."""


for _module in command_modules():
    importlib.import_module(_module).register(app)


def main() -> None:
    """Console-script entry point."""
    app()
