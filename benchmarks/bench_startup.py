"""Start-up CPU of the command line (issue 28 item 2), against the old import path in the same run.

Run from the repository root: ``python -m benchmarks.bench_startup [--repeat 3]``.

For each command (a one-step ``simulate`` of each simulated kind, ``dkf ch5-example-1-wg``,
``--help``) it measures the CPU seconds (user + system, best of ``--repeat``) of the whole
process twice:

* ``now``: ``python -m theory.cli …`` as a user runs it;
* ``old``: the same command in a process that first imports what the old code imported eagerly
  whether the command used it or not (:data:`OLD_EAGER`: scipy's sparse graph routines through
  ``theory.core.network``, python-flint and ``proofs_check`` through ``theory.core.exact``,
  python-control through ``theory.consensus.conditions``, pyplot through
  ``theory.consensus.kalman_filter``), then runs the same entry point.

It prints both and the ratio old/now. The floor beside them is a process importing only what
every command needs (typer, rich, numpy). No assertion: the numbers are the result; the
target is ``simulate`` of a one-step run ≤ 0.4 s of CPU.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile

OLD_EAGER = (
    "scipy.sparse.csgraph",
    "flint",
    "proofs_check.linalg",
    "control",
    "matplotlib.pyplot",
)
"""Modules the old code path imported on every command that loaded their importer."""

FLOOR = ("typer", "rich.console", "numpy")
"""What every command imports (the command line itself)."""


def commands(folder: str) -> dict[str, list[str]]:
    """The measured commands, by label."""
    one_step = ["--steps", "1", "--no-figures", "-o"]
    return {
        "--help": ["--help"],
        "simulate pursuit-table1-n3 (1 step)": [
            "simulate", "pursuit-table1-n3", *one_step, f"{folder}/pursuit",
        ],
        "simulate sim-ch4-fixed-b0 (1 step)": [
            "simulate", "sim-ch4-fixed-b0", *one_step, f"{folder}/tdoa",
        ],
        "simulate ch5-example-1-wg (1 step)": [
            "simulate", "ch5-example-1-wg", *one_step, f"{folder}/dkf",
        ],
        "dkf ch5-example-1-wg": ["dkf", "ch5-example-1-wg"],
    }  # fmt: skip


def cpu_seconds(code: str, argv: list[str], repeat: int) -> float:
    """Best CPU seconds (user + system) of ``python -c code argv…`` over ``repeat`` runs."""
    best = float("inf")
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(
            [sys.executable, "-c", code, *argv],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            check=False,
            env={**os.environ, "OPENBLAS_NUM_THREADS": "1"},
        )
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        used = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        best = min(best, used)
    return best


def entry(preload: tuple[str, ...]) -> str:
    """A ``python -c`` program importing ``preload``, then running ``trackcert`` on ``argv``."""
    imports = "".join(f"import {name}\n" for name in preload)
    return (
        f"import sys\n{imports}sys.argv = ['trackcert', *sys.argv[1:]]\n"
        "from theory.cli import main\nmain()\n"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per measurement (best kept)")
    args = parser.parse_args()
    floor = cpu_seconds("".join(f"import {m}\n" for m in FLOOR), [], args.repeat)
    print(f"floor (import {', '.join(FLOOR)}): {floor:.2f} s CPU")
    print(f"{'command':40} {'old':>7} {'now':>7} {'old/now':>8}")
    with tempfile.TemporaryDirectory(dir=".") as folder:
        for label, argv in commands(folder).items():
            old = cpu_seconds(entry(OLD_EAGER), argv, args.repeat)
            now = cpu_seconds(entry(()), argv, args.repeat)
            print(f"{label:40} {old:6.2f}s {now:6.2f}s {old / now:8.2f}")


if __name__ == "__main__":
    main()
