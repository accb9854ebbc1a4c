"""The ``trackcert`` command line: a thin layer over the library (DESIGN.md, *CLI*).

Each command lives in its own module under ``theory/cli/`` and registers itself on :data:`app`
through a ``register(app)`` function; :data:`COMMAND_MODULES` lists them. Exit codes: 0 the
property holds, 1 it does not, 2 bad input, 3 inconclusive.
"""

from __future__ import annotations

import importlib

import typer

__all__ = ["COMMAND_MODULES", "app", "main"]

COMMAND_MODULES: tuple[str, ...] = (
    "theory.cli.cases",
    "theory.cli.certify",
    "theory.cli.dkf",
    "theory.cli.falsify",
    "theory.cli.generic",
    "theory.cli.iss",
    "theory.cli.pf",
    "theory.cli.report",
    "theory.cli.simulate",
    "theory.cli.topology",
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


for _module in COMMAND_MODULES:
    importlib.import_module(_module).register(app)


def main() -> None:
    """Console-script entry point."""
    app()
