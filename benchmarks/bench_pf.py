"""Time per iteration of the distributed TDOA PF (P = 1000) next to the averaged EKF's.

Seed 002 §4.3.2 reports 2.73e-1 s per PF iteration and 2.68e-4 s per EKF iteration (MATLAB,
P = 1000, three nodes, complete graph, top 5 % shared). The target here is < 5 ms per PF
iteration (all nodes, vectorised numpy). Also the online learner's wrapped-Cauchy ML fit
(seed 002 §3.2.2), damped Newton against the BFGS it replaced, CPU time in the same run.

And the Monte Carlo of every bundled ``kind: pf`` case (CPU seconds per run, the learned
model, which refits every node at every step) on the ``"numpy"`` engine (the NumPy reference
fits, the path before the kernels) against the ``"numba"`` engine
(:mod:`theory.particle.kernels`), in the same run, plus eq. (3.9) per step as
:func:`theory.tdoa.model.range_differences` against the filter's :func:`particle_tdoa`.
Run from the repository root: ``python -m benchmarks.bench_pf [RUNS]``.
"""

from __future__ import annotations

import sys
import time
import timeit

import numpy as np

from theory.core.case_file import bundled_cases
from theory.kinds import load_case
from theory.particle import dcrw
from theory.particle.case import DcrwParams, Model, PfConfig, PfNetwork
from theory.particle.dcrw import sample_wrapped_cauchy
from theory.particle.experiments import monte_carlo
from theory.particle.filter import DcrwMotion, initial_state, measure, particle_tdoa, pf_step
from theory.particle.pf_vs_ekf import EkfConfig, consensus_weights, ekf_step
from theory.tdoa.model import cv_discrete, range_differences

TARGET_S = 5e-3
THESIS_PF_S, THESIS_EKF_S = 2.73e-1, 2.68e-4


def _network(n: int) -> PfNetwork:
    angles = np.pi / 2 + 2 * np.pi * np.arange(n) / n
    nodes = 40.0 * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    hears = ~np.eye(n, dtype=bool)
    return PfNetwork(nodes, hears, tuple(range(n)))


def _best_of(function, repeat: int = 7, number: int = 50) -> float:
    return min(timeit.repeat(function, repeat=repeat, number=number)) / number


def time_pf(network: PfNetwork, y: np.ndarray) -> float:
    """Seconds for one :func:`pf_step` of every node (P = 1000, m = 50, the thesis's 5 %)."""
    rng = np.random.default_rng(0)
    n = len(network.filters)
    config = PfConfig(particles=1000, share=50, sigma=1.0)
    state = initial_state(n, 1000, np.array([[-50, 50], [-50, 50]]), rng)
    motion = DcrwMotion(DcrwParams(0.0, 0.7, 2.0, 3.0))
    return _best_of(lambda: pf_step(state, y, network, config, motion, rng))


def time_ekf(network: PfNetwork, y: np.ndarray) -> float:
    """Seconds for one averaged-EKF iteration of every node (correct, average, predict)."""
    n = len(network.filters)
    A, B = cv_discrete(1.0, dim=2)
    config = EkfConfig()
    Q = B @ B.T * config.accel_sigma**2
    W = consensus_weights(network)
    x = np.hstack([np.random.default_rng(1).uniform(-10, 10, (n, 2)), np.zeros((n, 2))])
    P = np.broadcast_to(np.eye(4) * 100.0, (n, 4, 4)).copy()

    def iteration() -> None:
        x_bar, P_bar = ekf_step(x, P, y, network, config, W)
        _ = x_bar @ A.T, A @ P_bar @ A.T + Q

    return _best_of(iteration)


def time_wrapped_cauchy_fits(samples: int = 300) -> tuple[float, float]:
    """CPU seconds per wrapped-Cauchy ML fit, (Newton, BFGS), over ``samples`` samples of 95
    turning angles (the learner's largest) from one moment start each."""
    rng = np.random.default_rng(3)
    angles = [sample_wrapped_cauchy(rng, 0.0, g, (95,)) for g in rng.uniform(0, 0.9, samples)]
    problems = [(z, dcrw._moment_start(z)) for z in (np.exp(1j * phi) for phi in angles)]
    seconds = []
    for fit in (dcrw._wrapped_cauchy_newton, dcrw._wrapped_cauchy_bfgs):
        start = time.process_time()
        for z, psi0 in problems:
            fit(z, psi0)
        seconds.append((time.process_time() - start) / samples)
    return seconds[0], seconds[1]


