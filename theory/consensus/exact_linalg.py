"""Exact rational linear algebra for the ch. 5 decisions (python-flint ``fmpq_mat`` underneath).

Matrices are lists of rows of :class:`fractions.Fraction` (the format of :mod:`proofs_check`);
these helpers (with :func:`proofs_check.linalg.identity`, re-exported) convert to and from
``flint.fmpq_mat`` for the heavy steps (reduced row echelon
form, solving, characteristic polynomials) and read float data as the decimals it prints as.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from flint import fmpq, fmpq_mat

from proofs_check.linalg import Matrix, identity
from theory.core.rationalize import exact_matrix

__all__ = [
    "Matrix",
    "fractions_of",
    "identity",
    "kron",
    "null_basis",
    "rational_eigenvalues",
    "rational_matrix",
    "to_fmpq",
]


def to_fmpq(rows: Matrix) -> fmpq_mat:
    """``rows`` (Fractions) as a ``flint.fmpq_mat`` (an empty list gives ``0 × 0``)."""
    m, n = len(rows), len(rows[0]) if rows else 0
    return fmpq_mat(m, n, [fmpq(x.numerator, x.denominator) for row in rows for x in row])


def fractions_of(M: fmpq_mat) -> Matrix:
    """The ``flint.fmpq_mat`` ``M`` as rows of Fractions."""
    return [[Fraction(int(x.p), int(x.q)) for x in row] for row in M.tolist()]


def rational_matrix(M: np.ndarray | Matrix) -> Matrix:
    """The matrix ``M``, floats read as the decimals they print as (0.24 → 6/25), Fractions kept."""
    if isinstance(M, list) and M and isinstance(M[0], list) and M[0]:
        if isinstance(M[0][0], Fraction):
            return M
    return exact_matrix(np.atleast_2d(np.asarray(M, dtype=float)))


def kron(a: Matrix, b: Matrix) -> Matrix:
    """The Kronecker product ``a ⊗ b`` (``np.kron``'s layout).

    Parameters
    ----------
    a, b : list of rows of Fraction
        Exact matrices.
    """
    return [[x * y for x in ra for y in rb] for ra in a for rb in b]


def null_basis(rows: Matrix, n: int) -> list[list[Fraction]]:
    """A rational basis of ``{x ∈ Qⁿ : rows · x = 0}`` (from the reduced row echelon form).

    Parameters
    ----------
    rows : list of rows of Fraction
        The matrix (possibly with no rows: then the basis is the identity's columns).
    n : int
        Number of columns.

    Returns
    -------
    list of vectors (lists of Fraction)
    """
    if not rows:
        return [[Fraction(int(i == j)) for i in range(n)] for j in range(n)]
    R, rank = to_fmpq(rows).rref()
    R = fractions_of(R)[:rank]
    pivots = [next(j for j, x in enumerate(r) if x != 0) for r in R]
    basis = []
    for free in (j for j in range(n) if j not in pivots):
        v = [Fraction(0)] * n
        v[free] = Fraction(1)
        for r, p in zip(R, pivots, strict=True):
            v[p] = -r[free]
        basis.append(v)
    return basis


def rational_eigenvalues(A: Matrix) -> list[Fraction]:
    """The distinct rational eigenvalues of ``A`` (linear factors of its characteristic polynomial).

    Parameters
    ----------
    A : list of rows of Fraction
        Square matrix.

    Returns
    -------
    list of Fraction
        Sorted by decreasing modulus.
    """
    _, factors = to_fmpq(A).charpoly().factor()
    roots = []
    for poly, _ in factors:
        if poly.degree() == 1:
            b, a = poly.coeffs()
            roots.append(-Fraction(int(b.p), int(b.q)) / Fraction(int(a.p), int(a.q)))
    return sorted(roots, key=lambda r: -abs(r))
