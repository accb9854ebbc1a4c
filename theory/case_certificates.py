"""Every certificate a case supports, and the claim that reports them (DESIGN.md, *Certificates*).

:data:`CERTIFIERS` maps a case kind to a function ``(case, seed) -> list of certificate dicts``.
Supported now: ``tdoa`` (``generic-rank`` of the network observability matrix and of each agent's
block column). The ``dkf`` kind's ``s-detectability`` certificate needs the LMI witness of the
consensus-filter module and is wired when that lands; ``iss`` certificates are not defined yet.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from theory.case_file import Case
from theory.claims import ClaimResult, register
from theory.errors import InconclusiveError
from theory.rationalize import RationalizationError
from theory.tdoa_rank_certificates import generic_rank_certificates

__all__ = ["CERTIFIERS", "case_certificates", "generic_rank_claim"]


def _tdoa(case: Case, seed: int) -> list[dict[str, Any]]:
    return generic_rank_certificates(case.spec, seed=seed, case=case.name)


CERTIFIERS: dict[str, Callable[[Case, int], list[dict[str, Any]]]] = {"tdoa": _tdoa}
"""Case kind → builder of its certificates."""


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
        If the case's kind has no certificate kinds yet, or a witness cannot be rationalized
        (:class:`~theory.rationalize.RationalizationError`).
    """
    if case.kind not in CERTIFIERS:
        raise InconclusiveError(
            f"no certificate kinds for case kind {case.kind!r} yet "
            f"(supported: {sorted(CERTIFIERS)})"
        )
    return CERTIFIERS[case.kind](case, seed)


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
        One per certificate (``verified``), or one ``inconclusive`` result saying why none.
    """
    try:
        certs = case_certificates(case)
    except RationalizationError as error:
        return [
            ClaimResult(
                "seed000.eq4.36.certified", case.name, "exact", "inconclusive", message=str(error)
            )
        ]
    return [
        ClaimResult(
            "seed000.eq4.36.certified",
            case.name,
            "exact",
            "verified",
            evidence={
                "agent": cert["claim"]["agent"],
                "rank_at_least": cert["claim"]["rank_at_least"],
                "rows": cert["witness"]["rows"],
                "cols": cert["witness"]["cols"],
                "minor": cert["witness"]["minor"],
                "seed": cert["produced_by"]["seed"],
            },
            message=cert["claim"]["statement"],
        )
        for cert in certs
    ]
