"""Rank of the networked TDOA observability matrix of a large sparse network (seed 000 eq. (4.36)).

Same quantity as :mod:`~theory.tdoa.observability.spectral` (``W`` similar to a symmetric
matrix by a diagonal scaling), without an eigen-decomposition of ``W``. Notation as there:
``S = {Y ∈ R^{N×d} : G_j Y_j = 0 ∀ j}`` (``G_j`` agent ``j``'s own TDOA rows), ``V*`` the
largest subspace of ``S`` with ``W V* ⊆ V*`` (``W`` acting on the agent index), ``m_0 = dim
ker W``, ``κ_0 = dim(ker W ∩ S)``. Since ``W`` is diagonalisable, every ``W``-invariant
subspace is the sum of its intersections with the eigenspaces, so ``V* = ⊕_μ (E_μ ∩ S)``,
``dim V* = Σ_μ κ_μ``, ``κ_0 = dim ker(W|_{V*})`` and the formula of the spectral method reads

    rank O = 2dN − 2 dim V* + κ_0 − d·m_0,

with unobservable eigenvalues: those of ``W|_{V*}`` (nonzero ones twice, zeros once) and ``0``
``d·m_0`` more times. ``V*`` lives on the *blind* agents, whose own rows do not have rank
``d`` (``ker G_j ≠ 0``): ``S`` has dimension ``s = Σ_j dim ker G_j``, small in a network where
most agents hear ≥ ``d`` others, and ``V*`` is the limit of ``V_0 = S``,
``V_{k+1} = {Y ∈ V_k : WY ∈ V_k}`` (at most ``s`` steps, each an SVD with ``s`` columns and
rows on the blind agents and their neighbours). ``m_0`` is counted by Sylvester's law of
inertia: the negative pivots of sparse ``LDLᵀ`` factorizations of ``S_W ∓ t I``
(``S_W = diag(s) W diag(s)^{-1}`` symmetric, ``t = cluster_tol``) give the number of
eigenvalues in ``[−t, t)``.

Tolerances: ``ker G_j`` and each step of ``V_k`` by ``rank_tol`` relative to the largest
singular value (as :func:`~theory.tdoa.observability.spectral.eigenspace_defects`); the
zero eigenvalues of ``W|_{V*}`` by ``cluster_tol``; ``m_0`` is conclusive when the counts at
``±t/F`` and ``±t·F`` (``F = inconclusive_factor``) agree and each factorization's
normwise backward error (measured on a random right-hand side) is below ``t/F``; otherwise the
returned margin is below ``F``.
"""

from __future__ import annotations

import numpy as np

from theory.core.observability import RANK_TOL
from theory.core.sparse_weights import SparseWeights
from theory.core.tolerances import CLUSTER_TOL, INCONCLUSIVE_FACTOR
from theory.core.validation import check_estimate
from theory.tdoa.observability.spectral import GRAM_SAFE_RATIO, SpectralRank

__all__ = ["sparse_network_rank"]


def sparse_network_rank(
    W: SparseWeights,
    row_agents: np.ndarray,
    row_vectors: np.ndarray,
    *,
    scale: np.ndarray,
    rank_tol: float = RANK_TOL,
    cluster_tol: float = CLUSTER_TOL,
    inconclusive_factor: float = INCONCLUSIVE_FACTOR,
) -> SpectralRank | None:
    """``rank O`` of ``(W ⊗ A, D_H)`` for one component held by its entries; ``scale``
    symmetrizes ``W``; the TDOA rows as in
    :func:`~theory.tdoa.observability.spectral.spectral_network_rank`; ``None`` when the
    factorization counting ``dim ker W`` fails its check. Seed 000 eqs. (4.24), (4.36)."""
    n, dim = W.n, row_vectors.shape[1]
    agents, vectors, margin = _own_kernels(n, row_agents, row_vectors, rank_tol)
    basis, restricted, invariant_margin = _invariant_subspace(W, agents, vectors, rank_tol)
    mu = np.sort(np.linalg.eigvals(restricted).real) if restricted.size else np.zeros(0)
    zero = np.abs(mu) <= cluster_tol
    eig_margin = _band_margin(np.abs(mu), cluster_tol)
    m_0, kernel_margin = _kernel_dimension(W, scale, cluster_tol, inconclusive_factor)
    if m_0 is None:
        return None
    lost = 2 * basis - int(zero.sum()) + dim * m_0
    eigenvalues = sorted([*mu[~zero].tolist() * 2, *[0.0] * (int(zero.sum()) + dim * m_0)])
    return SpectralRank(
        2 * dim * n - lost,
        2 * dim * n,
        tuple(eigenvalues),
        float(min(margin, invariant_margin, eig_margin, kernel_margin)),
    )


