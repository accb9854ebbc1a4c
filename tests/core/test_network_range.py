"""``comm_range`` links decided exactly on the decimals written (strict ``<``, seed 000 §4.4)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from theory.core.exact import exact_decimal
from theory.core.network import adjacency_from_range, near_pairs

decimals = st.integers(-999, 999).map(lambda k: k / 10)


@given(st.lists(st.tuples(decimals, decimals), min_size=2, max_size=6), st.integers(1, 400))
def test_links_equal_the_exact_comparison(points, tenths) -> None:
    positions, comm_range = np.array(points), tenths / 10
    got = adjacency_from_range(positions, comm_range)
    for i, p in enumerate(points):
        for j, q in enumerate(points):
            squared = sum(
                (exact_decimal(a) - exact_decimal(b)) ** 2 for a, b in zip(p, q, strict=True)
            )
            assert got[i, j] == (i != j and squared < Fraction(tenths, 10) ** 2)


def test_a_pair_exactly_at_the_range_is_not_linked() -> None:
    """0.1 → 0.4 is 0.30000000000000004 in floats; exactly 0.3: not linked at range 0.3."""
    assert not adjacency_from_range(np.array([[0.1], [0.4]]), 0.3)[0, 1]
    assert adjacency_from_range(np.array([[0.1], [0.4]]), 0.300000000001)[0, 1]


@given(
    st.lists(st.lists(decimals, min_size=3, max_size=3), min_size=0, max_size=30),
    st.integers(1, 300),
    st.integers(1, 50),
)
def test_near_pairs_list_every_close_pair_once(points, tenths, chunk) -> None:
    """The grid lists each pair ``i < j`` at most once and every pair within the reach."""
    positions, reach = np.array(points, dtype=float).reshape(-1, 3), tenths / 10
    chunks = near_pairs(positions, reach, chunk=chunk)
    listed = [(int(a), int(b)) for i, j in chunks for a, b in zip(i, j, strict=True)]
    assert all(i < j for i, j in listed) and len(listed) == len(set(listed))
    close = {
        (i, j)
        for i in range(len(points))
        for j in range(i + 1, len(points))
        if np.linalg.norm(positions[i] - positions[j]) <= reach
    }
    assert close <= set(listed)
