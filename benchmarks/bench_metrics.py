"""Cost of the filter metrics (NEES/NIS bands, OSPA/GOSPA; theory/core/consistency.py) against
the simulation they summarize, in the same run.

For each simulated filter — the averaged EKF (``sim-ch4-fixed-b0``), the consensus KF
(``ch5-example-1-wg``), the DEKF (``pursuit-table1-n3``, replayed on the recorded geometry) and
the particle filter (``pf-topology-a``) — prints the CPU time of the runs and of their metrics,
and the ratio metrics / runs. Target: every ratio ≤ 0.25 (the metrics never cost more than a
quarter of the runs they describe).

Usage: ``python benchmarks/bench_metrics.py [--runs 4]``
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from theory.consensus.kalman_filter import consensus_kf_metrics, run_dkf_case
from theory.kinds import load_case
from theory.particle.experiments import monte_carlo as pf_monte_carlo
from theory.particle.experiments import pf_metrics
from theory.pursuit.filter_metrics import dekf_metrics
from theory.pursuit.simulation import dec_arguments, run_pursuit_case
from theory.tdoa.estimation.scenario import run_tdoa_scenario
from theory.tdoa.estimation.simulation import tdoa_filter_metrics

TARGET = 0.25
"""Largest acceptable CPU-time ratio of the metrics to the runs."""


def _cpu(function, *args, **kwargs) -> tuple[float, object]:
    start = time.process_time()
    result = function(*args, **kwargs)
    return time.process_time() - start, result


def _report(name: str, runs_time: float, metrics_time: float) -> bool:
    ratio = metrics_time / runs_time
    verdict = "meets" if ratio <= TARGET else "MISSES"
    print(
        f"{name}: runs {runs_time:.2f} s CPU, metrics {metrics_time:.3f} s CPU, "
        f"ratio {ratio:.3f} ({verdict} the target ≤ {TARGET})"
    )
    return ratio <= TARGET


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=4, help="Monte Carlo runs per filter")
    args = parser.parse_args()
    seeds = [np.random.default_rng(s) for s in range(args.runs)]
    results = []

    tdoa = dataclasses.replace(load_case("sim-ch4-fixed-b0").spec, steps=60)
    runs_time, runs = _cpu(lambda: [run_tdoa_scenario(tdoa, rng) for rng in seeds])
    metrics_time, _ = _cpu(tdoa_filter_metrics, runs)
    results.append(_report("averaged EKF, 60 pings", runs_time, metrics_time))

    seeds = [np.random.default_rng(s) for s in range(args.runs)]
    dkf = load_case("ch5-example-1-wg").spec
    runs_time, runs = _cpu(lambda: [run_dkf_case(dkf, rng, 400) for rng in seeds])
    metrics_time, _ = _cpu(consensus_kf_metrics, dkf.C, runs)
    results.append(_report("consensus KF, 400 steps", runs_time, metrics_time))

    seeds = [np.random.default_rng(s) for s in range(args.runs)]
    pursuit = load_case("pursuit-table1-n3").spec
    runs_time, runs = _cpu(lambda: [run_pursuit_case(pursuit, rng, 1500) for rng in seeds])
    arguments = dec_arguments(pursuit, 1500)
    metrics_time, _ = _cpu(dekf_metrics, runs, arguments)
    results.append(_report("DEKF replay, 150 s", runs_time, metrics_time))

    pf = load_case("pf-topology-a").spec
    runs_time, mc = _cpu(pf_monte_carlo, pf, runs=args.runs)
    metrics_time, _ = _cpu(pf_metrics, mc, pf)
    results.append(_report("particle filter, 100 steps", runs_time, metrics_time))
    print("all ratios meet the target" if all(results) else "some ratio misses the target")


if __name__ == "__main__":
    main()
