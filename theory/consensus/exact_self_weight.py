"""Thm 5.2.10's self-weight bound and detectability decided in exact rational arithmetic (flint).

``w_ii r_σ(A_iᵘ)² < 1`` is decided without floating point, so boundary cases such as seed 000
Example 1's ``W_c`` (``w_ii = 0.25``, ``r_σ = 2``: exactly on the bound) get a verdict:

1. the data are read as the decimals written (:func:`theory.core.exact.exact_decimal`,
   re-exported as ``to_fraction``: 0.24 is 6/25);
2. the unobservable subspace ``N = null O`` (observability matrix, eq. (4.18)) gets a rational
   basis ``V`` from the reduced row echelon form; ``A_u = (V'V)⁻¹ V' A V`` (exact: ``N`` is
   A-invariant, so ``A V = V A_u``);
3. with ``p(x) = det(x I − A_u)`` of degree k, ``s(z) = (−1)^k p(√z) p(−√z)`` has the roots
   ``λ²``, and ``t(z) = w^k s(z / w)`` the roots ``w λ²``;
4. ``w r_σ(A_u)² < 1`` iff ``t`` is Schur stable, decided by the Schur–Cohn reduction: with
   ``|t_0| < |t_k|``, ``t`` is Schur stable iff ``(t_k t(z) − t_0 t*(z)) / z`` is, where ``t*`` is
   ``t`` with reversed coefficients; ``|t_0| ≥ |t_k|`` means the product of the roots has modulus
   ≥ 1, so some root is outside the open disk.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from flint import fmpq_mat

from theory.core.exact import exact_decimal as to_fraction
from theory.core.exact import fractions_of, null_basis, rational_matrix, to_fmpq

__all__ = [
    "detectable_exact",
    "exact_unobservable_part",
    "schur_stable",
    "self_weight_ok_exact",
    "to_fraction",
]


def exact_unobservable_part(A: np.ndarray, C: np.ndarray) -> fmpq_mat:
    """``A_u`` of the Kalman decomposition of ``(A, C)``, exact over the rationals.

    Parameters
    ----------
    A : ndarray, shape (n, n)
        System matrix (entries read as written decimals).
    C : ndarray, shape (p, n), or list of rows of Fraction
        Measurement matrix (``p = 0`` allowed; exact rows are used as they are).

    Returns
    -------
    flint.fmpq_mat
        ``k × k`` with ``k = n − rank O`` (``0 × 0`` if observable).
    """
    n = len(A) if isinstance(A, list) else A.shape[0]
    Aq = to_fmpq(rational_matrix(A))
    rows: list[list[Fraction]] = []
    if isinstance(C, list):  # exact rows already
        block = C
    else:
        block = rational_matrix(np.asarray(C, dtype=float).reshape(-1, n)) if np.size(C) else []
    power = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    for _ in range(n):
        if block:
            product = to_fmpq(block) * to_fmpq(power)
            rows.extend(fractions_of(product))
        power = fractions_of(to_fmpq(power) * Aq)
    V = null_basis(rows, n)
    if not V:
        return fmpq_mat(0, 0)
    Vq = to_fmpq([[V[c][r] for c in range(len(V))] for r in range(n)])
    Vt = Vq.transpose()
    return (Vt * Vq).solve(Vt * Aq * Vq)


def schur_stable(coefficients: list[Fraction]) -> bool:
    """Whether every root of ``Σ c_j z^j`` lies in the open unit disk (Schur–Cohn, exact).

    Parameters
    ----------
    coefficients : list of Fraction
        ``c_0, …, c_k`` with ``c_k ≠ 0``.
    """
    c = list(coefficients)
    while len(c) > 1:
        if abs(c[0]) >= abs(c[-1]):
            return False
        lead, const = c[-1], c[0]
        reduced = [lead * a - const * b for a, b in zip(c, reversed(c), strict=True)]
        c = reduced[1:]
    return True


def self_weight_ok_exact(A: np.ndarray, C: np.ndarray, w: float) -> bool:
    """``w r_σ(A_u)² < 1`` decided exactly (seed 000 Thm 5.2.10 (2)).

    Parameters
    ----------
    A : ndarray, shape (n, n)
        System matrix.
    C : ndarray, shape (p, n)
        Agent i's measurement matrix.
    w : float
        The self-weight ``w_ii`` (read as the written decimal).

    Returns
    -------
    bool

    References
    ----------
    seed 000 Thm 5.2.10 (2); this module's docstring for the method.
    """
    A_u = exact_unobservable_part(A, C)
    k = A_u.nrows()
    if k == 0:
        return True
    p = [Fraction(int(x.p), int(x.q)) for x in A_u.charpoly().coeffs()]  # c_0 … c_k
    p_neg = [c * (-1) ** j for j, c in enumerate(p)]
    product = [Fraction(0)] * (2 * k + 1)
    for i, a in enumerate(p):
        for j, b in enumerate(p_neg):
            product[i + j] += a * b
    s = [(-1) ** k * product[2 * j] for j in range(k + 1)]
    wq = to_fraction(w)
    if wq == 0:
        return True
    t = [s[j] * wq ** (k - j) for j in range(k + 1)]
    return schur_stable(t)


def detectable_exact(A: np.ndarray, C: np.ndarray) -> bool:
    """Whether ``(A, C)`` is detectable, decided exactly: ``A_u`` is Schur stable (Schur–Cohn).

    Every unobservable eigenvalue is an eigenvalue of ``A_u`` (Kalman decomposition), so the pair
    is detectable iff ``det(zI − A_u)`` has all its roots in the open unit disk.

    Parameters
    ----------
    A : ndarray, shape (n, n)
        System matrix (entries read as written decimals).
    C : ndarray, shape (p, n), or list of rows of Fraction
        Measurement matrix (``p = 0`` allowed).

    Returns
    -------
    bool

    References
    ----------
    seed 000 Def. 5.2.9, Thm 5.2.10 (1).
    """
    A_u = exact_unobservable_part(A, C)
    if A_u.nrows() == 0:
        return True
    return schur_stable([Fraction(int(x.p), int(x.q)) for x in A_u.charpoly().coeffs()])
