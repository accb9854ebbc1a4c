"""Seed 000 App. C.2: how the covariance bound of arbitrary gains exceeds that of the gains (C.2).

With ``Π = E_i(P(k))``, ``Π* = E_i(P*(k))`` (eq. (5.12)), one step of the bound (5.15) is

    ``P_i(k+1) = (A − L_i C_i) Π (A − L_i C_i)' + L_i R_i L_i' + Q``,

and ``L*_i = A Π* C_i' S*⁻¹`` with ``S* = R_i + C_i Π* C_i'`` (eq. (C.2)). App. C.2 prints

    ``P*_i(k+1) − P_i(k+1) = (A − L*_i C_i) E_i(P* − P) (A − L*_i C_i)'
    − (L_i − L*_i)(R_i + C_i Π C_i')(L_i − L*_i)``

(the last factor lacks its transpose, so the product is defined only when ``n = p``; we read it
with the transpose). It is false: ``A = C = R = 1``, ``Q = 0``, ``Π* = 1``, ``Π = 2`` give
``L* = 1/2``; with ``L = 0`` the true difference is ``−3/2`` and the printed right side ``−1``.
What is true (:func:`corrected_gap`) is

    ``P_i(k+1) − P*_i(k+1) = (A − L_i C_i) E_i(P − P*) (A − L_i C_i)'
    + (L_i − L*_i) S* (L_i − L*_i)'``,

with the *arbitrary* gain in the first term and ``Π*`` (not ``Π``) in the second. Proof, valid for
every size: for any ``K`` in place of ``L*``, expanding both sides in the free algebra with
involution gives the residual ``(L − K) N' + N (L − K)'`` with ``N = K S* − A Π* C'``, and
(C.2) says exactly ``N = 0`` (:func:`free_algebra_residuals`). The printed right side misses the
cross term: printed − true ``= −(M C Δ G' + G Δ C' M')`` with ``M = L − L*``, ``Δ = Π − Π*``,
``G = A − L* C`` (:func:`printed_discrepancy`), a rational function of the data that is not
identically zero, so the printed identity holds only on a null set (e.g. ``L = L*`` or
``Π = Π*``).

The paper's conclusion survives: if ``P(k) ≥ P*(k)`` then ``Δ ⪰ 0`` (``w_ij ≥ 0``) and
``S* ≻ 0``, so both terms of the corrected form are positive semidefinite and
``P_i(k+1) ⪰ P*_i(k+1)``. The claim ``seed000.appC.2``
(:mod:`theory.consensus.suboptimal_gains_claims`) also checks (C.3), the Riccati form of
``P*_i(k+1)``.
"""

from __future__ import annotations

import itertools

import flint
import sympy as sp

__all__ = [
    "bound_step",
    "corrected_gap",
    "entrywise_proof",
    "free_algebra_residuals",
    "is_psd",
    "optimal_gain",
    "printed_discrepancy",
    "printed_gap",
    "riccati_form",
]


def _t(M: flint.fmpq_mat) -> flint.fmpq_mat:
    return M.transpose()


def bound_step(
    A: flint.fmpq_mat,
    C: flint.fmpq_mat,
    R: flint.fmpq_mat,
    Q: flint.fmpq_mat,
    L: flint.fmpq_mat,
    Pi: flint.fmpq_mat,
) -> flint.fmpq_mat:
    """One step of the covariance bound: ``(A − L C) Π (A − L C)' + L R L' + Q`` (exact).

    Parameters
    ----------
    A : fmpq_mat, n × n
        State matrix.
    C : fmpq_mat, p × n
        Agent ``i``'s output matrix ``C_i``.
    R : fmpq_mat, p × p
        Agent ``i``'s measurement noise covariance ``R_i``.
    Q : fmpq_mat, n × n
        Process noise covariance.
    L : fmpq_mat, n × p
        Agent ``i``'s gain ``L_i``.
    Pi : fmpq_mat, n × n
        ``Π = E_i(P(k)) = Σ_j w_ij P_j(k)`` (eq. (5.12)).

    Returns
    -------
    fmpq_mat
        ``P_i(k+1)`` of eq. (5.15), ``L_i(P(k)) = Γ_i E_i(P(k)) Γ_i'`` with ``Γ_i = A − L_i C_i``.

    References
    ----------
    seed 000, eqs. (5.12), (5.13), (5.15).
    """
    gamma = A - L * C
    return gamma * Pi * _t(gamma) + L * R * _t(L) + Q


