"""Start-up CPU of the command line (issue 28 item 2), against the old code path in the same run.

Run from the repository root: ``python -m benchmarks.bench_startup [--repeat 5]``.

For each command (a one-step ``simulate`` of each simulated kind, with and without figures,
the pursuit loop on each engine; ``simulate`` of a ``pf`` case with one run; ``dkf``;
``--help``) it measures the CPU seconds (user + system, best of ``--repeat``) of the whole
process twice:

* ``now``: ``trackcert …`` as a user runs it (the entry point in a fresh interpreter);
* ``old``: the same command as the old code path (commit b709bd7) ran it, reproduced by
  :data:`OLD`: the modules it imported and today's does not, and the settings that select its
  path — the pursuit loop on numba for any job (``TRACKCERT_ENGINE=numba``: numba imported and
  the cached kernels loaded, ~0.5 s), ``distributed`` imported by the engine's "am I a Dask
  worker?" question on every command with more than one worker.

It prints both, the ratio old/now and, for the one-step ``simulate`` rows, the target (≤ 0.4 s
of CPU) and whether it is met; then the floors: a process importing only what every command
imports (typer, which parses every option with pydantic; rich; numpy), that plus
``scipy.special`` (the χ² quantiles of every simulation's summary), and plus ``scipy.linalg``
(the model of every kind but a one-tracker pursuit). No assertion: the numbers are the
result.

Every process reads compiled bytecode as an installed package does (a private
``PYTHONPYCACHEPREFIX``, filled by one unmeasured run of each command first): with
``PYTHONDONTWRITEBYTECODE`` set and no ``__pycache__``, each process would also compile
trackcert's own modules (about 0.08 s), which no installed copy does.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
from typing import NamedTuple

TARGET = 0.4
"""CPU seconds of a one-step ``trackcert simulate`` (issue 28 item 2)."""


class Old(NamedTuple):
    """How the old code path ran a command: modules it imported on top of today's, settings."""

    preload: tuple[str, ...] = ()
    env: tuple[tuple[str, str], ...] = ()


NUMBA = (("TRACKCERT_ENGINE", "numba"),)
"""b709bd7 ran every pursuit job on the numba engine (import and cached kernels)."""

DASK = ("distributed",)
"""b709bd7 imported ``distributed`` to ask whether it ran on a Dask worker (workers > 1)."""

OLD: dict[str, Old] = {
    "--help": Old(),
    "simulate pursuit-table1-n3 (1 step)": Old(env=NUMBA),
    "simulate pursuit-table1-n3 (1 step, figures)": Old(env=NUMBA),
    "simulate pursuit-table1-n3 (1 step, numba engine)": Old(),
    "simulate pursuit-table1-n3 (1 step, numpy engine)": Old(),
    "simulate sim-ch4-fixed-b0 (1 step)": Old(),
    "simulate sim-ch4-fixed-b0 (1 step, figures)": Old(),
    "simulate ch5-example-1-wg (1 step)": Old(),
    "simulate pf-path3 (1 run)": Old(preload=DASK),
    "dkf ch5-example-1-wg": Old(),
}
"""Per command: what the old code path did that today's does not (``sys.modules`` compared)."""

FLOOR = ("typer", "rich.console", "numpy", "pydantic")
"""What every command imports (the command line itself; typer coerces options with pydantic)."""


class Command(NamedTuple):
    """A measured command: its arguments and the settings it runs with (both paths)."""

    argv: list[str]
    env: tuple[tuple[str, str], ...] = ()


