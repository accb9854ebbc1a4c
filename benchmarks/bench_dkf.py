"""LMI decision time of S-detectability vs network size: clarabel against SCS in the same run.

Issue 4 item 10. Systems: ``A`` random with spectral radius 1.2 (unstable), each agent measures
one random row (``p_i = 1``), so no agent can estimate alone; networks: a directed ring with
self-weight 0.3, and a random strongly connected digraph (ring plus random chords, density 0.1).
Target: N = 50, n = 6 under 60 s with the better solver. Prints a table; the baseline of each row
is clarabel's time in the same run (ratio = SCS / clarabel). Run:
``python -m benchmarks.bench_dkf [--quick] [--seed 0]`` from the repository root.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from theory.consensus.s_detectability import decide_s_detectability

ROW = "{:7} {:>3} {:>2} {:>9} {:>8} {:>9} {:>8} {:>6}"


def system(rng: np.random.Generator, n: int, N: int) -> tuple[np.ndarray, list[np.ndarray]]:
    A = rng.normal(size=(n, n))
    A *= 1.2 / max(abs(np.linalg.eigvals(A)))
    return A, [rng.normal(size=(1, n)) for _ in range(N)]


def ring(N: int) -> np.ndarray:
    W = 0.3 * np.eye(N)
    for i in range(N):
        W[i, (i - 1) % N] += 0.7
    return W


def random_graph(rng: np.random.Generator, N: int, density: float = 0.1) -> np.ndarray:
    support = (rng.random((N, N)) < density) | (ring(N) > 0)
    raw = np.where(support, rng.uniform(0.2, 1.0, (N, N)), 0.0)
    return raw / raw.sum(axis=1, keepdims=True)


def timed(A, C, W, solver):
    start = time.perf_counter()
    result = decide_s_detectability(
        A, C, W, solver=solver, cert_tol=1e-7 if solver == "CLARABEL" else 1e-4
    )
    return time.perf_counter() - start, result.verdict


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="N ≤ 10 only")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    sizes = [3, 10] if args.quick else [3, 10, 25, 50]
    print(f"seed {args.seed}; time in seconds; ratio = SCS / clarabel (same run)")
    head = ("graph", "N", "n", "clarabel", "verdict", "SCS", "verdict", "ratio")
    print(ROW.format(*head))
    worst = 0.0
    for N in sizes:
        for n in (2, 4, 6):
            A, C = system(rng, n, N)
            for name, W in (("ring", ring(N)), ("random", random_graph(rng, N))):
                t_c, v_c = timed(A, C, W, "CLARABEL")
                t_s, v_s = timed(A, C, W, "SCS")
                worst = max(worst, min(t_c, t_s)) if (N, n) == (50, 6) else worst
                cells = (
                    name,
                    N,
                    n,
                    f"{t_c:.3f}",
                    str(v_c),
                    f"{t_s:.3f}",
                    str(v_s),
                    f"{t_s / t_c:.2f}",
                )
                print(ROW.format(*cells))
    if not args.quick:
        verdict = "met" if worst < 60 else "MISSED"
        print(f"N = 50, n = 6: best solver {worst:.2f} s (target < 60 s): {verdict}")


if __name__ == "__main__":
    main()