def _own_kernels(
    n: int, row_agents: np.ndarray, row_vectors: np.ndarray, rank_tol: float
) -> tuple[np.ndarray, np.ndarray, float]:
    """Orthonormal bases of ``ker G_j`` for every agent: one basis vector per row of the
    result (its agent, its vector), and the margin of the rank decisions.

    Agents whose ``d × d`` Gram matrix is clearly of full rank (``σ_min/σ_max ≥``
    :data:`~theory.tdoa.observability.spectral.GRAM_SAFE_RATIO`) have ``ker G_j = 0``; the
    others get an SVD of their rows."""
    dim = row_vectors.shape[1]
    gram = np.zeros((n, dim, dim))
    np.add.at(gram, row_agents, row_vectors[:, :, None] * row_vectors[:, None, :])
    values = np.linalg.eigvalsh(gram)
    top = values[:, -1]
    ratio = np.sqrt(np.clip(values[:, 0], 0, None) / np.where(top > 0, top, 1.0))
    seeing = (top > 0) & (ratio >= GRAM_SAFE_RATIO)
    margin = float((ratio[seeing] / rank_tol).min(initial=np.inf))
    agents, vectors = [], []
    for j in np.flatnonzero(~seeing):
        rows = row_vectors[row_agents == j]
        kernel, item_margin = _kernel(rows, dim, rank_tol)
        margin = min(margin, item_margin)
        agents += [j] * kernel.shape[0]
        vectors += list(kernel)
    return np.asarray(agents, dtype=np.int64), np.reshape(vectors, (-1, dim)), margin


def _kernel(matrix: np.ndarray, columns: int, rank_tol: float) -> tuple[np.ndarray, float]:
    """Rows: an orthonormal basis of ``ker matrix`` (``rank_tol`` relative to ``σ_max``)."""
    if matrix.size == 0:
        return np.eye(columns), np.inf
    _, sv, vt = np.linalg.svd(matrix, full_matrices=True)
    if sv[0] == 0:
        return np.eye(columns), np.inf
    threshold = rank_tol * sv[0]
    rank = int(np.sum(sv > threshold))
    return vt[rank:], _split_margin(sv, rank, threshold)


def _split_margin(sv: np.ndarray, rank: int, threshold: float) -> float:
    """How many times the singular values clear ``threshold`` on either side of ``rank``."""
    above = sv[rank - 1] / threshold if rank > 0 else np.inf
    below = threshold / sv[rank] if rank < sv.size and sv[rank] > 0 else np.inf
    return float(min(above, below))


def _invariant_subspace(
    W: SparseWeights, agents: np.ndarray, vectors: np.ndarray, rank_tol: float
) -> tuple[int, np.ndarray, float]:
    """``dim V*``, the matrix of ``W|_{V*}`` in an orthonormal basis, and the margin.

    ``S`` is spanned by the orthonormal columns ``e_{agents[k]} ⊗ vectors[k]``; ``WS`` touches
    only the blind agents and the agents hearing them, so both are dense matrices on those
    agents' rows."""
    s, dim = len(agents), vectors.shape[1] if vectors.size else 0
    if s == 0:
        return 0, np.zeros((0, 0)), np.inf
    hearing = np.isin(W.sender, agents)
    touched = np.union1d(agents, W.receiver[hearing])
    check_estimate(
        "memory_bytes",
        2 * 8.0 * dim * touched.size * s,
        "tdoa.agents",
        f"2 × 8 B × d·{touched.size}·{s} for the blind agents' kernels (network rank)",
        alternative="Pass --no-network-rank to skip the rank of the whole networked O.",
    )
    local = np.full(W.n, -1)
    local[touched] = np.arange(touched.size)
    basis = np.zeros((touched.size, dim, s))  # E: the basis of S
    basis[local[agents], :, np.arange(s)] = vectors
    image = np.zeros((touched.size, dim, s))  # W E
    image[local[agents], :, np.arange(s)] = W.diagonal[agents, None] * vectors
    column = {}
    for k, j in enumerate(agents.tolist()):
        column.setdefault(j, []).append(k)
    for receiver, sender, weight in zip(
        W.receiver[hearing], W.sender[hearing], W.weight[hearing], strict=True
    ):
        for k in column[int(sender)]:
            image[local[receiver], :, k] += weight * vectors[k]
    E, M = basis.reshape(-1, s), image.reshape(-1, s)
    threshold = rank_tol * max(float(np.linalg.norm(M, 2)), np.finfo(float).tiny)
    C, margin = np.eye(s), np.inf
    while C.shape[1]:
        P, X = E @ C, M @ C
        residual = X - P @ (P.T @ X)
        _, sv, vt = np.linalg.svd(residual, full_matrices=True)
        rank = int(np.sum(sv > threshold))
        margin = min(margin, _split_margin(sv, rank, threshold))
        if rank == 0:
            break
        C = C @ vt[rank:].T
    P = E @ C
    return C.shape[1], P.T @ (M @ C), margin


