"""Exact TDOA geometry (:mod:`theory.tdoa.geometry.exact`) against independent computations."""

from __future__ import annotations

from fractions import Fraction

from hypothesis import assume, given
from hypothesis import strategies as st

from theory.tdoa.geometry.exact import (
    exact_affine_rank,
    exact_direction_rank,
    exact_mirror,
    same_ray_pair,
    sqrt_sum_vanishes,
)
from theory.tdoa.observability.properties import _direction_rank, _sqrt_sum_is_zero

F = Fraction
small = st.integers(-6, 6)
points3 = st.lists(st.tuples(small, small, small), min_size=1, max_size=6, unique=True)


@given(st.lists(st.tuples(st.integers(-5, 5), st.integers(1, 60)), max_size=5), st.integers(1, 9))
def test_sqrt_sums_agree_with_ball_arithmetic(terms, square) -> None:
    """Includes cancelling pairs: c√q and −c·k√(q/k²)."""
    terms = [(F(c), F(q)) for c, q in terms]
    if terms:
        c, q = terms[0]
        terms.append((-c * square, q / square**2))
    assert sqrt_sum_vanishes(terms) == _sqrt_sum_is_zero(terms)


@given(points3, st.tuples(small, small, small))
def test_direction_rank_agrees_with_the_oracle(agents, target) -> None:
    assume(target not in agents)
    agents = [[F(x) for x in p] for p in agents]
    target = [F(x) for x in target]
    assert exact_direction_rank(target, agents) == _direction_rank(tuple(target), agents)


def test_cone_survives_a_huge_square_factor() -> None:
    """Regression: sympy's square-free split extracts only factors below 2^15, so scaling one
    agent along its ray by a large prime broke the old test (rank 3 reported for a cone)."""
    p = 2**61 - 1
    cone = [[3, 4, 5], [5, 0, 5], [0, -5, 5], [-4 * p, 3 * p, 5 * p]]
    assert exact_direction_rank([0, 0, 0], cone) == 2
    assert exact_direction_rank([0, 0, 0], [*cone[:3], [-4, 3, 6]]) == 3


@given(points3, st.tuples(small, small, small))
def test_mirror_point_keeps_every_range(points, target) -> None:
    dim, mirror = exact_mirror(points, target)
    assert dim == exact_affine_rank(points)
    if mirror is not None:
        assert mirror != tuple(F(x) for x in target)
        for p in points:
            assert sum((F(a) - b) ** 2 for a, b in zip(p, mirror, strict=True)) == sum(
                (a - b) ** 2 for a, b in zip(p, target, strict=True)
            )
    else:
        assert dim == 3 or exact_affine_rank([*points, target]) == dim


def test_same_ray_pair_is_exact() -> None:
    assert same_ray_pair([0, 0, 0], [[1, 2, 3], [2, 2, 2], [0.5, 1, 1.5]]) == (0, 2)
    assert same_ray_pair([0, 0, 0], [[1, 2, 3], [2, 4, 6.000000000001]]) is None
    assert same_ray_pair([0, 0, 0], [[1, 2, 3], [-1, -2, -3]]) is None
