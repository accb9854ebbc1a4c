"""Every certificate a case supports, from the domain of its kind (DESIGN.md, *Certificates*).

A domain offers the certificates of its case kind from a module named ``certificates.py`` or
``*_certificates.py`` (:mod:`theory.core.discovery`), by decorating a builder
``(case, seed) -> (certificates, reasons)`` with :func:`register_certifier`; ``reasons`` says why
a certificate the kind could have is missing. Today:

* ``tdoa``: ``generic-rank`` of the network observability matrix and of each agent's block
  column (:mod:`theory.tdoa.case_certificates`);
* ``dkf``: ``s-detectability`` with the gains of the LMI witness and, when the case fixes gains,
  with those gains (:mod:`theory.consensus.case_certificates`);
* ``pursuit``: ``iss`` (:mod:`theory.pursuit.certificates`).

A case whose property is decided false raises :class:`~theory.core.errors.PropertyFails`:
``trackcert certify`` exits 1 and the certificate claims do not apply to it
(:class:`~theory.core.claims.NotApplicable`). :func:`certificate_bundle` is what
``trackcert certify`` prints or writes: the bundle, already accepted by ``proofs_check``.
"""

from __future__ import annotations

import importlib
import json
from collections.abc import Callable
from typing import Any

from theory.core.case_file import Case
from theory.core.claims import DOCUMENT_KEY, ClaimResult, NotApplicable
from theory.core.discovery import role_modules
from theory.core.errors import InconclusiveError, PropertyFails, SolverError

__all__ = [
    "Certified",
    "case_certificates",
    "certificate_bundle",
    "certificate_results",
    "certificates_or_inconclusive",
    "certified_result",
    "certifiers",
    "register_certifier",
]

Certified = tuple[list[dict[str, Any]], list[str]]
"""What a certifier returns: the certificates, and why any the kind could have is missing."""

Certifier = Callable[[Case, int], Certified]

_CERTIFIERS: dict[str, list[Certifier]] = {}


def register_certifier(kind: str) -> Callable[[Certifier], Certifier]:
    """Decorator registering a builder of the certificates of ``kind`` cases.

    Parameters
    ----------
    kind : str
        The case kind, e.g. ``tdoa``; a kind may have several certifiers (run in turn).

    Returns
    -------
    callable
        The decorator; it returns the builder unchanged.
    """

    def decorate(build: Certifier) -> Certifier:
        _CERTIFIERS.setdefault(kind, []).append(build)
        return build

    return decorate


def certifiers() -> dict[str, tuple[Certifier, ...]]:
    """Case kind → its certifiers (imports every certificate module first), sorted by kind.

    Returns
    -------
    dict
    """
    for module in role_modules("certificates"):
        importlib.import_module(module)
    return dict(sorted((kind, tuple(builds)) for kind, builds in _CERTIFIERS.items()))


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
    known = certifiers()
    if case.kind not in known:
        raise InconclusiveError(
            f"no certificate kinds for case kind {case.kind!r} yet (supported: {sorted(known)})"
        )
    certs: list[dict[str, Any]] = []
    reasons: list[str] = []
    for build in known[case.kind]:
        found, why = build(case, seed)
        certs += found
        reasons += why
    return _nonempty(case, certs, reasons)


def _nonempty(case: Case, certs: list[dict], reasons: list[str]) -> list[dict]:
    if not certs:
        raise InconclusiveError(f"no certificate for {case.name}: " + "; ".join(reasons))
    return certs


def certificate_bundle(case: Case, *, seed: int = 0) -> dict[str, Any]:
    """The bundle of every certificate of ``case``, re-checked by ``proofs_check`` as written.

    Parameters
    ----------
    case : Case
        A loaded case.
    seed : int
        Seed of any random evaluation point.

    Returns
    -------
    dict
        A ``"kind": "bundle"`` certificate document.

    Raises
    ------
    InconclusiveError, PropertyFails
        As :func:`case_certificates`.
    SolverError
        If the document, serialised and parsed back, does not pass ``proofs_check`` (a bug).
    """
    import proofs_check
    import proofs_check.parse
    from theory.core.certificate_format import bundle

    document = bundle(case_certificates(case, seed=seed), case=case.name)
    text = json.dumps(document, indent=1, ensure_ascii=False)
    if not proofs_check.check_certificate(proofs_check.parse.loads(text)).valid:
        raise SolverError("the written certificate did not pass proofs_check (a bug)")
    return document


def certificates_or_inconclusive(
    claim_id: str, case: Case, make: Callable[[], Certified] | None = None
) -> list[dict] | ClaimResult:
    """The case's certificates, or the ``inconclusive`` result of ``claim_id`` saying why none.

    Parameters
    ----------
    claim_id : str
        The certificate claim asking.
    case : Case
        A loaded case.
    make : callable, optional
        Builds ``(certificates, reasons)`` from results the caller already computed (for
        example the case's S-detectability decision); by default every certifier of the kind
        runs (:func:`case_certificates`).

    Returns
    -------
    list of dict or ClaimResult

    Raises
    ------
    NotApplicable
        If the property to certify is decided false (there is nothing to certify).
    """
    try:
        return _nonempty(case, *make()) if make is not None else case_certificates(case)
    except InconclusiveError as error:
        return ClaimResult(claim_id, case.name, "exact", "inconclusive", message=str(error))
    except PropertyFails as error:
        raise NotApplicable(str(error)) from error


def certificate_results(
    claim_id: str,
    case: Case,
    evidence: Callable[[dict], dict],
    make: Callable[[], Certified] | None = None,
) -> list[ClaimResult]:
    """One ``verified`` result of ``claim_id`` per certificate, carrying it as a document.

    Parameters
    ----------
    claim_id : str
        The certificate claim.
    case : Case
        A loaded case.
    evidence : callable
        ``evidence(certificate)`` → the evidence shown beside the document.
    make : callable, optional
        As in :func:`certificates_or_inconclusive`.

    Returns
    -------
    list of ClaimResult
        Or the one ``inconclusive`` result of :func:`certificates_or_inconclusive`.
    """
    certs = certificates_or_inconclusive(claim_id, case, make)
    if isinstance(certs, ClaimResult):
        return [certs]
    return [
        certified_result(
            claim_id, case, evidence(cert), document=cert, message=cert["claim"]["statement"]
        )
        for cert in certs
    ]


def certified_result(
    claim_id: str, case: Case, evidence: dict[str, Any], *, document: dict, message: str
) -> ClaimResult:
    """The ``verified`` result of a certificate claim, carrying ``document`` for the report.

    Parameters
    ----------
    claim_id : str
        The certificate claim.
    case : Case
        The case certified.
    evidence : dict
        Shown beside the document.
    document : dict
        The certificate (or bundle) the report writes and re-checks with ``proofs_check``.
    message : str
        What it certifies, in one sentence.

    Returns
    -------
    ClaimResult
        Method ``exact``: the document was accepted by ``proofs_check`` when it was built.
    """
    return ClaimResult(
        claim_id,
        case.name,
        "exact",
        "verified",
        evidence={**evidence, DOCUMENT_KEY: document},
        message=message,
    )
