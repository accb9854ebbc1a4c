"""Outputs written whole or not at all: a folder replaced in one swap, a file by one rename.

Every command that writes (``report``, ``simulate``, ``pf``, ``sweep``: a folder; ``certify``: a
file) goes through this module, so that a full disk, an exception, SIGINT, SIGTERM or SIGKILL
leaves either the complete old output or the complete new one, never a mix:

* :func:`replaced_folder` yields a fresh **staging** folder beside the target
  (``.NAME.trackcert-new-PID-RANDOM``, same file system); the command writes everything there.
  On success the old folder is renamed aside (``.NAME.trackcert-old-PID-RANDOM``), the staging
  folder renamed to ``NAME``, and the old one deleted (:func:`_swap`). On any failure the
  staging folder is deleted and ``NAME`` is untouched; an ``OSError`` becomes an
  :class:`~theory.core.errors.OutputError` naming the path (CLI exit 4).
* :func:`write_file` writes ``.NAME.trackcert-tmp-PID-RANDOM`` (flushed and ``fsync``-ed), then
  ``os.replace`` it onto ``NAME``.
* SIGINT and SIGTERM are held back during the two renames (:func:`_signals_held`) and delivered
  right after them, so a signal never lands between them.
* Only SIGKILL can stop the process elsewhere (a folder's files are not flushed to disk before
  the swap: the guarantee is against the process dying, not the machine). What it leaves is
  settled by
  :func:`recover`, which every writer runs first on its target: a sibling whose process (the
  ``PID`` in its name) is no longer running is stale. If ``NAME`` is missing and a stale
  ``…-old-…`` sibling exists, the process died between the two renames, and that sibling — the
  complete old output — is renamed back to ``NAME`` (the new output is discarded: the rule is
  deterministic and never picks a half-written folder). Every other stale sibling is deleted.

A folder is replaced as a whole, so :func:`replaceable_problem` refuses, before any work, to
replace a folder that is not the command's own output: a non-empty folder without the command's
marker file (``report.json``, ``summary.json``, ``pf.json``, ``sweep.json``), the current
folder or one of its parents.
"""

from __future__ import annotations

import os
import re
import secrets
import shutil
import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from theory.core.errors import COMMAND_LINE, CaseError, OutputError, TrackcertError

__all__ = [
    "check_replaceable",
    "recover",
    "replaceable_problem",
    "replaced_folder",
    "write_file",
]

_SIBLING = re.compile(r"\.(?P<name>.+)\.trackcert-(?P<role>new|old|tmp)-(?P<pid>\d+)-[0-9a-f]+")


def _sibling(target: Path, role: str) -> Path:
    """A fresh name beside ``target`` for ``role`` (``new``, ``old`` or ``tmp``)."""
    return target.parent / f".{target.name}.trackcert-{role}-{os.getpid()}-{secrets.token_hex(4)}"


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


def _stale(target: Path) -> list[tuple[str, Path]]:
    """(role, path) of the siblings of ``target`` left by processes no longer running, by name."""
    if not target.parent.is_dir():
        return []
    found = []
    for entry in sorted(target.parent.iterdir()):
        match = _SIBLING.fullmatch(entry.name)
        if match and match["name"] == target.name and not _alive(int(match["pid"])):
            found.append((match["role"], entry))
    return found


def recover(target: str | Path) -> None:
    """Settle what a killed writer of ``target`` left beside it (see the module docstring)."""
    target = Path(target)
    stale = _stale(target)
    asides = [path for role, path in stale if role == "old"]
    if asides and not os.path.lexists(target):
        os.rename(asides[0], target)  # killed between the two renames: the old output returns
        stale = [(role, path) for role, path in stale if path != asides[0]]
    for _, path in stale:
        _remove(path)


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        path.unlink(missing_ok=True)


def replaceable_problem(target: str | Path, marker: str) -> str:
    """Why ``target`` may not be replaced whole by a command whose outputs hold ``marker`` (what
    the folder must be, for a :class:`CaseError`), or ``""``."""
    real = Path(target).resolve()
    if real == Path.cwd().resolve() or real in Path.cwd().resolve().parents:
        return "a folder other than the current one or one of its parents (it is replaced whole)"
    if not real.is_dir() or (real / marker).is_file():
        return ""
    if any(_SIBLING.fullmatch(p.name) is None for p in real.iterdir()):
        return (
            f"a new or empty folder, or one this command wrote (with {marker}): the folder is "
            "replaced whole, and this one holds other files"
        )
    return ""


