"""The certificates of a ``kind: dkf`` case (``trackcert certify``, :mod:`theory.certify`).

``s-detectability`` certificates (:func:`theory.consensus.certificates.s_detectability_certificate`)
with the gains of the LMI witness (:func:`theory.consensus.s_detectability.witness_from_decision`)
and, when the case fixes gains, with those gains. The Lyapunov tuple is the primal one solving
``X − T(X) = I`` (:func:`primal_lyapunov`); the LMI's dual tuple is the fallback.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from theory.certify import Certified, register_certifier
from theory.consensus.certificates import s_detectability_certificate
from theory.consensus.operators import (
    closed_loop,
    covariance_operator_matrix,
    unvec_tuple,
    vec_tuple,
)
from theory.consensus.s_detectability import decide_s_detectability, witness_from_decision
from theory.core.case_file import Case
from theory.core.errors import PropertyFails
from theory.core.rationalize import RationalizationError

__all__ = ["dkf_certificates", "primal_lyapunov"]


def primal_lyapunov(
    A: np.ndarray, C: Any, W: np.ndarray, gains: Any, order: str
) -> np.ndarray | None:
    """The tuple ``X = Σ_k T^k(I)`` solving ``X − T(X) = I`` (``T`` of ``order``), if ``X ≻ 0``.

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
        ``r_σ(T) ≥ 1``).
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


def _gains_certificate(case: Case, gains: Any, dual: np.ndarray | None, label: str) -> Certified:
    spec = case.spec
    attempts = [(primal_lyapunov(spec.A, spec.C, spec.W, gains, spec.order), False)]
    if dual is not None:
        attempts.append((dual, True))
    reasons = []
    for witness, is_dual in attempts:
        if witness is None:
            reasons.append(f"{label}: X − T(X) = I has no positive definite solution")
            continue
        try:
            cert = s_detectability_certificate(
                spec.A,
                spec.C,
                spec.W,
                spec.order,
                gains,
                list(witness),
                dual=is_dual,
                case=case.name,
            )
            return [cert], []
        except RationalizationError as error:
            reasons.append(f"{label}: {error}")
    return [], reasons


@register_certifier("dkf")
def dkf_certificates(case: Case, seed: int) -> Certified:
    """The ``s-detectability`` certificates of ``case`` (seed 000 Def. 5.2.4, Lemma 5.2.2).

    The witness used is the primal Lyapunov tuple of the filter's order (:func:`primal_lyapunov`);
    the dual tuple of the LMI is the fallback.

    Parameters
    ----------
    case : Case
        A ``kind: dkf`` case.
    seed : int
        Unused (no random point): accepted as every certifier takes it.

    Returns
    -------
    (list of dict, list of str)
        One certificate with the LMI witness's gains and, when the case fixes gains, one with
        those; the reasons for any missing.

    Raises
    ------
    PropertyFails
        If the case is decided not S-detectable (there is nothing to certify).
    """
    del seed
    spec = case.spec
    certs, reasons = [], []
    decision = decide_s_detectability(spec.A, spec.C, spec.W, order=spec.order)
    if decision.verdict is False:
        raise PropertyFails(
            f"{case.name} is not S-detectable ({decision.reason}; seed000.def5.2.4, trackcert "
            "dkf): there is nothing to certify"
        )
    witness = witness_from_decision(decision, spec.order)
    if witness is None:
        reasons.append("the LMI found no verified S-detectability witness (see trackcert dkf)")
    else:
        found, why = _gains_certificate(case, witness["gains"], witness["Y"], "LMI gains")
        certs += found
        reasons += why
    if spec.L is not None:
        found, why = _gains_certificate(case, spec.L, None, "the case's gains")
        certs += found
        reasons += why
    return certs, reasons
