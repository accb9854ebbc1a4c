"""Start-up CPU of the command line (issue 28 item 2), against the old import path in the same run.

Run from the repository root: ``python -m benchmarks.bench_startup [--repeat 3]``.

For each command (a one-step ``simulate`` of each simulated kind, ``dkf ch5-example-1-wg``,
``--help``) it measures the CPU seconds (user + system, best of ``--repeat``) of the whole
process twice:

* ``now``: ``trackcert …`` as a user runs it (the entry point in a fresh interpreter);
* ``old``: the same command in a process that first imports the modules the old code path
  (commit 0af1f31) imported for that command and today's does not (:data:`OLD_EAGER`, listed
  by comparing ``sys.modules`` after each command on both revisions): scipy's sparse graph
  routines through ``theory.core.network``, python-flint through ``theory.tdoa.geometry.crb``,
  python-control through ``theory.consensus.conditions``, pyplot through
  ``theory.consensus.kalman_filter``.

It prints both and the ratio old/now, and the floor: a process importing only what every
command needs (typer, rich, numpy). No assertion: the numbers are the result; the target is
``simulate`` of a one-step run ≤ 0.4 s of CPU.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile

OLD_EAGER: dict[str, tuple[str, ...]] = {
    "--help": (),
    "simulate pursuit-table1-n3 (1 step)": (),  # seed 003's ISS needs them still
    "simulate sim-ch4-fixed-b0 (1 step)": ("scipy.sparse.csgraph", "flint", "proofs_check.linalg"),
    "simulate ch5-example-1-wg (1 step)": ("matplotlib.pyplot",),
    "dkf ch5-example-1-wg": ("control", "matplotlib.pyplot"),
}
"""Per command: what the old code path imported on top of today's (``sys.modules`` compared)."""

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
            old = cpu_seconds(entry(OLD_EAGER[label]), argv, args.repeat)
            now = cpu_seconds(entry(()), argv, args.repeat)
            print(f"{label:40} {old:6.2f}s {now:6.2f}s {old / now:8.2f}")


if __name__ == "__main__":
    main()
