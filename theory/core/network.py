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

import itertools
import sys
from collections.abc import Iterator
from fractions import Fraction

import numpy as np

__all__ = [
    "NAMED_WEIGHTS",
    "adjacency_from_edges",
    "adjacency_from_range",
    "component_labels",
    "components",
    "exact_metropolis_weights",
    "exact_uniform_weights",
    "exact_weights",
    "is_symmetric",
    "link_component_labels",
    "metropolis_entries",
    "metropolis_weights",
    "near_pairs",
    "pairs_within_range",
    "stationary_vector",
    "uniform_entries",
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
    """Undirected adjacency of agents at ``positions`` closer than ``comm_range`` (the pairs of
    :func:`pairs_within_range` as an ``N × N`` boolean matrix)."""
    n = np.asarray(positions).shape[0]
    adjacency = np.zeros((n, n), dtype=bool)
    i, j = pairs_within_range(positions, comm_range)
    adjacency[i, j] = adjacency[j, i] = True
    return adjacency


def pairs_within_range(positions: np.ndarray, comm_range: float) -> tuple[np.ndarray, np.ndarray]:
    """The pairs ``i < j`` of agents at ``positions`` closer than ``comm_range``, as two index
    arrays (``O(N + E)`` memory: no ``N × N`` array).

    The rule is strict (``<``), as in seed 000 §4.4, and decided exactly on the numbers as
    written (:func:`theory.core.exact.exact_decimal`): pairs whose float squared distance
    lies within a rounding bound of ``comm_range²`` are re-compared in rationals, so an agent at
    exactly the range is never linked and one a hair inside always is. Only pairs in
    neighbouring cells of a grid are compared (:func:`near_pairs`).
    """
    positions = np.asarray(positions, dtype=float)
    band = _range_band(positions, comm_range)
    found_i, found_j = [np.zeros(0, dtype=np.int64)], [np.zeros(0, dtype=np.int64)]
    for i, j in near_pairs(positions, float(np.sqrt(comm_range**2 + band))):
        squared = ((positions[i] - positions[j]) ** 2).sum(axis=-1)
        linked = squared < comm_range**2
        for k in np.flatnonzero(np.abs(squared - comm_range**2) <= band):
            linked[k] = _exactly_closer(positions[i[k]], positions[j[k]], comm_range)
        found_i.append(i[linked])
        found_j.append(j[linked])
    return np.concatenate(found_i), np.concatenate(found_j)


def near_pairs(
    points: np.ndarray, reach: float, *, chunk: int = 1 << 21
) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Every pair ``i < j`` of ``points`` (``N × d``) within distance ``reach`` of each other,
    and possibly some farther ones, in chunks of about ``chunk`` pairs.

    The points are binned in a grid of cubes of side slightly above ``reach`` (by a relative
    ``10⁻⁶`` and the coordinates' rounding, so that no float error splits a close pair across
    non-neighbouring cells), and at least ``2⁻⁴⁰`` of the points' span (cell indices stay far
    from overflow; larger cells only list more pairs); only pairs in the same or neighbouring
    cells are listed. Work and memory ``O(N + pairs listed)``.
    """
    points = np.asarray(points, dtype=float)
    n, dim = points.shape
    if n < 2:
        return
    low = points.min(axis=0)
    span = float((points.max(axis=0) - low).max())
    side = reach * (1 + 1e-6) + 64 * sys.float_info.epsilon * float(np.abs(points).max())
    side = max(side, span * 2.0**-40)
    cells, member_of = np.unique(
        np.floor((points - low) / side).astype(np.int64), axis=0, return_inverse=True
    )
    member_of = member_of.reshape(-1)
    order = np.argsort(member_of, kind="stable")
    starts = np.searchsorted(member_of[order], np.arange(len(cells) + 1))
    index = {tuple(c): k for k, c in enumerate(cells.tolist())}
    for offset in itertools.product((-1, 0, 1), repeat=dim):
        if offset < (0,) * dim:
            continue  # its mirror image lists the same pairs
        yield from _cell_pairs(order, starts, member_of, cells, index, offset, chunk)


def _cell_pairs(order, starts, member_of, cells, index, offset, chunk):
    """The pairs of :func:`near_pairs` between each cell and its neighbour at ``offset``."""
    target = np.array(
        [index.get(tuple(c), -1) for c in (cells + np.array(offset)).tolist()], dtype=np.int64
    )
    point_target = target[member_of]
    count = np.where(point_target >= 0, starts[point_target + 1] - starts[point_target], 0)
    ends = np.cumsum(count)
    bounds = np.searchsorted(ends, np.arange(chunk, int(ends[-1]) + chunk, chunk), side="right")
    first = 0
    for last in (*bounds.tolist(), len(count)):
        if last <= first:
            continue
        source = np.arange(first, last)
        many = count[source]
        i = np.repeat(source, many)
        within = np.arange(int(many.sum())) - np.repeat(np.cumsum(many) - many, many)
        j = order[np.repeat(starts[point_target[source]], many) + within]
        keep = i < j if not any(offset) else np.ones(len(i), dtype=bool)
        i, j = i[keep], j[keep]
        first = last
        yield np.minimum(i, j), np.maximum(i, j)


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
    from theory.core.exact import exact_decimal  # python-flint: only near the boundary

    squared = sum((exact_decimal(a) - exact_decimal(b)) ** 2 for a, b in zip(p, q, strict=True))
    return squared < exact_decimal(comm_range) ** 2


def metropolis_weights(adjacency: np.ndarray) -> np.ndarray:
    """Metropolis weights of the undirected graph ``adjacency`` (rows and columns sum to 1)."""
    r, s = np.nonzero(adjacency)
    n = adjacency.shape[0]
    return _on_links(n, r, s, *metropolis_entries(n, r, s))


def uniform_weights(adjacency: np.ndarray) -> np.ndarray:
    """Uniform weights on ``adjacency``: each agent averages itself and its in-neighbours."""
    r, s = np.nonzero(adjacency)
    n = adjacency.shape[0]
    return _on_links(n, r, s, *uniform_entries(n, r, s))


def metropolis_entries(
    n: int, receiver: np.ndarray, sender: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Metropolis weights by their entries: ``w_rs = 1/(1 + max(d_r, d_s))`` on each link
    ``(receiver[k], sender[k])`` of an undirected graph (both directions listed) and the self-
    weights ``w_ii = 1 − Σ_j w_ij``; ``O(N + E)``."""
    degree = np.bincount(receiver, minlength=n)
    values = 1.0 / (1.0 + np.maximum(degree[receiver], degree[sender]))
    return values, 1.0 - np.bincount(receiver, weights=values, minlength=n)


