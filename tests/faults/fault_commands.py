"""The writing commands the fault tests interrupt, and the tools to interrupt them.

Each command is run twice over the same output path with different inputs (``old`` then ``new``),
so the two complete outputs differ; a fault test then interrupts the ``new`` run at a seeded
"write event" — an ``open`` for writing, a ``mkdir``, a ``rename`` or ``replace`` — and checks
that the path holds the complete old output or the complete new one (:func:`snapshot`).
"""

from __future__ import annotations

import builtins
import contextlib
import hashlib
import io
import os
import shutil
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import yaml
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases

runner = CliRunner()


@dataclass(frozen=True)
class Command:
    """A writing command: its name, the output's name and the arguments of each run."""

    name: str
    output: str
    old: tuple[str, ...]
    new: tuple[str, ...]

    def args(self, which: str, target: Path) -> list[str]:
        """The command line of run ``which`` (``old`` or ``new``) writing ``target``."""
        return [self.name, *getattr(self, which), "-o", str(target)]


def tiny_pf_case(folder: Path) -> Path:
    """``pf-path3`` made small (20 particles, 8 steps, 2 runs) and without expectations."""
    data = yaml.safe_load(bundled_cases()["pf-path3"].read_text())
    data["name"] = "pf-tiny"
    data["pf"].update(particles=20, share=3, steps=8, runs=2)
    data.pop("expect", None)
    path = folder / "pf-tiny.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def commands(folder: Path) -> dict[str, Command]:
    """The five writing commands, small enough for about a second a run (``folder`` holds the
    tiny pf case)."""
    pf = str(tiny_pf_case(folder))
    serial = ("--workers", "1")
    report = ["ch5-example-1-wg", "pursuit-table1-n1", *serial]
    report += ["--only", "seed000.def5.2.4.certified", "--only", "seed003.thm2.certified"]
    pursuit = ("pursuit-table1-n1", *serial)
    return {
        "report": Command("report", "report", (*report, "--seed", "1"), tuple(report)),
        "simulate": Command(
            "simulate", "sim", (*pursuit, "--steps", "100"), (*pursuit, "--steps", "200")
        ),
        "pf": Command("pf", "pf", (pf, "--seed", "1", *serial), (pf, "--seed", "2", *serial)),
        "sweep": Command(
            "sweep",
            "sweep",
            (*pursuit, "--param", "k_gamma=100", "--steps", "50"),
            (*pursuit, "--param", "k_gamma=100,200", "--steps", "50"),
        ),
        "certify": Command("certify", "cert.json", ("fig43-case-d",), ("ch5-example-1-wg",)),
    }


def snapshot(path: Path) -> dict[str, str]:
    """SHA-256 of every file under ``path`` (or of the file ``path``) by relative name;
    ``timings.json`` (wall times) only as present. Empty if nothing is there."""
    if path.is_file():
        return {"": hashlib.sha256(path.read_bytes()).hexdigest()}
    found = {}
    for file in sorted(path.rglob("*")) if path.is_dir() else []:
        if file.is_file():
            name = file.relative_to(path).as_posix()
            digest = hashlib.sha256(file.read_bytes()).hexdigest()
            found[name] = "present" if name == "timings.json" else digest
    return found


def restore(copy: Path, target: Path) -> None:
    """Put the saved ``copy`` of an output back at ``target``."""
    if target.is_dir():
        shutil.rmtree(target)
    elif target.exists():
        target.unlink()
    if copy.is_dir():
        shutil.copytree(copy, target)
    else:
        shutil.copyfile(copy, target)


def siblings(target: Path) -> list[str]:
    """Names left beside ``target`` by the writer (staging, aside, temporary)."""
    return sorted(p.name for p in target.parent.iterdir() if ".trackcert-" in p.name)


@contextlib.contextmanager
def write_events(on_event: Callable[[int, str], None]) -> Iterator[list[str]]:
    """Call ``on_event(k, what)`` before the k-th write event (1-based) of the block: an
    ``open`` for writing, ``os.mkdir``, ``os.rename`` or ``os.replace``. Yields the list of
    events seen."""
    seen: list[str] = []
    real = {"open": builtins.open, "mkdir": os.mkdir, "rename": os.rename, "replace": os.replace}

    def event(what: str) -> None:
        seen.append(what)
        on_event(len(seen), what)

    def opened(file, mode="r", *args, **kwargs):
        if any(c in mode for c in "wxa+"):
            event(f"open {file}")
        return real["open"](file, mode, *args, **kwargs)

    def wrap(name: str) -> Callable:
        def call(*args, **kwargs):
            event(f"{name} {args[0]}")
            return real[name](*args, **kwargs)

        return call

    patches = [(builtins, "open", opened), (io, "open", opened)]
    patches += [(os, name, wrap(name)) for name in ("mkdir", "rename", "replace")]
    try:
        for module, name, value in patches:
            setattr(module, name, value)
        yield seen
    finally:
        builtins.open = io.open = real["open"]
        os.mkdir, os.rename, os.replace = real["mkdir"], real["rename"], real["replace"]


def run(args: list[str]):
    """``trackcert ARGS`` in this process (CliRunner)."""
    return runner.invoke(app, args)


def run_forked(args: list[str], on_event: Callable[[int, str], None], log: Path) -> int:
    """``trackcert ARGS`` in a forked child whose write events call ``on_event``; returns the
    child's wait status (``os.waitstatus_to_exitcode``: negative for a signal). The child's
    output and any exception go to ``log``."""
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        code = 99
        try:
            with write_events(on_event):
                result = run(args)
            error = result.exception
            unhandled = error is not None and not isinstance(error, SystemExit)
            log.write_text(result.output + (f"Traceback: {error!r}" if unhandled else ""))
            code = result.exit_code
        finally:
            os._exit(code)
    _, status = os.waitpid(pid, 0)
    return os.waitstatus_to_exitcode(status)
