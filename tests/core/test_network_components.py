"""Graph components by scipy's csgraph agree with networkx's on random digraphs (the library
uses csgraph in the commands that must not pay networkx's import)."""

from __future__ import annotations

import networkx as nx
import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.sparse.csgraph import connected_components

from theory.core.network import components


def _digraphs():
    return st.integers(1, 9).flatmap(
        lambda n: arrays(np.int64, (n, n), elements=st.integers(0, 1)).map(
            lambda a: a * (1 - np.eye(n, dtype=np.int64))
        )
    )


@given(_digraphs())
def test_weak_components_are_networkx_ones(adjacency: np.ndarray) -> None:
    graph = nx.from_numpy_array(adjacency, create_using=nx.DiGraph)
    expected = sorted((sorted(c) for c in nx.weakly_connected_components(graph)), key=min)
    assert components(adjacency) == expected


@given(_digraphs())
def test_strong_connectivity_is_networkx_one(adjacency: np.ndarray) -> None:
    graph = nx.from_numpy_array(adjacency, create_using=nx.DiGraph)
    strongly = connected_components(adjacency, connection="strong")[0] == 1
    assert strongly == nx.is_strongly_connected(graph)
