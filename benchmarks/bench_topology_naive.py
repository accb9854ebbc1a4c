"""Benchmark: the topology library on random geometric networks vs the naive full matrix.

Run from the repository root:
``python -m benchmarks.bench_topology_naive [--seed S] [--naive-max N]``
(``benchmarks/bench_topology.py`` times the command on 100 … 10,000 agents).

For N = 10, 100, 1000 agents placed uniformly in a cube with a communication radius giving a
mean degree of about 8, it times

* ``verdicts``: per-agent ranks of O_i, σ_min, heuristic, mirror, global uniqueness and the
  detectability of the networked pair (``analyze_topology(..., network_rank=False)``), which
  should grow near-linearly in N + E;
* ``checker``: the same plus the rank of the whole networked pair from the spectrum of W
  (``analyze_topology``), an eigen-decomposition per component, cubic in its size;
* ``naive``: forming O = [D_H; D_H (W⊗A); …; D_H (W⊗A)^{6N−1}] (seed 000 eq. (4.36)) with numpy
  and ranking it by SVD (``numpy.linalg.matrix_rank``), for N up to ``--naive-max``; beyond, its
  time is extrapolated with the power law fitted (least squares in log-log) to the three largest
  sizes measured, and its memory is stated exactly.

It prints every time and the ratios naive/checker and naive/verdicts. No assertion: the numbers
are the result. Each timing is the best of ``--repeat`` runs.

BLAS runs single-threaded (``OPENBLAS_NUM_THREADS=1`` etc., unless already set) for both methods:
on a shared machine multi-threaded BLAS spends most of its time waiting (a 100 × 100 ``eigh``
took 0.2 s threaded vs 2 ms single-threaded on the development machine).
"""

from __future__ import annotations

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import argparse  # noqa: E402  (BLAS threads must be fixed before numpy loads)
import time  # noqa: E402

import numpy as np  # noqa: E402

from theory.core.network import adjacency_from_range  # noqa: E402
from theory.core.sparse_weights import SparseWeights  # noqa: E402
from theory.tdoa.case import TdoaSpec  # noqa: E402
from theory.tdoa.model import cv_discrete, unit_directions  # noqa: E402
from theory.tdoa.observability.topology import analyze_topology  # noqa: E402

MEAN_DEGREE = 8.0
SIDE = 100.0


def random_geometric_scene(n: int, rng: np.random.Generator) -> TdoaSpec:
    """N agents uniform in a cube of side 100, radius for mean degree ≈ 8, target inside."""
    positions = rng.uniform(0, SIDE, size=(n, 3))
    radius = SIDE * (3 * MEAN_DEGREE / (4 * np.pi * max(n - 1, 1))) ** (1 / 3)
    hears = adjacency_from_range(positions, radius)
    target = rng.uniform(0.25 * SIDE, 0.75 * SIDE, size=3)
    return TdoaSpec(
        1.0,
        3,
        positions[None],
        target[None],
        (SparseWeights.named(n, *np.nonzero(hears), "metropolis"),),
        "metropolis",
        False,
        radius,
    )


def naive_rank(spec: TdoaSpec) -> int:
    """Form the whole observability matrix of (W ⊗ A, D_H) with numpy and rank it."""
    n, dim = spec.n_agents, spec.dim
    A, _ = cv_discrete(spec.T, dim)
    WA = np.kron(spec.weights[0], A)
    units = unit_directions(spec.target[0], spec.agents[0])
    agent, other = np.nonzero(spec.hears[0])
    D_H = np.zeros((agent.size, 2 * dim * n))
    for row, (i, j) in enumerate(zip(agent, other, strict=True)):
        D_H[row, 2 * dim * i : 2 * dim * i + dim] = units[i] - units[j]
    blocks, block = [], D_H
    for _ in range(2 * dim * n):
        blocks.append(block)
        block = block @ WA
    return int(np.linalg.matrix_rank(np.vstack(blocks)))


def best_time(function, repeat: int) -> tuple[float, object]:
    best, value = np.inf, None
    for _ in range(repeat):
        start = time.perf_counter()
        value = function()
        best = min(best, time.perf_counter() - start)
    return best, value


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=20261122)
    parser.add_argument("--naive-max", type=int, default=40)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    threads = os.environ["OPENBLAS_NUM_THREADS"]
    print(
        f"seed {args.seed}; mean degree ≈ {MEAN_DEGREE}; best of {args.repeat} runs; "
        f"OPENBLAS_NUM_THREADS={threads}\n"
    )

    naive_sizes = [n for n in (5, 10, 15, 20, 30, 40, 50, 60) if n <= args.naive_max]
    naive_times = {}
    print("naive: form O (6N columns, 6N·2E rows) and rank it by SVD")
    for n in naive_sizes:
        spec = random_geometric_scene(n, rng)
        seconds, rank = best_time(lambda spec=spec: naive_rank(spec), 1 if n > 20 else args.repeat)
        checked = analyze_topology(spec).network.rank
        naive_times[n] = seconds
        rows = 6 * n * int(spec.hears[0].sum())
        print(f"  N={n:5d}  O is {rows}×{6 * n}  {seconds:9.4f} s  rank {rank} (checker {checked})")
    sizes = sorted(naive_times)[-3:]
    slope, intercept = np.polyfit(np.log(sizes), np.log([naive_times[n] for n in sizes]), 1)
    print(f"  fitted naive time ∝ N^{slope:.2f} on N = {sizes} (theory: ~N^4 for SVD of O)\n")

    print(
        f"{'N':>6} {'E':>7} {'verdicts s':>11} {'checker s':>10} {'naive s':>12} "
        f"{'naive/checker':>14} {'naive/verdicts':>15} {'verdicts µs/(N+E)':>18}"
    )
    for n in (10, 100, 1000):
        spec = random_geometric_scene(n, rng)
        edges = int(spec.hears[0].sum()) // 2
        t_fast, fast = best_time(
            lambda spec=spec: analyze_topology(spec, network_rank=False), args.repeat
        )
        t_full, _ = best_time(lambda spec=spec: analyze_topology(spec), args.repeat)
        if n in naive_times:
            naive, label = naive_times[n], f"{naive_times[n]:.4g}"
        else:
            naive = float(np.exp(intercept) * n**slope)
            label = f"~{naive:.3g}*"
        per = 1e6 * t_fast / (n + edges)
        ok = sum(a.localizes for a in fast.agents)
        print(
            f"{n:6d} {edges:7d} {t_fast:11.4f} {t_full:10.4f} {label:>12} "
            f"{naive / t_full:14.3g} {naive / t_fast:15.3g} {per:18.1f}   ({ok}/{n} localize)"
        )
        if n not in naive_times:
            gigabytes = 8 * (6 * n * 2 * edges) * (6 * n) / 1e9
            print(f"{'':6} * extrapolated; the naive O would need {gigabytes:,.1f} GB")


if __name__ == "__main__":
    main()
