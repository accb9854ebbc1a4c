"""Every certificate a case supports, and the claims that report them (DESIGN.md, *Certificates*).

:data:`CERTIFIERS` maps a case kind to a function ``(case, seed) -> (certificates, reasons)``;
``reasons`` says why a certificate the kind could have is missing. Supported:

* ``tdoa``: ``generic-rank`` of the network observability matrix and of each agent's block
  column (:mod:`theory.tdoa.rank_certificates`);
* ``dkf``: ``s-detectability`` with the gains of the LMI witness
  (:func:`theory.consensus.s_detectability.witness_from_decision`), and, when the case fixes gains,
  with
  those gains. The witness used is the primal Lyapunov tuple of the filter's order; the dual
  tuple is the fallback.
* ``pursuit``: ``iss`` (:mod:`theory.pursuit.certificates`), when the case's conditions hold.

A case whose property is decided false (not S-detectable, a condition of the ISS analysis
failing) raises :class:`~theory.core.errors.PropertyFails`: ``trackcert certify`` exits 1 and the
claims here do not apply to it (:class:`~theory.core.claims.NotApplicable`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from theory.consensus.certificates import s_detectability_certificate
from theory.consensus.operators import (
    closed_loop,
    covariance_operator_matrix,
    unvec_tuple,
    vec_tuple,
)
from theory.consensus.s_detectability import decide_s_detectability, witness_from_decision
from theory.core.case_file import Case
from theory.core.certificate_format import bundle
from theory.core.claims import DOCUMENT_KEY, ClaimResult, NotApplicable, register
from theory.core.errors import InconclusiveError, PropertyFails
from theory.core.rationalize import RationalizationError
from theory.pursuit.certificates import pursuit_certificates
from theory.tdoa.rank_certificates import generic_rank_certificates

__all__ = [
    "CERTIFIERS",
    "case_certificates",
    "dkf_certificate_claim",
    "generic_rank_claim",
    "primal_lyapunov",
]

Certified = tuple[list[dict[str, Any]], list[str]]


def _tdoa(case: Case, seed: int) -> Certified:
    try:
        return generic_rank_certificates(case.spec, seed=seed, case=case.name), []
    except RationalizationError as error:
        return [], [str(error)]


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


def _dkf(case: Case, seed: int) -> Certified:
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


CERTIFIERS: dict[str, Callable[[Case, int], Certified]] = {
    "tdoa": _tdoa,
    "dkf": _dkf,
    "pursuit": pursuit_certificates,
}
"""Case kind → builder of its certificates (and of the reasons for missing ones)."""


def case_certificates(case: Case, *, seed: int = 0) -> list[dict[str, Any]]:
    """All certificates ``case`` supports (each already accepted by ``proofs_check``).

    Parameters
    ----------
    case : Case
        A loaded case.
    seed : int
        Seed of any random evaluation point (recorded in the certificates).

    Returns
    -------
    list of dict

    Raises
    ------
    InconclusiveError
        If the case's kind has no certificate kinds yet, or no certificate could be made (the
        message gives every reason, e.g. a witness that cannot be rationalized).
    PropertyFails
        If the property to certify is decided false for this case.
    """
    if case.kind not in CERTIFIERS:
        raise InconclusiveError(
            f"no certificate kinds for case kind {case.kind!r} yet "
            f"(supported: {sorted(CERTIFIERS)})"
        )
    certs, reasons = CERTIFIERS[case.kind](case, seed)
    if not certs:
        raise InconclusiveError(f"no certificate for {case.name}: " + "; ".join(reasons))
    return certs


def _certified(claim_id: str, case: Case) -> list[dict] | ClaimResult:
    """The case's certificates, or the ``inconclusive`` result saying why there are none."""
    try:
        return case_certificates(case)
    except InconclusiveError as error:
        return ClaimResult(claim_id, case.name, "exact", "inconclusive", message=str(error))
    except PropertyFails as error:
        raise NotApplicable(str(error)) from error


