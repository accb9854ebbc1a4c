"""Exact rational linear algebra on lists of lists of :class:`fractions.Fraction`.

Positive definiteness is decided by Sylvester's criterion computed with fraction-free (Bareiss)
elimination, never by eigenvalues: a symmetric ``S`` is positive definite iff every leading
principal minor is positive, and the ``k``-th pivot of Gaussian elimination without pivoting
(the ``D`` of ``S = L D Lᵀ``) is the ratio of the ``k``-th to the ``(k−1)``-th leading minor.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import lcm, prod

from proofs_check.deadline import tick

__all__ = [
    "Definiteness",
    "add",
    "determinant",
    "first_asymmetry",
    "identity",
    "matmul",
    "positive_definite",
    "rank",
    "scale",
    "sub",
    "trace",
    "transpose",
]

Matrix = list[list[Fraction]]


def identity(n: int) -> Matrix:
    """The ``n × n`` identity."""
    return [[Fraction(int(r == c)) for c in range(n)] for r in range(n)]


def transpose(a: Matrix) -> Matrix:
    """``aᵀ``."""
    return [list(column) for column in zip(*a, strict=True)]


def matmul(a: Matrix, b: Matrix) -> Matrix:
    """``a b`` (zero entries of ``a`` are skipped)."""
    width = len(b[0])
    out = []
    for row in a:
        tick()
        acc = [Fraction(0)] * width
        for k, entry in enumerate(row):
            if entry:
                for c, other in enumerate(b[k]):
                    if other:
                        acc[c] += entry * other
        out.append(acc)
    return out


def add(a: Matrix, b: Matrix) -> Matrix:
    """``a + b``."""
    return [[x + y for x, y in zip(ra, rb, strict=True)] for ra, rb in zip(a, b, strict=True)]


def sub(a: Matrix, b: Matrix) -> Matrix:
    """``a − b``."""
    return [[x - y for x, y in zip(ra, rb, strict=True)] for ra, rb in zip(a, b, strict=True)]


def scale(factor: Fraction, a: Matrix) -> Matrix:
    """``factor · a``."""
    return [[factor * x for x in row] for row in a]


def trace(a: Matrix) -> Fraction:
    """``tr a``."""
    return sum((row[i] for i, row in enumerate(a)), Fraction(0))


def first_asymmetry(a: Matrix) -> tuple[int, int, Fraction] | None:
    """The first ``(r, c, a[r][c] − a[c][r])`` with a non-zero difference, or ``None``."""
    for r, row in enumerate(a):
        for c in range(r + 1, len(row)):
            if row[c] != a[c][r]:
                return r, c, row[c] - a[c][r]
    return None


@dataclass(frozen=True)
class Definiteness:
    """Outcome of the exact (semi)definiteness test: whether it is ``positive``; else ``order``,
    the first failing leading minor, and ``pivot``, the LDLᵀ pivot there (by how much it fails);
    when positive, ``order`` is 0 and ``pivot`` the smallest pivot (how much room there is)."""

    positive: bool
    order: int
    pivot: Fraction


def positive_definite(a: Matrix, *, semi: bool = False) -> Definiteness:
    """Exact Sylvester test of a symmetric matrix (the caller checks symmetry first).

    Rows and columns are scaled by positive integers ``d_i`` (a congruence, which keeps the
    signs of the leading minors) so that Bareiss elimination runs on integers. With ``semi``
    it tests ``a ⪰ 0``: a zero pivot whose row is zero is dropped (the Schur complement is
    ``0 ⊕ S′`` and elimination goes on with ``S′``); a zero pivot with a non-zero row fails,
    since a 2 × 2 principal minor of the Schur complement is then negative.
    """
    n = len(a)
    d = [lcm(*(x.denominator for x in a[i])) for i in range(n)]
    m = [[int(a[i][j] * d[i] * d[j]) for j in range(n)] for i in range(n)]
    previous, smallest = 1, None
    for k in range(n):
        tick()
        minor = m[k][k]
        pivot = Fraction(minor, previous) / (d[k] * d[k])
        if semi and minor == 0 and not any(m[k][k + 1 :]):
            smallest = pivot
            continue
        if minor <= 0:
            return Definiteness(False, k + 1, pivot)
        smallest = pivot if smallest is None or pivot < smallest else smallest
        for i in range(k + 1, n):
            for j in range(k + 1, n):
                m[i][j] = (m[i][j] * minor - m[i][k] * m[k][j]) // previous
        previous = minor
    return Definiteness(True, 0, smallest if smallest is not None else Fraction(0))


def determinant(a: Matrix) -> Fraction:
    """Exact determinant of a square matrix (Bareiss with row exchanges, integer arithmetic)."""
    n = len(a)
    d = [lcm(*(x.denominator for x in row)) for row in a]
    m = [[int(x * d[i]) for x in row] for i, row in enumerate(a)]
    sign, previous = 1, 1
    for k in range(n):
        tick()
        swap = next((i for i in range(k, n) if m[i][k] != 0), None)
        if swap is None:
            return Fraction(0)
        if swap != k:
            m[k], m[swap], sign = m[swap], m[k], -sign
        for i in range(k + 1, n):
            for j in range(k + 1, n):
                m[i][j] = (m[i][j] * m[k][k] - m[i][k] * m[k][j]) // previous
        previous = m[k][k]
    return Fraction(sign * m[n - 1][n - 1], prod(d)) if n else Fraction(1)


def rank(a: Matrix) -> int:
    """Exact rank (Gaussian elimination over the rationals)."""
    rows = [list(row) for row in a]
    found = 0
    for c in range(len(rows[0]) if rows else 0):
        tick()
        pivot = next((r for r in range(found, len(rows)) if rows[r][c] != 0), None)
        if pivot is None:
            continue
        rows[found], rows[pivot] = rows[pivot], rows[found]
        for r in range(found + 1, len(rows)):
            factor = rows[r][c] / rows[found][c]
            if factor:
                rows[r] = [x - factor * y for x, y in zip(rows[r], rows[found], strict=True)]
        found += 1
    return found
