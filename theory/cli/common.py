"""Helpers shared by the CLI commands: error handling, JSON output, exit codes."""

from __future__ import annotations

import functools
import json
import sys
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np
import typer
from rich.console import Console

from theory.errors import CaseError, InconclusiveError, SolverError, TrackcertError

__all__ = [
    "EXIT_BAD_INPUT",
    "EXIT_FAILS",
    "EXIT_HOLDS",
    "EXIT_INCONCLUSIVE",
    "console",
    "error_console",
    "print_json",
    "reports_errors",
    "to_jsonable",
]

EXIT_HOLDS, EXIT_FAILS, EXIT_BAD_INPUT, EXIT_INCONCLUSIVE = 0, 1, 2, 3

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
        except TrackcertError as error:
            _fail(f"error: {error}", EXIT_BAD_INPUT)

    return wrapper  # type: ignore[return-value]


def _fail(message: str, code: int) -> None:
    error_console.print(message, markup=False, highlight=False)
    raise typer.Exit(code)


def to_jsonable(value: Any) -> Any:
    """``value`` with numpy scalars/arrays, tuples and complex numbers made plain JSON types."""
    if isinstance(value, dict):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [to_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return to_jsonable(value.tolist())
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating | float):
        number = float(value)
        return number if np.isfinite(number) else str(number)
    if isinstance(value, complex | np.complexfloating):
        return {"re": float(value.real), "im": float(value.imag)}
    return value


def print_json(data: Any) -> None:
    """Write ``data`` as indented JSON to stdout."""
    sys.stdout.write(json.dumps(to_jsonable(data), indent=2, sort_keys=False) + "\n")