def check_replaceable(target: str | Path, marker: str, option: str = "-o") -> None:
    """A :class:`CaseError` naming ``option`` unless ``target`` may be replaced whole
    (:func:`replaceable_problem`)."""
    problem = replaceable_problem(target, marker)
    if problem:
        raise CaseError(option, problem, str(target), file=COMMAND_LINE)


@contextmanager
def replaced_folder(target: str | Path, marker: str) -> Iterator[Path]:
    """A fresh staging folder beside ``target``; on success it replaces ``target`` whole (created
    with its parents; a symbolic link is followed), else ``target`` is left as it was.

    Raises :class:`CaseError` if ``target`` is not the command's to replace
    (:func:`replaceable_problem`), :class:`OutputError` if writing or swapping fails with an
    ``OSError`` (the staging folder is removed).
    """
    shown = Path(target)
    check_replaceable(shown, marker)
    real = shown.resolve()
    existed = real.is_dir()
    left = f"{shown} is left as it was" if existed else f"{shown} was not created"
    staging = None
    try:
        recover(real)
        real.parent.mkdir(parents=True, exist_ok=True)
        staging = _sibling(real, "new")
        staging.mkdir()
        yield staging
        _swap(staging, real)
    except BaseException as error:
        if staging is not None:
            shutil.rmtree(staging, ignore_errors=True)
        if isinstance(error, OSError) and not isinstance(error, TrackcertError):
            raise OutputError(_named(error, staging, shown), _reason(error), left) from None
        raise


def _swap(staging: Path, real: Path) -> None:
    """Put ``staging`` in place of ``real`` (which may not exist) with two renames, then delete
    the old folder — only once the new one is in place (also when a signal held during the
    renames is delivered after them). If the second rename fails, the old folder is renamed
    back; if that fails too, it stays aside and :func:`recover` restores it on the next run."""
    replaced = None
    try:
        with _signals_held():
            if not os.path.lexists(real):
                os.rename(staging, real)
                return
            aside = _sibling(real, "old")
            os.rename(real, aside)
            try:
                os.rename(staging, real)
            except BaseException:
                os.rename(aside, real)
                raise
            replaced = aside
    finally:
        if replaced is not None:
            shutil.rmtree(replaced, ignore_errors=True)


def write_file(path: str | Path, content: str | bytes) -> Path:
    """Write ``content`` (text as UTF-8, or bytes) to ``path`` through a flushed temporary file
    and one rename; :class:`OutputError` if writing fails (``path`` is left as it was)."""
    path = Path(path)
    data = content.encode("utf-8") if isinstance(content, str) else content
    left = f"{path} is left as it was" if path.exists() else f"{path} was not created"
    temporary = _sibling(path, "tmp")
    try:
        recover(path)
        with open(temporary, "xb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        with _signals_held():
            os.replace(temporary, path)
    except BaseException as error:
        temporary.unlink(missing_ok=True)
        if isinstance(error, OSError) and not isinstance(error, TrackcertError):
            raise OutputError(str(path), _reason(error), left) from None
        raise
    return path


def _named(error: OSError, staging: Path | None, shown: Path) -> str:
    """The path the user would see for the file ``error`` is about (in the target, not staging)."""
    filename = error.filename
    if filename is None or staging is None:
        return str(shown)
    try:
        return str(shown / Path(os.fsdecode(filename)).relative_to(staging))
    except ValueError:
        return os.fsdecode(filename)


def _reason(error: OSError) -> str:
    return error.strerror or str(error) or type(error).__name__


@contextmanager
def _signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back during the block and deliver them after it (main thread
    only: elsewhere Python runs no signal handler, so there is nothing to hold)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending: list[int] = []
    held = {
        s: signal.signal(s, lambda signum, _frame: pending.append(signum))
        for s in (signal.SIGINT, signal.SIGTERM)
    }
    try:
        yield
    finally:
        for s, handler in held.items():
            signal.signal(s, handler)
        for signum in pending[:1]:
            signal.raise_signal(signum)
