"""The claim ``seed003.thm2.certified``: the exact ``iss`` certificate of a pursuit case.

References
----------
seed 003, Theorem 2 and Lemmas 1–4 (corrected, docs/theory/pursuit-iss.md §5, §7).
"""

from __future__ import annotations

from fractions import Fraction

from theory.core.case_file import Case
from theory.core.claims import DOCUMENT_KEY, ClaimResult, NotApplicable, register
from theory.core.errors import InconclusiveError, PropertyFails
from theory.pursuit.certificates import STATEMENT, iss_certificate

__all__ = ["iss_certificate_claim"]


@register(
    "seed003.thm2.certified",
    source="seed 003, Theorem 2 and Lemmas 1–4 (corrected, docs/theory/pursuit-iss.md §5, §7)",
    statement="the corrected ISS estimate of the pursuit and coordination errors is certified by "
    "exact inequalities E1–E5, C1–C6 re-derived by proofs_check (kind iss)",
    kinds=("pursuit",),
)
def iss_certificate_claim(case: Case) -> list[ClaimResult]:
    """Build the ``iss`` certificate of a pursuit case and report it (method ``exact``).

    Parameters
    ----------
    case : Case
        A ``pursuit`` case.

    Returns
    -------
    list of ClaimResult
        ``verified`` with the certified constants as evidence, or ``inconclusive`` naming the
        conditions inside their tolerance.

    Raises
    ------
    NotApplicable
        If a condition fails: the corrected Theorem 2 says nothing about the case (``trackcert
        iss`` and claim ``seed003.thm2`` report the failure).
    """
    claim_id = "seed003.thm2.certified"
    try:
        cert = iss_certificate(case.spec, case=case.name)
    except InconclusiveError as error:
        return [ClaimResult(claim_id, case.name, "exact", "inconclusive", message=str(error))]
    except PropertyFails as error:
        raise NotApplicable(str(error)) from error
    witness = cert["witness"]
    keys = [k for k in ("lambda", "alpha", "kappa", "g_e", "g_xi", "gain") if k in witness]
    evidence = {k: witness[k] for k in keys} | {
        f"{k}_approx": float(Fraction(witness[k])) for k in keys
    }
    evidence[DOCUMENT_KEY] = cert
    return [ClaimResult(claim_id, case.name, "exact", "verified", evidence, message=STATEMENT)]