def uniform_entries(
    n: int, receiver: np.ndarray, sender: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Uniform weights by their entries: ``w_rs = 1/(d_r + 1)`` on each link and on the
    diagonal (``d_r`` the in-degree of ``r``); ``O(N + E)``."""
    share = 1.0 / (np.bincount(receiver, minlength=n) + 1.0)
    return share[receiver], share


def _on_links(
    n: int, r: np.ndarray, s: np.ndarray, values: np.ndarray, diagonal: np.ndarray
) -> np.ndarray:
    """The ``n × n`` matrix with ``values`` at ``(r, s)``, ``diagonal`` on the diagonal and zeros
    elsewhere (written link by link: ``O(N + E)`` writes, not an ``N²`` sweep)."""
    weights = np.zeros((n, n))
    weights[r, s] = values
    weights[np.arange(n), np.arange(n)] = diagonal
    return weights


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


def is_symmetric(adjacency: np.ndarray) -> bool:
    """Whether every link of ``adjacency`` has its reverse (``O(N² / 8 + E)``: no transpose
    of the whole matrix)."""
    r, s = np.nonzero(adjacency)
    return bool(np.all(adjacency[s, r] == adjacency[r, s]))


def weights_support(weights: np.ndarray) -> np.ndarray:
    """Off-diagonal boolean support of ``weights`` (``w_ij > 0``)."""
    support = weights > 0
    np.fill_diagonal(support, False)
    return support


def stationary_vector(weights: np.ndarray) -> np.ndarray:
    """A positive ``π`` with ``πᵀW = πᵀ``, summing to 1 on each weakly connected component of
    ``W``'s support, for a row-stochastic ``W`` whose components are irreducible (every ``W`` on
    an undirected network, seed 000 §4.2.2): per component the left Perron vector of ``W_CC``,
    the null space of ``W_CCᵀ − I``. ``ValueError`` if a component has no positive one."""
    W = np.asarray(weights, float)
    pi = np.zeros(len(W))
    for part in components(weights_support(W)):
        block = W[np.ix_(part, part)]
        values, vectors = np.linalg.eig(block.T)
        top = np.real(vectors[:, np.argmin(np.abs(values - 1))])
        top = top / top.sum()
        if not np.all(top > 0):
            raise ValueError(f"the weights on agents {part} have no positive stationary vector")
        pi[part] = top
    return pi


def components(adjacency: np.ndarray) -> list[list[int]]:
    """Weakly connected components of ``adjacency``: sorted lists of 0-based agents, ordered by
    their first agent."""
    labels = component_labels(adjacency)
    order = np.argsort(labels, kind="stable")
    _, starts = np.unique(labels[order], return_index=True)
    parts = [piece.tolist() for piece in np.split(order, starts[1:])]
    return sorted(parts, key=lambda c: c[0])


def component_labels(adjacency: np.ndarray) -> np.ndarray:
    """Each agent's weakly connected component, labelled by its smallest agent."""
    return link_component_labels(adjacency.shape[0], *np.nonzero(adjacency))


def link_component_labels(n: int, r: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Each of ``n`` agents' weakly connected component under the links ``(r[k], s[k])``,
    labelled by its smallest agent (``O((N + E) log N)``: hooking of roots onto the smaller
    root, then pointer jumping, until no link joins two trees)."""
    root = np.arange(n)
    while True:
        low = np.minimum(root[r], root[s])
        hooked = root.copy()
        np.minimum.at(hooked, root[r], low)
        np.minimum.at(hooked, root[s], low)
        while not np.array_equal(hooked[hooked], hooked):
            hooked = hooked[hooked]
        if np.array_equal(hooked, root):
            return root
        root = hooked
