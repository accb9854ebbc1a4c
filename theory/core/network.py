"""Communication networks: adjacency from edges or a distance rule, consensus weights, components.

Agent ids are 0-based inside the library and 1-based wherever a user sees them. Named weights
(docs/topology.md, *Named weights*): ``metropolis`` is w_ij = 1/(1 + max(d_i, d_j)) on each
edge with w_ii = 1 − Σ_j w_ij; ``uniform`` is w_ij = 1/(d_i + 1) for j ∈ N_i ∪ {i}. Each rule is
written once in floats (:func:`metropolis_weights`, :func:`uniform_weights`, what filters and
simulations use) and once in exact rationals (:func:`exact_metropolis_weights`,
:func:`exact_uniform_weights`, what certificates and exact claims use), side by side
(:data:`NAMED_WEIGHTS`).
"""

from __future__ import annotations

import sys
from fractions import Fraction

import numpy as np
from scipy.sparse.csgraph import connected_components

from theory.core.exact import exact_decimal

__all__ = [
    "NAMED_WEIGHTS",
    "adjacency_from_edges",
    "adjacency_from_range",
    "components",
    "exact_metropolis_weights",
    "exact_uniform_weights",
    "exact_weights",
    "metropolis_weights",
    "uniform_weights",
    "weights_support",
]


def adjacency_from_edges(n: int, edges: np.ndarray, *, directed: bool = False) -> np.ndarray:
    """Boolean "hears" matrix ``A[r, s]`` (agent r receives from agent s) of ``n`` agents from
    0-based ``edges`` ``(s, r)``; undirected edges are symmetrised."""
    adjacency = np.zeros((n, n), dtype=bool)
    for s, r in np.asarray(edges, dtype=int).reshape(-1, 2):
        adjacency[r, s] = True
        if not directed:
            adjacency[s, r] = True
    return adjacency


def adjacency_from_range(positions: np.ndarray, comm_range: float) -> np.ndarray:
    """Undirected adjacency of agents at ``positions`` closer than ``comm_range``.

    The rule is strict (``<``), as in seed 000 §4.4, and decided exactly on the numbers as
    written (:func:`theory.core.exact.exact_decimal`): pairs whose float squared distance
    lies within a rounding bound of ``comm_range²`` are re-compared in rationals, so an agent at
    exactly the range is never linked and one a hair inside always is.
    """
    positions = np.asarray(positions, dtype=float)
    diff = positions[:, None, :] - positions[None, :, :]
    squared = (diff**2).sum(axis=-1)
    adjacency = squared < comm_range**2
    for i, j in zip(
        *np.nonzero(np.abs(squared - comm_range**2) <= _range_band(positions, comm_range)),
        strict=True,
    ):
        if i < j:
            adjacency[i, j] = adjacency[j, i] = _exactly_closer(
                positions[i], positions[j], comm_range
            )
    np.fill_diagonal(adjacency, False)
    return adjacency


def _range_band(positions: np.ndarray, comm_range: float) -> float:
    """A bound on the float error of ``‖p_i − p_j‖² − r²`` (generous: 64 d ε (max|p| + r)²).

    Each coordinate difference is within ``2ε·max|p|`` of the exact one (both inputs within
    ``ε/2`` relative of the decimals written, one rounded subtraction); squaring and summing
    ``d`` terms and ``r²`` add a few more ulps of ``(max|p| + r)²``.
    """
    top = float(np.abs(positions).max(initial=0.0)) + abs(comm_range)
    return 64 * positions.shape[1] * sys.float_info.epsilon * top * top


def _exactly_closer(p: np.ndarray, q: np.ndarray, comm_range: float) -> bool:
    """``‖p − q‖ < comm_range`` in exact rationals (coordinates read as written)."""
    squared = sum((exact_decimal(a) - exact_decimal(b)) ** 2 for a, b in zip(p, q, strict=True))
    return squared < exact_decimal(comm_range) ** 2


def metropolis_weights(adjacency: np.ndarray) -> np.ndarray:
    """Metropolis weights of the undirected graph ``adjacency`` (rows and columns sum to 1)."""
    degree = adjacency.sum(axis=1)
    weights = np.where(adjacency, 1.0 / (1.0 + np.maximum(degree[:, None], degree[None, :])), 0.0)
    np.fill_diagonal(weights, 1.0 - weights.sum(axis=1))
    return weights


def uniform_weights(adjacency: np.ndarray) -> np.ndarray:
    """Uniform weights on ``adjacency``: each agent averages itself and its in-neighbours."""
    closed = adjacency | np.eye(adjacency.shape[0], dtype=bool)
    return closed / closed.sum(axis=1, keepdims=True)


def exact_metropolis_weights(adjacency: np.ndarray) -> list[list[Fraction]]:
    """:func:`metropolis_weights` in exact rationals: ``w_ij = 1/(1 + max(d_i, d_j))`` on each
    edge, ``w_ii = 1 − Σ_j w_ij``."""
    degree = np.asarray(adjacency, dtype=bool).sum(axis=1)
    return _exact(adjacency, lambda r, s: Fraction(1, 1 + int(max(degree[r], degree[s]))))


def exact_uniform_weights(adjacency: np.ndarray) -> list[list[Fraction]]:
    """:func:`uniform_weights` in exact rationals: ``w_rs = 1/(d_r + 1)`` for ``s ∈ N_r ∪ {r}``."""
    degree = np.asarray(adjacency, dtype=bool).sum(axis=1)
    return _exact(adjacency, lambda r, s: Fraction(1, 1 + int(degree[r])))


NAMED_WEIGHTS = {
    "metropolis": (metropolis_weights, exact_metropolis_weights),
    "uniform": (uniform_weights, exact_uniform_weights),
}
"""Weight rule name → (float weights, exact weights): one rule, two arithmetics."""


def exact_weights(adjacency: np.ndarray, rule: str) -> list[list[Fraction]]:
    """The named weights ``rule`` (``metropolis`` or ``uniform``; else ``ValueError``) of
    ``adjacency`` in exact rationals."""
    if rule not in NAMED_WEIGHTS:
        raise ValueError(f"rule must be 'metropolis' or 'uniform'; got {rule!r}")
    return NAMED_WEIGHTS[rule][1](adjacency)


def _exact(adjacency: np.ndarray, weight) -> list[list[Fraction]]:
    """Off-diagonal ``weight(r, s)`` on the edges, the diagonal completing each row to 1."""
    hears = np.asarray(adjacency, dtype=bool)
    n = hears.shape[0]
    W = [[Fraction(0)] * n for _ in range(n)]
    for r in range(n):
        for s in np.flatnonzero(hears[r]):
            if s != r:
                W[r][int(s)] = weight(r, int(s))
        W[r][r] = 1 - sum(W[r])
    return W


def weights_support(weights: np.ndarray) -> np.ndarray:
    """Off-diagonal boolean support of ``weights`` (``w_ij > 0``)."""
    support = weights > 0
    np.fill_diagonal(support, False)
    return support


def components(adjacency: np.ndarray) -> list[list[int]]:
    """Weakly connected components of ``adjacency``: sorted lists of 0-based agents."""
    count, labels = connected_components(adjacency, connection="weak")
    parts = [np.flatnonzero(labels == c).tolist() for c in range(count)]
    return sorted(parts, key=lambda c: c[0])
