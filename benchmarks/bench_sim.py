"""Speed of the closed-loop simulation (seed 000 §4.4 scenario), with same-run baselines.

Prints, for the bundled case ``sim-ch4-fixed-b0``:

* time per run, pings/second and robot-integration steps/second (one worker);
* Monte Carlo throughput over all local cores against one worker (ratio);
* the vectorised agent controller against a per-agent Python loop (ratio);
* the 12 runs of the ``seed000.sec4.4.b-tradeoff`` sweep in lock step against one by one
  (CPU time, ratio).

and for the seed 003 2-D three-tracker scenario (Table I, 4501 steps of 0.1 s, DEKF every 2 s):
time per run, steps/second, and Monte Carlo throughput over all local cores against one worker.

Usage: ``python benchmarks/bench_sim.py [--steps 100] [--runs 4]``
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from concurrent.futures import ProcessPoolExecutor

from theory.kinds import load_case
from theory.pursuit.closed_loop import DecSettings, simulate_dec
from theory.pursuit.dekf import table_target
from theory.sim.simulate import monte_carlo
from theory.tdoa.estimation.agents import linearizing_control
from theory.tdoa.estimation.scenario import run_tdoa_scenario, run_tdoa_scenarios
from theory.tdoa.estimation.simulation import B_SWEEP, SWEEP_MAX_STEPS, SWEEP_SEEDS


def _timed(function, *args, **kwargs) -> float:
    start = time.perf_counter()
    function(*args, **kwargs)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100, help="pings per run")
    parser.add_argument("--runs", type=int, default=4, help="Monte Carlo runs")
    args = parser.parse_args()
    spec = dataclasses.replace(load_case("sim-ch4-fixed-b0").spec, steps=args.steps)
    fine_steps = args.steps * spec.rounds * spec.substeps

    tdoa = {"simulate": run_tdoa_scenario, "seed": 0}
    one = _timed(monte_carlo, spec, runs=1, workers=1, **tdoa)
    print(f"§4.4 scenario, {args.steps} pings, N = {spec.n_agents}: {one:.2f} s per run")
    print(f"  {args.steps / one:.0f} pings/s, {fine_steps / one:.0f} RK4 steps/s (one worker)")

    cores = os.cpu_count() or 1
    serial = _timed(monte_carlo, spec, runs=args.runs, workers=1, **tdoa)
    parallel = _timed(monte_carlo, spec, runs=args.runs, workers=cores, **tdoa)
    print(
        f"Monte Carlo {args.runs} runs: {args.runs / serial:.2f} runs/s on 1 worker, "
        f"{args.runs / parallel:.2f} runs/s on {cores} workers (ratio {serial / parallel:.2f})"
    )

    rng = np.random.default_rng(0)
    states = rng.normal(size=(spec.n_agents, 9))
    states[:, 3] = 1.0
    target = rng.normal(size=(spec.n_agents, 3, 3))
    repeats = 2000
    vectorised = _timed(lambda: [linearizing_control(states, target, 0.5) for _ in range(repeats)])
    looped = _timed(
        lambda: [
            [linearizing_control(states[i : i + 1], target[i : i + 1], 0.5) for i in range(8)]
            for _ in range(repeats)
        ]
    )
    print(
        f"controller, {repeats} evaluations of {spec.n_agents} agents: vectorised "
        f"{vectorised * 1e6 / repeats:.0f} µs, per-agent loop {looped * 1e6 / repeats:.0f} µs "
        f"(ratio {looped / vectorised:.1f})"
    )
    bench_lock_step(spec)
    bench_dec(args.runs)


def _cpu(function, *args) -> float:
    start = time.process_time()
    function(*args)
    return time.process_time() - start


def bench_lock_step(spec) -> None:
    """The b-tradeoff sweep's runs, one by one against in lock step (CPU seconds, same run)."""
    specs = [dataclasses.replace(spec, b=b, steps=SWEEP_MAX_STEPS) for b in B_SWEEP]
    specs = [s for s in specs for _ in SWEEP_SEEDS]
    seeds = [seed for _ in B_SWEEP for seed in SWEEP_SEEDS]

    def solo() -> None:
        for s, seed in zip(specs, seeds, strict=True):
            run_tdoa_scenario(s, np.random.default_rng(seed))

    def together() -> None:
        run_tdoa_scenarios(specs, [np.random.default_rng(seed) for seed in seeds])

    one_by_one, lock_step = _cpu(solo), _cpu(together)
    print(
        f"b-tradeoff sweep, {len(specs)} runs of {SWEEP_MAX_STEPS} pings: one by one "
        f"{one_by_one:.2f} s CPU, lock step {lock_step:.2f} s CPU "
        f"(ratio {one_by_one / lock_step:.2f})"
    )


def _dec_run(seed: int) -> float:
    steps = 4500
    target = table_target("I", 0.1 * np.arange(steps + 1))
    start = target[0, :2] + np.array([[-40.0, -40.0], [-30.0, -45.0], [-45.0, -30.0]])
    x0 = np.concatenate([target[0, :2] + [5.0, -5.0], [0.0, 0.0]])
    run = simulate_dec(
        target, start, np.zeros(3), np.array([0.0, 1.0, 2.0]), [[1], [2], [0]], x0,
        10 * np.eye(4), steps, np.random.default_rng(seed), DecSettings(),
    )  # fmt: skip
    return float(run.localization_errors[-1].max())


def bench_dec(runs: int) -> None:
    """Seed 003 Table I, three trackers."""
    one = _timed(_dec_run, 0)
    print(f"seed 003 2-D, 3 trackers, 4501 steps: {one:.2f} s per run, {4501 / one:.0f} steps/s")
    cores = os.cpu_count() or 1
    serial = _timed(lambda: [_dec_run(s) for s in range(runs)])
    with ProcessPoolExecutor(max_workers=cores) as pool:
        parallel = _timed(lambda: list(pool.map(_dec_run, range(runs))))
    print(
        f"  Monte Carlo {runs} runs: {runs / serial:.2f} runs/s on 1 worker, "
        f"{runs / parallel:.2f} runs/s on {cores} workers (ratio {serial / parallel:.2f})"
    )


if __name__ == "__main__":
    main()
