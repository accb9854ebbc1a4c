"""A full disk while each writing command writes over an existing output: exit 4 (a fault, not a
verdict), one line naming the path and the reason, no traceback, the old output untouched and no
staging or temporary file left. The disk "fills" at a seeded write event (a patched writer); one
test also lets the kernel refuse the writes (``RLIMIT_FSIZE``)."""

from __future__ import annotations

import errno
import random
import resource
import signal
import subprocess
import sys

import pytest
from fault_commands import restore, run, siblings, snapshot, write_events

from theory.core.verdicts import EXIT_FAULT

COMMANDS = ["report", "simulate", "pf", "sweep", "certify"]


def _full(k: int):
    """From write event ``k`` on, creating a file or a folder fails (a rename needs no space)."""

    def fill(event: int, what: str) -> None:
        kind, path = what.split(" ", 1)
        if event >= k and kind in ("open", "mkdir"):
            raise OSError(errno.ENOSPC, "No space left on device", path)

    return fill


@pytest.mark.parametrize("name", COMMANDS)
def test_a_full_disk_is_exit_4_naming_the_path_and_leaves_the_old_output(prepared, name) -> None:
    this = prepared[name]
    command, target, copy, old, writes = (
        this.command, this.target, this.copy, this.old, this.indices("open", "mkdir")
    )
    rng = random.Random(f"disk:{name}")
    faulted_in_target = 0
    for k in sorted({writes[0], writes[-1], *rng.sample(writes, min(3, len(writes)))}):
        restore(copy, target)
        with write_events(_full(k)):
            done = run(command.args("new", target))
        assert done.exit_code == EXIT_FAULT, (k, done.output)
        assert done.exception is None or isinstance(done.exception, SystemExit)
        message = done.stderr.strip().splitlines()[-1]
        assert message.startswith("fault: ") and "No space left on device" in message, message
        assert ".trackcert-" not in message  # the user's path, never the staging folder's
        assert "Traceback" not in done.output
        assert snapshot(target) == old and siblings(target) == []
        faulted_in_target += f"could not write {target}" in message
    assert faulted_in_target  # some trial filled the disk inside the output itself


def _limit_file_size(size: int) -> None:  # pragma: no cover - runs in the child
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (size, size))


def test_the_kernel_refusing_a_write_is_exit_4(prepared) -> None:
    """``RLIMIT_FSIZE`` makes write(2) fail with EFBIG in whatever library writes (numpy's NPZ,
    matplotlib's PNG, the CSV writer): the same path as a full disk."""
    this = prepared["simulate"]
    command, target, copy, old = this.command, this.target, this.copy, this.old
    restore(copy, target)
    done = subprocess.run(
        [sys.executable, "-m", "theory.cli", *command.args("new", target)],
        capture_output=True,
        text=True,
        preexec_fn=lambda: _limit_file_size(4096),
        timeout=300,
        check=False,
    )
    assert done.returncode == EXIT_FAULT, done.stderr
    assert "fault: could not write" in done.stderr and "File too large" in done.stderr
    assert "Traceback" not in done.stderr + done.stdout
    assert snapshot(target) == old and siblings(target) == []
