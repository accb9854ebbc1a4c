"""Builders of exact certificates from plain numpy data and floating witnesses.

Each builder takes the data of a claim (floats are read as the decimals they print as, or exact
``Fraction`` entries), a floating witness from a solver, checks that the witness is strictly
feasible with a relative margin above ``certificate_margin``, rounds it to rationals
(:mod:`theory.core.rationalize`) and keeps the first rounding that the independent checker
:mod:`proofs_check` accepts. The result is a certificate dict in the format of
``docs/certificates.md`` (``"format": "trackcert-certificate/1"``). Nothing weaker is ever
emitted: failure raises :class:`~theory.core.rationalize.RationalizationError`.

Kinds built here: ``mjls-stability`` (seed 000 Lemma 5.2.2) and ``s-detectability``
(Def. 5.2.4), from a float witness (:func:`s_detectability_certificate`) or from exact gains and
an exact Lyapunov tuple (:func:`exact_s_detectability_certificate`). Elsewhere:
``s-detectability-infeasible`` in :mod:`theory.consensus.infeasibility`, ``covariance-bound``
(Lemma A.2.1, Cor. A.2.2, the ch. 4 averaged EKF) in :mod:`theory.tdoa.covariance_certificates`,
``generic-rank`` in :mod:`theory.tdoa.rank_certificates`; the envelope and the rounding loop are
:mod:`theory.core.certificate_format`.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from proofs_check.linalg import Matrix, matmul, scale, sub
from proofs_check.operators import apply_operator as exact_operator
from theory.consensus.operators import apply_operator
from theory.core.certificate_format import (
    checked,
    envelope,
    rational_bound,
    rounded,
    strings,
)
from theory.core.rationalize import (
    PRECISIONS,
    RationalizationError,
    exact_matrix,
    fraction_strings,
    stochastic_matrix,
    symmetric_projection,
)
from theory.core.tolerances import CERTIFICATE_MARGIN

__all__ = [
    "ORDERS",
    "SOURCES",
    "decrease_strings",
    "exact_s_detectability_certificate",
    "float_margin",
    "mjls_stability_certificate",
    "s_detectability_certificate",
]


ORDERS = {"consensus-then-filter": "L", "filter-then-consensus": "J"}
"""Order of the consensus and filtering steps → operator: eq. (5.13) or eq. (C.6)."""

SOURCES = {
    "mjls-stability": "seed 000, Lemma 5.2.2",
    "s-detectability": "seed 000, Definition 5.2.4 and Lemma 5.2.2",
    "gains-radius-below": "seed 000, Lemma 5.2.2; docs/theory/s-detectability.md, Lemma 1",
}


def float_margin(
    operator: str,
    W: np.ndarray,
    gammas: Sequence[np.ndarray],
    P: Sequence[np.ndarray],
    bound: float = 1.0,
) -> float:
    """Relative margin of a float Lyapunov witness.

    .. math:: \\mu = \\min_i \\min(\\lambda_{\\min}(P_i),\\ \\lambda_{\\min}(\\rho P_i - T_i(P)))
              / \\max_i \\|P_i\\|_2

    Positive iff the witness is strictly feasible in floating point.

    Parameters
    ----------
    operator : {"L", "J", "L-adjoint", "J-adjoint"}
        The operator ``T`` (see :mod:`proofs_check.operators`).
    W : (N, N) array
        Consensus weights.
    gammas : sequence of (n, n) arrays
        ``Γ_i`` (or ``M^i``).
    P : sequence of (n, n) arrays
        The float witness.
    bound : float
        ``ρ``.

    Returns
    -------
    float
    """
    P = [symmetric_projection(p) for p in P]
    images = apply_operator(operator, W, np.stack([np.asarray(g, float) for g in gammas]), P)
    scale = max(float(np.linalg.norm(p, 2)) for p in P)
    if not np.isfinite(scale) or scale == 0:
        return float("-inf")
    lows = [np.linalg.eigvalsh(p)[0] for p in P]
    lows += [
        np.linalg.eigvalsh(symmetric_projection(bound * p - t))[0]
        for p, t in zip(P, images, strict=True)
    ]
    return float(min(lows)) / scale


def decrease_strings(
    operator: str, W: Matrix, gammas: list[Matrix], P: list[Matrix], bound: Fraction
) -> list:
    """Exact ``bound · P_i − T_i(P)`` as strings (the checker recomputes and compares).

    Parameters
    ----------
    operator : {"L", "J", "L-adjoint", "J-adjoint"}
        The operator ``T``.
    W : exact matrix
        Consensus weights.
    gammas, P : lists of exact matrices
        ``Γ_i`` and the Lyapunov tuple.
    bound : Fraction
        ``ρ``.

    Returns
    -------
    list of nested lists of str
    """
    images = exact_operator(operator, W, gammas, P)
    return [fraction_strings(sub(scale(bound, p), t)) for p, t in zip(P, images, strict=True)]


def mjls_stability_certificate(
    gammas: Sequence[np.ndarray],
    W: np.ndarray,
    P: Sequence[np.ndarray],
    *,
    operator: str = "L",
    spectral_radius_below: float | Fraction = 1,
    certificate_margin: float = CERTIFICATE_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Certificate of ``r_σ(L) < ρ`` for given ``Γ_i`` and ``W`` (seed 000 Lemma 5.2.2).

    Parameters
    ----------
    gammas : sequence of (n, n) arrays
        ``Γ_1 … Γ_N`` of eq. (5.13).
    W : (N, N) array
        Consensus weights (non-negative).
    P : sequence of (n, n) arrays
        Float witness: ``P_i ≻ 0`` and ``ρ P_i − T_i(P) ≻ 0``.
    operator : {"L", "J", "L-adjoint", "J-adjoint"}
        Which of the four equivalent operators ``P`` is a Lyapunov matrix for.
    spectral_radius_below : float or Fraction
        ``ρ ∈ (0, 1]`` (limited to denominators ≤ 10⁶).
    certificate_margin : float
        Relative margin (:func:`float_margin`) the float witness must exceed before it is rounded
        (the exact check decides; this only skips futile roundings).
    precisions : sequence of int
        Significant bits tried when rounding ``P``.
    case : str, optional
        Case name recorded in the certificate.

    Returns
    -------
    dict
        The certificate.

    Raises
    ------
    RationalizationError
        If the float witness is not strictly feasible or no rounding passes the exact check.

    References
    ----------
    seed 000, Lemma 5.2.2 and eq. (5.13).
    """
    bound = rational_bound(spectral_radius_below)
    claim = {"statement": "r_σ(L) < ρ for the given Γ_i and W", "spectral_radius_below": str(bound)}
    W_q, gammas_q = stochastic_matrix(W), [exact_matrix(g) for g in gammas]
    data = {"W": fraction_strings(W_q), "Gamma": strings(gammas_q)}
    margin = float_margin(operator, W, gammas, P, float(bound))

    def build(exact: dict[str, list[Matrix]]) -> dict:
        P_q = exact["P"]
        witness = {
            "operator": operator,
            "P": strings(P_q),
            "decrease": decrease_strings(operator, W_q, gammas_q, P_q, bound),
        }
        return envelope(
            "mjls-stability", claim, data, witness, source=SOURCES["mjls-stability"], case=case
        )

    return rounded(
        build,
        {"P": [symmetric_projection(p) for p in P]},
        margin=margin,
        lmi_margin=certificate_margin,
        precisions=precisions,
        what="mjls-stability",
    )


