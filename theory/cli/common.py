"""Helpers shared by the CLI commands: error handling, JSON output, exit codes.

The exit codes and the verdict → code rule are the library's (:mod:`theory.core.verdicts`);
JSON conversion is :func:`theory.core.jsonable.plain`.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, NoReturn, TypeVar

import numpy as np
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
    "COMMAND_LINE",
    "NUMERICAL_FAILURES",
    "case_argument",
    "check_output",
    "console",
    "error_console",
    "finish",
    "json_option",
    "print_json",
    "progress_bar",
    "reports_errors",
    "scheduler_option",
    "workers_option",
]

COMMAND_LINE = "<command line>"
"""The ``file`` of an error in a command-line option (not in a case file)."""

console = Console()
error_console = Console(stderr=True)

F = TypeVar("F", bound=Callable[..., Any])


NUMERICAL_FAILURES = (ArithmeticError, np.linalg.LinAlgError)
"""Floating-point failures (overflow, a non-converging SVD …) on input the validation accepted:
reported as inconclusive (exit 3), never as a verdict and never as a traceback."""
NUMERICAL_FAILURE = (
    "a floating-point computation failed on this input (numbers this large or small may be "
    "beyond what the method handles; see the 'exponent' limit, docs/cli.md)"
)


def reports_errors(command: F) -> F:
    """Wrap ``command`` so trackcert errors become a stderr line and the DESIGN.md exit code.

    A numerical failure the library did not turn into a :class:`SolverError`
    (:data:`NUMERICAL_FAILURES`) is inconclusive too (exit 3), naming the error.
    """

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
        except NUMERICAL_FAILURES as error:
            _fail(
                f"inconclusive: {NUMERICAL_FAILURE}: {type(error).__name__}: {error}",
                EXIT_INCONCLUSIVE,
            )

    return wrapper  # type: ignore[return-value]


def _fail(message: str, code: int) -> None:
    # one line, verbatim (no markup, no emoji codes such as ':b:')
    error_console.print(message, markup=False, highlight=False, soft_wrap=True, emoji=False)
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


def check_output(path: str | Path, option: str, *, folder: bool) -> Path:
    """Refuse an output path that cannot be written, before any work is done (nothing written).

    A folder may not exist yet (it and missing parents are created later) but nothing on its way
    may be a file, and its nearest existing ancestor must be a writable folder; a file's folder
    must exist and be writable, and the file itself must not be a folder.

    Parameters
    ----------
    path : str or Path
        The value of the option.
    option : str
        The option, as named in the message (``-o/--output``).
    folder : bool
        Whether the option names a folder (else a file).

    Returns
    -------
    Path

    Raises
    ------
    CaseError
        Naming ``option`` (file ``<command line>``), what it must be and the path.
    """
    path = Path(path)
    problem = _folder_problem(path) if folder else _file_problem(path)
    if problem:
        raise CaseError(option, problem, str(path), file=COMMAND_LINE)
    return path


def _folder_problem(path: Path) -> str:
    if path.exists() and not path.is_dir():
        return "a folder (a file of that name exists)"
    ancestor = next((p for p in (path, *path.parents) if p.exists()), Path("."))
    if not ancestor.is_dir():
        return f"a folder path (its parent {str(ancestor)!r} is a file)"
    if not os.access(ancestor, os.W_OK | os.X_OK):
        return f"a folder that can be created or written ({str(ancestor)!r} is not writable)"
    return ""


def _file_problem(path: Path) -> str:
    parent = path.parent
    if path.is_dir():
        return "a file path (a folder of that name exists)"
    if not parent.is_dir():
        why = "is a file" if parent.exists() else "does not exist"
        return f"a file in an existing folder ({str(parent)!r} {why})"
    if not os.access(parent, os.W_OK | os.X_OK) or (path.exists() and not os.access(path, os.W_OK)):
        return "a writable file path"
    return ""


def workers_option(help: str = "Local worker processes (default: all cores; 1: serial).") -> Any:
    """The ``--workers N`` option of a command running tasks (:mod:`theory.core.parallel`).

    Parameters
    ----------
    help : str
        Its help text.
    """
    return typer.Option(None, "--workers", min=1, help=help)


def scheduler_option() -> Any:
    """The ``--scheduler ADDRESS`` option: run the tasks on an existing Dask cluster."""
    return typer.Option(
        None,
        "--scheduler",
        metavar="ADDRESS",
        help="Dask scheduler to run the tasks on, e.g. tcp://host:8786 "
        "(default: $TRACKCERT_SCHEDULER, else a local cluster).",
    )


@contextlib.contextmanager
def progress_bar(
    total: int, description: str, *, quiet: bool = False
) -> Iterator[Callable[..., None]]:
    """A progress bar on stderr (done/total, elapsed, ETA) and the hook advancing it.

    Quiet (the hook does nothing) when ``quiet`` (``--json``) or when stdout or stderr is not a
    terminal.

    Parameters
    ----------
    total : int
        Number of units (tasks, runs, checks).
    description : str
        Shown beside the bar.
    quiet : bool
        Show nothing.

    Yields
    ------
    callable
        ``advance(done, label=None, total=None)``: ``done`` units finished so far; ``label``
        replaces the description (e.g. the check that just finished); ``total`` corrects the
        number of units once it is known.
    """
    if quiet or not (console.is_terminal and error_console.is_terminal):
        yield lambda done, label=None, total=None: None
        return
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
    )
    with Progress(*columns, console=error_console, transient=True) as progress:
        task = progress.add_task(description, total=total)

        def advance(done: int, label: str | None = None, total: int | None = None) -> None:
            progress.update(task, completed=done, description=label or description)
            if total is not None:
                progress.update(task, total=total)

        yield advance
