"""How long the exact checker takes, against a float eigenvalue check of the same inequalities.

Run: ``python benchmarks/bench_proofs_check.py`` (from the repository root). For networks of N
agents with n = 6 (the TDOA state) it builds an ``mjls-stability`` certificate and prints the
time of ``proofs_check`` (exact LDLᵀ on rationals) and the ratio to a numpy check of the same
inequalities (``eigvalsh`` of ``P_i`` and ``P_i − L_i(P)``) measured in the same run.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from proofs_check import check_certificate
from theory.consensus.certificates import mjls_stability_certificate


def network(N: int, n: int, rng: np.random.Generator):
    W = rng.uniform(0.1, 1.0, (N, N)) * (rng.random((N, N)) < 0.5) + np.eye(N)
    W /= W.sum(axis=1, keepdims=True)
    gammas = [g * 0.9 / np.linalg.norm(g, 2) for g in rng.standard_normal((N, n, n))]
    P = [np.eye(n) for _ in range(N)]
    for _ in range(300):
        P = [
            np.eye(n) + g @ np.tensordot(w, np.array(P), 1) @ g.T
            for g, w in zip(gammas, W, strict=True)
        ]
    return W, gammas, P


def float_check(W, gammas, P) -> bool:
    ok = all(np.linalg.eigvalsh(p)[0] > 0 for p in P)
    for g, w, p in zip(gammas, W, P, strict=True):
        ok &= np.linalg.eigvalsh(p - g @ np.tensordot(w, np.array(P), 1) @ g.T)[0] > 0
    return bool(ok)


def timed(function, *args, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function(*args)
        best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    rng = np.random.default_rng(0)
    print(f"{'N':>3} {'n':>3} {'exact (s)':>10} {'float (s)':>10} {'ratio':>8}")
    for N in (2, 4, 8, 16):
        W, gammas, P = network(N, 6, rng)
        cert = mjls_stability_certificate(gammas, W, P)
        exact = timed(check_certificate, cert)
        baseline = timed(float_check, W, gammas, P)
        print(f"{N:>3} {6:>3} {exact:>10.4f} {baseline:>10.5f} {exact / baseline:>8.0f}")


if __name__ == "__main__":
    main()
