"""Rank of the networked TDOA observability matrix from the spectrum of W (no 6N-column matrix).

The networked pair of seed 000 eq. (4.24) is ``(W ⊗ A, D_H)`` with ``A = [[I, T I], [0, I]]``
and ``D_H = diag(H_j)``, each ``H_j = [G_j, 0]`` measuring positions only. Write a state as
``(Z_p, Z_v)``, two ``N × d`` matrices (positions and velocities, one row per agent). Step ``l``
of the output is ``G_j · row_j(W^l (Z_p + l T Z_v))``. When ``W`` is diagonalisable and
``T ≠ 0``, the sequences ``μ^l`` and ``l μ^l`` separate by eigenvalue, which gives

* for each eigenvalue ``μ`` of ``W`` with right eigenvectors ``V_μ`` (``N × m``), the defect
  ``κ_μ = dim{c ∈ R^{m×d} : G_j (V_μ c)_j = 0 ∀ j}``;
* unobservable subspace dimension ``2 Σ_{μ≠0} κ_μ + κ_0 + d·m_0`` (velocities in ``ker W`` are
  never seen: ``l·0^l = 0``), hence ``rank O = 2dN − that``;
* eigenvalues of ``W ⊗ A`` on the unobservable subspace (algebraic multiplicity, as in
  :mod:`theory.tdoa.observability.network`): ``μ`` ``2κ_μ`` times, ``0`` ``κ_0 + d·m_0`` times.

The proof is in ``docs/topology.md``. Only ``W`` similar to a symmetric matrix through a diagonal
scaling is handled here (Metropolis weights, uniform weights on an undirected graph, symmetric
explicit weights): its eigenvalues are real and its eigenvectors well conditioned.
:func:`symmetrizing_scale` says whether ``W`` qualifies; otherwise use the dense
:mod:`theory.tdoa.observability.network`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.core.exact import exact_decimal
from theory.core.observability import RANK_TOL
from theory.core.sparse_weights import SparseWeights
from theory.core.tolerances import CLUSTER_TOL

__all__ = [
    "SpectralRank",
    "eigenspace_defects",
    "spectral_network_rank",
    "symmetrizing_scale",
]


GRAM_SAFE_RATIO = 1e-5
"""σ_min/σ_max above this is read from the d×d Gram matrix (its eigenvalues then carry ≥ 5 correct
digits); below it the defect matrix itself goes through an SVD."""

_CHUNK_BYTES = 32_000_000


@dataclass(frozen=True)
class SpectralRank:
    """``rank O`` of seed 000 eq. (4.36) for one network (or component) of ``n_states = 2dN``
    states, the eigenvalues of ``W ⊗ A`` on the unobservable subspace (with multiplicity), and
    the smallest factor by which a decision (clustering, zero test, defect rank) clears its
    tolerance."""

    rank: int
    n_states: int
    unobservable_eigenvalues: tuple[float, ...]
    margin: float


def symmetrizing_scale(W: SparseWeights) -> np.ndarray | None:
    """A vector ``s > 0`` with ``diag(s) W diag(s)^{-1}`` symmetric, or ``None``; decided exactly.

    Tries ``s = 1`` (``W = Wᵀ``, e.g. Metropolis) and ``s_i = w_ii^{-1/2}`` (uniform weights
    ``W = D^{-1}(A + I)`` on an undirected graph), which symmetrizes iff ``w_ij w_jj = w_ji w_ii``:
    checked in floats, then on the support in exact rationals (the decimals as written), so a
    ``W`` only nearly symmetrizable is never ranked as its symmetrized neighbour. ``O(E)`` on
    the entries (a link without its reverse: ``None``)."""
    reverse = W.reverse_weights()
    if reverse is None:
        return None
    if np.array_equal(W.weight, reverse):
        return np.ones(W.n)
    i, j, diagonal = W.receiver, W.sender, W.diagonal
    lhs, rhs = W.weight * diagonal[j], reverse * diagonal[i]
    if not np.allclose(lhs, rhs, rtol=8 * np.finfo(float).eps, atol=0.0):
        return None
    for k in np.flatnonzero(i < j):
        exact = exact_decimal(float(W.weight[k])) * exact_decimal(float(diagonal[j[k]]))
        if exact != exact_decimal(float(reverse[k])) * exact_decimal(float(diagonal[i[k]])):
            return None
    return 1.0 / np.sqrt(diagonal)


def spectral_network_rank(
    W: np.ndarray,
    row_agents: np.ndarray,
    row_vectors: np.ndarray,
    *,
    scale: np.ndarray,
    rank_tol: float = RANK_TOL,
    cluster_tol: float = CLUSTER_TOL,
) -> SpectralRank:
    """``rank O`` of ``(W ⊗ A, D_H)`` from the eigen-decomposition of ``W`` (symmetrized by
    ``scale``); each TDOA row is the position block ``row_vectors[r]`` of agent ``row_agents[r]``'s
    ``H_j``; eigenvalues within ``cluster_tol`` are one. Seed 000 eqs. (4.24), (4.36)."""
    n, dim = W.shape[0], row_vectors.shape[1]
    S = scale[:, None] * W / scale[None, :]
    mu, Q = np.linalg.eigh(0.5 * (S + S.T))
    V = Q / scale[:, None]
    V /= np.linalg.norm(V, axis=0, keepdims=True)
    clusters, margin = _clusters(mu, cluster_tol)
    bases = [V[:, idx] for idx in clusters]
    defects, defect_margin = eigenspace_defects(bases, row_agents, row_vectors, rank_tol=rank_tol)
    lost, eigenvalues = 0, []
    for idx, kappa in zip(clusters, defects, strict=True):
        value = float(mu[idx].mean())
        if abs(value) <= cluster_tol:
            lost += kappa + dim * len(idx)
            eigenvalues += [0.0] * (kappa + dim * len(idx))
        else:
            margin = min(margin, abs(value) / cluster_tol)
            lost += 2 * kappa
            eigenvalues += [value] * (2 * kappa)
    return SpectralRank(
        2 * dim * n - lost, 2 * dim * n, tuple(eigenvalues), min(margin, defect_margin)
    )


def eigenspace_defects(
    bases: list[np.ndarray],
    row_agents: np.ndarray,
    row_vectors: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
) -> tuple[list[int], float]:
    """For each eigenspace basis ``V`` (``N × m``), ``κ = dim{c : G_j (V c)_j = 0 ∀ j}``, and the
    smallest factor by which a singular value clears ``rank_tol · σ_max``.

    The defect matrix of ``V`` has one row ``kron(V[j, :], g)`` per TDOA row ``(j, g)``; bases of
    equal size are stacked and decomposed together."""
    defects = [0] * len(bases)
    margin = np.inf
    rows = max(len(row_agents), 1)
    by_size: dict[int, list[int]] = {}
    for k, basis in enumerate(bases):
        by_size.setdefault(basis.shape[1], []).append(k)
    dim = row_vectors.shape[1]
    for m, members in by_size.items():
        chunk = max(1, _CHUNK_BYTES // (8 * rows * m * dim))
        for start in range(0, len(members), chunk):
            batch = members[start : start + chunk]
            if m == 1:
                batch, decided = _gram_screen(
                    bases, batch, row_agents, row_vectors, rank_tol, defects
                )
                margin = min([margin, *decided])
                if not batch:
                    continue
            stack = np.stack([bases[k][row_agents] for k in batch])
            matrices = (stack[:, :, :, None] * row_vectors[None, :, None, :]).reshape(
                len(batch), len(row_agents), m * dim
            )
            sv = np.linalg.svd(matrices, compute_uv=False) if len(row_agents) else None
            for pos, k in enumerate(batch):
                kappa, item_margin = _defect(sv[pos] if sv is not None else None, m * dim, rank_tol)
                defects[k] = kappa
                margin = min(margin, item_margin)
    return defects, float(margin)


def _gram_screen(
    bases: list[np.ndarray],
    batch: list[int],
    row_agents: np.ndarray,
    row_vectors: np.ndarray,
    rank_tol: float,
    defects: list[int],
) -> tuple[list[int], list[float]]:
    """Decide one-dimensional eigenspaces from ``Σ_rows v_j² g gᵀ`` when clearly full rank.

    Returns the eigenspaces left for the SVD and the margins of those decided here (their
    defect is 0, already the default in ``defects``).
    """
    if not len(row_agents):
        return batch, []
    weights = np.stack([bases[k][row_agents, 0] ** 2 for k in batch])
    outer = (row_vectors[:, :, None] * row_vectors[:, None, :]).reshape(len(row_agents), -1)
    dim = row_vectors.shape[1]
    eigenvalues = np.linalg.eigvalsh((weights @ outer).reshape(len(batch), dim, dim))
    top = eigenvalues[:, -1]
    ratio = np.sqrt(np.clip(eigenvalues[:, 0], 0, None) / np.where(top > 0, top, 1.0))
    safe = (top > 0) & (ratio >= GRAM_SAFE_RATIO)
    for k in np.asarray(batch)[safe]:
        defects[k] = 0
    left = [k for k, ok in zip(batch, safe, strict=True) if not ok]
    return left, (ratio[safe] / rank_tol).tolist()


def _defect(sv: np.ndarray | None, columns: int, rank_tol: float) -> tuple[int, float]:
    if sv is None or sv.size == 0 or sv[0] == 0:
        return columns, np.inf
    threshold = rank_tol * sv[0]
    rank = int(np.sum(sv > threshold))
    above = sv[rank - 1] / threshold
    below = threshold / sv[rank] if rank < sv.size and sv[rank] > 0 else np.inf
    return columns - rank, float(min(above, below))


def _clusters(mu: np.ndarray, cluster_tol: float) -> tuple[list[np.ndarray], float]:
    """Split sorted eigenvalues at gaps > ``cluster_tol``; margin = how far gaps clear it."""
    gaps = np.diff(mu)
    cuts = np.flatnonzero(gaps > cluster_tol) + 1
    clusters = np.split(np.arange(mu.size), cuts)
    outside = gaps[gaps > cluster_tol]
    inside = gaps[gaps <= cluster_tol]
    margin = min(
        float(outside.min() / cluster_tol) if outside.size else np.inf,
        float(cluster_tol / inside.max()) if inside.size and inside.max() > 0 else np.inf,
    )
    return clusters, margin