def commands(folder: str) -> dict[str, Command]:
    """The measured commands, by label."""
    one = ["--steps", "1"]
    bare = [*one, "--no-figures"]
    return {
        "--help": Command(["--help"]),
        "simulate pursuit-table1-n3 (1 step)": Command(
            ["simulate", "pursuit-table1-n3", *bare, "-o", f"{folder}/p"]
        ),
        "simulate pursuit-table1-n3 (1 step, figures)": Command(
            ["simulate", "pursuit-table1-n3", *one, "-o", f"{folder}/pf"]
        ),
        "simulate pursuit-table1-n3 (1 step, numba engine)": Command(
            ["simulate", "pursuit-table1-n3", *bare, "-o", f"{folder}/pn"], NUMBA
        ),
        "simulate pursuit-table1-n3 (1 step, numpy engine)": Command(
            ["simulate", "pursuit-table1-n3", *bare, "-o", f"{folder}/pp"],
            (("TRACKCERT_ENGINE", "numpy"),),
        ),
        "simulate sim-ch4-fixed-b0 (1 step)": Command(
            ["simulate", "sim-ch4-fixed-b0", *bare, "-o", f"{folder}/t"]
        ),
        "simulate sim-ch4-fixed-b0 (1 step, figures)": Command(
            ["simulate", "sim-ch4-fixed-b0", *one, "-o", f"{folder}/tf"]
        ),
        "simulate ch5-example-1-wg (1 step)": Command(
            ["simulate", "ch5-example-1-wg", *bare, "-o", f"{folder}/d"]
        ),
        "simulate pf-path3 (1 run)": Command(
            ["simulate", "pf-path3", "--runs", "1", "--no-figures", "-o", f"{folder}/f"]
        ),
        "dkf ch5-example-1-wg": Command(["dkf", "ch5-example-1-wg"]),
    }


def child_environment(pycache: str) -> dict[str, str]:
    """This environment with bytecode read and written under ``pycache``, BLAS on one thread."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    return {**env, "PYTHONPYCACHEPREFIX": pycache, "OPENBLAS_NUM_THREADS": "1"}


def cpu_seconds(code: str, argv: list[str], env: dict[str, str], repeat: int) -> float:
    """Best CPU seconds (user + system) of ``python -c code argv…`` over ``repeat`` runs."""
    best = float("inf")
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(
            [sys.executable, "-c", code, *argv],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            check=False,
            env=env,
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


def target_column(label: str, now: float) -> str:
    """``≤ 0.4 s: met`` (or ``missed``) for a one-step ``simulate`` without figures, else blank."""
    if not label.startswith("simulate") or "figures" in label or "1 step" not in label:
        return ""
    return f"≤ {TARGET} s: {'met' if now <= TARGET else 'missed'}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per measurement (best kept)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(dir=".") as folder:
        env = child_environment(os.path.abspath(f"{folder}/pycache"))
        table = commands(folder)
        for command in table.values():  # fill the bytecode cache, unmeasured
            cpu_seconds(entry(()), command.argv, {**env, **dict(command.env)}, 1)
        floor = "".join(f"import {m}\n" for m in FLOOR)
        print(f"{'command':52} {'old':>7} {'now':>7} {'old/now':>8}  target")
        for label, command in table.items():
            old = OLD[label]
            old_env = {**env, **dict(command.env), **dict(old.env)}
            before = cpu_seconds(entry(old.preload), command.argv, old_env, args.repeat)
            now = cpu_seconds(entry(()), command.argv, {**env, **dict(command.env)}, args.repeat)
            ratio = before / now
            print(
                f"{label:52} {before:6.2f}s {now:6.2f}s {ratio:8.2f}  {target_column(label, now)}"
            )
        base = cpu_seconds(floor, [], env, args.repeat)
        special = floor + "import scipy.special\n"
        quantiles = cpu_seconds(special, [], env, args.repeat)
        linalg = cpu_seconds(special + "import scipy.linalg\n", [], env, args.repeat)
        imports = ", ".join(FLOOR)
        print(
            f"floor (import {imports}): {base:.2f} s CPU; with scipy.special (the χ² bands of "
            f"every simulation's summary) {quantiles:.2f} s; and scipy.linalg {linalg:.2f} s"
        )


if __name__ == "__main__":
    main()
