"""Graph components (hooking and pointer jumping in ``theory.core.network``) and strong
connectivity (scipy's csgraph in seed 003's ISS), agree with networkx on random and on all
three-node digraphs."""

from __future__ import annotations

import dataclasses
import itertools

import networkx as nx
import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from theory.core.network import components
from theory.kinds import load_case
from theory.pursuit.iss import coordination_iss


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


def test_pursuit_strong_connectivity_is_networkx_one_on_every_three_tracker_digraph() -> None:
    """seed 003 Lemma 3 needs a strongly connected digraph (`coordination_iss`)."""
    spec = load_case("pursuit-table1-n3").spec
    off = [(i, j) for i in range(3) for j in range(3) if i != j]
    for chosen in itertools.product((0, 1), repeat=len(off)):
        adjacency = np.zeros((3, 3), dtype=bool)
        for (i, j), edge in zip(off, chosen, strict=True):
            adjacency[i, j] = bool(edge)
        graph = nx.from_numpy_array(adjacency.astype(int), create_using=nx.DiGraph)
        found = coordination_iss(dataclasses.replace(spec, adjacency=adjacency))
        assert found.strongly_connected == nx.is_strongly_connected(graph), adjacency
