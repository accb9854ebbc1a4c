"""Numeric observability and detectability of a pair ``(A, C)`` with stated tolerances.

Used by the TDOA topology checker (seed 000 §4.2), the consensus filter checks (seed 000 ch. 5)
and the simulations. Ranks are decided from singular values against a scale-aware tolerance
``rank_tol · σ_max``; a singular value within a factor of the tolerance is reported so that the
caller can say "inconclusive" instead of guessing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.core.tolerances import EIGEN_TOL, INCONCLUSIVE_FACTOR, RANK_TOL

__all__ = [
    "RANK_TOL",
    "RankResult",
    "distinct_values",
    "numeric_rank",
    "observability_matrix",
    "unobservable_eigenvalues",
]


@dataclass(frozen=True)
class RankResult:
    """A numerical rank and what decided it: the singular values (descending), the absolute
    ``threshold`` ``rank_tol · σ_max``, and the ``margin`` ``min(σ_r / threshold, threshold /
    σ_{r+1})`` (∞ when not applicable) by which the decision clears it."""

    rank: int
    singular_values: tuple[float, ...]
    threshold: float
    rank_tol: float
    margin: float

    def conclusive(self, inconclusive_factor: float = INCONCLUSIVE_FACTOR) -> bool:
        """Whether every singular value clears the threshold by ``inconclusive_factor``."""
        return self.margin >= inconclusive_factor


def numeric_rank(matrix: np.ndarray, *, rank_tol: float = RANK_TOL) -> RankResult:
    """Rank from the SVD, threshold ``rank_tol · σ_max`` (scale-aware).

    Parameters
    ----------
    matrix : ndarray
        Any real matrix.
    rank_tol : float
        Relative tolerance.

    Returns
    -------
    RankResult
    """
    sv = np.linalg.svd(np.atleast_2d(matrix), compute_uv=False) if matrix.size else np.zeros(0)
    top = float(sv[0]) if sv.size else 0.0
    threshold = rank_tol * top if top > 0 else rank_tol
    rank = int(np.sum(sv > threshold))
    above = sv[rank - 1] / threshold if rank > 0 else np.inf
    below = threshold / sv[rank] if rank < sv.size and sv[rank] > 0 else np.inf
    return RankResult(
        rank, tuple(float(s) for s in sv), float(threshold), rank_tol, float(min(above, below))
    )


def observability_matrix(A: np.ndarray, C: np.ndarray, steps: int | None = None) -> np.ndarray:
    """``O = [C; C A; …; C A^{steps−1}]`` (seed 000 eq. (4.18))."""
    n = A.shape[0]
    blocks, block = [], np.asarray(C, dtype=float).reshape(-1, n)
    for _ in range(n if steps is None else steps):
        blocks.append(block)
        block = block @ A
    return np.vstack(blocks)


def unobservable_eigenvalues(
    A: np.ndarray, C: np.ndarray, *, rank_tol: float = RANK_TOL
) -> list[complex]:
    """Eigenvalues λ of ``A`` failing the PBH test ``rank [A − λI; C] = n``, each listed once
    per lost rank (so ``n − rank O`` of them when ``A`` is diagonalisable)."""
    n = A.shape[0]
    scale = max(1.0, float(np.abs(A).max(initial=0.0)))
    distinct = distinct_values(np.linalg.eigvals(A), scale=scale)
    lost: list[complex] = []
    for lam in distinct:
        pencil = np.vstack([A - lam * np.eye(n), np.asarray(C, dtype=complex).reshape(-1, n)])
        defect = n - numeric_rank(pencil, rank_tol=rank_tol).rank
        lost.extend([complex(lam)] * defect)
    return lost


def distinct_values(values: np.ndarray, *, scale: float, rel: float = EIGEN_TOL) -> list[complex]:
    """``values`` without repeats: a value within ``rel · scale`` of an earlier one is dropped."""
    out: list[complex] = []
    for value in values:
        if all(abs(value - seen) > rel * scale for seen in out):
            out.append(complex(value))
    return out
