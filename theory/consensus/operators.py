"""The operators of seed 000 §5.2 and App. C.3, as maps on N-tuples and as explicit matrices.

An N-tuple ``V = (V_1, …, V_N)`` of ``n × n`` matrices (the space ℍⁿ of the paper) is stored as an
array of shape ``(N, n, n)``. **Vectorization convention**: ``vec`` stacks columns (Fortran /
column-major order), so ``vec(Γ X Γ') = (Γ ⊗ Γ) vec(X)``, and a tuple is vectorized as
``[vec V_1; …; vec V_N]`` (length ``N n²``). :func:`vec_tuple` and :func:`unvec_tuple` implement it;
every explicit matrix below acts on vectors in that convention.

With ``Γ_i = A − L_i C_i``:

* ``B = diag[Γ_i] (W ⊗ I_n)`` — eq. (5.11), noise-free error dynamics, consensus then filter;
* ``B₂ = (W ⊗ I_n) diag[Γ_i]`` — eq. (C.5), filter then consensus;
* ``E_i(V) = Σ_j w_ij V_j``, matrix ``W ⊗ I_{n²}`` — eq. (5.12);
* ``L_i(V) = Γ_i E_i(V) Γ_i'``, matrix ``diag[Γ_i ⊗ Γ_i] (W ⊗ I_{n²})`` — eq. (5.13), Lemma 5.2.2;
* ``J_i(V) = Σ_j w_ij Γ_j V_j Γ_j'``, matrix ``(W ⊗ I_{n²}) diag[Γ_j ⊗ Γ_j]`` — App. C.3;
* the adjoint of L for the trace inner product, ``L*_j(Y) = Σ_i w_ij Γ_i' Y_i Γ_i``, matrix
  ``𝓛ᵀ`` — the "dual operator" in which gains enter linearly after ``G_i = Y_i L_i``;
* the adjoint of J, ``J*_j(Y) = Γ_j' (Σ_i w_ij Y_i) Γ_j``, matrix ``𝓙ᵀ``.

:func:`apply_operator` applies any of the four by the names :mod:`proofs_check.operators` uses
(``L``, ``J``, ``L-adjoint``, ``J-adjoint``); the exact checker has its own rational twin on
purpose (it imports nothing from ``theory``).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = [
    "OPERATORS",
    "B2_matrix",
    "B_matrix",
    "E_map",
    "E_matrix",
    "J_adjoint_map",
    "J_map",
    "J_matrix",
    "L_adjoint_map",
    "L_map",
    "L_matrix",
    "apply_operator",
    "closed_loop",
    "covariance_operator_matrix",
    "spectral_radius",
    "unvec_tuple",
    "vec_tuple",
]


def closed_loop(A: np.ndarray, C: Sequence[np.ndarray], L: Sequence[np.ndarray]) -> np.ndarray:
    """``Γ_i = A − L_i C_i`` for every agent, shape ``(N, n, n)`` (seed 000 eq. (5.5)).

    Parameters
    ----------
    A : ndarray, shape (n, n)
        System matrix.
    C : sequence of ndarray, shapes (p_i, n)
        Measurement matrices (zero rows allowed).
    L : sequence of ndarray, shapes (n, p_i)
        Gains.

    Returns
    -------
    ndarray, shape (N, n, n)
    """
    return np.stack([A - Li @ Ci for Li, Ci in zip(L, C, strict=True)])


def vec_tuple(V: np.ndarray) -> np.ndarray:
    """``[vec V_1; …; vec V_N]`` of the tuple ``V``, column-stacking ``vec`` (length ``N n²``)."""
    return np.concatenate([Vi.reshape(-1, order="F") for Vi in V])


def unvec_tuple(v: np.ndarray, N: int, n: int) -> np.ndarray:
    """Inverse of :func:`vec_tuple`: an array of shape ``(N, n, n)``.

    Parameters
    ----------
    v : ndarray, shape (N n²,)
        Stacked column-major vectorizations.
    N, n : int
        Number of agents and matrix size.
    """
    return np.stack([v[i * n * n : (i + 1) * n * n].reshape(n, n, order="F") for i in range(N)])


def E_map(W: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``E_i(V) = Σ_j w_ij V_j`` (seed 000 eq. (5.12)).

    Parameters
    ----------
    W : ndarray, shape (N, N)
        Consensus weights.
    V : ndarray, shape (N, n, n)
        The tuple the map is applied to.
    """
    return np.einsum("ij,jab->iab", W, V)


def L_map(W: np.ndarray, Gamma: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``L_i(V) = Γ_i E_i(V) Γ_i'`` (seed 000 eq. (5.13)).

    Parameters
    ----------
    W : ndarray, shape (N, N)
        Consensus weights.
    Gamma : ndarray, shape (N, n, n)
        Closed loops ``Γ_i`` (see :func:`closed_loop`).
    V : ndarray, shape (N, n, n)
        The tuple the map is applied to.
    """
    return Gamma @ E_map(W, V) @ Gamma.transpose(0, 2, 1)


def L_adjoint_map(W: np.ndarray, Gamma: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """``L*_j(Y) = Σ_i w_ij Γ_i' Y_i Γ_i``, the adjoint of L for ``⟨V, Y⟩ = Σ_i tr(V_i' Y_i)``.

    Parameters
    ----------
    W, Gamma, Y : ndarray
        As ``W``, ``Gamma``, ``V`` in :func:`L_map`.
    """
    return E_map(W.T, Gamma.transpose(0, 2, 1) @ Y @ Gamma)


def J_map(W: np.ndarray, Gamma: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``J_i(V) = Σ_j w_ij Γ_j V_j Γ_j'`` (seed 000 App. C.3).

    Parameters
    ----------
    W, Gamma, V : ndarray
        As in :func:`L_map`.
    """
    return E_map(W, Gamma @ V @ Gamma.transpose(0, 2, 1))


