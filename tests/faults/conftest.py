"""Shared by the fault tests: each writing command's old and new outputs, made once."""

from __future__ import annotations

import signal
from dataclasses import dataclass
from pathlib import Path

import pytest
from fault_commands import Command, commands, restore, run, snapshot, write_events


@pytest.fixture(autouse=True)
def _sigint_raises():
    """SIGINT raises KeyboardInterrupt as at a terminal, also when pytest runs as a background job
    (which starts with SIGINT ignored, so Python installs no handler)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


@dataclass(frozen=True)
class Prepared:
    """One command over one output path: the old output saved in ``copy`` (restore it before
    each trial), both outputs' snapshots, and the write events of the new run."""

    command: Command
    target: Path
    copy: Path
    old: dict[str, str]
    new: dict[str, str]
    events: tuple[str, ...]

    def indices(self, *kinds: str) -> list[int]:
        """The 1-based indices of the new run's write events of these kinds (``open`` …)."""
        return [k for k, what in enumerate(self.events, 1) if what.startswith(kinds)]


@pytest.fixture(scope="session")
def prepared(tmp_path_factory) -> dict[str, Prepared]:
    folder = tmp_path_factory.mktemp("faults")
    found = {}
    for name, command in commands(folder).items():
        target = folder / command.output
        assert run(command.args("new", target)).exit_code in (0, 3)  # first-use writes (caches)
        with write_events(lambda k, what: None) as seen:
            assert run(command.args("new", target)).exit_code in (0, 3)
        new = snapshot(target)
        assert run(command.args("old", target)).exit_code in (0, 3)
        old = snapshot(target)
        assert old and new and old != new, name
        copy = folder / f"{command.output}.old-copy"
        restore(target, copy)
        found[name] = Prepared(command, target, copy, old, new, tuple(seen))
    return found
