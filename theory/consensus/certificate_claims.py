"""Claim ``seed000.def5.2.4.certified``: S-detectability of a dkf case certified exactly.

The certificates come from :mod:`theory.consensus.case_certificates` through
:func:`theory.certify.case_certificates`; each result carries one as a document that the report
re-checks with ``proofs_check``.
"""

from __future__ import annotations

from typing import Any

from theory.certify import certificate_results
from theory.consensus.case_certificates import decision_certificates
from theory.core.case_file import Case
from theory.core.claims import ClaimResult, register

__all__ = ["dkf_certificate_claim"]


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
    make = None if analysis is None else (lambda: decision_certificates(case, analysis.decision))
    return certificate_results(
        "seed000.def5.2.4.certified",
        case,
        lambda cert: {
            "operator": cert["witness"]["operator"],
            "gains": cert["witness"]["gains"],
            **{k: v for k, v in cert["produced_by"].items() if k != "tool"},
        },
        make,
    )
