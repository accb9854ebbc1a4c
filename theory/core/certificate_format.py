"""The certificate envelope shared by every builder (docs/certificates.md, *Format*).

A certificate is ``{"format", "kind", "source", "case"?, "claim", "data", "witness",
"produced_by"?}`` with every number an exact rational string (``docs/certificates.md``); a bundle
is ``{"format", "kind": "bundle", "case"?, "certificates"}``. The builders of each domain
(:mod:`theory.consensus.certificates`, :mod:`theory.consensus.infeasibility`,
:mod:`theory.tdoa.estimation.stability`, …) compute claim, data and witness; this module
wraps them, and :func:`rounded` turns a floating witness into the first dyadic rounding that the
independent checker :mod:`proofs_check` accepts — never into anything weaker.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

import proofs_check
from theory.core.claims import DOCUMENT_KEY, ClaimResult, Method, NotApplicable, Status
from theory.core.errors import InconclusiveError, PropertyFails
from theory.core.exact import (
    PRECISIONS,
    RationalizationError,
    dyadic_matrix,
    first_success,
    fraction_strings,
)

__all__ = [
    "FORMAT",
    "Certified",
    "Certifier",
    "bundle",
    "certificate_results",
    "certified_result",
    "checked",
    "envelope",
    "rational_bound",
    "rounded",
    "strings",
]

FORMAT = proofs_check.FORMAT
"""The format version every certificate carries."""

if TYPE_CHECKING:
    from theory.core.case_file import Case

Matrix = list[list[Fraction]]

Certified = tuple[list[dict[str, Any]], list[str]]
"""What a certifier returns: the certificates, and why any the kind could have is missing."""

Certifier = Callable[["Case", int], Certified]
"""``build(case, seed)`` → the certificates of a case (each accepted by ``proofs_check``)."""


def envelope(
    kind: str,
    claim: dict[str, Any],
    data: dict[str, Any],
    witness: dict[str, Any],
    *,
    source: str = "",
    case: str | None = None,
) -> dict[str, Any]:
    """One certificate of ``kind`` (:data:`proofs_check.kinds.KINDS`): where its claim comes
    from (``seed 000, Lemma 5.2.2``), the claim, data and witness (in exact strings)."""
    cert: dict[str, Any] = {"format": FORMAT, "kind": kind, "source": source, "claim": claim}
    cert |= {"data": data, "witness": witness}
    if case is not None:
        cert["case"] = case
    return cert


def bundle(certificates: Sequence[dict], *, case: str | None = None) -> dict:
    """Several certificates in one file (``"kind": "bundle"``), valid iff each one is."""
    out: dict[str, Any] = {"format": FORMAT, "kind": "bundle"}
    if case is not None:
        out["case"] = case
    out["certificates"] = list(certificates)
    return out


def checked(cert: dict[str, Any]) -> str | None:
    """Run :mod:`proofs_check` on ``cert``: None if it is valid, else why not.

    A certificate the checker refuses as too costly (work estimate, time budget) is reported like
    an invalid one, so a builder moves on instead of failing.
    """
    try:
        verdict = proofs_check.check_certificate(cert)
    except proofs_check.MalformedError as error:
        return f"proofs_check refuses it: {error}"
    if verdict.valid:
        return None
    failed = next((c for c in verdict.checks if not c.valid), None)
    return f"{failed.name}: {failed.detail}" if failed else "no checks"


def strings(mats: Sequence[Matrix]) -> list:
    """The exact matrices ``mats`` as nested lists of rational strings."""
    return [fraction_strings(m) for m in mats]


def rational_bound(value: float | Fraction) -> Fraction:
    """The bound ``value`` (``ρ``, a rate) as a rational with denominator at most 10⁶."""
    return Fraction(value).limit_denominator(10**6)


def rounded(
    build: Callable[[dict[str, list[Matrix]]], dict],
    matrices: dict[str, list[np.ndarray]],
    *,
    margin: float,
    lmi_margin: float,
    precisions: Sequence[int] = PRECISIONS,
    what: str,
) -> dict:
    """The first certificate ``build({name: [exact matrices]})`` that :mod:`proofs_check`
    accepts, rounding the float witness ``matrices`` to each of ``precisions`` significant bits,
    with ``produced_by`` (tool, bits, float margin, ``lmi_margin``).

    Raises :class:`RationalizationError` (naming ``what``) if ``margin`` does not exceed
    ``lmi_margin`` or no rounding passes the exact check.
    """
    if not margin > lmi_margin:
        raise RationalizationError(
            f"{what}: the float witness's relative margin {margin:.3g} does not exceed "
            f"lmi_margin = {lmi_margin:g}; it is not strictly feasible, so no certificate"
        )

    failures: list[str] = []

    def attempt(bits: int) -> dict | None:
        exact = {name: [dyadic_matrix(m, bits) for m in mats] for name, mats in matrices.items()}
        cert = build(exact)
        why = checked(cert)
        failures.append(f"{bits} bits: {why}")
        return cert if why is None else None

    try:
        cert, bits = first_success(attempt, precisions=precisions, what=what)
    except RationalizationError as error:
        raise RationalizationError(f"{error} (last attempt, {failures[-1]})") from None
    cert["produced_by"] = {
        "tool": "trackcert",
        "significant_bits": bits,
        "float_margin": f"{margin:.6g}",
        "lmi_margin": f"{lmi_margin:g}",
    }
    return cert


def certificate_results(
    case: Case, make: Callable[[], Certified], evidence: Callable[[dict], dict]
) -> list[ClaimResult]:
    """One ``verified`` result per certificate ``make()`` builds for ``case``, as a document.

    ``evidence(certificate)`` is shown beside the document. No certificate at all gives one
    ``inconclusive`` result listing the reasons; a property decided false raises
    :class:`NotApplicable` (there is nothing to certify).
    """
    try:
        certs, reasons = make()
    except InconclusiveError as error:
        return [ClaimResult(Status.INCONCLUSIVE, Method.EXACT, message=str(error))]
    except PropertyFails as error:
        raise NotApplicable(str(error)) from error
    if not certs:
        why = f"no certificate for {case.name}: " + "; ".join(reasons)
        return [ClaimResult(Status.INCONCLUSIVE, Method.EXACT, message=why)]
    return [
        certified_result(evidence(cert), document=cert, message=cert["claim"]["statement"])
        for cert in certs
    ]


def certified_result(evidence: dict[str, Any], *, document: dict, message: str) -> ClaimResult:
    """The ``verified`` result of a certificate claim, carrying ``document`` for the report
    (method ``exact``: the document was accepted by ``proofs_check`` when it was built)."""
    return ClaimResult(
        Status.VERIFIED, Method.EXACT, {**evidence, DOCUMENT_KEY: document}, message=message
    )
