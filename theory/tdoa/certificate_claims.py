"""Claim ``seed000.eq4.36.certified``: generic ranks of a TDOA case certified exactly.

The certificates come from :mod:`theory.tdoa.case_certificates` through
:func:`theory.certify.case_certificates`; each result carries its bundle as a document that the
report re-checks with ``proofs_check``.
"""

from __future__ import annotations

from typing import Any

from theory.certify import certificates_or_inconclusive, certified_result
from theory.core.case_file import Case
from theory.core.certificate_format import bundle
from theory.core.claims import ClaimResult, register

__all__ = ["generic_rank_claim"]


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
    certs = certificates_or_inconclusive(claim_id, case)
    if isinstance(certs, ClaimResult):
        return [certs]
    networks: dict[tuple[int, ...], list[dict]] = {}
    for cert in certs:
        networks.setdefault(tuple(cert["produced_by"].get("steps", [1])), []).append(cert)
    return [
        certified_result(
            claim_id,
            case,
            _rank_evidence(steps, group),
            document=bundle(group, case=case.name),
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
