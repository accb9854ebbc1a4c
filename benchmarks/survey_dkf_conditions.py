"""How sharp are the necessary conditions? Random problems decided by the LMI (issue 4 item 7).

Samples seeded random problems (n ≤ 3, N ≤ 5, unstable A, sparse measurements, directed
weights), decides S-detectability by the LMI and evaluates Thm 5.2.10's conditions and the
blind-set condition. Prints the counts: any case where the LMI is feasible but a necessary
condition fails would refute that condition (expected: 0); cases where a condition holds but the
LMI is infeasible show it is not sufficient. Run from the repository root:
``python -m benchmarks.survey_dkf_conditions [--count 200] [--seed 0]``.
"""

from __future__ import annotations

import argparse
from collections import Counter

import numpy as np

from theory.consensus.conditions import necessary_conditions
from theory.consensus.s_detectability import decide_s_detectability


def problem(rng: np.random.Generator):
    n, N = int(rng.integers(1, 4)), int(rng.integers(2, 6))
    A = rng.normal(size=(n, n))
    A *= rng.uniform(1.05, 2.5) / max(abs(np.linalg.eigvals(A)))
    C = [rng.integers(-1, 2, (int(rng.integers(0, 2)), n)).astype(float) for _ in range(N)]
    support = rng.random((N, N)) < rng.uniform(0.2, 0.9)
    np.fill_diagonal(support, True)
    raw = np.where(support, rng.uniform(0.1, 1.0, (N, N)), 0.0)
    return A, C, raw / raw.sum(axis=1, keepdims=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    counts: Counter[str] = Counter()
    for _ in range(args.count):
        A, C, W = problem(rng)
        verdict = decide_s_detectability(A, C, W).verdict
        cond = necessary_conditions(A, C, W)
        counts[f"lmi={verdict}"] += 1
        if verdict is True:
            counts["violations: feasible but paper's conditions fail"] += (
                cond.paper_conditions is False
            )
            counts["violations: feasible but blind-set condition fails"] += (
                cond.blind_set_condition is False
            )
        if verdict is False:
            counts["infeasible, paper's conditions hold"] += cond.paper_conditions is True
            counts["infeasible, blind-set condition holds"] += cond.blind_set_condition is True
    print(f"seed {args.seed}, {args.count} problems")
    for key in sorted(counts):
        print(f"  {key}: {counts[key]}")


if __name__ == "__main__":
    main()
