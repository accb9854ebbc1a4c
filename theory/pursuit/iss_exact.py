"""Exact decisions of the seed 003 ISS conditions: nothing here compares a float with a threshold.

Every number of a ``kind: pursuit`` case denotes its shortest decimal
(:func:`theory.core.exact.exact_decimal`), so the matrices the conditions are about are
rational, and each condition is decided in rational arithmetic:

* ``K ≻ 0`` (seed 003 eq. (66); K = diag(K_p, k_γ) or K_p): Sylvester's test by exact Bareiss
  elimination (:func:`proofs_check.linalg.positive_definite`);
* ``λ_min(K) ≥ 1`` (the printed region (72) follows from the argument iff it holds):
  ``K − I ⪰ 0`` exactly;
* ``a(L) > 0`` (Definition 1): with the exact left eigenvector ``r > 0`` and the rational basis
  ``B`` of ``r⊥``, ``a(L) = λ_min(BᵀMB, 2BᵀRB)`` and ``BᵀRB ≻ 0``, so ``a(L) > 0`` iff
  ``BᵀMB ≻ 0`` exactly (``M = RL + LᵀR``).

The float values (λ_min(K), a(L)) stay in the output as margins; they decide nothing.
:func:`safe_constant` turns a float estimate into a rational witness constant that passes its
exact check, moving it in the safe direction until it does.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction

import numpy as np

from proofs_check.linalg import positive_definite
from theory.core.exact import exact_decimal
from theory.core.tolerances import ISS_SAFE_STEPS

__all__ = [
    "exact_gain_matrix",
    "gain_matrix_definite",
    "r_perp_connectivity_positive",
    "region_argument_sound",
    "safe_constant",
    "symmetric_part",
]


def exact_gain_matrix(K: np.ndarray) -> list[list[Fraction]]:
    """``K`` with every entry read as its shortest decimal.

    Parameters
    ----------
    K : ndarray
        The decay matrix of seed 003 eq. (66) (:func:`theory.pursuit.iss.gain_matrix`).

    Returns
    -------
    list of lists of Fraction
    """
    return [[exact_decimal(float(x)) for x in row] for row in np.asarray(K, dtype=float)]


def symmetric_part(matrix: list[list[Fraction]]) -> list[list[Fraction]]:
    """The symmetric part ``(K + Kᵀ)/2`` of a square rational ``matrix`` K (exact)."""
    n = len(matrix)
    return [[(matrix[i][j] + matrix[j][i]) / 2 for j in range(n)] for i in range(n)]


def gain_matrix_definite(K: np.ndarray) -> tuple[bool, bool]:
    """Whether ``K`` is exactly symmetric, and whether its symmetric part is positive definite.

    ``eᵀKe = eᵀ sym(K) e``, so V̇ = −eᵀKe ≤ −λ_min(sym K)‖e‖² (seed 003 Lemma 2) needs only the
    symmetric part; the ``iss`` certificate (E2) states ``K`` itself and needs it symmetric.

    Parameters
    ----------
    K : ndarray
        Decay matrix.

    Returns
    -------
    (symmetric, definite) : (bool, bool)
    """
    exact = exact_gain_matrix(K)
    symmetric = all(exact[i][j] == exact[j][i] for i in range(len(exact)) for j in range(i))
    return symmetric, positive_definite(symmetric_part(exact)).positive


def region_argument_sound(K: np.ndarray) -> bool:
    """Whether ``λ_min(sym K) ≥ 1`` exactly (``sym K − I ⪰ 0``), the condition under which the
    printed region (72) ``‖e‖ ≥ c‖x̃‖/θ`` follows from the proof's argument.

    Parameters
    ----------
    K : ndarray
        Decay matrix.
    """
    S = symmetric_part(exact_gain_matrix(K))
    shifted = [[x - (1 if i == j else 0) for j, x in enumerate(row)] for i, row in enumerate(S)]
    return positive_definite(shifted, semi=True).positive


def _r_perp_gram(laplacian: np.ndarray, r: tuple[Fraction, ...]) -> list[list[Fraction]]:
    """``BᵀMB`` for ``M = RL + LᵀR`` and ``B = [e_i − (r_i/r_N) e_N]_{i<N}`` (exact)."""
    n = len(r)
    L = [[Fraction(int(x)) for x in row] for row in np.asarray(laplacian)]
    M = [[r[i] * L[i][j] + L[j][i] * r[j] for j in range(n)] for i in range(n)]
    B = [[Fraction(int(i == j)) if i < n - 1 else -r[j] / r[n - 1] for j in range(n - 1)]
         for i in range(n)]  # fmt: skip
    MB = [[sum((M[i][k] * B[k][j] for k in range(n)), Fraction(0)) for j in range(n - 1)]
          for i in range(n)]  # fmt: skip
    return [[sum((B[k][i] * MB[k][j] for k in range(n)), Fraction(0)) for j in range(n - 1)]
            for i in range(n - 1)]  # fmt: skip


def r_perp_connectivity_positive(laplacian: np.ndarray, r: tuple[Fraction, ...]) -> bool:
    """Whether the generalized algebraic connectivity a(L) is positive, decided exactly.

    Parameters
    ----------
    laplacian : ndarray of int
        L = D_in − A (N ≥ 2 trackers).
    r : tuple of Fraction
        The exact left eigenvector, ``r > 0``, ``rᵀL = 0``, ``rᵀ1 = 1``.

    Returns
    -------
    bool
        ``BᵀMB ≻ 0`` (Sylvester, exact), equivalent to ``a(L) > 0`` because ``BᵀRB ≻ 0``.

    References
    ----------
    seed 003, Definition 1; docs/theory/pursuit-iss.md, section 4.
    """
    return positive_definite(_r_perp_gram(laplacian, r)).positive


def safe_constant(
    estimate: Fraction, holds: Callable[[Fraction], bool], *, towards_zero: bool
) -> Fraction | None:
    """The first of ``estimate``, then halved (``towards_zero``) or doubled, that ``holds``.

    Parameters
    ----------
    estimate : Fraction
        A rounded float estimate of the constant (e.g. λ rounded below λ_min(K)).
    holds : callable
        The constant's exact check (e.g. ``K − λI ⪰ 0``), monotone in the safe direction.
    towards_zero : bool
        Halve (a lower bound such as λ, a) or double (an upper bound such as b, k̄_p, κ).

    Returns
    -------
    Fraction or None
        None when ``iss_safe_steps`` moves (:data:`theory.core.tolerances.ISS_SAFE_STEPS`) do
        not reach a constant that holds.
    """
    value = estimate
    for _ in range(ISS_SAFE_STEPS):
        if holds(value):
            return value
        value = value / 2 if towards_zero else value * 2
    return None