def optimal_gain(
    A: flint.fmpq_mat, C: flint.fmpq_mat, R: flint.fmpq_mat, Pi_star: flint.fmpq_mat
) -> flint.fmpq_mat:
    """``L* = A Π* C' (R + C Π* C')⁻¹`` (seed 000 eq. (C.2)), exact.

    Parameters
    ----------
    A : fmpq_mat, n × n
        State matrix.
    C : fmpq_mat, p × n
        Output matrix ``C_i``.
    R : fmpq_mat, p × p
        Measurement noise covariance ``R_i``.
    Pi_star : fmpq_mat, n × n
        ``Π* = E_i(P*(k))``.

    Returns
    -------
    fmpq_mat, n × p

    Raises
    ------
    ZeroDivisionError
        If ``R + C Π* C'`` is singular.

    References
    ----------
    seed 000, eq. (C.2).
    """
    return A * Pi_star * _t(C) * (R + C * Pi_star * _t(C)).inv()


def printed_gap(
    A: flint.fmpq_mat,
    C: flint.fmpq_mat,
    R: flint.fmpq_mat,
    L: flint.fmpq_mat,
    Pi: flint.fmpq_mat,
    Pi_star: flint.fmpq_mat,
) -> flint.fmpq_mat:
    """The right side App. C.2 prints for ``P*_i(k+1) − P_i(k+1)`` (with the missing transpose).

    ``(A − L* C)(Π* − Π)(A − L* C)' − (L − L*)(R + C Π C')(L − L*)'``, ``L*`` from (C.2).

    Parameters
    ----------
    A, C, R : fmpq_mat
        As in :func:`optimal_gain`.
    L : fmpq_mat, n × p
        The arbitrary gain ``L_i``.
    Pi : fmpq_mat, n × n
        ``Π = E_i(P(k))``.
    Pi_star : fmpq_mat, n × n
        ``Π* = E_i(P*(k))``.

    Returns
    -------
    fmpq_mat, n × n

    References
    ----------
    seed 000, App. C.2 (the display after "It can be shown through matrix manipulation").
    """
    K = optimal_gain(A, C, R, Pi_star)
    G = A - K * C
    M = L - K
    return G * (Pi_star - Pi) * _t(G) - M * (R + C * Pi * _t(C)) * _t(M)


def corrected_gap(
    A: flint.fmpq_mat,
    C: flint.fmpq_mat,
    R: flint.fmpq_mat,
    L: flint.fmpq_mat,
    Pi: flint.fmpq_mat,
    Pi_star: flint.fmpq_mat,
) -> flint.fmpq_mat:
    """The true ``P_i(k+1) − P*_i(k+1)``: ``(A − L C)(Π − Π*)(A − L C)' + (L − L*) S* (L − L*)'``.

    Parameters
    ----------
    A, C, R, L, Pi, Pi_star : fmpq_mat
        As in :func:`printed_gap`.

    Returns
    -------
    fmpq_mat, n × n
        With ``S* = R + C Π* C'`` and ``L*`` from (C.2).

    References
    ----------
    seed 000, App. C.2 (corrected; module docstring).
    """
    S_star = R + C * Pi_star * _t(C)
    M = L - optimal_gain(A, C, R, Pi_star)
    gamma = A - L * C
    return gamma * (Pi - Pi_star) * _t(gamma) + M * S_star * _t(M)


