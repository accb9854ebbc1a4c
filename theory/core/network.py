"""Communication networks: adjacency from edges or a distance rule, consensus weights, components.

Agent ids are 0-based inside the library and 1-based wherever a user sees them (DESIGN.md).
Named weights follow DESIGN.md: ``metropolis`` is w_ij = 1/(1 + max(d_i, d_j)) on each edge with
w_ii = 1 − Σ_j w_ij; ``uniform`` is w_ij = 1/(d_i + 1) for j ∈ N_i ∪ {i}. Each rule is written
once in floats (:func:`metropolis_weights`, :func:`uniform_weights`, what filters and simulations
use) and once in exact rationals (:func:`exact_metropolis_weights`, :func:`exact_uniform_weights`,
what certificates and exact claims use), side by side (:data:`NAMED_WEIGHTS`).
"""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import numpy as np

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
    """Boolean "hears" matrix ``A[r, s]`` of ``n`` agents from 0-based ``edges``.

    ``A[r, s]`` means "agent r receives from agent s".

    Parameters
    ----------
    n : int
        Number of agents.
    edges : ndarray of int, shape (m, 2)
        0-based pairs ``(s, r)``. A directed edge ``(s, r)`` means information flows from sender
        ``s`` to receiver ``r``, so row ``r`` of a consensus matrix ``W`` has ``w_rs > 0``.
    directed : bool
        Whether ``edges`` are directed; undirected edges are symmetrised.

    Returns
    -------
    ndarray of bool, shape (n, n)
    """
    adjacency = np.zeros((n, n), dtype=bool)
    for s, r in np.asarray(edges, dtype=int).reshape(-1, 2):
        adjacency[r, s] = True
        if not directed:
            adjacency[s, r] = True
    return adjacency


def adjacency_from_range(positions: np.ndarray, comm_range: float) -> np.ndarray:
    """Undirected adjacency of agents at ``positions`` closer than ``comm_range``.

    The rule is strict (``<``), as in seed 000 §4.4.

    Parameters
    ----------
    positions : ndarray, shape (N, d)
        Agent positions, one per row.
    comm_range : float
        Communication range: agents ``i ≠ j`` are linked iff ``‖p_i − p_j‖ < comm_range``.

    Returns
    -------
    ndarray of bool, shape (N, N)
        Symmetric, with a false diagonal.
    """
    diff = positions[:, None, :] - positions[None, :, :]
    distance = np.sqrt((diff**2).sum(axis=-1))
    adjacency = distance < comm_range
    np.fill_diagonal(adjacency, False)
    return adjacency


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
    """The Metropolis weights of :func:`metropolis_weights` in exact rationals (DESIGN.md).

    Parameters
    ----------
    adjacency : ndarray of bool, shape (N, N)
        Symmetric adjacency without self-loops.

    Returns
    -------
    list of list of Fraction
        ``w_ij = 1/(1 + max(d_i, d_j))`` on each edge, ``w_ii = 1 − Σ_j w_ij``, 0 elsewhere.
    """
    degree = np.asarray(adjacency, dtype=bool).sum(axis=1)
    return _exact(adjacency, lambda r, s: Fraction(1, 1 + int(max(degree[r], degree[s]))))


def exact_uniform_weights(adjacency: np.ndarray) -> list[list[Fraction]]:
    """The uniform weights of :func:`uniform_weights` in exact rationals (DESIGN.md).

    Parameters
    ----------
    adjacency : ndarray of bool, shape (N, N)
        ``adjacency[r, s]``: ``r`` hears ``s``.

    Returns
    -------
    list of list of Fraction
        ``w_rs = 1/(d_r + 1)`` for ``s ∈ N_r ∪ {r}``, 0 elsewhere.
    """
    degree = np.asarray(adjacency, dtype=bool).sum(axis=1)
    return _exact(adjacency, lambda r, s: Fraction(1, 1 + int(degree[r])))


NAMED_WEIGHTS = {
    "metropolis": (metropolis_weights, exact_metropolis_weights),
    "uniform": (uniform_weights, exact_uniform_weights),
}
"""Weight rule name → (float weights, exact weights): one rule, two arithmetics."""


def exact_weights(adjacency: np.ndarray, rule: str) -> list[list[Fraction]]:
    """The named weights ``rule`` of ``adjacency`` in exact rationals.

    Parameters
    ----------
    adjacency : ndarray of bool, shape (N, N)
        ``adjacency[r, s]``: ``r`` hears ``s`` (symmetric for ``metropolis``).
    rule : {"metropolis", "uniform"}
        The weight rule.

    Returns
    -------
    list of list of Fraction

    Raises
    ------
    ValueError
        For another rule.
    """
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
    graph = nx.from_numpy_array(adjacency.astype(int), create_using=nx.DiGraph)
    parts = [sorted(c) for c in nx.weakly_connected_components(graph)]
    return sorted(parts, key=lambda c: c[0])