def _results(claim_id: str, case: Case, evidence: Callable[[dict], dict]) -> list[ClaimResult]:
    certs = _certified(claim_id, case)
    if isinstance(certs, ClaimResult):
        return [certs]
    return [
        ClaimResult(
            claim_id,
            case.name,
            "exact",
            "verified",
            evidence={**evidence(cert), DOCUMENT_KEY: cert},
            message=cert["claim"]["statement"],
        )
        for cert in certs
    ]


@register(
    "seed000.eq4.36.certified",
    source="seed 000, eqs. (4.36)–(4.37)",
    statement="the generic rank of the TDOA network observability matrix O and of each block "
    "column O_i is certified by an exact non-vanishing minor at a rational point",
    kinds=("tdoa",),
)
def generic_rank_claim(case: Case) -> list[ClaimResult]:
    """Run the generic-rank certificates of a TDOA case as claim results (method ``exact``).

    Parameters
    ----------
    case : Case
        A ``tdoa`` case.

    Returns
    -------
    list of ClaimResult
        One ``verified`` result per distinct network of the scene (one for a static scene),
        with the certified ranks of ``O`` (agent 0) and of each ``O_i`` and the steps the network
        holds; or one ``inconclusive`` result saying why there is none.
    """
    claim_id = "seed000.eq4.36.certified"
    certs = _certified(claim_id, case)
    if isinstance(certs, ClaimResult):
        return [certs]
    networks: dict[tuple[int, ...], list[dict]] = {}
    for cert in certs:
        networks.setdefault(tuple(cert["produced_by"].get("steps", [1])), []).append(cert)
    return [
        ClaimResult(
            claim_id,
            case.name,
            "exact",
            "verified",
            evidence={**_rank_evidence(steps, group), DOCUMENT_KEY: bundle(group, case=case.name)},
            message=_rank_message(group),
        )
        for steps, group in networks.items()
    ]


def _rank_evidence(steps: tuple[int, ...], group: list[dict]) -> dict[str, Any]:
    return {
        "steps": list(steps),
        "ranks_at_least": {c["claim"]["agent"]: c["claim"]["rank_at_least"] for c in group},
        "certificates": [
            {
                "agent": c["claim"]["agent"],
                "rank_at_least": c["claim"]["rank_at_least"],
                "rows": c["witness"]["rows"],
                "cols": c["witness"]["cols"],
                "minor": c["witness"]["minor"],
            }
            for c in group
        ],
        "seed": group[0]["produced_by"]["seed"],
    }


def _rank_message(group: list[dict]) -> str:
    """The statement of the certificate of ``O``, then the certified ranks of each ``O_i``."""
    ranks = {c["claim"]["agent"]: c["claim"]["rank_at_least"] for c in group}
    whole = [c["claim"]["statement"] for c in group if c["claim"]["agent"] == 0]
    agents = len(group[0]["data"]["neighbours"])
    blocks = ", ".join(str(ranks.get(i, 0)) for i in range(1, agents + 1))
    return "; ".join([*whole, f"block columns O_1 … O_{agents} have rank at least {blocks}"])


@register(
    "seed000.def5.2.4.certified",
    source="seed 000, Definition 5.2.4 and Lemma 5.2.2",
    statement="S-detectability is certified by rational gains and a Lyapunov tuple whose strict "
    "inequalities are verified in exact arithmetic (proofs_check)",
    kinds=("dkf",),
)
def dkf_certificate_claim(case: Case) -> list[ClaimResult]:
    """Run the s-detectability certificates of a dkf case as claim results (method ``exact``).

    Parameters
    ----------
    case : Case
        A ``dkf`` case.

    Returns
    -------
    list of ClaimResult
        One per certificate (``verified``), or one ``inconclusive`` result saying why none
        (a case that is not S-detectable has no such certificate).
    """
    return _results(
        "seed000.def5.2.4.certified",
        case,
        lambda cert: {
            "operator": cert["witness"]["operator"],
            "gains": cert["witness"]["gains"],
            "significant_bits": cert["produced_by"]["significant_bits"],
            "float_margin": cert["produced_by"]["float_margin"],
        },
    )