def printed_discrepancy(
    A: flint.fmpq_mat,
    C: flint.fmpq_mat,
    R: flint.fmpq_mat,
    L: flint.fmpq_mat,
    Pi: flint.fmpq_mat,
    Pi_star: flint.fmpq_mat,
) -> flint.fmpq_mat:
    """Printed right side minus the true ``P*_i(k+1) − P_i(k+1)``, in closed form.

    ``−(M C Δ G' + G Δ C' M')`` with ``M = L − L*``, ``Δ = Π − Π*``, ``G = A − L* C``; zero iff
    ``M C Δ G'`` is skew-symmetric (for instance ``L = L*`` or ``Π = Π*``).

    Parameters
    ----------
    A, C, R, L, Pi, Pi_star : fmpq_mat
        As in :func:`printed_gap`.

    Returns
    -------
    fmpq_mat, n × n

    References
    ----------
    seed 000, App. C.2.
    """
    K = optimal_gain(A, C, R, Pi_star)
    cross = (L - K) * C * (Pi - Pi_star) * _t(A - K * C)
    return -(cross + _t(cross))


def riccati_form(
    A: flint.fmpq_mat,
    C: flint.fmpq_mat,
    R: flint.fmpq_mat,
    Q: flint.fmpq_mat,
    Pi_star: flint.fmpq_mat,
) -> flint.fmpq_mat:
    """Right side of (C.3): ``A Π* A' + Q − A Π* C' (C Π* C' + R)⁻¹ C Π* A'``.

    Parameters
    ----------
    A, C, R : fmpq_mat
        As in :func:`optimal_gain`.
    Q : fmpq_mat, n × n
        Process noise covariance.
    Pi_star : fmpq_mat, n × n
        ``Π* = E_i(P*(k))``.

    Returns
    -------
    fmpq_mat, n × n
        Equal to :func:`bound_step` with the gain (C.2) (checked by the claim).

    References
    ----------
    seed 000, eq. (C.3).
    """
    gain_part = A * Pi_star * _t(C) * (C * Pi_star * _t(C) + R).inv() * C * Pi_star * _t(A)
    return A * Pi_star * _t(A) + Q - gain_part


def is_psd(M: flint.fmpq_mat) -> bool:
    """Whether a rational matrix is symmetric positive semidefinite, decided exactly.

    A symmetric matrix is positive semidefinite iff every principal minor is ``≥ 0``; all
    ``2ⁿ − 1`` of them are computed (meant for ``n ≤ 8``).

    Parameters
    ----------
    M : fmpq_mat, n × n
        The matrix.

    Returns
    -------
    bool
    """
    n = M.nrows()
    if M.ncols() != n or M != _t(M):
        return False
    for size in range(1, n + 1):
        for rows in itertools.combinations(range(n), size):
            sub = flint.fmpq_mat(size, size, [M[i, j] for i in rows for j in rows])
            if sub.det() < 0:
                return False
    return True


# ---------------------------------------------------------------- symbolic proofs


