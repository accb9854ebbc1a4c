"""Consensus weights held by their entries (``theory.core.sparse_weights``) are the dense rules of
``theory.core.network`` entry for entry, on random graphs (seed 000 §4.2.2: ``w_ij > 0`` exactly
when ``i`` hears ``j``)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from theory.core.network import (
    component_labels,
    is_symmetric,
    metropolis_weights,
    uniform_weights,
)
from theory.core.sparse_weights import SparseWeights
from theory.kinds import parse_case


def _graphs(*, symmetric: bool):
    def shape(a: np.ndarray) -> np.ndarray:
        a = a.astype(bool) & ~np.eye(a.shape[0], dtype=bool)
        return a | a.T if symmetric else a

    return st.integers(1, 9).flatmap(
        lambda n: arrays(np.int64, (n, n), elements=st.integers(0, 1)).map(shape)
    )


@given(_graphs(symmetric=True))
def test_metropolis_entries_are_the_dense_rule(adjacency: np.ndarray) -> None:
    W = SparseWeights.named(adjacency.shape[0], *np.nonzero(adjacency), "metropolis")
    assert np.array_equal(W.dense(), metropolis_weights(adjacency))
    assert np.array_equal(W.hears(), adjacency)
    assert W.symmetric() and W.count == int(adjacency.sum())


@given(_graphs(symmetric=False), st.data())
def test_uniform_entries_blocks_links_and_components_are_the_dense_ones(
    adjacency: np.ndarray, data: st.DataObject
) -> None:
    n = adjacency.shape[0]
    # the links in a shuffled order: the entries come out sorted by receiver, then sender
    r, s = np.nonzero(adjacency)
    order = data.draw(st.permutations(range(r.size)))
    W = SparseWeights.named(n, r[list(order)], s[list(order)], "uniform")
    dense = uniform_weights(adjacency)
    assert np.array_equal(W.dense(), dense)
    assert W.symmetric() == is_symmetric(adjacency)
    assert np.array_equal(W.component_labels(), component_labels(adjacency))
    rows = data.draw(st.lists(st.integers(0, n - 1), unique=True, min_size=1))
    cols = data.draw(st.lists(st.integers(0, n - 1), unique=True, min_size=1))
    assert np.array_equal(W.block(rows, cols), dense[np.ix_(rows, cols)])
    again = SparseWeights.from_dense(dense)
    assert again.key() == W.key() and np.array_equal(again.dense(), dense)


def test_a_parsed_case_keeps_no_dense_matrix_until_one_is_asked_for() -> None:
    """``trackcert topology`` reads only the entries; the dense ``W`` is made on request."""
    case = parse_case(
        {
            "name": "path",
            "kind": "tdoa",
            "tdoa": {
                "T": 1.0,
                "agents": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                "target": [3, 2, 5],
                "edges": [[1, 2], [2, 3], [3, 4]],
            },
        }
    )
    spec = case.spec
    assert "weights" not in vars(spec) and "hears" not in vars(spec)
    assert spec.links[0].count == 6
    assert np.array_equal(spec.weights[0], spec.links[0].dense())
    assert spec.weights[0][1, 2] == 1 / 3 and spec.weights[0][0, 0] == 1 - 1 / 3  # Metropolis
