"""Speed of enumerating every 6×6 minor of the single-agent O (seed 000 eq. 4.20).

Baseline, measured in the same run: sympy determinants of the actual rows of O (berkowitz) on a
seeded sample of minors, extrapolated to all C(18, 6) = 18564. Candidate: the vectorised Laplace
expansion of ``theory.tdoa.observability.single_agent.minor_expansions``. Prints the ratio;
asserts nothing.

Run: ``python benchmarks/generic_rank_minors.py [--sample 20] [--seed 0]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from theory.tdoa.observability.single_agent import minor_expansions, symbolic_single_agent_matrix


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sample", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    start = time.perf_counter()
    expansions = minor_expansions(3, 3)
    laplace = time.perf_counter() - start
    O, _, _ = symbolic_single_agent_matrix(3, 3)
    rng = np.random.default_rng(args.seed)
    picks = rng.choice(expansions.n_minors, size=args.sample, replace=False)
    start = time.perf_counter()
    for index in picks:
        rows = [int(r) for r in expansions.row_sets[index]]
        O.extract(rows, list(range(6))).det(method="berkowitz").expand()
    per_minor = (time.perf_counter() - start) / args.sample
    baseline = per_minor * expansions.n_minors
    print(f"minors: {expansions.n_minors} (seed {args.seed}, sample {args.sample})")
    print(f"baseline sympy (extrapolated): {baseline:.1f} s")
    print(f"laplace expansion (all minors): {laplace:.2f} s")
    print(f"speed-up: {baseline / laplace:.0f}x")


if __name__ == "__main__":
    main()