def s_detectability_certificate(
    A: np.ndarray,
    Cs: Sequence[np.ndarray],
    W: np.ndarray,
    order: str,
    gains: Sequence[np.ndarray],
    Ps: Sequence[np.ndarray],
    *,
    dual: bool = False,
    rho: float | Fraction = 1,
    certificate_margin: float = CERTIFICATE_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Certificate that ``(A, C, W)`` is S-detectable (seed 000 Def. 5.2.4), from a float witness.

    The witness is the gains ``L_i`` and Lyapunov matrices ``P_i`` with ``P ≻ 0`` and
    ``ρP − T(P) ≻ 0`` for ``Γ_i = A − L_i C_i``: ``T`` is the operator of ``order`` (``L`` of eq.
    (5.13) for ``"consensus-then-filter"``, ``J`` of eq. (C.6) for ``"filter-then-consensus"``),
    or with ``dual`` the adjoint ``L*_j(Y) = Σ_i w_ij Γ_iᵀ Y_i Γ_i`` (the LMI's dual tuple, the
    same for both orders). All of them prove ``r_σ(L) = r_σ(J) < 1``. An agent without
    measurements (``p_i = 0``) is written as one zero row of ``C_i`` with a zero gain column,
    which leaves ``Γ_i = A`` unchanged.

    Parameters
    ----------
    A : (n, n) array
        System matrix, eq. (5.1).
    Cs : sequence of (p_i, n) arrays
        Measurement matrices, eq. (5.2).
    W : (N, N) array
        Consensus weights.
    order : {"consensus-then-filter", "filter-then-consensus"}
        Order of the steps: eqs. (5.3)–(5.4) or Appendix C.3.
    gains : sequence of (n, p_i) arrays
        Float gains ``L_i``.
    Ps : sequence of (n, n) arrays
        Float Lyapunov matrices.
    dual : bool
        Whether ``Ps`` is the dual tuple ``Y`` (operator ``L-adjoint``).
    rho : float or Fraction
        ``ρ > 0``: the claim is ``r_σ(L) < ρ``; the kind is ``s-detectability`` for ``ρ ≤ 1``
        (1 for S-detectability), ``gains-radius-below`` above 1.
    certificate_margin : float
        As in :func:`mjls_stability_certificate`.
    precisions : sequence of int
        As in :func:`mjls_stability_certificate`.
    case : str, optional
        Case name recorded in the certificate.

    Returns
    -------
    dict

    Raises
    ------
    RationalizationError
        If no rounding passes the exact check.
    ValueError
        For an unknown ``order``.

    References
    ----------
    seed 000, Definition 5.2.4, Lemma 5.2.2, Appendix C.3.
    """
    if order not in ORDERS:
        raise ValueError(f"order must be one of {sorted(ORDERS)}, got {order!r}")
    operator = "L-adjoint" if dual else ORDERS[order]
    bound = rational_bound(rho)
    Cs, gains = _padded(A, Cs, [np.asarray(g, float) for g in gains])
    exact = _exact_data(A, Cs, W)
    A_f = np.asarray(A, float)
    gammas = [A_f - g @ c for g, c in zip(gains, Cs, strict=True)]
    margin = float_margin(operator, W, gammas, Ps, float(bound))

    def build(witness: dict[str, list[Matrix]]) -> dict:
        return _document(exact, operator, witness["gains"], witness["P"], bound, case)

    matrices = {"gains": gains, "P": [symmetric_projection(p) for p in Ps]}
    return rounded(
        build,
        matrices,
        margin=margin,
        lmi_margin=certificate_margin,
        precisions=precisions,
        what="s-detectability",
    )


def exact_s_detectability_certificate(
    A: np.ndarray,
    Cs: Sequence[np.ndarray],
    W: np.ndarray,
    gains: Sequence[Matrix],
    P: Sequence[Matrix],
    *,
    operator: str,
    rho: float | Fraction = 1,
    case: str | None = None,
) -> dict:
    """The ``s-detectability`` certificate of exact gains and an exact Lyapunov tuple.

    Nothing is rounded: ``gains`` and ``P`` are already rational (e.g. ``P`` solving
    ``P − T(P) = I`` exactly, :mod:`theory.consensus.exact_radius`), so a witness with any
    positive margin, however small, is a proof.

    Parameters
    ----------
    A, Cs, W : array_like
        The data (floats read as the decimals they print as).
    gains : sequence of exact (n, p_i) matrices
        ``L_i`` (for an agent without sensor: one zero column).
    P : sequence of exact (n, n) matrices
        The Lyapunov tuple for ``operator``.
    operator : {"L", "J", "L-adjoint", "J-adjoint"}
        The operator ``T`` of ``P ≻ 0``, ``ρP − T(P) ≻ 0``.
    rho : float or Fraction
        ``ρ > 0`` (as in :func:`s_detectability_certificate`).
    case : str, optional
        Case name recorded in the certificate.

    Returns
    -------
    dict

    Raises
    ------
    RationalizationError
        If :mod:`proofs_check` rejects the certificate (the message names the failing check).

    References
    ----------
    seed 000, Definition 5.2.4, Lemma 5.2.2.
    """
    n = np.asarray(A).shape[0]
    Cs, _ = _padded(A, Cs, [np.zeros((n, 0))] * len(Cs))
    zero = [[Fraction(0)] for _ in range(n)]
    gains = [g if g and g[0] else zero for g in gains]
    cert = _document(_exact_data(A, Cs, W), operator, gains, list(P), rational_bound(rho), case)
    why = checked(cert)
    if why is not None:
        raise RationalizationError(f"s-detectability: {why}")
    cert["produced_by"] = {"tool": "trackcert", "witness": "exact (no rounding)"}
    return cert


def _padded(
    A: np.ndarray, Cs: Sequence[np.ndarray], gains: list[np.ndarray]
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """``C_i`` and ``L_i`` with an agent without sensor as one zero row and one zero column."""
    n = np.asarray(A).shape[0]
    Cs = [np.asarray(c, float).reshape(-1, n) for c in Cs]
    gains = [np.asarray(g, float).reshape(n, -1) for g in gains]
    gains = [g if c.shape[0] else np.zeros((n, 1)) for g, c in zip(gains, Cs, strict=True)]
    return [c if c.shape[0] else np.zeros((1, n)) for c in Cs], gains


def _exact_data(A: np.ndarray, Cs: Sequence[np.ndarray], W: np.ndarray) -> dict[str, list]:
    return {
        "A": exact_matrix(A),
        "C": [exact_matrix(c) for c in Cs],
        "W": stochastic_matrix(W),
    }


def _document(
    exact: dict[str, list],
    operator: str,
    gains: list[Matrix],
    P: list[Matrix],
    bound: Fraction,
    case: str | None,
) -> dict:
    A_q, C_q, W_q = exact["A"], exact["C"], exact["W"]
    gammas = [sub(A_q, matmul(g, c)) for g, c in zip(gains, C_q, strict=True)]
    kind = "s-detectability" if bound <= 1 else "gains-radius-below"
    claim = {
        "statement": ("(A, C, W) is S-detectable: " if bound <= 1 else "")
        + "r_σ(L) < ρ with Γ_i = A − L_i C_i",
        "spectral_radius_below": str(bound),
    }
    data = {"A": fraction_strings(A_q), "C": strings(C_q), "W": fraction_strings(W_q)}
    witness = {
        "operator": operator,
        "gains": strings(gains),
        "P": strings(P),
        "decrease": decrease_strings(operator, W_q, gammas, P, bound),
    }
    return envelope(kind, claim, data, witness, source=SOURCES[kind], case=case)
