"""Exact univariate polynomials over the rationals: lists of Fractions, constant term first.

What the kind ``self-weight-necessary-violated`` needs and nothing more: arithmetic, the
characteristic polynomial (Faddeev–LeVerrier), the number of distinct real roots in an interval
(Sturm), and whether every root lies in the open unit disk (Schur–Cohn). Every step is exact.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import pairwise

from proofs_check import linalg as la
from proofs_check.deadline import tick
from proofs_check.linalg import Matrix

__all__ = [
    "Poly",
    "add",
    "charpoly",
    "divide",
    "evaluate",
    "mul",
    "real_roots_in",
    "schur_stable",
    "trim",
]

Poly = list[Fraction]


def trim(p: Poly) -> Poly:
    """``p`` without zero leading coefficients (the zero polynomial is ``[]``)."""
    out = list(p)
    while out and out[-1] == 0:
        out.pop()
    return out


def add(p: Poly, q: Poly) -> Poly:
    """``p + q``."""
    size = max(len(p), len(q))
    padded = [list(p) + [Fraction(0)] * (size - len(p)), list(q) + [Fraction(0)] * (size - len(q))]
    return trim([x + y for x, y in zip(*padded, strict=True)])


def mul(p: Poly, q: Poly) -> Poly:
    """``p · q``."""
    if not p or not q:
        return []
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, x in enumerate(p):
        tick()
        for j, y in enumerate(q):
            out[i + j] += x * y
    return trim(out)


def evaluate(p: Poly, x: Fraction) -> Fraction:
    """``p(x)`` (Horner)."""
    value = Fraction(0)
    for c in reversed(p):
        value = value * x + c
    return value


def divide(p: Poly, q: Poly) -> tuple[Poly, Poly]:
    """``(quotient, remainder)`` of ``p`` divided by ``q ≠ 0``."""
    r, q = trim(p), trim(q)
    out = [Fraction(0)] * max(len(r) - len(q) + 1, 0)
    while len(r) >= len(q):
        tick()
        factor, shift = r[-1] / q[-1], len(r) - len(q)
        out[shift] = factor
        r = trim([c - (factor * q[k - shift] if k >= shift else 0) for k, c in enumerate(r)])
    return trim(out), r


def _derivative(p: Poly) -> Poly:
    return trim([k * c for k, c in enumerate(p)][1:])


def _gcd(p: Poly, q: Poly) -> Poly:
    p, q = trim(p), trim(q)
    while q:
        p, q = q, divide(p, q)[1]
    return p


def _sign_changes(chain: list[Poly], x: Fraction) -> int:
    signs = [v for v in (evaluate(p, x) for p in chain) if v != 0]
    return sum(1 for a, b in pairwise(signs) if (a > 0) != (b > 0))


def real_roots_in(p: Poly, low: Fraction, high: Fraction) -> int:
    """The number of distinct real roots of ``p ≠ 0`` in ``(low, high]`` (Sturm's theorem on the
    square-free part ``p / gcd(p, p′)``, ``low < high``)."""
    free = divide(p, _gcd(p, _derivative(p)))[0]
    chain = [free, _derivative(free)]
    while chain[-1]:
        chain.append([-c for c in divide(chain[-2], chain[-1])[1]])
    chain.pop()
    return _sign_changes(chain, low) - _sign_changes(chain, high)


def schur_stable(p: Poly) -> bool:
    """Whether every root of ``p`` (real coefficients, degree ≥ 0, ``p ≠ 0``) lies in the open
    unit disk. Schur–Cohn: if ``|p_0| ≥ |p_k|`` the product of the roots has modulus ``≥ 1``;
    else ``p`` is Schur stable iff ``(p_k p(z) − p_0 p*(z)) / z`` is (``p*``: reversed)."""
    c = trim(p)
    while len(c) > 1:
        tick()
        if abs(c[0]) >= abs(c[-1]):
            return False
        c = [c[-1] * a - c[0] * b for a, b in zip(c, reversed(c), strict=True)][1:]
    return bool(c)


def charpoly(a: Matrix) -> Poly:
    """``det(z I − a)`` (Faddeev–LeVerrier: ``N_k = a N_{k−1} + c_{m−k+1} I``, ``c_{m−k} =
    −tr(a N_k)/k``)."""
    m = len(a)
    coefficients = [Fraction(0)] * m + [Fraction(1)]
    N = [[Fraction(0)] * m for _ in range(m)]
    for k in range(1, m + 1):
        N = la.add(la.matmul(a, N), la.scale(coefficients[m - k + 1], la.identity(m)))
        coefficients[m - k] = -la.trace(la.matmul(a, N)) / k
    return coefficients
