"""Every certificate a case supports, from the domain of its kind (DESIGN.md, *Certificates*).

A domain lists the builders of its kind's certificates, ``(case, seed) -> (certificates,
reasons)``, in its registry (``CERTIFIERS``, read by :func:`theory.registry.certifiers`);
``reasons`` says why a certificate the kind could have is missing. Today:

* ``tdoa``: ``generic-rank`` of the network observability matrix and of each agent's block
  column (:mod:`theory.tdoa.observability.certificates`);
* ``dkf``: ``s-detectability`` with the gains of the LMI witness and, when the case fixes gains,
  with those gains (:mod:`theory.consensus.analysis`);
* ``pursuit``: ``iss`` (:mod:`theory.pursuit.certificates`).

A case whose property is decided false raises :class:`~theory.core.errors.PropertyFails`:
``trackcert certify`` exits 1 and the certificate claims do not apply to it
(:class:`~theory.core.claims.NotApplicable`). :func:`certificate_bundle` is what
``trackcert certify`` prints or writes: the bundle, already accepted by ``proofs_check``.
"""

from __future__ import annotations

import json
from typing import Any

from theory.core.case_file import Case
from theory.core.errors import InconclusiveError, SolverError
from theory.registry import certifiers

__all__ = ["case_certificates", "certificate_bundle"]


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