def _band_margin(values: np.ndarray, tol: float) -> float:
    """How many times ``values`` clear ``tol`` on either side."""
    if not values.size:
        return np.inf
    above = values[values > tol]
    below = values[(values <= tol) & (values > 0)]
    return float(
        min(
            above.min() / tol if above.size else np.inf,
            tol / below.max() if below.size else np.inf,
        )
    )


def _kernel_dimension(
    W: SparseWeights, scale: np.ndarray, tol: float, factor: float
) -> tuple[int | None, float]:
    """``dim ker W``: eigenvalues of the symmetrized ``W`` in ``[−tol, tol)``, by inertia
    (``None`` when a factorization at ``±tol`` fails its check), and the margin: ``factor``
    when the counts at ``±tol/factor`` and ``±tol·factor`` agree, else 1 (inside the band)."""
    counts = [_eigenvalues_below(W, scale, shift, tol / factor) for shift in _shifts(tol, factor)]
    if counts[1] is None or counts[4] is None:
        return None, 1.0
    inside = counts[1] - counts[4]
    if None in counts or not counts[0] - counts[5] == inside == counts[2] - counts[3]:
        return inside, 1.0
    return inside, factor


def _shifts(tol: float, factor: float) -> tuple[float, ...]:
    """``t·F, t, t/F, −t/F, −t, −t·F`` with ``t = tol``, ``F = factor`` (counted below each)."""
    return (tol * factor, tol, tol / factor, -tol / factor, -tol, -tol * factor)


def _eigenvalues_below(
    W: SparseWeights, scale: np.ndarray, shift: float, backward_tol: float
) -> int | None:
    """Number of eigenvalues of ``diag(s) W diag(s)^{-1}`` below ``shift`` (Sylvester: the
    negative pivots of ``LDLᵀ`` of the shifted matrix), or ``None`` when the factorization's
    normwise backward error exceeds ``backward_tol`` or it pivoted off the diagonal."""
    import scipy.sparse as sparse  # only for the network rank of large components
    from scipy.sparse.linalg import splu

    n = W.n
    rows = np.concatenate([W.receiver, np.arange(n)])
    cols = np.concatenate([W.sender, np.arange(n)])
    values = np.concatenate([W.weight, W.diagonal]) * scale[rows] / scale[cols]
    values[W.receiver.size :] -= shift
    A = sparse.csc_matrix((values, (rows, cols)), shape=(n, n))
    A = 0.5 * (A + A.T)
    try:
        lu = splu(
            A.tocsc(),
            permc_spec="MMD_AT_PLUS_A",
            diag_pivot_thresh=0.0,
            options={"SymmetricMode": True},
        )
    except RuntimeError:  # an exactly singular pivot: the shift is an eigenvalue
        return None
    if not np.array_equal(lu.perm_r, lu.perm_c):
        return None
    b = np.random.default_rng(0).standard_normal(n)
    x = lu.solve(b)
    scale_A = float(abs(A).sum(axis=1).max())
    error = np.linalg.norm(A @ x - b, np.inf) / (scale_A * np.linalg.norm(x, np.inf))
    if not error <= backward_tol:
        return None
    return int(np.sum(lu.U.diagonal() < 0))
