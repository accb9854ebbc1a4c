"""Builders of exact certificates from plain numpy data and floating witnesses.

Each builder takes the data of a claim (floats are read as the decimals they print as, or exact
``Fraction`` entries), a floating witness from a solver, checks that the witness is strictly
feasible with a relative margin above ``lmi_margin``, rounds it to rationals
(:mod:`theory.core.rationalize`) and keeps the first rounding that the independent checker
:mod:`proofs_check` accepts. The result is a certificate dict in the format of
``docs/certificates.md`` (``"format": "trackcert-certificate/1"``). Nothing weaker is ever
emitted: failure raises :class:`~theory.core.rationalize.RationalizationError`.

Kinds built here: ``mjls-stability`` (seed 000 Lemma 5.2.2), ``s-detectability`` (Def. 5.2.4),
``covariance-bound`` (Lemma A.2.1, Cor. A.2.2). ``generic-rank`` is built in
:mod:`theory.tdoa.rank_certificates`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import Any

import numpy as np

import proofs_check
from proofs_check.linalg import Matrix, identity, matmul, scale, sub
from proofs_check.operators import apply_operator
from theory.core.rationalize import (
    PRECISIONS,
    RationalizationError,
    dyadic_matrix,
    exact_matrix,
    first_success,
    fraction_strings,
    stochastic_matrix,
    symmetric_projection,
)
from theory.core.tolerances import CERTIFICATE_MARGIN as LMI_MARGIN

__all__ = [
    "LMI_MARGIN",
    "ORDERS",
    "bundle",
    "covariance_bound_certificate",
    "ekf_covariance_bound_certificate",
    "float_margin",
    "mjls_stability_certificate",
    "s_detectability_certificate",
]


ORDERS = {"consensus-then-filter": "L", "filter-then-consensus": "J"}
"""Order of the consensus and filtering steps → operator: eq. (5.13) or eq. (C.6)."""

SOURCES = {
    "mjls-stability": "seed 000, Lemma 5.2.2",
    "s-detectability": "seed 000, Definition 5.2.4 and Lemma 5.2.2",
    "covariance-bound": "seed 000, Lemma A.2.1 and Corollary A.2.2",
}


def _image(operator: str, W: np.ndarray, gammas: Sequence[np.ndarray], P: Sequence[np.ndarray]):
    """Float ``T(P)`` for the operators of ``proofs_check.operators`` (the untrusted side)."""
    W, P = np.asarray(W, float), np.asarray(P, float)
    gammas = [np.asarray(g, float) for g in gammas]

    def congruence(g: np.ndarray, v: np.ndarray) -> np.ndarray:
        return g @ v @ g.T

    if operator == "L":
        return [congruence(g, np.tensordot(W[i], P, 1)) for i, g in enumerate(gammas)]
    if operator == "J":
        moved = np.array([congruence(g, p) for g, p in zip(gammas, P, strict=True)])
        return [np.tensordot(W[i], moved, 1) for i in range(len(W))]
    if operator == "L-adjoint":
        moved = np.array([congruence(g.T, p) for g, p in zip(gammas, P, strict=True)])
        return [np.tensordot(W[:, j], moved, 1) for j in range(len(W))]
    if operator == "J-adjoint":
        return [congruence(gammas[j].T, np.tensordot(W[:, j], P, 1)) for j in range(len(W))]
    raise ValueError(f"unknown operator {operator!r}")


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
    images = _image(operator, np.asarray(W, float), [np.asarray(g, float) for g in gammas], P)
    scale = max(float(np.linalg.norm(p, 2)) for p in P)
    if not np.isfinite(scale) or scale == 0:
        return float("-inf")
    lows = [np.linalg.eigvalsh(p)[0] for p in P]
    lows += [
        np.linalg.eigvalsh(symmetric_projection(bound * p - t))[0]
        for p, t in zip(P, images, strict=True)
    ]
    return float(min(lows)) / scale


def _certificate(kind: str, claim: dict, data: dict, witness: dict, case: str | None) -> dict:
    cert: dict[str, Any] = {
        "format": proofs_check.FORMAT,
        "kind": kind,
        "source": SOURCES.get(kind, ""),
        "claim": claim,
        "data": data,
        "witness": witness,
    }
    if case is not None:
        cert["case"] = case
    return cert


def _rounded(
    build: Callable[[dict[str, list[Matrix]]], dict],
    matrices: dict[str, list[np.ndarray]],
    *,
    margin: float,
    lmi_margin: float,
    precisions: Sequence[int],
    what: str,
) -> dict:
    """Round the float ``matrices`` with growing precision until ``build(rounded)`` checks."""
    if not margin > lmi_margin:
        raise RationalizationError(
            f"{what}: the float witness's relative margin {margin:.3g} does not exceed "
            f"lmi_margin = {lmi_margin:g}; it is not strictly feasible, so no certificate"
        )

    def attempt(bits: int) -> dict | None:
        rounded = {name: [dyadic_matrix(m, bits) for m in mats] for name, mats in matrices.items()}
        cert = build(rounded)
        return cert if proofs_check.check_certificate(cert).valid else None

    cert, bits = first_success(attempt, precisions=precisions, what=what)
    cert["produced_by"] = {
        "tool": "trackcert",
        "significant_bits": bits,
        "float_margin": f"{margin:.6g}",
        "lmi_margin": f"{lmi_margin:g}",
    }
    return cert


def _decrease(
    operator: str, W: Matrix, gammas: list[Matrix], P: list[Matrix], bound: Fraction
) -> list:
    """Exact ``bound · P_i − T_i(P)`` as strings (the checker recomputes and compares)."""
    images = apply_operator(operator, W, gammas, P)
    return [fraction_strings(sub(scale(bound, p), t)) for p, t in zip(P, images, strict=True)]


def _strings(mats: Sequence[Matrix]) -> list:
    return [fraction_strings(m) for m in mats]


def _bound(value: float | Fraction) -> Fraction:
    return Fraction(value).limit_denominator(10**6)


def mjls_stability_certificate(
    gammas: Sequence[np.ndarray],
    W: np.ndarray,
    P: Sequence[np.ndarray],
    *,
    operator: str = "L",
    spectral_radius_below: float | Fraction = 1,
    lmi_margin: float = LMI_MARGIN,
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
    lmi_margin : float
        Relative margin (:func:`float_margin`) the float witness must exceed.
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
    bound = _bound(spectral_radius_below)
    claim = {"statement": "r_σ(L) < ρ for the given Γ_i and W", "spectral_radius_below": str(bound)}
    W_q, gammas_q = stochastic_matrix(W), [exact_matrix(g) for g in gammas]
    data = {"W": fraction_strings(W_q), "Gamma": _strings(gammas_q)}
    margin = float_margin(operator, W, gammas, P, float(bound))

    def build(rounded: dict[str, list[Matrix]]) -> dict:
        P_q = rounded["P"]
        witness = {
            "operator": operator,
            "P": _strings(P_q),
            "decrease": _decrease(operator, W_q, gammas_q, P_q, bound),
        }
        return _certificate("mjls-stability", claim, data, witness, case)

    return _rounded(
        build,
        {"P": [symmetric_projection(p) for p in P]},
        margin=margin,
        lmi_margin=lmi_margin,
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
    lmi_margin: float = LMI_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Certificate that ``(A, C, W)`` is S-detectable (seed 000 Def. 5.2.4).

    The witness is the gains ``L_i`` and Lyapunov matrices ``P_i`` with ``P ≻ 0`` and
    ``P − T(P) ≻ 0`` for ``Γ_i = A − L_i C_i``: ``T`` is the operator of ``order`` (``L`` of eq.
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
    lmi_margin : float
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
    n = np.asarray(A).shape[0]
    Cs = [np.asarray(c, float).reshape(-1, n) for c in Cs]
    gains = [np.asarray(g, float).reshape(n, -1) for g in gains]
    gains = [g if c.shape[0] else np.zeros((n, 1)) for g, c in zip(gains, Cs, strict=True)]
    Cs = [c if c.shape[0] else np.zeros((1, n)) for c in Cs]
    claim = {
        "statement": "(A, C, W) is S-detectable: r_σ(L) < 1 with Γ_i = A − L_i C_i",
        "spectral_radius_below": "1",
    }
    A_q, C_q, W_q = exact_matrix(A), [exact_matrix(c) for c in Cs], stochastic_matrix(W)
    data = {"A": fraction_strings(A_q), "C": _strings(C_q), "W": fraction_strings(W_q)}
    A_f = np.asarray(A, float)
    gammas = [
        A_f - np.asarray(g, float) @ np.asarray(c, float) for g, c in zip(gains, Cs, strict=True)
    ]
    margin = float_margin(operator, W, gammas, Ps)

    def build(rounded: dict[str, list[Matrix]]) -> dict:
        gains_q, P_q = rounded["gains"], rounded["P"]
        gammas_q = [sub(A_q, matmul(g, c)) for g, c in zip(gains_q, C_q, strict=True)]
        witness = {
            "operator": operator,
            "gains": _strings(gains_q),
            "P": _strings(P_q),
            "decrease": _decrease(operator, W_q, gammas_q, P_q, Fraction(1)),
        }
        return _certificate("s-detectability", claim, data, witness, case)

    matrices = {
        "gains": [np.asarray(g, float) for g in gains],
        "P": [symmetric_projection(p) for p in Ps],
    }
    return _rounded(
        build,
        matrices,
        margin=margin,
        lmi_margin=lmi_margin,
        precisions=precisions,
        what="s-detectability",
    )


def covariance_bound_certificate(
    W: np.ndarray,
    modes: Sequence[Sequence[np.ndarray]],
    X: Sequence[np.ndarray],
    *,
    rate: float | Fraction = 1,
    lmi_margin: float = LMI_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Certificate of ``Xⁱ ≻ f₁ⁱ(M, X)`` for each listed mode ``M`` (seed 000 Lemma A.2.1).

    Parameters
    ----------
    W : (N, N) array
        Consensus weights.
    modes : sequence of sequences of (n, n) arrays
        Each mode is ``(M¹ … M^N)``; one common ``X`` must work for all of them.
    X : sequence of (n, n) arrays
        Float witness.
    rate : float or Fraction
        ``r ∈ (0, 1]`` with ``f₁ⁱ(M, X) ≺ r Xⁱ``.
    lmi_margin : float
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

    References
    ----------
    seed 000, Lemma A.2.1, eqs. (A.53)–(A.54).
    """
    modes_q = [[exact_matrix(m) for m in mode] for mode in modes]
    data = {
        "W": fraction_strings(stochastic_matrix(W)),
        "modes": [{"M": _strings(m)} for m in modes_q],
    }
    floats = [[np.asarray(m, float) for m in mode] for mode in modes]
    return _covariance(data, W, floats, modes_q, X, rate, lmi_margin, precisions, case)


