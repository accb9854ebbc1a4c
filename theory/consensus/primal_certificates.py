"""Exact certificates that ``(A, C, W)`` **is** S-detectable, from every source of gains we have.

A positive verdict rests on an ``s-detectability`` certificate that :mod:`proofs_check` accepts
(seed 000 Def. 5.2.4, Lemma 5.2.2): rational gains ``L_i`` and a Lyapunov tuple ``P ≻ 0`` with
``ρP − T(P) ≻ 0``. Two routes, tried in turn by :func:`primal_certificate`:

1. **the LMI witness**, when its float margin clears ``lmi_margin``: gains and the primal tuple
   ``X`` (``X − T(X) = I``, float) or the dual tuple ``Y``, rounded with growing precision
   (:func:`theory.consensus.certificates.s_detectability_certificate`);
2. **exact Lyapunov tuples** for candidate gains (the LMI's, rounded to dyadics; the projection
   gains ``L_i = A C_i⁺``, which make ``Γ_i = A (I − C_i⁺C_i)`` vanish on what agent i sees; the
   case's; the Riccati iteration's): ``X`` solving ``X − T(X)/ρ = I`` exactly
   (:mod:`theory.consensus.exact_radius`), then rounded to dyadics well inside its exact margin
   ``I``. This needs no float margin at all, so it settles problems whose best margin is far
   below ``lmi_margin`` (seed 000 Example 1 at ``w = 0.249999999``: ``r_σ(L) = 4w``).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from theory.consensus.certificates import (
    ORDERS,
    exact_s_detectability_certificate,
    s_detectability_certificate,
)
from theory.consensus.exact_radius import exact_lyapunov
from theory.consensus.operators import (
    closed_loop,
    covariance_operator_matrix,
    unvec_tuple,
    vec_tuple,
)
from theory.core.certificate_format import rational_bound
from theory.core.exact import (
    Matrix,
    RationalizationError,
    dyadic_matrix,
    fractions_of,
    rational_matrix,
    stochastic_matrix,
    to_fmpq,
)
from theory.core.tolerances import EXACT_DIM, ROUNDING_BITS, bits_ladder

__all__ = [
    "certificate_gains",
    "exact_gain_certificate",
    "primal_certificate",
    "primal_lyapunov",
    "projection_gains",
]



def primal_lyapunov(
    A: np.ndarray, C: Sequence[np.ndarray], W: np.ndarray, gains: Sequence[np.ndarray], order: str
) -> np.ndarray | None:
    """The float ``X = Σ_k T^k(I)`` solving ``X − T(X) = I`` (``T`` of ``order``), if ``X ≻ 0``.

    Parameters
    ----------
    A : ndarray, shape (n, n)
        System matrix.
    C : sequence of ndarray
        Measurement matrices.
    W : ndarray, shape (N, N)
        Consensus weights.
    gains : sequence of ndarray
        Gains ``L_i``.
    order : str
        ``consensus-then-filter`` (operator L) or ``filter-then-consensus`` (operator J).

    Returns
    -------
    ndarray of shape (N, n, n), or None
        None when ``I − T`` is singular or the solution is not positive definite (then
        ``r_σ(T) ≥ 1`` up to rounding).

    References
    ----------
    seed 000 Lemma 5.2.2 ("only if": the witness ``P = Σ_k T^k(I)``).
    """
    N, n = np.asarray(W).shape[0], np.asarray(A).shape[0]
    T = covariance_operator_matrix(W, closed_loop(A, C, gains), order)
    try:
        x = np.linalg.solve(
            np.eye(T.shape[0]) - T, vec_tuple(np.broadcast_to(np.eye(n), (N, n, n)))
        )
    except np.linalg.LinAlgError:
        return None
    X = unvec_tuple(x, N, n)
    X = (X + X.transpose(0, 2, 1)) / 2
    return X if all(np.linalg.eigvalsh(Xi)[0] > 0 for Xi in X) else None


def projection_gains(A: np.ndarray, C: Sequence[np.ndarray]) -> list[Matrix]:
    """Exact gains ``L_i = A C_i⁺`` (``C_i⁺`` on a maximal set of independent rows, zero else).

    With them ``Γ_i = A − L_i C_i = A (I − C_i⁺ C_i)``: agent i removes everything it measures.

    Parameters
    ----------
    A : (n, n) array
        System matrix (read as written decimals).
    C : sequence of (p_i, n) arrays
        Measurement matrices.

    Returns
    -------
    list of exact (n, p_i) matrices (``[]`` for an agent without sensor)
    """
    n = np.asarray(A).shape[0]
    A_q = to_fmpq(rational_matrix(A))
    out = []
    for Ci in C:
        rows = rational_matrix(np.asarray(Ci, float).reshape(-1, n)) if np.size(Ci) else []
        keep: list[int] = []
        for r in range(len(rows)):
            if to_fmpq([rows[k] for k in [*keep, r]]).rank() == len(keep) + 1:
                keep.append(r)
        if not keep:
            out.append([[Fraction(0)] * len(rows) for _ in range(n)] if rows else [])
            continue
        Ck = to_fmpq([rows[k] for k in keep])
        pinv = Ck.transpose() * (Ck * Ck.transpose()).inv()
        partial = fractions_of(A_q * pinv)
        gain = [[Fraction(0)] * len(rows) for _ in range(n)]
        for col, k in enumerate(keep):
            for r in range(n):
                gain[r][k] = partial[r][col]
        out.append(gain)
    return out


def _dyadic_exact(M: Matrix, bits: int) -> Matrix:
    """An exact matrix rounded to ``bits`` significant bits of its largest entry (no floats)."""
    top = max((abs(x) for row in M for x in row), default=Fraction(0))
    if top == 0:
        return M
    exponent = top.numerator.bit_length() - top.denominator.bit_length() - bits
    unit = Fraction(2) ** exponent
    return [[round(x / unit) * unit for x in row] for row in M]


def exact_gain_certificate(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    gains: Sequence[Matrix],
    *,
    order: str,
    rho: float | Fraction = 1,
    case: str | None = None,
) -> dict:
    """The certificate of exact ``gains`` with the exact Lyapunov tuple of the order's operator.

    Parameters
    ----------
    A, C, W : array_like
        The data (read as written decimals; ``W``'s rows summing to exactly 1).
    gains : sequence of exact (n, p_i) matrices
        ``L_i``.
    order : str
        One of :data:`theory.consensus.case.ORDERS` (operator L or J).
    rho : float or Fraction
        ``ρ ∈ (0, 1]``.
    case : str, optional
        Case name recorded in the certificate.

    Returns
    -------
    dict
        Accepted by :mod:`proofs_check`.

    Raises
    ------
    RationalizationError
        If ``N n²`` exceeds :data:`~theory.core.tolerances.EXACT_DIM`, ``r_σ(T) ≥ ρ`` for
        these gains (no positive definite solution), or no rounding of it checks.
    """
    n, N = np.asarray(A).shape[0], np.asarray(W).shape[0]
    if N * n * n > EXACT_DIM:
        raise RationalizationError(f"N n² = {N * n * n} exceeds EXACT_DIM = {EXACT_DIM}")
    A_q, W_q, bound = rational_matrix(A), stochastic_matrix(W), rational_bound(rho)
    C_q = [rational_matrix(np.asarray(c, float).reshape(-1, n)) if np.size(c) else [] for c in C]
    gammas = [
        A_q if not c else fractions_of(to_fmpq(A_q) - to_fmpq(g) * to_fmpq(c))
        for g, c in zip(gains, C_q, strict=True)
    ]
    X = exact_lyapunov(ORDERS[order], W_q, gammas, bound)
    if X is None:
        raise RationalizationError("I − T/ρ is singular for these gains: r_σ(T) ≥ ρ")
    reasons = []
    for P in ([_dyadic_exact(x, b) for x in X] for b in bits_ladder(ROUNDING_BITS)):
        try:
            return exact_s_detectability_certificate(
                A, C, W, gains, P, operator=ORDERS[order], rho=bound, case=case
            )
        except RationalizationError as error:
            reasons.append(str(error))
    raise RationalizationError("; ".join(reasons[-1:]) or "no rounding of X checks")


def _exact_candidates(
    A: np.ndarray, C: Sequence[np.ndarray], candidates: Sequence[tuple[str, Sequence[np.ndarray]]]
) -> list[tuple[str, list[Matrix]]]:
    out = [("projection gains L_i = A C_i⁺", projection_gains(A, C))]
    bits = bits_ladder(ROUNDING_BITS)[0]
    for label, gains in candidates:
        floats = [np.asarray(g, float) for g in gains]
        if len(floats) == len(C) and all(np.all(np.isfinite(g)) for g in floats):
            rounded = [dyadic_matrix(g, bits) if g.size else [] for g in floats]
            out.append((label, rounded))
    return out


def primal_certificate(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    order: str,
    rho: float = 1.0,
    witness: tuple[Sequence[np.ndarray], np.ndarray] | None = None,
    candidates: Sequence[tuple[str, Sequence[np.ndarray]]] = (),
    case: str | None = None,
) -> tuple[dict | None, str, list[str]]:
    """The first checked ``s-detectability`` certificate the routes of the module docstring give.

    Parameters
    ----------
    A, C, W : array_like
        The data.
    order : str
        Filter order (operator of the primal tuple).
    rho : float
        ``ρ ∈ (0, 1]``.
    witness : (gains, Y), optional
        The LMI's float witness, when its margin cleared ``lmi_margin``.
    candidates : sequence of (label, gains)
        Further float gains to try with exact Lyapunov tuples.
    case : str, optional
        Case name recorded in the certificate.

    Returns
    -------
    certificate : dict or None
    route : str
        What produced it (empty when none did).
    reasons : list of str
        Why each route failed.
    """
    reasons: list[str] = []
    if witness is not None:
        gains, Y = witness
        X = primal_lyapunov(A, C, W, gains, order)
        for tuple_, dual in ((X, False), (Y, True)):
            if tuple_ is None:
                continue
            try:
                cert = s_detectability_certificate(
                    A, C, W, order, gains, list(tuple_), dual=dual, rho=rho, case=case
                )
                return cert, f"LMI witness, {'dual Y' if dual else 'primal X'} rounded", reasons
            except RationalizationError as error:
                reasons.append(f"LMI witness: {error}")
    for label, gains_q in _exact_candidates(A, C, candidates):
        try:
            cert = exact_gain_certificate(A, C, W, gains_q, order=order, rho=rho, case=case)
            return cert, f"{label}, exact Lyapunov tuple", reasons
        except RationalizationError as error:
            reasons.append(f"{label}: {error}")
    return None, "", reasons


def certificate_gains(cert: dict[str, Any], C: Sequence[np.ndarray]) -> tuple[np.ndarray, ...]:
    """The certificate's gains as floats, ``n × p_i`` (``n × 0`` for an agent without sensor).

    Parameters
    ----------
    cert : dict
        An ``s-detectability`` certificate.
    C : sequence of ndarray
        The measurement matrices (to drop the padding column of sensorless agents).
    """
    out = []
    for g, Ci in zip(cert["witness"]["gains"], C, strict=True):
        gain = np.array([[float(Fraction(x)) for x in row] for row in g])
        out.append(gain if np.size(Ci) else gain[:, :0])
    return tuple(out)