def free_algebra_residuals() -> dict[str, str]:
    """Both sides of App. C.2 expanded in the free algebra with involution (every size at once).

    Matrices are non-commuting symbols; ``X'`` is a separate symbol ``Xt`` with ``(XY)' = Y'X'``
    applied by hand, and ``Π, Π*, R, Q`` are symmetric. ``K`` stands for any gain in place of
    ``L*`` and ``N = K S* − A Π* C'`` (``N = 0`` is (C.2)). A polynomial identity in this algebra
    holds for matrices of every compatible size, so a zero residual is a proof for all ``n, p``.

    Returns
    -------
    dict
        ``corrected_residual`` — expanded ``(P − P*) − [corrected] − [(L − K) N' + N (L − K)']``
        (``"0"`` proves the corrected identity whenever ``N = 0``); ``printed_residual`` —
        expanded ``[printed] − (P* − P) − [D + (L − K) N' + N (L − K)']`` with
        ``D = −((L − K) C Δ G' + G Δ C' (L − K)')`` (``"0"`` proves that the printed right side
        is off by exactly ``D`` under (C.2)); and the formulas used.

    References
    ----------
    seed 000, eqs. (5.15), (C.2), App. C.2.
    """
    A, At, C, Ct, L, Lt, K, Kt, R, Q, Pi, Ps = sp.symbols(
        "A At C Ct L Lt K Kt R Q Pi Pi_star", commutative=False
    )

    def step(gain: sp.Expr, gain_t: sp.Expr, middle: sp.Expr) -> sp.Expr:
        return (A - gain * C) * middle * (At - Ct * gain_t) + gain * R * gain_t + Q

    S_star = R + C * Ps * Ct
    S = R + C * Pi * Ct
    gap = step(L, Lt, Pi) - step(K, Kt, Ps)  # P_i(k+1) − P*_i(k+1)
    N, Nt = K * S_star - A * Ps * Ct, S_star * Kt - C * Ps * At
    off = (L - K) * Nt + N * (Lt - Kt)
    corrected = (A - L * C) * (Pi - Ps) * (At - Ct * Lt) + (L - K) * S_star * (Lt - Kt)
    printed = (A - K * C) * (Ps - Pi) * (At - Ct * Kt) - (L - K) * S * (Lt - Kt)
    G, Gt = A - K * C, At - Ct * Kt
    D = -((L - K) * C * (Pi - Ps) * Gt + G * (Pi - Ps) * Ct * (Lt - Kt))
    return {
        "corrected_residual": str(sp.expand(gap - corrected - off)),
        "printed_residual": str(sp.expand(printed + gap - D - off)),
        "N": "K S* − A Π* C'  (zero for K = L* of (C.2))",
        "off_term": "(L − K) N' + N (L − K)'",
        "D": "−((L − L*) C (Π − Π*) (A − L* C)' + its transpose)",
    }


def entrywise_proof(n: int, p: int) -> bool:
    """Prove the corrected identity entry by entry for general symbolic ``n × n``, ``p × n`` data.

    ``A, C, L`` have independent symbolic entries, ``R, Π, Π*, Q`` are symmetric symbolic, and
    ``L* = A Π* C' adj(S*)/det S*`` is substituted; after multiplying by ``det(S*)²`` both sides
    are polynomials, expanded and compared.

    Parameters
    ----------
    n : int
        State dimension.
    p : int
        Output dimension of agent ``i``.

    Returns
    -------
    bool
        ``True`` when ``det(S*)² [(P − P*) − corrected]`` expands to the zero matrix.

    References
    ----------
    seed 000, eqs. (5.15), (C.2), App. C.2.
    """

    def general(name: str, rows: int, cols: int) -> sp.Matrix:
        return sp.Matrix(rows, cols, lambda i, j: sp.Symbol(f"{name}_{i}{j}"))

    def symmetric(name: str, size: int) -> sp.Matrix:
        return sp.Matrix(size, size, lambda i, j: sp.Symbol(f"{name}_{min(i, j)}{max(i, j)}"))

    A, C, L = general("a", n, n), general("c", p, n), general("l", n, p)
    R, Pi, Ps, Q = symmetric("r", p), symmetric("x", n), symmetric("y", n), symmetric("q", n)
    S_star = R + C * Ps * C.T
    d = S_star.det()
    Kd = A * Ps * C.T * S_star.adjugate()  # det(S*) L*
    P_next = (A - L * C) * Pi * (A - L * C).T + L * R * L.T + Q
    P_star_next = (A * d - Kd * C) * Ps * (A * d - Kd * C).T + Kd * R * Kd.T + Q * d**2
    corrected = (A - L * C) * (Pi - Ps) * (A - L * C).T * d**2 + (L * d - Kd) * S_star * (
        L * d - Kd
    ).T
    residual = (P_next * d**2 - P_star_next - corrected).applyfunc(sp.expand)
    return bool(residual.is_zero_matrix)


# ---------------------------------------------------------------- exact instances
