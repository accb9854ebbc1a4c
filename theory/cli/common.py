"""Helpers shared by the CLI commands: error handling, JSON output, exit codes.

The exit codes and the verdict → code rule are the library's (:mod:`theory.core.verdicts`);
JSON conversion is :func:`theory.core.jsonable.plain`.
"""

from __future__ import annotations

import functools
import json
import sys
from collections.abc import Callable
from typing import Any, NoReturn, TypeVar

import typer
from rich.console import Console

from theory.core.errors import (
    CaseError,
    InconclusiveError,
    PropertyFails,
    SolverError,
    TrackcertError,
)
from theory.core.jsonable import plain
from theory.core.verdicts import (
    EXIT_BAD_INPUT,
    EXIT_FAILS,
    EXIT_INCONCLUSIVE,
)

__all__ = [
    "case_argument",
    "console",
    "error_console",
    "finish",
    "json_option",
    "print_json",
    "reports_errors",
]

console = Console()
error_console = Console(stderr=True)

F = TypeVar("F", bound=Callable[..., Any])


def reports_errors(command: F) -> F:
    """Wrap ``command`` so trackcert errors become a stderr line and the DESIGN.md exit code."""

    @functools.wraps(command)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return command(*args, **kwargs)
        except CaseError as error:
            _fail(f"error: {error}", EXIT_BAD_INPUT)
        except (InconclusiveError, SolverError) as error:
            _fail(f"inconclusive: {error}", EXIT_INCONCLUSIVE)
        except PropertyFails as error:
            _fail(f"does not hold: {error}", EXIT_FAILS)
        except TrackcertError as error:
            _fail(f"error: {error}", EXIT_BAD_INPUT)

    return wrapper  # type: ignore[return-value]


def _fail(message: str, code: int) -> None:
    error_console.print(message, markup=False, highlight=False)
    raise typer.Exit(code)


def print_json(data: Any) -> None:
    """Write ``data`` as indented JSON to stdout."""
    sys.stdout.write(json.dumps(plain(data), indent=2, sort_keys=False) + "\n")


def case_argument(help: str = "Case file or bundled case name.") -> Any:
    """The positional ``CASE`` argument of a command (a ``typer.Argument``).

    Parameters
    ----------
    help : str
        Its help text.
    """
    return typer.Argument(..., help=help)


def json_option(help: str = "Print JSON.") -> Any:
    """The ``--json`` flag of a command (a ``typer.Option``, default off).

    Parameters
    ----------
    help : str
        Its help text.
    """
    return typer.Option(False, "--json", help=help)


def finish(data: Any, code: int, *, as_json: bool, show: Callable[[], None]) -> NoReturn:
    """Print ``data`` as JSON (``as_json``) or call ``show``, then exit with ``code``.

    Parameters
    ----------
    data : Any
        The command's JSON record.
    code : int
        Exit code.
    as_json : bool
        The ``--json`` flag.
    show : callable
        Prints the human-readable form.

    Raises
    ------
    typer.Exit
        Always, with ``code``.
    """
    if as_json:
        print_json(data)
    else:
        show()
    raise typer.Exit(code)
