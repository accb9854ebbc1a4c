"""``proofs_check.polynomials`` against sympy: the characteristic polynomial, Sturm's count of
distinct real roots in ``(a, b]`` (repeated roots included), and Schur–Cohn's "every root in the
open unit disk" (decided here from sympy's roots, a root on the circle found exactly)."""

from __future__ import annotations

from fractions import Fraction

import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from proofs_check import polynomials as poly

z = sp.Symbol("z")
small = st.integers(-4, 4)


def _sympy(p: list[Fraction]) -> sp.Poly:
    return sp.Poly([sp.Rational(c.numerator, c.denominator) for c in reversed(p)], z)


@given(st.integers(1, 4).flatmap(lambda k: st.lists(st.lists(small, min_size=k, max_size=k),
                                                    min_size=k, max_size=k)))  # fmt: skip
def test_charpoly_is_det_zI_minus_a(rows: list[list[int]]) -> None:
    a = [[Fraction(x) for x in row] for row in rows]
    expected = sp.Matrix(rows).charpoly(z)
    assert _sympy(poly.charpoly(a)) == sp.Poly(expected.as_expr(), z)


@given(
    roots=st.lists(st.fractions(-3, 3, max_denominator=4), min_size=1, max_size=4),
    twice=st.booleans(),
    quadratic=st.integers(0, 3),
    ends=st.tuples(st.fractions(-4, 4, max_denominator=3), st.fractions(-4, 4, max_denominator=3)),
)
def test_sturm_counts_distinct_real_roots_in_a_half_open_interval(roots, twice, quadratic, ends):
    """``Π (z − r)`` (each root twice when ``twice``) times ``z² + q`` (no real roots for q > 0)."""
    p = [Fraction(1)]
    for r in roots + (roots if twice else []):
        p = poly.mul(p, [-r, Fraction(1)])
    p = poly.mul(p, [Fraction(quadratic), Fraction(0), Fraction(1)])
    low, high = sorted(ends)
    if low == high:
        return
    expected = {r for r in roots if low < r <= high} | (
        {Fraction(0)} if quadratic == 0 and low < 0 <= high else set()
    )
    assert poly.real_roots_in(p, low, high) == len(expected)


@given(st.lists(small, min_size=2, max_size=6).filter(lambda c: c[-1] != 0))
def test_schur_cohn_agrees_with_the_exact_roots(coefficients: list[int]) -> None:
    p = [Fraction(c, 2) for c in coefficients]
    assert poly.schur_stable(p) is _inside_unit_disk(_sympy(p))


def _inside_unit_disk(p: sp.Poly) -> bool:
    """Every root of ``p`` in the open unit disk. A root on the circle (|r| = 1, undecidable by
    comparing sympy's root objects) is also a root of the reciprocal ``zⁿp(1/z)``, as is every
    r whose 1/r̄ is a root; a disk-stable ``p`` shares no root with it. With no common root, no
    root lies on the circle and 50 digits decide each |r| < 1."""
    reciprocal = sp.Poly(list(reversed(p.all_coeffs())), z)
    if sp.gcd(p, reciprocal).degree() > 0:
        return False
    return all(sp.Abs(r).evalf(50) < 1 for r in p.all_roots())
