"""Speed of ``trackcert simulate`` on the seed 003 pursuit cases, with a same-run baseline.

For each case it prints

* the wall time of ``trackcert simulate CASE --seed 2`` in a fresh process (start-up, the 450 s
  run, files and figures) and its exit code, and the start-up alone
  (``python -c "import theory.cli"``);
* the time of one library run (:func:`theory.pursuit.simulation.run_pursuit_case`) with the
  vectorized vector field, and with the per-tracker field of the regression oracle
  (``tests/pursuit/dec_oracle.py``: every tracker through ``model.closed_loop_rates`` in a Python
  loop, the pre-vectorization form), both over ``--seconds`` of simulated time, and their ratio.

Every time is the best of ``--repeat`` runs; CPU time (user + system, this process and its
children) is printed beside wall time because the machine is shared. Usage:
``python benchmarks/bench_pursuit.py [--seconds 100] [--repeat 3] [--cases NAME ...]``
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests" / "pursuit"))

from dec_oracle import per_tracker_field  # noqa: E402

from theory.core.case_file import load_case  # noqa: E402
from theory.pursuit.closed_loop import build_loop, simulate_dec  # noqa: E402
from theory.pursuit.simulation import RECORD_INTERVAL, dec_arguments  # noqa: E402

CASES = (
    "pursuit-table1-n1",
    "pursuit-table1-n3",
    "pursuit-table2-n1",
    "pursuit-table2-n3",
    "pursuit-table2-n3-kgamma5",
)


def _best(function, repeat: int) -> tuple[float, float]:
    """Best wall time and best CPU time (this process and its children) of ``repeat`` calls."""
    walls, cpus = [], []
    for _ in range(repeat):
        start, cpu = time.perf_counter(), _cpu()
        function()
        walls.append(time.perf_counter() - start)
        cpus.append(_cpu() - cpu)
    return min(walls), min(cpus)


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def _cli(name: str, seed: int, codes: list[int]) -> None:
    """One ``trackcert simulate`` in a fresh process; its exit code is appended to ``codes`` (1
    when the run leaves the case's ``simulation_bounded`` expectation, e.g. a runaway)."""
    with tempfile.TemporaryDirectory() as folder:
        command = [sys.executable, "-m", "theory.cli", "simulate", name, "--seed", str(seed)]
        done = subprocess.run([*command, "-o", folder], cwd=ROOT, capture_output=True)
        codes.append(done.returncode)


def _startup() -> None:
    subprocess.run([sys.executable, "-c", "import theory.cli"], cwd=ROOT, check=True)


def _library_runs(name: str, seconds: float, repeat: int) -> tuple[float, float, int]:
    """Best CPU times of the vectorized and the per-tracker run, and the integration steps."""
    spec = load_case(name).spec
    arguments = dec_arguments(spec, round(seconds / RECORD_INTERVAL))
    loop = build_loop(
        arguments["settings"], arguments["paths"], arguments["in_neighbours"], spec.dim
    )
    oracle = per_tracker_field(loop, arguments["paths"], spec.controller)
    steps = simulate_dec(rng=np.random.default_rng(2), **arguments).steps
    _, fast = _best(lambda: simulate_dec(rng=np.random.default_rng(2), **arguments), repeat)
    _, slow = _best(
        lambda: simulate_dec(rng=np.random.default_rng(2), field=oracle, **arguments), repeat
    )
    return fast, slow, steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=100.0, help="simulated s per library run")
    parser.add_argument("--repeat", type=int, default=3, help="repetitions (best is printed)")
    parser.add_argument("--cases", nargs="*", default=list(CASES), help="bundled case names")
    parser.add_argument("--seed", type=int, default=2, help="--seed of trackcert simulate")
    args = parser.parse_args()
    wall, cpu = _best(_startup, args.repeat)
    print(f"start-up (import theory.cli): wall {wall:.2f} s, CPU {cpu:.2f} s")
    header = (
        f"{'case':28} {'wall (s)':>9} {'CPU (s)':>8} {'vectorized':>11} {'per-tracker':>12} "
        f"{'ratio':>6} {'steps':>7}"
    )
    print(
        f"trackcert simulate: 450 s, --seed {args.seed} (wall and CPU); library runs: CPU s over "
        f"{args.seconds:g} s simulated"
    )
    print(header + " exit")
    for name in args.cases:
        codes: list[int] = []
        wall, cpu = _best(lambda name=name, codes=codes: _cli(name, args.seed, codes), args.repeat)
        fast, slow, steps = _library_runs(name, args.seconds, args.repeat)
        row = f"{name:28} {wall:9.2f} {cpu:8.2f} {fast:11.3f} {slow:12.3f} {slow / fast:6.1f}"
        print(f"{row} {steps:7d} {codes[0]:4d}")


if __name__ == "__main__":
    main()
