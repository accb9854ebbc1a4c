"""Hypothesis strategies and helpers for the topology tests: TDOA scenes and edge lists."""

from __future__ import annotations

import numpy as np
from hypothesis import assume
from hypothesis import strategies as st

from theory.tdoa.case import parse_tdoa

SEPARATION = 2.0
"""Draws with two points closer than this (scene units) are rejected."""


@st.composite
def scenes(draw, *, min_agents: int = 2, max_agents: int = 6, dims=(2, 3)):
    """Integer agents and target, pairwise separated (no bound on the Jacobian's conditioning:
    near-degenerate draws are discarded below through the result's own margin)."""
    dim = draw(st.sampled_from(dims))
    n = draw(st.integers(min_agents, max_agents))
    coords = st.lists(st.integers(-20, 20), min_size=dim, max_size=dim)
    points = np.array(draw(st.lists(coords, min_size=n + 1, max_size=n + 1)), dtype=float)
    gaps = np.linalg.norm(points[:, None] - points[None], axis=-1) + np.eye(n + 1) * 1e9
    assume(gaps.min() > SEPARATION)
    return points[1:], points[0]


@st.composite
def edge_lists(draw, n: int, *, directed: bool = False):
    """Random 1-based edges on ``n`` agents (possibly disconnected)."""
    pairs = [[i, j] for i in range(1, n + 1) for j in range(1, n + 1) if i != j]
    if not directed:
        pairs = [p for p in pairs if p[0] < p[1]]
    return draw(st.lists(st.sampled_from(pairs), unique_by=tuple, max_size=2 * n))


def spec_of(agents, target, edges, *, directed=False, weights=None):
    block = {
        "T": 1.0,
        "agents": np.asarray(agents).tolist(),
        "target": np.asarray(target).tolist(),
        "edges": [list(e) for e in edges],
        "directed": directed,
        "weights": weights or ("uniform" if directed else "metropolis"),
    }
    return parse_tdoa(block)
