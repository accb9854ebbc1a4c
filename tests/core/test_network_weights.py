"""Named consensus weights: one rule in floats and in exact rationals (``theory.core.network``),
and the two exact readings of a float (``theory.core.exact``)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.exact import RationalizationError, exact_decimal, exact_float
from theory.core.network import (
    NAMED_WEIGHTS,
    exact_metropolis_weights,
    exact_uniform_weights,
    exact_weights,
    metropolis_weights,
    uniform_weights,
)
from theory.core.tolerances import ROUNDING_TOL


@st.composite
def graphs(draw, *, symmetric: bool = True) -> np.ndarray:
    """A random graph on 1–8 agents (symmetric, or directed), no self-loops."""
    n = draw(st.integers(1, 8))
    bits = draw(st.lists(st.booleans(), min_size=n * n, max_size=n * n))
    adjacency = np.array(bits, dtype=bool).reshape(n, n)
    if symmetric:
        adjacency = adjacency | adjacency.T
    np.fill_diagonal(adjacency, False)
    return adjacency


@given(graphs())
def test_float_metropolis_is_the_exact_rule_rounded(adjacency: np.ndarray) -> None:
    """Off-diagonal weights are one division (correctly rounded); the diagonal, 1 − Σ, is within
    a few ulps (rounding_tol)."""
    floats, exact = metropolis_weights(adjacency), exact_metropolis_weights(adjacency)
    n = adjacency.shape[0]
    for i in range(n):
        for j in range(n):
            if i != j:
                assert floats[i, j] == float(exact[i][j])
        assert abs(exact_float(floats[i, i]) - exact[i][i]) <= ROUNDING_TOL
        assert sum(exact[i]) == 1 and exact[i][i] > 0


@given(graphs(symmetric=False))
def test_float_uniform_is_the_exact_rule_rounded(adjacency: np.ndarray) -> None:
    floats, exact = uniform_weights(adjacency), exact_uniform_weights(adjacency)
    assert floats.tolist() == [[float(x) for x in row] for row in exact]
    assert all(sum(row) == 1 for row in exact)


@given(graphs())
def test_exact_metropolis_is_symmetric(adjacency: np.ndarray) -> None:
    exact = exact_weights(adjacency, "metropolis")
    assert exact == [list(col) for col in zip(*exact, strict=True)]


def test_the_design_rules_on_a_path() -> None:
    path = np.array([[0, 1, 0], [1, 0, 1], [0, 1, 0]], dtype=bool)
    third, half = Fraction(1, 3), Fraction(1, 2)
    assert exact_weights(path, "metropolis") == [
        [1 - third, third, 0],
        [third, third, third],
        [0, third, 1 - third],
    ]
    assert exact_weights(path, "uniform") == [
        [half, half, 0],
        [third, third, third],
        [0, half, half],
    ]
    assert set(NAMED_WEIGHTS) == {"metropolis", "uniform"}
    with pytest.raises(ValueError, match="rule"):
        exact_weights(path, "maximum-degree")


def test_decimal_as_written_and_float_in_memory() -> None:
    assert exact_decimal(0.24) == Fraction(6, 25)
    assert exact_decimal(0.1) == Fraction(1, 10)
    assert exact_decimal(3) == 3 and exact_decimal(Fraction(2, 7)) == Fraction(2, 7)
    assert exact_float(0.1) == Fraction(3602879701896397, 36028797018963968)
    assert exact_float(0.1) != exact_decimal(0.1)
    assert float(exact_float(0.1)) == 0.1 == float(exact_decimal(0.1))
    for bad in (float("nan"), float("inf")):
        with pytest.raises(RationalizationError):
            exact_decimal(bad)
        with pytest.raises(RationalizationError):
            exact_float(bad)


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_both_readings_round_trip(x: float) -> None:
    assert float(exact_decimal(x)) == x
    assert float(exact_float(x)) == x
