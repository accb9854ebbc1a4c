"""Exact rational arithmetic: reading numbers exactly, linear algebra on python-flint, and
rational witnesses from floating-point ones (Peyrl–Parrilo style).

Matrices are lists of rows of :class:`fractions.Fraction` (the format of :mod:`proofs_check`)
at the boundaries; :func:`to_fmpq` / :func:`fractions_of` convert to and from
``flint.fmpq_mat`` for the heavy steps (reduced row echelon form, characteristic polynomials).
Numbers are read exactly in two ways only: :func:`exact_decimal` (the decimal a user wrote, for
case data) and :func:`exact_float` (the binary float's exact value, for the floats the suite
computes with).

A numerical solver returns a witness (Lyapunov matrices, gains, evaluation points) that satisfies
strict inequalities only up to rounding. To prove the inequalities we

1. project onto the equality constraints that must hold exactly — symmetry ``P = Pᵀ``
   (orthogonal projection: ``(P + Pᵀ)/2``), unit norm ``‖u‖ = 1`` (through the rational
   parametrisation of the sphere by inverse stereographic projection) and, for the data, the
   row sums ``Σ_j w_ij = 1`` of consensus weights (exact orthogonal projection onto the affine
   set, :func:`project_affine`);
2. round it to dyadic rationals with a chosen number of significant bits;
3. re-check every strict inequality exactly (``proofs_check``); when the float witness was
   strictly feasible with margin ``μ``, a rounding error well below ``μ`` keeps it feasible.

Precision grows until the exact check passes; if it never does, :class:`RationalizationError`
says so and no certificate is produced — never a weaker one.

References
----------
H. Peyrl and P. A. Parrilo, "Computing sum of squares decompositions with rational
coefficients", Theoretical Computer Science 409 (2008) 269–281.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from proofs_check.linalg import Matrix, identity
from theory.core.errors import InconclusiveError

if TYPE_CHECKING:
    from flint import fmpq_mat

__all__ = [
    "PRECISIONS",
    "Matrix",
    "RationalizationError",
    "dyadic",
    "dyadic_matrix",
    "exact_decimal",
    "exact_float",
    "exact_matrix",
    "first_success",
    "fraction_strings",
    "fractions_of",
    "identity",
    "kron",
    "null_basis",
    "project_affine",
    "rational_eigenvalues",
    "rational_matrix",
    "rational_unit_vector",
    "stochastic_matrix",
    "symmetric_projection",
    "to_fmpq",
]

PRECISIONS = (20, 32, 44, 56)
"""Significant bits tried in turn when rounding a witness."""

T = TypeVar("T")


class RationalizationError(InconclusiveError):
    """No valid exact certificate could be produced (the CLI reports it as inconclusive, exit 3)."""


def dyadic(x: float, exponent: int) -> Fraction:
    """``x`` rounded exactly to the nearest multiple of ``2**exponent`` (finite ``x`` only)."""
    if not np.isfinite(x):
        raise RationalizationError(f"cannot round the non-finite value {x!r} to a rational")
    scaled = round(exact_float(x) / Fraction(2) ** exponent)
    return Fraction(scaled) * Fraction(2) ** exponent


def dyadic_matrix(matrix: np.ndarray, bits: int) -> list[list[Fraction]]:
    """Every entry rounded to ``bits`` significant bits of the largest one (whose grid the
    smaller entries share); a vector becomes one row."""
    array = np.atleast_2d(np.asarray(matrix, dtype=float))
    top = float(np.abs(array).max(initial=0.0))
    exponent = (int(np.floor(np.log2(top))) if top > 0 else 0) - bits
    return [[dyadic(float(x), exponent) for x in row] for row in array]


def symmetric_projection(matrix: np.ndarray) -> np.ndarray:
    """Orthogonal projection onto symmetric matrices, ``(M + Mᵀ)/2``.

    Float addition is commutative, so the result is exactly symmetric and stays so after
    entrywise rounding.
    """
    array = np.asarray(matrix, dtype=float)
    return (array + array.T) / 2


def exact_decimal(x: float | int | Fraction) -> Fraction:
    """The rational a user meant by a number: a float's shortest round-trip decimal (0.24 → 6/25).

    This is how the suite reads data written in a case file (coordinates, weights, system
    matrices): the decimal as written, not the binary float nearest to it. Integers and
    ``Fraction`` are returned exactly; a non-finite ``x`` raises :class:`RationalizationError`.
    """
    if isinstance(x, Fraction | int) and not isinstance(x, bool):
        return Fraction(x)
    if not np.isfinite(x):
        raise RationalizationError(f"data value {x!r} is not finite")
    return Fraction(repr(float(x)))


def exact_float(x: float) -> Fraction:
    """The exact value of the binary float ``x`` (``0.1 → 3602879701896397/36028797018963968``).

    For checks about the floats the suite actually computes with (e.g. the zero pattern of the
    powers of a float ``W``), where the decimal a user wrote (:func:`exact_decimal`) is not the
    number in memory.
    """
    if not np.isfinite(x):
        raise RationalizationError(f"cannot read the non-finite value {x!r} as a rational")
    return Fraction(float(x))


def exact_matrix(matrix: Any) -> list[list[Fraction]]:
    """A matrix of exact rationals: ``Fraction`` entries kept, floats read as decimals, a vector
    as one row."""
    rows = matrix if isinstance(matrix, list) else np.atleast_2d(np.asarray(matrix)).tolist()
    return [
        [exact_decimal(x if isinstance(x, Fraction) else float(x)) for x in np.atleast_1d(row)]
        for row in rows
    ]


def project_affine(x: Sequence[Fraction], a: Sequence[Fraction], b: Fraction) -> list[Fraction]:
    """Exact orthogonal projection of ``x`` onto ``{y : a·y = b}``: ``y = x + (b − a·x)/(a·a) a``
    (``ValueError`` if ``a = 0``)."""
    norm2 = sum(Fraction(v) * v for v in a)
    if norm2 == 0:
        raise ValueError("the constraint vector a is zero")
    step = (Fraction(b) - sum(Fraction(v) * u for v, u in zip(a, x, strict=True))) / norm2
    return [Fraction(u) + step * v for u, v in zip(x, a, strict=True)]


def stochastic_matrix(W: Any) -> list[list[Fraction]]:
    """Consensus weights as exact rationals whose rows sum to exactly one.

    Entries are read as decimals (:func:`exact_matrix`); each row is then projected onto
    ``Σ_j w_ij = 1`` within its support (zeros stay zero), moving each entry by at most the
    row's rounding error divided by its support size. Rows already summing to one are unchanged;
    a negative or zero row, or one needing a change above ``1e-9``, raises
    :class:`RationalizationError`.
    """
    out = []
    for i, row in enumerate(exact_matrix(W)):
        support = [Fraction(int(x != 0)) for x in row]
        if any(x < 0 for x in row) or not any(support):
            raise RationalizationError(f"weights row {i + 1} is not non-negative and non-zero")
        projected = project_affine(row, support, Fraction(1))
        if max(abs(p - x) for p, x in zip(projected, row, strict=True)) > Fraction(1, 10**9):
            raise RationalizationError(f"weights row {i + 1} sums to {float(sum(row))}, not 1")
        out.append(projected)
    return out


def fraction_strings(value: Any) -> Any:
    """Nested lists of Fractions as nested lists of exact strings ``"p/q"`` (``TypeError`` for
    anything else)."""
    if isinstance(value, Fraction):
        return str(value)
    if isinstance(value, Iterable) and not isinstance(value, str):
        return [fraction_strings(v) for v in value]
    raise TypeError(f"expected Fractions, got {type(value).__name__}")


def rational_unit_vector(u: Sequence[float], bits: int) -> list[Fraction]:
    """A rational point exactly on the unit sphere near the unit vector ``u``.

    Inverse stereographic projection from the pole ``±e_d`` farther from ``u`` maps rational
    ``s ∈ Q^{d−1}`` to ``(2s, ±(1 − |s|²)) / (1 + |s|²)``, a rational unit vector; ``s`` is
    ``u``'s projection rounded to ``bits`` bits, so the result (``d ≥ 2`` rationals whose squares
    sum to exactly one) is within ``~2^{−bits}`` of ``u``.
    """
    vector = np.asarray(u, dtype=float)
    vector = vector / np.linalg.norm(vector)
    sign = 1.0 if vector[-1] >= 0 else -1.0
    s = [dyadic(x, -bits) for x in vector[:-1] / (1.0 + sign * vector[-1])]
    norm2 = sum(x * x for x in s)
    last = (1 - norm2) / (1 + norm2) * int(sign)
    return [2 * x / (1 + norm2) for x in s] + [last]


def first_success(
    attempt: Callable[[int], T | None], *, precisions: Sequence[int] = PRECISIONS, what: str
) -> tuple[T, int]:
    """The first result of ``attempt(bits)`` (``None``: that precision fails) over ``precisions``,
    and its bits; :class:`RationalizationError` naming ``what`` if every precision fails."""
    for bits in precisions:
        result = attempt(bits)
        if result is not None:
            return result, bits
    raise RationalizationError(
        f"{what}: no rounding to {', '.join(map(str, precisions))} significant bits passes the "
        "exact check; the float witness is not strictly feasible with enough margin, so no "
        "certificate is produced"
    )


def to_fmpq(rows: Matrix) -> fmpq_mat:
    """``rows`` (Fractions) as a ``flint.fmpq_mat`` (an empty list gives ``0 × 0``); python-flint
    is imported on use (a command that never needs exact linear algebra does not pay for it)."""
    from flint import fmpq, fmpq_mat

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
    """The Kronecker product ``a ⊗ b`` of exact matrices (``np.kron``'s layout)."""
    return [[x * y for x in ra for y in rb] for ra in a for rb in b]


def null_basis(rows: Matrix, n: int) -> list[list[Fraction]]:
    """A rational basis of ``{x ∈ Qⁿ : rows · x = 0}`` (from the reduced row echelon form; no
    rows: the identity's columns)."""
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
    """The distinct rational eigenvalues of ``A`` (linear factors of its characteristic
    polynomial), by decreasing modulus."""
    _, factors = to_fmpq(A).charpoly().factor()
    roots = []
    for poly, _ in factors:
        if poly.degree() == 1:
            b, a = poly.coeffs()
            roots.append(-Fraction(int(b.p), int(b.q)) / Fraction(int(a.p), int(a.q)))
    return sorted(roots, key=lambda r: -abs(r))
