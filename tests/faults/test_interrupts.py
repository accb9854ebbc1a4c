"""SIGINT, SIGTERM and SIGKILL at seeded points of each writing command's run over an existing
output: the exit code is in the contract, nothing is a traceback, and the output is the complete
old one or the complete new one (after :func:`theory.core.atomic_output.recover`, which every
writer runs first, settles what a SIGKILL left)."""

from __future__ import annotations

import os
import random
import signal

import pytest
from fault_commands import restore, run_forked, siblings, snapshot

from theory.core.atomic_output import recover
from theory.core.verdicts import interrupted_code

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork")

SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGKILL)


def _points(name: str, signum: int, events: int, last_rename: int) -> list[int]:
    """One seeded write event of the run, and for SIGINT and SIGKILL also the last rename (the
    one that puts the new output in place: for a folder, after the old one was moved aside)."""
    chosen = random.Random(f"{name}:{int(signum)}").randrange(1, events + 1)
    return [chosen] if signum == signal.SIGTERM else [chosen, last_rename]


@pytest.mark.parametrize("signum", SIGNALS, ids=lambda s: s.name)
@pytest.mark.parametrize("name", ["report", "simulate", "pf", "sweep", "certify"])
def test_an_interrupted_write_leaves_the_old_output_or_the_new_one(
    prepared, name, signum, tmp_path
) -> None:
    this = prepared[name]
    command, target, copy, old, new = this.command, this.target, this.copy, this.old, this.new
    events, last_rename = len(this.events), this.indices("rename", "replace")[-1]
    for k in _points(name, signum, events, last_rename):
        restore(copy, target)
        log = tmp_path / f"{k}.log"

        def interrupt(event: int, what: str, k=k) -> None:
            if event == k:
                os.kill(os.getpid(), signum)

        code = run_forked(command.args("new", target), interrupt, log)
        if signum == signal.SIGKILL:
            assert code == -signal.SIGKILL
            if k == last_rename and target.name != "cert.json":  # killed between the renames
                assert not target.exists() and siblings(target)
            recover(target)
        else:
            output = log.read_text()
            assert code == interrupted_code(signum), (k, output)
            assert "Traceback" not in output and f"interrupted by {signum.name}" in output
        found = snapshot(target)
        assert found in (old, new), f"{name} interrupted at write event {k} of {events}"
        assert siblings(target) == [], siblings(target)
