"""The four minimal connections of agent 1 in seed 000 Fig. 4.3 (App. B.1), symbolically.

App. B.1 gives each undirected edge ``e = (i, j)``, ``i < j``, a free vector ``λ_e``: agent ``i``
has the row ``[λ_e 0]`` and agent ``j`` the row ``[−λ_e 0]`` (the TDOA rows ``u_i − u_j`` and
``u_j − u_i``). :func:`agent_rank_witness` proves ``rank O_i = 6`` for almost all ``λ, T`` by a
``6 × 6`` minor of ``O_i`` equal to ``c · T³ · det(Λ)²`` (``Λ`` the three edge vectors, ``c`` a
non-zero rational from the powers of ``W``; the tests recompute one such minor by a full sympy
determinant); :func:`fig43_analysis` adds the whole ``O`` at an
exact random point, where the paper's ``rank O = Σ rank O_i`` fails for the stars (a) and (b).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np
import sympy as sp

from theory.core.network import adjacency_from_edges
from theory.tdoa.model import cv_discrete
from theory.tdoa.networked_observability import (
    analyze_network,
    exact_weights,
    network_generic_rank,
)

__all__ = [
    "FIG43_EDGES",
    "agent_rank_witness",
    "fig43_analysis",
    "shared_lambda_jacobians",
]

FIG43_EDGES: dict[str, tuple[tuple[int, int], ...]] = {
    "a": ((0, 1), (0, 2), (0, 3)),
    "b": ((0, 1), (1, 2), (1, 3)),
    "c": ((0, 1), (0, 2), (2, 3)),
    "d": ((0, 1), (1, 2), (2, 3)),
}
"""Edges (0-based) of Fig. 4.3 (a)–(d): agent 1 has 3, 1, 2, 1 neighbours."""


def shared_lambda_jacobians(
    edges: Sequence[tuple[int, int]], n_agents: int, dim: int = 3
) -> tuple[list[sp.Matrix], sp.Matrix]:
    """Per-agent ``H_i(λ)`` with App. B.1's shared-``λ`` sign structure.

    Parameters
    ----------
    edges : sequence of (int, int)
        Undirected edges (0-based); edge ``t`` in sorted order gets ``λ_{dt+1}, …, λ_{dt+d}``.
    n_agents : int
        Number of agents.
    dim : int
        2 or 3.

    Returns
    -------
    H : list of sympy.Matrix
        ``H_i`` of shape ``(deg i, 2·dim)``; rows in edge order.
    Lambda : sympy.Matrix
        The edge vectors as rows.

    References
    ----------
    seed 000, §4.2.2 (case (d)) and App. B.1 (cases (a)–(c)).
    """
    ordered = sorted((min(e), max(e)) for e in edges)
    symbols = sp.symbols(f"lambda1:{dim * len(ordered) + 1}")
    Lambda = sp.Matrix(len(ordered), dim, symbols)
    rows: list[list[sp.Matrix]] = [[] for _ in range(n_agents)]
    for t, (i, j) in enumerate(ordered):
        rows[i].append(Lambda.row(t))
        rows[j].append(-Lambda.row(t))
    H = [
        sp.Matrix.vstack(*r).row_join(sp.zeros(len(r), dim)) if r else sp.zeros(0, 2 * dim)
        for r in rows
    ]
    return H, Lambda


def agent_rank_witness(
    edges: Sequence[tuple[int, int]], W: Sequence[Sequence[Fraction]], agent: int, dim: int = 3
) -> dict:
    """A ``2d × 2d`` minor of ``O_agent`` equal to ``c · T^d · det(Λ)²`` with ``c ≠ 0`` rational.

    For each edge vector ``λ_e`` the rows ``[W^l]_{m,agent} [±λ_e, lTλ_e]`` of an agent ``m``
    holding it are taken at the two smallest powers ``l`` with ``[W^l]_{m,agent} ≠ 0``. These
    rows are ``S · (I_2 ⊗ Λ)`` with ``S`` free of ``λ``, so the minor is ``det(S) · det(Λ)²``
    exactly; ``det S`` is computed by sympy and divided by ``T^d``. Requires a spanning tree
    (``d`` edges on ``d + 1`` agents), as in Fig. 4.3.

    Parameters
    ----------
    edges : sequence of (int, int)
        Undirected edges, 0-based.
    W : sequence of sequences of Fraction
        Exact consensus weights.
    agent : int
        0-based agent ``i`` whose block column ``O_i`` (eq. 4.37) is examined.
    dim : int
        2 or 3.

    Returns
    -------
    dict
        ``rows`` (power ``l``, agent ``m`` 1-based, edge 1-based), ``c`` (str), ``minor``
        (factored str) and ``rank`` (``2d`` when ``c ≠ 0``).

    Raises
    ------
    ValueError
        Unless there are exactly ``dim`` edges.

    References
    ----------
    seed 000, eq. (4.37), Lemma 4.2.2, App. B.1.
    """
    if len(edges) != dim:
        raise ValueError(f"need exactly {dim} edges (a spanning tree of {dim + 1} agents)")
    T = sp.Symbol("T")
    Wq = sp.Matrix([[sp.Rational(x.numerator, x.denominator) for x in r] for r in W])
    powers = [sp.eye(len(W))]
    for _ in range(2 * dim * len(W)):
        powers.append(powers[-1] * Wq)
    selector, chosen = _witness_rows(powers, sorted((min(e), max(e)) for e in edges), agent, T)
    # The chosen rows are S·(I_2 ⊗ Λ) with S = [E, T·L·E] free of λ, so the minor factors as
    # det(S)·det(Λ)² exactly (block-diagonal I_2 ⊗ Λ).
    c_T = sp.factor(sp.Matrix.vstack(*selector).det())
    ratio = sp.cancel(c_T / T**dim)
    constant = ratio.is_Rational and ratio != 0
    return {
        "rows": chosen,
        "c": str(ratio),
        "minor": f"({c_T})*det(Lambda)**2",
        "rank": 2 * dim if constant else None,
    }


def _witness_rows(
    powers: list[sp.Matrix], ordered: list[tuple[int, int]], agent: int, T: sp.Symbol
) -> tuple[list[sp.Matrix], list[tuple[int, int, int]]]:
    """For each tree edge, the two lowest powers ``W^l`` reaching ``agent`` from its nearer
    end ``m``: the selector rows ``[e_t, l·T·e_t]·[W^l]_{m,agent}`` and their ``(l, m, t)``."""
    selector, chosen = [], []
    for t, (i, j) in enumerate(ordered):
        m = min((i, j), key=lambda k: _distance(ordered, agent, k))
        sign = 1 if m == i else -1
        for l in [l for l in range(len(powers)) if powers[l][m, agent] != 0][:2]:
            unit = sp.zeros(1, len(ordered))
            unit[t] = powers[l][m, agent] * sign
            selector.append(unit.row_join(l * T * unit))
            chosen.append((l, m + 1, t + 1))
    return selector, chosen


def _distance(edges: Sequence[tuple[int, int]], source: int, target: int) -> int:
    frontier, seen, steps = {source}, {source}, 0
    while target not in frontier:
        frontier = {b for a, b in edges if a in frontier} | {a for a, b in edges if b in frontier}
        frontier -= seen
        seen |= frontier
        steps += 1
        if not frontier:
            return 10**9
    return steps


def fig43_analysis(case: str, *, rule: str = "metropolis", seed: int = 0) -> dict:
    """Fig. 4.3 case ``a``–``d``: symbolic ``rank O_i``, exact whole ``O``, detectability.

    Parameters
    ----------
    case : {"a", "b", "c", "d"}
        The minimal connection of agent 1.
    rule : {"metropolis", "uniform"}
        Consensus weights.
    seed : int
        Seed for the random point (exact ranks) and the numeric instance (detectability).

    Returns
    -------
    dict
        ``witnesses`` (per agent, symbolic), ``exact`` (:class:`NetworkGenericRank` fields),
        ``agree`` (symbolic and exact agent ranks coincide), ``detectable``,
        ``unobservable_eigenvalues`` and ``rank_sum_claim_holds``.

    Raises
    ------
    KeyError
        For an unknown case letter.

    References
    ----------
    seed 000, Fig. 4.3, Thm 4.2.3 and App. B.1.
    """
    edges = FIG43_EDGES[case]
    adjacency = adjacency_from_edges(4, np.array(edges))
    W = exact_weights(adjacency, rule)
    witnesses = [agent_rank_witness(edges, W, agent) for agent in range(4)]
    exact = network_generic_rank(adjacency, W, parametrization="edges", seed=seed)
    rng = np.random.default_rng(seed)
    lam = {e: rng.normal(size=3) for e in edges}
    H = [
        np.array([np.r_[lam[e] if e[0] == i else -lam[e], np.zeros(3)] for e in edges if i in e])
        for i in range(4)
    ]
    W_float = np.array([[float(x) for x in r] for r in W])
    numeric = analyze_network(cv_discrete(1.0, 3)[0], W_float, H)
    return {
        "case": case,
        "rule": rule,
        "witnesses": witnesses,
        "exact": dict(exact.__dict__),
        "agree": [w["rank"] for w in witnesses] == exact.agent_ranks,
        "rank_sum_claim_holds": exact.rank_sum_claim_holds,
        "network_observable": exact.network_rank == exact.n_states,
        "detectable": numeric.detectable,
        "numeric_conclusive": numeric.conclusive,
        "unobservable_eigenvalues": [complex(z) for z in numeric.unobservable_eigenvalues],
    }