def ekf_covariance_bound_certificate(
    A: np.ndarray,
    Ks: Sequence[Sequence[np.ndarray]],
    Hs: Sequence[Sequence[np.ndarray]],
    W: np.ndarray,
    X: Sequence[np.ndarray],
    *,
    rate: float | Fraction = 1,
    lmi_margin: float = LMI_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Cor. A.2.2's hypothesis at listed steps ``k``, with ``M_k^j = A (I − K_k^j H_k^j)``.

    Parameters
    ----------
    A : (n, n) array
        Target dynamics, eq. (4.6).
    Ks : sequence over steps of sequences over agents of (n, p_j) arrays
        Gains ``K_k^j`` (eq. (A.3)), taken as data exactly as given.
    Hs : sequence over steps of sequences over agents of (p_j, n) arrays
        Jacobians ``H_k^j``.
    W : (N, N) array
        Consensus weights.
    X : sequence of (n, n) arrays
        Float witness.
    rate : float or Fraction
        As in :func:`covariance_bound_certificate`.
    lmi_margin : float
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

    References
    ----------
    seed 000, Corollary A.2.2, eq. (A.55).
    """
    A_q = exact_matrix(A)
    eye = identity(len(A_q))
    Ks_q = [[exact_matrix(k) for k in ks] for ks in Ks]
    Hs_q = [[exact_matrix(h) for h in hs] for hs in Hs]
    modes_q = [
        [matmul(A_q, sub(eye, matmul(k, h))) for k, h in zip(ks, hs, strict=True)]
        for ks, hs in zip(Ks_q, Hs_q, strict=True)
    ]
    data = {
        "W": fraction_strings(stochastic_matrix(W)),
        "A": fraction_strings(A_q),
        "modes": [
            {"K": _strings(ks), "H": _strings(hs)} for ks, hs in zip(Ks_q, Hs_q, strict=True)
        ],
    }
    floats = [[np.array(m, dtype=float) for m in mode] for mode in modes_q]
    return _covariance(data, W, floats, modes_q, X, rate, lmi_margin, precisions, case)


def _covariance(data, W, modes, modes_q, X, rate, lmi_margin, precisions, case) -> dict:
    bound = _bound(rate)
    claim = {
        "statement": "f₁^i(M, X) ≺ rate · X^i for every listed mode M: f_n(M, P) → 0 and "
        "P_{k+1} = f₁(M_k, P_k) + U_k stays bounded for modes M_k from the list (Lemma A.2.1)",
        "rate": str(bound),
    }
    W_q = stochastic_matrix(W)
    margin = min(float_margin("J", W, m, X, float(bound)) for m in modes)

    def build(rounded: dict[str, list[Matrix]]) -> dict:
        X_q = rounded["X"]
        witness = {
            "X": _strings(X_q),
            "decrease": [_decrease("J", W_q, m, X_q, bound) for m in modes_q],
        }
        return _certificate("covariance-bound", claim, data, witness, case)

    return _rounded(
        build,
        {"X": [symmetric_projection(x) for x in X]},
        margin=margin,
        lmi_margin=lmi_margin,
        precisions=precisions,
        what="covariance-bound",
    )


def bundle(certificates: Sequence[dict], *, case: str | None = None) -> dict:
    """Several certificates in one file (``"kind": "bundle"``), valid iff each one is.

    Parameters
    ----------
    certificates : sequence of dict
        Certificates built by this module or :mod:`theory.tdoa.rank_certificates`.
    case : str, optional
        Case name recorded in the bundle.

    Returns
    -------
    dict
    """
    out: dict[str, Any] = {"format": proofs_check.FORMAT, "kind": "bundle"}
    if case is not None:
        out["case"] = case
    out["certificates"] = list(certificates)
    return out