def _cpu_per_run(spec, runs: int, engine: str) -> float:
    """CPU seconds per run of the learned model's Monte Carlo on ``engine``."""
    start = time.process_time()
    monte_carlo(spec, runs=runs, model=Model.LEARNED, engine=engine)
    return (time.process_time() - start) / runs


def time_monte_carlo(runs: int) -> None:
    """Print CPU per run of every bundled pf case, NumPy reference fits against the kernel,
    the two engines alternated (best of two each) so that load affects both alike."""
    names = sorted(n for n in bundled_cases() if n.startswith("pf-") and "tdoa" not in n)
    monte_carlo(load_case(names[0]).spec, runs=1, model=Model.LEARNED, engine="numba")  # compile
    print(f"{'case':>22} {'numpy s/run':>12} {'numba s/run':>12} {'numpy/numba':>12}")
    for name in names:
        spec = load_case(name).spec
        seconds = {"numpy": [], "numba": []}
        for _ in range(2):
            for engine, times in seconds.items():
                times.append(_cpu_per_run(spec, runs, engine))
        old, new = min(seconds["numpy"]), min(seconds["numba"])
        print(f"{name:>22} {old:>12.4f} {new:>12.4f} {old / new:>12.2f}")


def time_tdoa_model() -> tuple[float, float]:
    """Seconds per eq. (3.9) of a filter step (3 nodes × 100 particles): the shared TDOA model's
    ``range_differences`` and the filter's ``particle_tdoa`` (the same numbers)."""
    network = load_case("pf-learning").spec.network
    positions = np.random.default_rng(5).uniform(-60, 60, (len(network.filters), 100, 2))
    filters = np.asarray(network.filters)[:, None]
    old = _best_of(lambda: range_differences(positions, network.nodes, filters))
    return old, _best_of(lambda: particle_tdoa(positions, network))


def main() -> None:
    """Print PF and EKF seconds per iteration for 3, 4 and 5 nodes (complete graphs)."""
    header = ("nodes", "PF s/iter", "EKF s/iter", "PF/EKF", "PF/target", "thesis/PF")
    print(" ".join(f"{h:>11}" for h in header))
    for n in (3, 4, 5):
        network = _network(n)
        y = measure(np.array([3.0, -4.0]), network, 1.0, np.random.default_rng(2))
        pf, ekf = time_pf(network, y), time_ekf(network, y)
        row = (
            f"{n}",
            f"{pf:.3e}",
            f"{ekf:.3e}",
            f"{pf / ekf:.1f}",
            f"{pf / TARGET_S:.2f}",
            f"{THESIS_PF_S / pf:.0f}",
        )
        print(" ".join(f"{v:>11}" for v in row))
    print(
        f"target: PF < {TARGET_S:g} s per iteration (PF/target < 1); thesis (MATLAB, 3 nodes): "
        f"PF {THESIS_PF_S:g} s, EKF {THESIS_EKF_S:g} s, ratio {THESIS_PF_S / THESIS_EKF_S:.0f}"
    )
    newton, bfgs = time_wrapped_cauchy_fits()
    print(
        f"wrapped-Cauchy ML fit (95 angles): Newton {newton:.3e} s, BFGS {bfgs:.3e} s CPU, "
        f"BFGS/Newton {bfgs / newton:.1f}"
    )
    old, new = time_tdoa_model()
    print(
        f"eq. (3.9) per step: range_differences {old:.2e} s, "
        f"particle_tdoa {new:.2e} s, {old / new:.1f}x"
    )
    time_monte_carlo(int(sys.argv[1]) if len(sys.argv) > 1 else 10)


if __name__ == "__main__":
    main()
