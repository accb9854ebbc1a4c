"""The certificates of a ``kind: dkf`` case (``trackcert certify``, :mod:`theory.certify`).

The ``s-detectability`` certificate the exact decision rests on
(:func:`theory.consensus.s_detectability.decide_s_detectability`: a rounded LMI witness or an exact
Lyapunov tuple) and, when the case fixes gains, one for those gains (the float primal tuple
``X − T(X) = I`` rounded, else the exact tuple).
"""

from __future__ import annotations

from theory.certify import Certified, register_certifier
from theory.consensus.certificates import s_detectability_certificate
from theory.consensus.primal_certificates import exact_gain_certificate, primal_lyapunov
from theory.consensus.s_detectability import SDetectability, decide_s_detectability
from theory.core.case_file import Case
from theory.core.errors import PropertyFails
from theory.core.exact import RationalizationError, rational_matrix

__all__ = ["decision_certificates", "dkf_certificates"]


def _case_gains_certificate(case: Case) -> Certified:
    """The case's own gains certified: float primal tuple rounded, else the exact tuple."""
    spec = case.spec
    reasons = []
    X = primal_lyapunov(spec.A, spec.C, spec.W, spec.L, spec.order)
    if X is None:
        reasons.append("the case's gains: X − T(X) = I has no positive definite solution")
    else:
        try:
            cert = s_detectability_certificate(
                spec.A, spec.C, spec.W, spec.order, spec.L, list(X), case=case.name
            )
            return [cert], []
        except RationalizationError as error:
            reasons.append(f"the case's gains: {error}")
    exact = [rational_matrix(g) if g.size else [] for g in spec.L]
    try:
        cert = exact_gain_certificate(
            spec.A, spec.C, spec.W, exact, order=spec.order, case=case.name
        )
        return [cert], []
    except RationalizationError as error:
        return [], [*reasons, f"the case's gains (exact tuple): {error}"]


def decision_certificates(case: Case, decision: SDetectability) -> Certified:
    """The ``s-detectability`` certificates of a dkf case given its decision (computed once).

    Parameters
    ----------
    case : Case
        A ``dkf`` case.
    decision : SDetectability
        :func:`~theory.consensus.s_detectability.decide_s_detectability` of the case.

    Returns
    -------
    (certificates, reasons)
        The decision's own certificate and, when the case fixes gains, one for those gains.

    Raises
    ------
    PropertyFails
        If the decision is "not S-detectable" (an exact infeasibility certificate checked).
    """
    if decision.verdict is False:
        raise PropertyFails(
            f"{case.name} is not S-detectable ({decision.reason}; seed000.def5.2.4, trackcert "
            "dkf): there is nothing to certify"
        )
    certs, reasons = [], []
    if decision.verdict:
        certs.append(decision.certificate)
    else:
        reasons.append(f"no exact S-detectability certificate: {decision.reason}")
    if case.spec.L is not None:
        found, why = _case_gains_certificate(case)
        certs += found
        reasons += why
    return certs, reasons


@register_certifier("dkf")
def dkf_certificates(case: Case, seed: int) -> Certified:
    """The ``s-detectability`` certificates of ``case`` (seed 000 Def. 5.2.4, Lemma 5.2.2).

    Parameters
    ----------
    case : Case
        A ``kind: dkf`` case.
    seed : int
        Unused (no random point): accepted as every certifier takes it.

    Returns
    -------
    (list of dict, list of str)
        As :func:`decision_certificates`, after deciding the case (its own gains are candidates).

    Raises
    ------
    PropertyFails
        If the case is decided not S-detectable (there is nothing to certify).
    """
    del seed
    spec = case.spec
    candidates = [("the case's gains", spec.L)] if spec.L is not None else []
    decision = decide_s_detectability(
        spec.A, spec.C, spec.W, order=spec.order, candidate_gains=candidates, case=case.name
    )
    return decision_certificates(case, decision)
