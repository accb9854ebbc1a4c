"""Seed 000 Lemma 4.2.2 / seed 001 Lemma 1: the zero pattern of W^l is the path-length relation."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.kinds import load_case
from theory.registry import get_claim
from theory.tdoa.observability.weights import path_lemma_failures, path_lengths


@st.composite
def stochastic_matrices(draw, *, self_loops: bool = True):
    """A random row-stochastic W on a random digraph (positive diagonal when ``self_loops``)."""
    n = draw(st.integers(1, 6))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    support = rng.random((n, n)) < draw(st.floats(0.0, 0.6))
    np.fill_diagonal(support, self_loops)
    weights = np.where(support, rng.uniform(0.05, 1.0, (n, n)), 0.0)
    rows = weights.sum(axis=1, keepdims=True)
    return np.where(rows > 0, weights / np.where(rows > 0, rows, 1), 0.0)


@given(stochastic_matrices())
def test_the_lemma_holds_at_every_power_with_positive_self_weights(W) -> None:
    """Checked beyond N − 1 too: the support stops growing there (the module's argument)."""
    assert path_lemma_failures(W, range(2 * len(W) + 1)) == []


@given(stochastic_matrices())
def test_path_lengths_are_bfs_distances(W) -> None:
    d = path_lengths(W)
    n = len(W)
    for i in range(n):
        assert d[i][i] == 0
        for j in range(n):
            if i != j and W[i, j] > 0:
                assert d[i][j] == 1
            if d[i][j] is not None and d[i][j] > 1:  # a shortest path has a shortest prefix
                assert any(d[i][k] == d[i][j] - 1 and W[k, j] > 0 for k in range(n))


def test_without_self_weights_the_lemma_fails() -> None:
    """The hypothesis w_ii > 0 is needed: a 2-cycle alternates between I and W, so the
    adjacent agents 1 and 2 have [W²]_12 = 0 (and [W]_11 = 0 despite the empty path)."""
    W = np.array([[0.0, 1.0], [1.0, 0.0]])
    assert path_lemma_failures(W, [0]) == []
    failures = path_lemma_failures(W, [1, 2])
    assert {"l": 1, "i": 1, "j": 1, "positive": False, "path_length": 0} in failures
    assert {"l": 2, "i": 1, "j": 2, "positive": False, "path_length": 1} in failures


@pytest.mark.parametrize("name", ["fig43-case-d", "topology-directed-chain", "ch5-example-1-wg"])
def test_the_claim_verifies_bundled_networks(name: str) -> None:
    (result,) = get_claim("seed000.lem4.2.2").run(load_case(name))
    assert (result.status, result.method) == ("verified", "exact")
    assert all(not n["failures"] for n in result.evidence["networks"])


def test_time_varying_scenes_are_checked_per_network() -> None:
    (result,) = get_claim("seed000.lem4.2.2").run(load_case("topology-distance-rule-split"))
    steps = sorted(k for n in result.evidence["networks"] for k in n["steps"])
    assert steps == list(range(1, 31)) and len(result.evidence["networks"]) == 7
