"""Speed of the closed-loop simulation (seed 000 §4.4 scenario), with same-run baselines.

Prints, for the bundled case ``sim-ch4-fixed-b0``:

* time per run, pings/second and robot-integration steps/second (one worker);
* Monte Carlo throughput over all local cores against one worker (ratio);
* the vectorised agent controller against a per-agent Python loop (ratio).

The seed 003 three-tracker scenario is not implemented yet (see the issue's report).

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

from theory.case_file import load_case
from theory.sim.agents import linearizing_control
from theory.sim.runner import monte_carlo


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

    one = _timed(monte_carlo, spec, runs=1, seed=0, workers=1)
    print(f"§4.4 scenario, {args.steps} pings, N = {spec.n_agents}: {one:.2f} s per run")
    print(f"  {args.steps / one:.0f} pings/s, {fine_steps / one:.0f} RK4 steps/s (one worker)")

    cores = os.cpu_count() or 1
    serial = _timed(monte_carlo, spec, runs=args.runs, seed=0, workers=1)
    parallel = _timed(monte_carlo, spec, runs=args.runs, seed=0, workers=cores)
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


if __name__ == "__main__":
    main()
