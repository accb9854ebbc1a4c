"""Seed 000 Lemma 4.2.2 (seed 001 Lemma 1): the zero pattern of the powers of ``W``.

The lemma: for a stochastic ``W`` with ``w_ii > 0``, ``[W^l]_ij > 0`` if a path of length at most
``l`` joins ``i`` and ``j``, and ``[W^l]_ij = 0`` otherwise. With non-negative entries no
cancellation can happen, so ``[W^l]_ij > 0`` exactly when a *walk* of length ``l`` runs from
``i`` to ``j`` along positive entries (``i`` receives from ``j`` when ``w_ij > 0``: on a directed
network the paths are directed); the self-loops ``w_ii > 0`` pad any shorter path to length
``l``. Hence the support of ``W^l`` grows with ``l`` and equals reachability from ``l = N − 1``
on, so checking ``l = 0, …, N − 1`` decides the lemma for every ``l``. Without ``w_ii > 0`` it
fails: ``W = [[0, 1], [1, 0]]`` has ``[W²]_12 = 0`` although agents 1 and 2 are adjacent.

:func:`path_lemma_failures` compares the two patterns in exact rational arithmetic
(python-flint) on the floats the suite actually uses; the claim ``seed000.lem4.2.2``
(:mod:`theory.tdoa.path_lemma_claims`) runs it on every distinct network of a ``tdoa`` case and on
the ``W`` of a ``dkf`` case.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import flint
import networkx as nx
import numpy as np

from theory.core.exact import exact_float

__all__ = ["path_lemma_failures", "path_lengths"]


def path_lengths(W: np.ndarray) -> list[list[int | None]]:
    """Shortest path lengths along positive off-diagonal entries (``i → j`` when ``w_ij > 0``).

    Parameters
    ----------
    W : (N, N) array
        Non-negative weights.

    Returns
    -------
    list of list of int or None
        ``d[i][j]`` (``0`` on the diagonal), ``None`` when no path leads from ``i`` to ``j``.
    """
    n = len(W)
    graph = nx.DiGraph()
    graph.add_nodes_from(range(n))
    graph.add_edges_from((i, j) for i in range(n) for j in range(n) if i != j and W[i][j] > 0)
    lengths = dict(nx.all_pairs_shortest_path_length(graph))
    return [[lengths[i].get(j) for j in range(n)] for i in range(n)]


def path_lemma_failures(W: np.ndarray, powers: Sequence[int]) -> list[dict[str, Any]]:
    """Entries where the support of ``W^l`` differs from "a path of length ≤ l" (exact).

    Parameters
    ----------
    W : (N, N) array
        Non-negative weights; each float is taken as the exact rational it stores.
    powers : sequence of int
        The exponents ``l ≥ 0`` to compare.

    Returns
    -------
    list of dict
        One ``{"l", "i", "j", "positive", "path_length"}`` per disagreeing entry (1-based
        agents); empty when the lemma holds at every listed power.
    """
    n = len(W)
    exact = flint.fmpq_mat(n, n, [_rational(w) for row in np.asarray(W) for w in row])
    distance = path_lengths(np.asarray(W))
    failures: list[dict[str, Any]] = []
    power = flint.fmpq_mat(n, n, [int(i == j) for i in range(n) for j in range(n)])  # W^0
    current = 0
    for l in sorted(powers):
        while current < l:
            power, current = power * exact, current + 1
        for i in range(n):
            for j in range(n):
                near = distance[i][j] is not None and distance[i][j] <= l
                if (power[i, j] > 0) != near:
                    failures.append(
                        {
                            "l": l,
                            "i": i + 1,
                            "j": j + 1,
                            "positive": power[i, j] > 0,
                            "path_length": distance[i][j],
                        }
                    )
    return failures


def _rational(value: float) -> flint.fmpq:
    exact = exact_float(value)  # the float in memory, not the decimal written
    return flint.fmpq(exact.numerator, exact.denominator)
