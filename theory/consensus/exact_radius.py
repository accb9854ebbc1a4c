"""``r_σ(T) < ρ`` decided exactly for the positive operators of seed 000 ch. 5, rational ``Γ_i``.

For ``T`` one of L (eq. (5.13)), J (App. C.3) or their adjoints (all positive: ``w_ij ≥ 0``):
``r_σ(T) < ρ`` iff ``I − T/ρ`` is invertible and the solution ``X`` of ``X − T(X)/ρ = I``
(identity in every block) is positive definite. *Proof.* If ``r_σ(T) < ρ`` then
``X = Σ_k ρ^{-k} T^k(I) ⪰ I ≻ 0``; if a positive definite ``X`` has ``ρX − T(X) = ρI ≻ 0``, then
``r_σ(T) < ρ`` (Lemma 5.2.2; ``docs/theory/s-detectability.md``, Lemma 1). Both the solve and the
positivity test are exact (``flint.fmpq_mat`` and :func:`proofs_check.linalg.positive_definite`),
so the decision has no tolerance; its cost limits it to ``N n² ≤ EXACT_DIM``.

The explicit matrices use the column-stacking ``vec`` of :mod:`theory.consensus.operators`:
``mat(L) = diag[Γ_i ⊗ Γ_i](W ⊗ I)``, ``mat(J) = (W ⊗ I) diag[Γ_j ⊗ Γ_j]``, adjoints transposed.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from proofs_check.linalg import first_asymmetry, positive_definite
from theory.consensus.operators import (
    closed_loop,
    covariance_operator_matrix,
    spectral_radius,
)
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
    "exact_lyapunov",
    "exact_operator_matrix",
    "gains_stabilize",
    "nonnegative_radius_below",
    "radius_below",
]


def exact_operator_matrix(operator: str, W: Matrix, gammas: Sequence[Matrix]) -> Matrix:
    """The ``N n² × N n²`` matrix of ``operator`` (``L``, ``J``, ``L-adjoint``, ``J-adjoint``).

    Parameters
    ----------
    operator : str
        One of :data:`theory.consensus.operators.OPERATORS`.
    W : exact matrix
        Consensus weights.
    gammas : sequence of exact (n, n) matrices
        ``Γ_i``.

    Returns
    -------
    list of rows of Fraction

    Raises
    ------
    ValueError
        For an unknown operator.
    """
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
    """The exact solution ``X`` of ``X − T(X)/ρ = (I, …, I)``, or None if ``I − T/ρ`` is singular.

    Parameters
    ----------
    operator : str
        ``T`` (see :func:`exact_operator_matrix`).
    W : exact matrix
        Consensus weights.
    gammas : sequence of exact (n, n) matrices
        ``Γ_i``.
    rho : Fraction
        ``ρ > 0``.

    Returns
    -------
    list of exact (n, n) matrices, or None
    """
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
    """Whether ``r_σ(T) < ρ``, decided exactly (see the module docstring).

    Parameters
    ----------
    operator, W, gammas, rho
        As in :func:`exact_lyapunov` (``W ≥ 0`` entrywise, so ``T`` is positive).

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        If ``N n²`` exceeds :data:`~theory.core.tolerances.EXACT_DIM` or ``W`` has a negative entry.

    References
    ----------
    seed 000 Lemma 5.2.2; docs/theory/s-detectability.md, Lemma 1.
    """
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
    order: str,
    rho: Fraction = Fraction(1),
    radius_tol: float = RADIUS_TOL,
) -> bool | None:
    """Whether the float ``gains`` give ``r_σ(T) < ρ`` for the order's operator (L or J).

    The gains are read exactly (a float is a dyadic rational), the data as the decimals they
    print as (rows of ``W`` summing to exactly 1), and the answer is exact when ``N n² ≤
    EXACT_DIM``; above it the float radius decides outside ``ρ(1 ± radius_tol)``, and within
    that band the answer is None.

    Parameters
    ----------
    A, C, W : array_like
        The data (seed 000 eqs. (5.1)–(5.3)).
    gains : sequence of ndarray
        ``L_i``, shapes ``(n, p_i)``.
    order : str
        ``consensus-then-filter`` (L, eq. (5.13)) or ``filter-then-consensus`` (J, App. C.3).
    rho : Fraction
        ``ρ > 0``.
    radius_tol : float
        Relative band of the float decision.

    Returns
    -------
    bool or None

    References
    ----------
    seed 000 Lemma 5.2.2, footnote 5.
    """
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
    operator = "L" if order == "consensus-then-filter" else "J"
    return radius_below(operator, stochastic_matrix(W), gammas, rho)


def nonnegative_radius_below(M: Matrix, rho: Fraction = Fraction(1)) -> bool:
    """Whether ``r_σ(M) < ρ`` for an entrywise non-negative exact matrix ``M``.

    ``ρI − M`` is a Z-matrix; it is a nonsingular M-matrix — equivalently ``r_σ(M) < ρ`` — iff
    all its leading principal minors are positive (Berman–Plemmons, Thm 6.2.3).

    Parameters
    ----------
    M : exact (m, m) matrix
        Non-negative entries.
    rho : Fraction
        ``ρ > 0``.

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        If ``M`` has a negative entry.
    """
    if any(x < 0 for row in M for x in row):
        raise ValueError("M has a negative entry")
    m = len(M)
    shifted = [[(rho if r == c else 0) - M[r][c] for c in range(m)] for r in range(m)]
    return all(to_fmpq([row[:k] for row in shifted[:k]]).det() > 0 for k in range(1, m + 1))
