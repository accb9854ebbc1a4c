"""Every certificate a case supports, and the claims that report them (DESIGN.md, *Certificates*).

:data:`CERTIFIERS` maps a case kind to a function ``(case, seed) -> (certificates, reasons)``;
``reasons`` says why a certificate the kind could have is missing. Supported:

* ``tdoa``: ``generic-rank`` of the network observability matrix and of each agent's block
  column (:mod:`theory.tdoa.rank_certificates`);
* ``dkf``: the ``s-detectability`` certificate the exact decision rests on
  (:func:`theory.consensus.s_detectability.decide_s_detectability`: a rounded LMI witness or an
  exact Lyapunov tuple) and, when the case fixes gains, one for those gains.
* ``pursuit``: ``iss`` (:mod:`theory.pursuit.certificates`), when the case's conditions hold.

A case whose property is decided false (not S-detectable, a condition of the ISS analysis
failing) raises :class:`~theory.core.errors.PropertyFails`: ``trackcert certify`` exits 1 and the
claims here do not apply to it (:class:`~theory.core.claims.NotApplicable`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from theory.consensus.certificates import s_detectability_certificate
from theory.consensus.exact_linalg import rational_matrix
from theory.consensus.primal_certificates import exact_gain_certificate, primal_lyapunov
from theory.consensus.s_detectability import SDetectability, decide_s_detectability
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
    "dkf_certificates",
    "generic_rank_claim",
]

Certified = tuple[list[dict[str, Any]], list[str]]


def _tdoa(case: Case, seed: int) -> Certified:
    try:
        return generic_rank_certificates(case.spec, seed=seed, case=case.name), []
    except RationalizationError as error:
        return [], [str(error)]


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


def dkf_certificates(case: Case, decision: SDetectability) -> Certified:
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


def _dkf(case: Case, seed: int) -> Certified:
    del seed
    spec = case.spec
    candidates = [("the case's gains", spec.L)] if spec.L is not None else []
    decision = decide_s_detectability(
        spec.A, spec.C, spec.W, order=spec.order, candidate_gains=candidates, case=case.name
    )
    return dkf_certificates(case, decision)


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
    return _nonempty(case, *CERTIFIERS[case.kind](case, seed))


def _nonempty(case: Case, certs: list[dict], reasons: list[str]) -> list[dict]:
    if not certs:
        raise InconclusiveError(f"no certificate for {case.name}: " + "; ".join(reasons))
    return certs


def _certified(
    claim_id: str, case: Case, make: Callable[[], Certified] | None = None
) -> list[dict] | ClaimResult:
    """The case's certificates (from ``make`` when given), or the ``inconclusive`` result
    saying why there are none."""
    try:
        return _nonempty(case, *make()) if make is not None else case_certificates(case)
    except InconclusiveError as error:
        return ClaimResult(claim_id, case.name, "exact", "inconclusive", message=str(error))
    except PropertyFails as error:
        raise NotApplicable(str(error)) from error


def _results(
    claim_id: str,
    case: Case,
    evidence: Callable[[dict], dict],
    make: Callable[[], Certified] | None = None,
) -> list[ClaimResult]:
    certs = _certified(claim_id, case, make)
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
def dkf_certificate_claim(case: Case, analysis: Any = None) -> list[ClaimResult]:
    """Run the s-detectability certificates of a dkf case as claim results (method ``exact``).

    Parameters
    ----------
    case : Case
        A ``dkf`` case.
    analysis : DkfAnalysis, optional
        :func:`theory.consensus.claims.analyze_dkf` of the case, whose decision is reused.

    Returns
    -------
    list of ClaimResult
        One per certificate (``verified``), or one ``inconclusive`` result saying why none
        (a case that is not S-detectable has no such certificate).
    """
    make = None if analysis is None else (lambda: dkf_certificates(case, analysis.decision))
    return _results(
        "seed000.def5.2.4.certified",
        case,
        lambda cert: {
            "operator": cert["witness"]["operator"],
            "gains": cert["witness"]["gains"],
            **{k: v for k, v in cert["produced_by"].items() if k != "tool"},
        },
        make,
    )