def J_adjoint_map(W: np.ndarray, Gamma: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """``J*_j(Y) = Γ_j' (Σ_i w_ij Y_i) Γ_j``, the adjoint of J for ``⟨V, Y⟩ = Σ_i tr(V_i' Y_i)``.

    Parameters
    ----------
    W, Gamma, Y : ndarray
        As ``W``, ``Gamma``, ``V`` in :func:`L_map`.
    """
    return Gamma.transpose(0, 2, 1) @ E_map(W.T, Y) @ Gamma


OPERATORS = {"L": L_map, "J": J_map, "L-adjoint": L_adjoint_map, "J-adjoint": J_adjoint_map}
"""The four positive operators by the names of :data:`proofs_check.operators.OPERATORS`."""


def apply_operator(name: str, W: np.ndarray, Gamma: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``T(V)`` for ``T`` one of :data:`OPERATORS` (floating point).

    Parameters
    ----------
    name : {"L", "J", "L-adjoint", "J-adjoint"}
        The operator.
    W, Gamma, V : array_like
        As in :func:`L_map` (sequences of matrices are stacked).

    Returns
    -------
    ndarray, shape (N, n, n)

    Raises
    ------
    ValueError
        For an unknown ``name``.
    """
    if name not in OPERATORS:
        raise ValueError(f"unknown operator {name!r}; expected one of {sorted(OPERATORS)}")
    arrays = (np.asarray(x, dtype=float) for x in (W, Gamma, V))
    return OPERATORS[name](*arrays)


def _block_diag(blocks: np.ndarray) -> np.ndarray:
    return sla.block_diag(*blocks) if len(blocks) else np.zeros((0, 0))


def _mixed(W: np.ndarray, blocks: np.ndarray, *, consensus_first: bool) -> np.ndarray:
    """``diag[blocks] (W ⊗ I)`` if ``consensus_first``, else ``(W ⊗ I) diag[blocks]``."""
    mix = np.kron(W, np.eye(blocks.shape[1]))
    return _block_diag(blocks) @ mix if consensus_first else mix @ _block_diag(blocks)


def _kron_squares(Gamma: np.ndarray) -> np.ndarray:
    """``Γ_i ⊗ Γ_i`` for every agent, shape ``(N, n², n²)``."""
    return np.stack([np.kron(G, G) for G in Gamma])


def B_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``B = diag[Γ_i] (W ⊗ I_n)`` (seed 000 eq. (5.11)), acting on ``[ε_1; …; ε_N]``.

    Parameters
    ----------
    W, Gamma : ndarray
        As in :func:`L_map`.
    """
    return _mixed(W, Gamma, consensus_first=True)


def B2_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``B₂ = (W ⊗ I_n) diag[Γ_i]`` (seed 000 eq. (C.5)).

    Parameters
    ----------
    W, Gamma : ndarray
        As in :func:`L_map`.
    """
    return _mixed(W, Gamma, consensus_first=False)


def E_matrix(W: np.ndarray, n: int) -> np.ndarray:
    """``W ⊗ I_{n²}``: the matrix of E (eq. (5.12)) in the :func:`vec_tuple` convention.

    Parameters
    ----------
    W : ndarray, shape (N, N)
        Consensus weights.
    n : int
        State dimension.
    """
    return np.kron(W, np.eye(n * n))


def L_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``diag[Γ_i ⊗ Γ_i] (W ⊗ I_{n²})``: the matrix of L (Lemma 5.2.2's 𝒜).

    Parameters
    ----------
    W, Gamma : ndarray
        As in :func:`L_map`.
    """
    return _mixed(W, _kron_squares(Gamma), consensus_first=True)


def J_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``(W ⊗ I_{n²}) diag[Γ_j ⊗ Γ_j]``: the matrix of J (App. C.3).

    Parameters
    ----------
    W, Gamma : ndarray
        As in :func:`L_map`.
    """
    return _mixed(W, _kron_squares(Gamma), consensus_first=False)


def covariance_operator_matrix(W: np.ndarray, Gamma: np.ndarray, order: str) -> np.ndarray:
    """The covariance-bound operator of a filter order: L for ``consensus-then-filter``, J else.

    Parameters
    ----------
    W, Gamma : ndarray
        As in :func:`L_map`.
    order : str
        ``consensus-then-filter`` or ``filter-then-consensus``.
    """
    if order == "consensus-then-filter":
        return L_matrix(W, Gamma)
    if order == "filter-then-consensus":
        return J_matrix(W, Gamma)
    raise ValueError(f"order {order!r} is not consensus-then-filter or filter-then-consensus")


def spectral_radius(M: np.ndarray, *, dense_limit: int = 400) -> float:
    """Largest eigenvalue modulus ``r_σ(M)`` (0 for an empty matrix).

    Parameters
    ----------
    M : ndarray, shape (d, d)
        Square matrix.
    dense_limit : int
        Above this size the largest-modulus eigenvalue is found by ARPACK (``scipy.sparse.linalg
        .eigs``, relative tolerance 1e-12) on the sparse matrix; on ARPACK failure the dense
        eigenvalues are computed.
    """
    if not M.size:
        return 0.0
    if M.shape[0] > dense_limit:
        try:
            value = spla.eigs(
                sp.csr_matrix(M), k=1, which="LM", tol=1e-12, return_eigenvectors=False
            )
            return float(np.abs(value[0]))
        except spla.ArpackError:
            pass
    return float(np.max(np.abs(np.linalg.eigvals(M))))
