"""Certificates of the averaged EKF's covariance bound (seed 000 App. A, Lemma A.2.1, Cor. A.2.2).

Appendix A proves the stochastic stability of the ch. 4 averaged EKF: with
``M_k^j = A (I − K_k^j H_k^j)`` (eq. (A.3), gains and Jacobians of the TDOA filter), a common
``X ≻ 0`` with ``f₁ⁱ(M, X) ≺ r Xⁱ`` for every mode met keeps ``P_{k+1} = f₁(M_k, P_k) + U_k``
bounded. ``f₁`` is the operator ``J`` of :mod:`theory.consensus.operators` with ``Γ_j = M^j``; the
kind ``covariance-bound`` of :mod:`proofs_check` checks it exactly.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from proofs_check.linalg import Matrix, identity, matmul, sub
from theory.consensus.certificates import decrease_strings, float_margin
from theory.core.certificate_format import envelope, rational_bound, rounded, strings
from theory.core.exact import (
    PRECISIONS,
    exact_matrix,
    fraction_strings,
    stochastic_matrix,
    symmetric_projection,
)
from theory.core.tolerances import CERTIFICATE_MARGIN

__all__ = ["covariance_bound_certificate", "ekf_covariance_bound_certificate"]

SOURCE = "seed 000, Lemma A.2.1 and Corollary A.2.2"


def covariance_bound_certificate(
    W: np.ndarray,
    modes: Sequence[Sequence[np.ndarray]],
    X: Sequence[np.ndarray],
    *,
    rate: float | Fraction = 1,
    lmi_margin: float = CERTIFICATE_MARGIN,
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
        Relative margin (:func:`theory.consensus.certificates.float_margin`) the float witness
        must exceed.
    precisions : sequence of int
        Significant bits tried when rounding ``X``.
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
        "modes": [{"M": strings(m)} for m in modes_q],
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
    lmi_margin: float = CERTIFICATE_MARGIN,
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
        Relative margin (:func:`theory.consensus.certificates.float_margin`) the float witness
        must exceed.
    precisions : sequence of int
        Significant bits tried when rounding ``X``.
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
    Ks_q = [[exact_matrix(k) for k in ks] for ks in Ks]
    Hs_q = [[exact_matrix(h) for h in hs] for hs in Hs]
    modes_q = _closed_loop_modes(A_q, Ks_q, Hs_q)
    data = {
        "W": fraction_strings(stochastic_matrix(W)),
        "A": fraction_strings(A_q),
        "modes": [{"K": strings(ks), "H": strings(hs)} for ks, hs in zip(Ks_q, Hs_q, strict=True)],
    }
    floats = [[np.array(m, dtype=float) for m in mode] for mode in modes_q]
    return _covariance(data, W, floats, modes_q, X, rate, lmi_margin, precisions, case)


def _closed_loop_modes(
    A: Matrix, Ks: list[list[Matrix]], Hs: list[list[Matrix]]
) -> list[list[Matrix]]:
    """``M_k^j = A (I − K_k^j H_k^j)`` in exact rationals (seed 000 eq. (A.3))."""
    eye = identity(len(A))
    return [
        [matmul(A, sub(eye, matmul(k, h))) for k, h in zip(ks, hs, strict=True)]
        for ks, hs in zip(Ks, Hs, strict=True)
    ]


def _covariance(data, W, modes, modes_q, X, rate, lmi_margin, precisions, case) -> dict:
    bound = rational_bound(rate)
    claim = {
        "statement": "f₁^i(M, X) ≺ rate · X^i for every listed mode M: f_n(M, P) → 0 and "
        "P_{k+1} = f₁(M_k, P_k) + U_k stays bounded for modes M_k from the list (Lemma A.2.1)",
        "rate": str(bound),
    }
    W_q = stochastic_matrix(W)
    margin = min(float_margin("J", W, m, X, float(bound)) for m in modes)

    def build(exact: dict[str, list[Matrix]]) -> dict:
        X_q = exact["X"]
        witness = {
            "X": strings(X_q),
            "decrease": [decrease_strings("J", W_q, m, X_q, bound) for m in modes_q],
        }
        return envelope("covariance-bound", claim, data, witness, source=SOURCE, case=case)

    return rounded(
        build,
        {"X": [symmetric_projection(x) for x in X]},
        margin=margin,
        lmi_margin=lmi_margin,
        precisions=precisions,
        what="covariance-bound",
    )
