"""The operators of seed 000 §5.2 and App. C.3 on N-tuples of covariances, and ``r_σ < ρ`` decided
exactly for them.

An N-tuple ``V = (V_1, …, V_N)`` of ``n × n`` matrices (the space ℍⁿ of the paper) is an array of
shape ``(N, n, n)``. **Vectorization convention**: ``vec`` stacks columns (column-major), so
``vec(Γ X Γ') = (Γ ⊗ Γ) vec(X)``, and a tuple is ``[vec V_1; …; vec V_N]`` (length ``N n²``);
every explicit matrix below acts on vectors in that convention. With ``Γ_i = A − L_i C_i``:

* ``B = diag[Γ_i] (W ⊗ I_n)`` — eq. (5.11); ``B₂ = (W ⊗ I_n) diag[Γ_i]`` — eq. (C.5);
* ``E_i(V) = Σ_j w_ij V_j`` — eq. (5.12);
* ``L_i(V) = Γ_i E_i(V) Γ_i'``, matrix ``diag[Γ_i ⊗ Γ_i] (W ⊗ I_{n²})`` — eq. (5.13);
* ``J_i(V) = Σ_j w_ij Γ_j V_j Γ_j'``, matrix ``(W ⊗ I_{n²}) diag[Γ_j ⊗ Γ_j]`` — App. C.3;
* the adjoints for the trace inner product, ``L*_j(Y) = Σ_i w_ij Γ_i' Y_i Γ_i`` (the "dual
  operator" in which gains enter linearly after ``G_i = Y_i L_i``) and
  ``J*_j(Y) = Γ_j' (Σ_i w_ij Y_i) Γ_j``, matrices transposed.

The names ``L``, ``J``, ``L-adjoint``, ``J-adjoint`` are those of :mod:`proofs_check.operators`
(the exact checker has its own rational twin on purpose: it imports nothing from ``theory``).

**Exact decision.** For ``T`` one of the four (all positive: ``w_ij ≥ 0``), ``r_σ(T) < ρ`` iff
``I − T/ρ`` is invertible and the solution ``X`` of ``X − T(X)/ρ = I`` (identity in every block)
is positive definite. *Proof.* If ``r_σ(T) < ρ`` then ``X = Σ_k ρ^{-k} T^k(I) ⪰ I ≻ 0``; if a
positive definite ``X`` has ``ρX − T(X) = ρI ≻ 0``, then ``r_σ(T) < ρ`` (Lemma 5.2.2;
``docs/theory/s-detectability.md``, Lemma 1). The solve (``flint.fmpq_mat``) and the positivity
test (:func:`proofs_check.linalg.positive_definite`) are exact, so the decision has no
tolerance; its cost limits it to ``N n² ≤ EXACT_DIM``.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from proofs_check.linalg import first_asymmetry, positive_definite
from theory.consensus.case import Order
from theory.core.exact import (
    Matrix,
    fractions_of,
    identity,
    kron,
    rational_matrix,
    stochastic_matrix,
    to_fmpq,
)
from theory.core.tolerances import EXACT_DIM, RADIUS_TOL

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
    "exact_lyapunov",
    "exact_operator_matrix",
    "float_lyapunov",
    "gains_stabilize",
    "nonnegative_radius_below",
    "radius_below",
    "spectral_radius",
    "unvec_tuple",
    "vec_tuple",
]


def closed_loop(A: np.ndarray, C: Sequence[np.ndarray], L: Sequence[np.ndarray]) -> np.ndarray:
    """``Γ_i = A − L_i C_i`` for every agent, shape ``(N, n, n)`` (seed 000 eq. (5.5))."""
    return np.stack([A - Li @ Ci for Li, Ci in zip(L, C, strict=True)])


def vec_tuple(V: np.ndarray) -> np.ndarray:
    """``[vec V_1; …; vec V_N]`` of the tuple ``V``, column-stacking ``vec`` (length ``N n²``)."""
    return np.concatenate([Vi.reshape(-1, order="F") for Vi in V])


def unvec_tuple(v: np.ndarray, N: int, n: int) -> np.ndarray:
    """Inverse of :func:`vec_tuple`: an array of shape ``(N, n, n)``."""
    return np.stack([v[i * n * n : (i + 1) * n * n].reshape(n, n, order="F") for i in range(N)])


def E_map(W: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``E_i(V) = Σ_j w_ij V_j`` (seed 000 eq. (5.12))."""
    return np.einsum("ij,jab->iab", W, V)


