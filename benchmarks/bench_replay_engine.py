"""Issue 28: where the compiled DEKF replay pays for loading its kernel (the rule
:data:`theory.pursuit.filter_metrics.REPLAY_MIN_STEPS`), measured in the same run.

For each Table case, two fresh processes (one per engine) simulate one 450 s run on the numba
engine (numba imported, as in any job the kernels run) and then call
:func:`~theory.pursuit.filter_metrics.dekf_metrics` twice on it. The first call pays what is
loaded once (SciPy's χ² quantiles on both engines, the replay's cached kernel on numba), the
second only the replay. Printed per case: the kernel's load (first − second call on numba, less
the same difference on NumPy), both engines' cost a filter step, and the break-even: the filter
steps from which the compiled replay, its load included, finishes first.

Usage: ``python benchmarks/bench_replay_engine.py [--repeat 3]``
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CASES = ("pursuit-table1-n1", "pursuit-table1-n3", "pursuit-table2-n1", "pursuit-table2-n3")
STEPS = 4500
"""Records of the run (450 s at 0.1 s): 225 filter steps at T_s = 2 s."""


def child(name: str, engine: str) -> None:
    """Print the replay's filter steps and the CPU seconds of two ``dekf_metrics`` calls."""
    sys.path.insert(0, str(ROOT))
    import numpy as np

    from theory.kinds import load_case
    from theory.pursuit.filter_metrics import dekf_metrics
    from theory.pursuit.simulation import dec_arguments, run_pursuit_case

    spec = load_case(name).spec
    run = run_pursuit_case(spec, np.random.default_rng(0), STEPS, engine="numba")
    arguments = dec_arguments(spec, STEPS)
    times = []
    for _ in range(2):
        start = time.process_time()
        dekf_metrics([run], arguments, engine=engine)
        times.append(time.process_time() - start)
    every = round(arguments["settings"].Ts / arguments["settings"].dt)
    print((len(run.times) - 1) // every, *times)


def measure(name: str, engine: str) -> tuple[int, float, float]:
    """(filter steps, first call, second call) of :func:`child` in a fresh process."""
    done = subprocess.run(
        [sys.executable, __file__, "--child", name, engine],
        capture_output=True, text=True, check=True, cwd=ROOT,
    )  # fmt: skip
    steps, first, second = done.stdout.split()
    return int(steps), float(first), float(second)


def main() -> None:
    """One row per Table case, best of ``--repeat`` processes per engine."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        return child(*args.child)
    print(
        f"{'case':20} {'steps':>5} {'load s':>7} {'numba µs':>9} {'numpy µs':>9} {'break-even':>10}"
    )
    for name in CASES:
        best = {}
        for engine in ("numba", "numpy"):
            rows = [measure(name, engine) for _ in range(args.repeat)]
            best[engine] = (rows[0][0], min(r[1] for r in rows), min(r[2] for r in rows))
        steps = best["numba"][0]
        load = (best["numba"][1] - best["numba"][2]) - (best["numpy"][1] - best["numpy"][2])
        compiled, reference = best["numba"][2] / steps, best["numpy"][2] / steps
        even = load / (reference - compiled) if reference > compiled else float("inf")
        print(
            f"{name:20} {steps:5d} {load:7.3f} {compiled * 1e6:9.1f} {reference * 1e6:9.1f} "
            f"{even:10.0f}"
        )
    print("CPU seconds; break-even = load / (NumPy − numba a step), in filter steps")


if __name__ == "__main__":
    main()
