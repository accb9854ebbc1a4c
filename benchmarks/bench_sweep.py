"""Speed of ``trackcert sweep``: a 1,000-point sweep serially and on a 2-worker LocalCluster.

Issue 16 target: the 2-worker sweep within 1.1× of the ideal (serial time / 2). The sweep is the
issue's own example on a cheap case: ``pursuit-table1-n3`` (seed 003 Table I, 2-D, three
trackers), ``k_gamma=1:400:log100`` × ``seed=0:10`` = 1,000 points, each judged by
``trackcert iss``'s analysis and simulated for ``--steps`` records of 0.1 s (one run).

Prints serial and parallel wall time, the ideal (serial / 2) and the ratio parallel / ideal;
beside them the CPU time of this process and of the whole machine during the run
(``psutil.cpu_times``: the LocalCluster's workers are forked by a forkserver, not this process's
waited children, so ``RUSAGE_CHILDREN`` misses them; on a quiet machine the machine's CPU is this
process's and its workers'), since the machine may be shared, the cluster's start-up cost (a 2-point
sweep), and whether the two sweeps' rows are identical. Points run in batches
(:data:`theory.sweep.run.TASKS_PER_WORKER` tasks per worker, each a stride of the grid), so
Dask's per-task overhead is paid per batch, not per point.

Usage: ``python benchmarks/bench_sweep.py [--steps 10] [--gains 100] [--seeds 10] [--workers 2]``
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import psutil

from theory.sweep.run import TASKS_PER_WORKER, sweep_case

CASE = "pursuit-table1-n3"


def _machine_cpu() -> float:
    """CPU seconds every process of the machine has used (user + system, all cores)."""
    times = psutil.cpu_times()
    return times.user + times.system


def _timed_sweep(params: list[str], steps: int, workers: int):
    """(sweep, wall seconds, CPU of this process, CPU of the whole machine)."""
    cpu, machine, wall = time.process_time(), _machine_cpu(), time.perf_counter()
    result = sweep_case(CASE, params, steps=steps, workers=workers)
    wall = time.perf_counter() - wall
    return result, wall, time.process_time() - cpu, _machine_cpu() - machine


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=10, help="0.1 s records simulated per point")
    parser.add_argument("--gains", type=int, default=100, help="k_gamma values (log-spaced)")
    parser.add_argument("--seeds", type=int, default=10, help="seeds per gain")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster workers")
    args = parser.parse_args()
    params = [f"k_gamma=1:400:log{args.gains}", f"seed=0:{args.seeds}"]
    points = args.gains * args.seeds
    print(f"{CASE}: {' × '.join(params)} = {points} points, {args.steps} steps each")
    print(
        f"batches: {TASKS_PER_WORKER} tasks per worker "
        f"({points / (TASKS_PER_WORKER * args.workers):.1f} points per task)"
    )

    _, startup, _, _ = _timed_sweep(["k_gamma=1,2"], args.steps, args.workers)
    serial, s_wall, s_cpu, _ = _timed_sweep(params, args.steps, 1)
    parallel, p_wall, p_main, p_machine = _timed_sweep(params, args.steps, args.workers)
    p_workers = p_machine - p_main
    ideal = s_wall / args.workers

    print(
        f"serial (workers=1):     {s_wall:8.2f} s wall, {s_cpu:8.2f} s CPU "
        f"({s_cpu / points * 1e3:.1f} ms CPU per point)"
    )
    print(
        f"parallel (workers={args.workers}):   {p_wall:8.2f} s wall, {p_main:8.2f} s CPU here + "
        f"{p_workers:.2f} s CPU elsewhere on the machine (the workers)"
    )
    print(f"ideal (serial / {args.workers}):     {ideal:8.2f} s")
    print(f"ratio parallel / ideal: {p_wall / ideal:8.2f}   (target ≤ 1.10)")
    print(
        f"  without the cluster's start-up (parallel − 2-point sweep): "
        f"{(p_wall - startup) / ideal:.2f}"
    )
    print(
        f"CPU: workers' CPU / serial CPU = {p_workers / s_cpu:.2f} (work added by going parallel); "
        f"ideal from CPU = serial CPU / {args.workers} = {s_cpu / args.workers:.2f} s"
    )
    print(f"cluster start-up + 2-point sweep: {startup:.2f} s wall")
    same = serial.to_json() == parallel.to_json()
    print(f"rows identical serial vs parallel: {same}")
    if not same:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