def L_map(W: np.ndarray, Gamma: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``L_i(V) = Γ_i E_i(V) Γ_i'`` (seed 000 eq. (5.13))."""
    return Gamma @ E_map(W, V) @ Gamma.transpose(0, 2, 1)


def L_adjoint_map(W: np.ndarray, Gamma: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """``L*_j(Y) = Σ_i w_ij Γ_i' Y_i Γ_i``, the adjoint of L for ``⟨V, Y⟩ = Σ_i tr(V_i' Y_i)``."""
    return E_map(W.T, Gamma.transpose(0, 2, 1) @ Y @ Gamma)


def J_map(W: np.ndarray, Gamma: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``J_i(V) = Σ_j w_ij Γ_j V_j Γ_j'`` (seed 000 App. C.3)."""
    return E_map(W, Gamma @ V @ Gamma.transpose(0, 2, 1))


def J_adjoint_map(W: np.ndarray, Gamma: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """``J*_j(Y) = Γ_j' (Σ_i w_ij Y_i) Γ_j``, the adjoint of J for ``⟨V, Y⟩ = Σ_i tr(V_i' Y_i)``."""
    return Gamma.transpose(0, 2, 1) @ E_map(W.T, Y) @ Gamma


OPERATORS = {"L": L_map, "J": J_map, "L-adjoint": L_adjoint_map, "J-adjoint": J_adjoint_map}
"""The four positive operators by the names of :data:`proofs_check.operators.OPERATORS`."""


def apply_operator(name: str, W: np.ndarray, Gamma: np.ndarray, V: np.ndarray) -> np.ndarray:
    """``T(V)`` for ``T`` one of :data:`OPERATORS` (floats; sequences of matrices are stacked)."""
    if name not in OPERATORS:
        raise ValueError(f"unknown operator {name!r}; expected one of {sorted(OPERATORS)}")
    arrays = (np.asarray(x, dtype=float) for x in (W, Gamma, V))
    return OPERATORS[name](*arrays)


def _mixed(W: np.ndarray, blocks: np.ndarray, *, consensus_first: bool) -> np.ndarray:
    """``diag[blocks] (W ⊗ I)`` if ``consensus_first``, else ``(W ⊗ I) diag[blocks]``."""
    mix = np.kron(W, np.eye(blocks.shape[1]))
    diagonal = sla.block_diag(*blocks) if len(blocks) else np.zeros((0, 0))
    return diagonal @ mix if consensus_first else mix @ diagonal


def _kron_squares(Gamma: np.ndarray) -> np.ndarray:
    return np.stack([np.kron(G, G) for G in Gamma])


def B_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``B = diag[Γ_i] (W ⊗ I_n)`` (seed 000 eq. (5.11)), acting on ``[ε_1; …; ε_N]``."""
    return _mixed(W, Gamma, consensus_first=True)


def B2_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``B₂ = (W ⊗ I_n) diag[Γ_i]`` (seed 000 eq. (C.5))."""
    return _mixed(W, Gamma, consensus_first=False)


def E_matrix(W: np.ndarray, n: int) -> np.ndarray:
    """``W ⊗ I_{n²}``: the matrix of E (eq. (5.12))."""
    return np.kron(W, np.eye(n * n))


def L_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``diag[Γ_i ⊗ Γ_i] (W ⊗ I_{n²})``: the matrix of L (Lemma 5.2.2's 𝒜)."""
    return _mixed(W, _kron_squares(Gamma), consensus_first=True)


def J_matrix(W: np.ndarray, Gamma: np.ndarray) -> np.ndarray:
    """``(W ⊗ I_{n²}) diag[Γ_j ⊗ Γ_j]``: the matrix of J (App. C.3)."""
    return _mixed(W, _kron_squares(Gamma), consensus_first=False)


def covariance_operator_matrix(W: np.ndarray, Gamma: np.ndarray, order: Order | str) -> np.ndarray:
    """The covariance-bound operator of a filter order: L (consensus first) or J."""
    return L_matrix(W, Gamma) if Order(order).operator == "L" else J_matrix(W, Gamma)


def float_lyapunov(T: np.ndarray, N: int, n: int) -> np.ndarray:
    """The symmetrized float ``X`` with ``X − T(X) = (I, …, I)`` for the matrix ``T`` of an
    operator on N-tuples of ``n × n`` matrices (``LinAlgError`` when ``I − T`` is singular)."""
    x = np.linalg.solve(np.eye(T.shape[0]) - T, vec_tuple(np.broadcast_to(np.eye(n), (N, n, n))))
    X = unvec_tuple(x, N, n)
    return (X + X.transpose(0, 2, 1)) / 2


def spectral_radius(M: np.ndarray, *, dense_limit: int = 400) -> float:
    """Largest eigenvalue modulus ``r_σ(M)`` (0 for an empty matrix); above ``dense_limit`` rows
    by ARPACK on the sparse matrix (relative tolerance 1e-12), dense on ARPACK failure."""
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


def exact_operator_matrix(operator: str, W: Matrix, gammas: Sequence[Matrix]) -> Matrix:
    """The exact ``N n² × N n²`` matrix of ``operator`` (a name of :data:`OPERATORS`)."""
    base = operator.removesuffix("-adjoint")
    if base not in ("L", "J"):
        raise ValueError(f"unknown operator {operator!r}")
    squares = [kron(g, g) for g in gammas]
    N, m = len(W), len(squares[0])
    out = [[Fraction(0)] * (N * m) for _ in range(N * m)]
    for i in range(N):
        for j in range(N):
            if W[i][j]:
                block = squares[i] if base == "L" else squares[j]
                for r in range(m):
                    for c in range(m):
                        out[i * m + r][j * m + c] = W[i][j] * block[r][c]
    if operator.endswith("-adjoint"):
        out = [list(col) for col in zip(*out, strict=True)]
    return out


def exact_lyapunov(
    operator: str, W: Matrix, gammas: Sequence[Matrix], rho: Fraction = Fraction(1)
) -> list[Matrix] | None:
    """The exact ``X`` with ``X − T(X)/ρ = (I, …, I)``, or None if ``I − T/ρ`` is singular."""
    n, N = len(gammas[0]), len(W)
    T = exact_operator_matrix(operator, W, gammas)
    size = N * n * n
    system = [[Fraction(int(r == c)) - T[r][c] / rho for c in range(size)] for r in range(size)]
    rhs = [[Fraction(x)] for _ in range(N) for col in identity(n) for x in col]
    lhs = to_fmpq(system)
    if lhs.rank() < size:
        return None
    x = [row[0] for row in fractions_of(lhs.solve(to_fmpq(rhs)))]
    blocks = [x[k * n * n : (k + 1) * n * n] for k in range(N)]
    return [[[b[r + n * c] for c in range(n)] for r in range(n)] for b in blocks]


def radius_below(
    operator: str, W: Matrix, gammas: Sequence[Matrix], rho: Fraction = Fraction(1)
) -> bool:
    """Whether ``r_σ(T) < ρ``, decided exactly (module docstring; seed 000 Lemma 5.2.2);
    ``ValueError`` above ``EXACT_DIM`` or for a negative weight (``T`` not positive)."""
    size = len(W) * len(gammas[0]) ** 2
    if size > EXACT_DIM:
        raise ValueError(f"N n² = {size} exceeds EXACT_DIM = {EXACT_DIM}")
    if any(w < 0 for row in W for w in row):
        raise ValueError("W has a negative entry: the operator is not positive")
    X = exact_lyapunov(operator, W, gammas, rho)
    return X is not None and all(
        first_asymmetry(Xi) is None and positive_definite(Xi).positive for Xi in X
    )


def gains_stabilize(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    gains: Sequence[np.ndarray],
    *,
    order: Order | str,
    rho: Fraction = Fraction(1),
    radius_tol: float = RADIUS_TOL,
) -> bool | None:
    """Whether the float ``gains`` give ``r_σ(T) < ρ`` for the order's operator (seed 000
    Lemma 5.2.2, footnote 5).

    The gains are read exactly (a float is a dyadic rational), the data as the decimals they
    print as (rows of ``W`` summing to exactly 1); exact when ``N n² ≤ EXACT_DIM``, above it the
    float radius decides outside ``ρ(1 ± radius_tol)`` and within that band the answer is None.
    """
    operator = Order(order).operator
    n, N = np.asarray(A).shape[0], np.asarray(W).shape[0]
    if N * n * n > EXACT_DIM:
        radius = spectral_radius(covariance_operator_matrix(W, closed_loop(A, C, gains), order))
        if abs(radius - float(rho)) <= radius_tol * float(rho):
            return None
        return radius < float(rho)
    A_q = rational_matrix(A)
    gammas = []
    for g, c in zip(gains, C, strict=True):
        if not np.size(c):
            gammas.append(A_q)
            continue
        G = [[Fraction(float(x)) for x in row] for row in np.asarray(g, float)]
        product = to_fmpq(G) * to_fmpq(rational_matrix(np.asarray(c, float).reshape(-1, n)))
        gammas.append(fractions_of(to_fmpq(A_q) - product))
    return radius_below(operator, stochastic_matrix(W), gammas, rho)


def nonnegative_radius_below(M: Matrix, rho: Fraction = Fraction(1)) -> bool:
    """Whether ``r_σ(M) < ρ`` for an entrywise non-negative exact ``M``: ``ρI − M`` is a
    nonsingular M-matrix iff its leading principal minors are positive (Berman–Plemmons,
    Thm 6.2.3)."""
    if any(x < 0 for row in M for x in row):
        raise ValueError("M has a negative entry")
    m = len(M)
    shifted = [[(rho if r == c else 0) - M[r][c] for c in range(m)] for r in range(m)]
    return all(to_fmpq([row[:k] for row in shifted[:k]]).det() > 0 for k in range(1, m + 1))
