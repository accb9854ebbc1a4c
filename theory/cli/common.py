"""Helpers shared by the CLI commands: error handling, JSON output, exit codes, progress.

The exit codes and the verdict → code rule are the library's (:mod:`theory.core.verdicts`);
JSON conversion is :func:`theory.core.jsonable.plain`.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any, NoReturn, TypeVar

import numpy as np
import typer
from rich.console import Console

from theory.core.atomic_output import replaceable_problem
from theory.core.errors import (
    COMMAND_LINE,
    ENVIRONMENT,
    CaseError,
    FaultError,
    InconclusiveError,
    PropertyFails,
    SolverError,
    TrackcertError,
)
from theory.core.jsonable import plain
from theory.core.verdicts import (
    EXIT_BAD_INPUT,
    EXIT_FAILS,
    EXIT_FAULT,
    EXIT_INCONCLUSIVE,
    command_verdict,
    exit_code,
    interrupted_code,
)

__all__ = [
    "COMMAND_LINE",
    "NUMERICAL_FAILURES",
    "PROGRESS_SETTING",
    "case_argument",
    "check_file_output",
    "check_folder_output",
    "console",
    "error_console",
    "finish",
    "json_option",
    "print_exit_rule",
    "print_json",
    "progress_bar",
    "reports_errors",
    "scheduler_option",
    "workers_option",
]

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
    """Wrap ``command`` so that no error is a traceback and every one has its exit code.

    Trackcert errors become one stderr line and the code of :mod:`theory.core.verdicts`; a
    numerical failure the library did not turn into a :class:`SolverError`
    (:data:`NUMERICAL_FAILURES`) is inconclusive (exit 3), naming the error; a fault of the
    machine — a :class:`FaultError`, any other ``OSError``, ``MemoryError`` — is exit 4;
    SIGINT and SIGTERM stop the command with 128 + the signal's number (130, 143), after the
    outputs being written were discarded (:mod:`theory.core.atomic_output`).
    """

    @functools.wraps(command)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            with _terminate_raises():
                return command(*args, **kwargs)
        except CaseError as error:
            _fail(f"error: {error}", EXIT_BAD_INPUT)
        except (InconclusiveError, SolverError) as error:
            _fail(f"inconclusive: {error}", EXIT_INCONCLUSIVE)
        except PropertyFails as error:
            _fail(f"does not hold: {error}", EXIT_FAILS)
        except FaultError as error:
            _fail(f"fault: {error}", EXIT_FAULT)
        except TrackcertError as error:
            _fail(f"error: {error}", EXIT_BAD_INPUT)
        except NUMERICAL_FAILURES as error:
            _fail(
                f"inconclusive: {NUMERICAL_FAILURE}: {type(error).__name__}: {error}",
                EXIT_INCONCLUSIVE,
            )
        except OSError as error:
            _fail(f"fault: {_os_error(error)}", EXIT_FAULT)
        except MemoryError:
            _fail("fault: out of memory", EXIT_FAULT)
        except (KeyboardInterrupt, Terminated) as error:
            signum = getattr(error, "signum", signal.SIGINT)
            name = signal.Signals(signum).name
            message = f"interrupted by {name}: no output was left half-written"
            _fail(message, interrupted_code(signum))

    return wrapper  # type: ignore[return-value]


class Terminated(BaseException):
    """SIGTERM, raised in the main thread as SIGINT raises ``KeyboardInterrupt``."""

    def __init__(self, signum: int) -> None:
        self.signum = signum
        super().__init__(signal.Signals(signum).name)


@contextlib.contextmanager
def _terminate_raises() -> Iterator[None]:
    """SIGTERM raises :class:`Terminated` in the block (main thread only), so the outputs being
    written are cleaned up as for Ctrl-C instead of the process vanishing mid-write."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def raise_terminated(signum: int, _frame: Any) -> None:
        raise Terminated(signum)

    previous = signal.signal(signal.SIGTERM, raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _os_error(error: OSError) -> str:
    reason = error.strerror or str(error) or type(error).__name__
    return f"{error.filename}: {reason}" if error.filename else reason


def _fail(message: str, code: int) -> NoReturn:
    # one line, verbatim (no markup, no emoji codes such as ':b:')
    error_console.print(message, markup=False, highlight=False, soft_wrap=True, emoji=False)
    raise typer.Exit(code)


def print_exit_rule(property_verdict: bool | None, expectations: Sequence[Any]) -> None:
    """Say, when they differ, that the case's expectations and not the property decide the exit
    code (:func:`theory.core.verdicts.command_verdict`).
    """
    decided = command_verdict(property_verdict, expectations)
    if decided == property_verdict:
        return
    words = {True: "holds", False: "fails", None: "is inconclusive"}
    console.print(
        f"exit code {exit_code(decided)}: the case's expect block decides it (the property "
        f"{words[property_verdict]}; without expectations the property decides)",
        markup=False,
        highlight=False,
    )


def print_json(data: Any) -> None:
    """Write ``data`` as indented JSON to stdout."""
    sys.stdout.write(json.dumps(plain(data), indent=2, sort_keys=False) + "\n")


def case_argument(help: str = "Case file or bundled case name.") -> Any:
    """The positional ``CASE`` argument of a command (a ``typer.Argument``)."""
    return typer.Argument(..., help=help)


def json_option(help: str = "Print JSON.") -> Any:
    """The ``--json`` flag of a command (a ``typer.Option``, default off)."""
    return typer.Option(False, "--json", help=help)


def finish(
    data: Any,
    code: int,
    *,
    as_json: bool,
    show: Callable[[], None],
    verdicts: tuple[bool | None, Sequence[Any]] | None = None,
) -> NoReturn:
    """Print ``data`` as JSON (``as_json``) or call ``show`` — then, given the property's verdict
    and the expectations judged, :func:`print_exit_rule` — and exit with ``code``."""
    if as_json:
        print_json(data)
    else:
        show()
        if verdicts is not None:
            print_exit_rule(*verdicts)
    raise typer.Exit(code)


def check_folder_output(path: str | Path, option: str, marker: str) -> Path:
    """Refuse an output folder that cannot be written or replaced, before any work is done.

    The folder may not exist yet (it and missing parents are created later) but nothing on its
    way may be a file, and its nearest existing ancestor must be a writable folder. An existing
    folder is replaced whole (:mod:`theory.core.atomic_output`), so it must be empty or an
    earlier output of the command (it has ``marker``), and neither the current folder nor one
    of its parents.
    """
    path = Path(path)
    problem = _folder_problem(path) or replaceable_problem(path, marker)
    if problem:
        raise CaseError(option, problem, str(path), file=COMMAND_LINE)
    return path


def check_file_output(path: str | Path, option: str) -> Path:
    """Refuse an output file that cannot be written, before any work is done.

    Its folder must exist and be writable, and the file itself must not be a folder.
    """
    path = Path(path)
    problem = _file_problem(path)
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
    """The ``--workers N`` option of a command running tasks (:mod:`theory.core.parallel`)."""
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


PROGRESS_SETTING = "TRACKCERT_PROGRESS_SECONDS"
"""Environment setting: seconds between two progress lines off a terminal (0: only the first
and the last line)."""

PROGRESS_SECONDS = 15.0
"""Default seconds between two progress lines off a terminal."""


@contextlib.contextmanager
def progress_bar(
    total: int, description: str, *, quiet: bool = False
) -> Iterator[Callable[..., None]]:
    """Progress on stderr, and the hook advancing it.

    On a terminal (stderr is one): a bar (done/total, elapsed, ETA), not shown when ``quiet``
    (``--json``). Off a terminal (CI, ``nohup``, a notebook's ``!trackcert``, a file), whatever
    ``quiet`` says: plain lines — when the work starts, every :data:`PROGRESS_SECONDS`
    (``$TRACKCERT_PROGRESS_SECONDS``), and when it ends — so a long run is never silent.

    Yields ``advance(done, label=None, total=None)``: ``label`` replaces the description (e.g.
    the check that just finished), ``total`` corrects the number of units once known. Raises
    :class:`CaseError` if ``$TRACKCERT_PROGRESS_SECONDS`` is not a number ≥ 0.
    """
    if not error_console.is_terminal:
        with _progress_lines(total, description, _progress_seconds()) as advance:
            yield advance
        return
    if quiet or not console.is_terminal:
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


def _progress_seconds() -> float:
    text = os.environ.get(PROGRESS_SETTING)
    if text is None:
        return PROGRESS_SECONDS
    try:
        seconds = float(text)
    except ValueError:
        seconds = -1.0
    if not seconds >= 0:
        raise CaseError(PROGRESS_SETTING, "a number of seconds ≥ 0", text, file=ENVIRONMENT)
    return seconds


@contextlib.contextmanager
def _progress_lines(
    total: int, description: str, seconds: float
) -> Iterator[Callable[..., None]]:
    """Plain progress lines on stderr: first, every ``seconds`` (if > 0) from a timer thread,
    and last (when the block ends without an error)."""
    state = {"done": 0, "total": total, "label": ""}
    began = time.monotonic()
    lock = threading.Lock()
    stop = threading.Event()

    def line(what: str) -> None:
        elapsed = _duration(time.monotonic() - began)
        of = f"/{state['total']}" if state["total"] else ""
        last = f"; last: {state['label']}" if state["label"] else ""
        with lock:
            sys.stderr.write(f"{description}: {state['done']}{of} {what}, {elapsed}{last}\n")
            sys.stderr.flush()

    def beat() -> None:
        while not stop.wait(seconds):
            line("done")

    def advance(done: int, label: str | None = None, total: int | None = None) -> None:
        state["done"], state["label"] = done, label or state["label"]
        if total is not None:
            state["total"] = total

    line("done (started)")
    timer = threading.Thread(target=beat, name="trackcert-progress", daemon=True)
    if seconds > 0:
        timer.start()
    try:
        yield advance
    finally:
        stop.set()
        if timer.is_alive():
            timer.join()
    line("done (finished)")


def _duration(seconds: float) -> str:
    minutes, rest = divmod(int(seconds), 60)
    return f"{minutes}m{rest:02d}s elapsed" if minutes else f"{seconds:.0f}s elapsed"
