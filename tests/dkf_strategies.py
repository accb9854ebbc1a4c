"""Hypothesis strategies for consensus-filter problems (systems, networks, gains), bounded.

Each strategy draws a seed and builds the data with ``numpy.random.default_rng(seed)``, so a
failing example is reproduced from its seed. Entries are bounded and weights are at least
``min_weight`` on their support, which bounds the conditioning of everything derived.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from hypothesis import strategies as st

__all__ = ["DkfProblem", "dkf_problems", "weight_matrices"]


@dataclass(frozen=True)
class DkfProblem:
    """Random data: system, per-agent measurements, weights and gains (seeded)."""

    seed: int
    A: np.ndarray
    C: tuple[np.ndarray, ...]
    W: np.ndarray
    L: tuple[np.ndarray, ...]


def random_weights(rng: np.random.Generator, N: int, *, density: float, min_weight: float):
    """Row-stochastic W with positive diagonal, directed support of the given density."""
    support = rng.random((N, N)) < density
    np.fill_diagonal(support, True)
    raw = np.where(support, rng.uniform(min_weight, 1.0, (N, N)), 0.0)
    return raw / raw.sum(axis=1, keepdims=True)


def weight_matrices(*, min_agents: int = 1, max_agents: int = 5, min_weight: float = 0.1):
    """Strategy of row-stochastic matrices with w_ii > 0 (directed support allowed)."""
    if not 1 <= min_agents <= max_agents:
        raise ValueError(f"need 1 ≤ min_agents ≤ max_agents, got {min_agents}, {max_agents}")
    return st.tuples(
        st.integers(0, 2**32 - 1), st.integers(min_agents, max_agents), st.floats(0.2, 1.0)
    ).map(
        lambda t: random_weights(
            np.random.default_rng(t[0]), t[1], density=t[2], min_weight=min_weight
        )
    )


def dkf_problems(
    *,
    min_n: int = 1,
    max_n: int = 3,
    min_agents: int = 1,
    max_agents: int = 4,
    max_rows: int = 2,
    a_bound: float = 1.5,
    gain_bound: float = 1.0,
    integer_data: bool = False,
):
    """Strategy of :class:`DkfProblem` with bounded entries (``|a_ij| ≤ a_bound``)."""
    if not (1 <= min_n <= max_n and 1 <= min_agents <= max_agents and max_rows >= 0):
        raise ValueError("need 1 ≤ min_n ≤ max_n, 1 ≤ min_agents ≤ max_agents, max_rows ≥ 0")

    def build(seed: int) -> DkfProblem:
        rng = np.random.default_rng(seed)
        n = int(rng.integers(min_n, max_n + 1))
        N = int(rng.integers(min_agents, max_agents + 1))
        if integer_data:
            A = rng.integers(-2, 3, (n, n)).astype(float) / 2 * a_bound
            C = tuple(
                rng.integers(-1, 2, (int(rng.integers(0, max_rows + 1)), n)).astype(float)
                for _ in range(N)
            )
        else:
            A = rng.uniform(-a_bound, a_bound, (n, n))
            C = tuple(rng.uniform(-1, 1, (int(rng.integers(0, max_rows + 1)), n)) for _ in range(N))
        W = random_weights(rng, N, density=float(rng.uniform(0.2, 1.0)), min_weight=0.1)
        L = tuple(rng.uniform(-gain_bound, gain_bound, (n, Ci.shape[0])) for Ci in C)
        return DkfProblem(seed, A, C, W, L)

    return st.integers(0, 2**32 - 1).map(build)
