"""Everything the suite can check and certify: the claims, properties and certifiers of each
domain, and every certificate a case supports.

Each domain lists its own in its ``registry`` module (``CLAIMS``, ``PROPERTIES``, ``CERTIFIERS``:
case kind → builders ``(case, seed) -> (certificates, reasons)``); this module lists the domains.
A domain's registry imports all of its analyses, so it is imported only when its claims are
needed. :func:`certificate_bundle` is what ``trackcert certify`` writes: every certificate of the
case's kind, already accepted by ``proofs_check``; a case whose property is decided false raises
:class:`~theory.core.errors.PropertyFails` (exit 1, and its certificate claims do not apply).
"""

from __future__ import annotations

import functools
import json
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from types import ModuleType
from typing import Any

from theory.core.case_file import Case
from theory.core.certificate_format import Certifier, bundle
from theory.core.claims import Claim, Property
from theory.core.errors import InconclusiveError, SolverError

__all__ = [
    "all_claims",
    "all_properties",
    "case_certificates",
    "certificate_bundle",
    "certifiers",
    "claims_for",
    "claims_replaced",
    "domains",
    "get_claim",
    "properties_for",
]


@functools.cache
def domains() -> tuple[ModuleType, ...]:
    """The registries of the domains: TDOA, consensus, pursuit, particle filter."""
    from theory.consensus import registry as consensus
    from theory.particle import registry as particle
    from theory.pursuit import registry as pursuit
    from theory.tdoa import registry as tdoa

    return (tdoa, consensus, pursuit, particle)


_replacement: list[Iterable[Claim]] = []
"""The claims :func:`claims_replaced` puts in place of the domains' (innermost last)."""


@contextmanager
def claims_replaced(claims: Iterable[Claim]) -> Iterator[None]:
    """In the block, this process's registry holds ``claims`` (read at each lookup, e.g. a
    :class:`~theory.core.claims.ClaimSet` still being filled) instead of the domains'.

    For tests of the engines: the report, its in-process tasks and ``trackcert report
    --workers 1`` see only ``claims``; workers in other processes keep the domains' claims. The
    domains' cached registry is never touched, and leaving the block restores it.
    """
    _replacement.append(claims)
    try:
        yield
    finally:
        _replacement.pop()


@functools.cache
def _domain_claims() -> dict[str, Claim]:
    return _by_id(c for domain in domains() for c in domain.CLAIMS)


def _by_id(claims: Iterable[Claim]) -> dict[str, Claim]:
    found: dict[str, Claim] = {}
    for claim in claims:
        if claim.id in found:
            raise ValueError(f"claim id {claim.id!r} registered twice")
        found[claim.id] = claim
    return dict(sorted(found.items()))


def _claims_by_id() -> dict[str, Claim]:
    return _by_id(_replacement[-1]) if _replacement else _domain_claims()


def all_claims() -> list[Claim]:
    """Every registered claim, sorted by id."""
    return list(_claims_by_id().values())


def get_claim(claim_id: str) -> Claim:
    """The claim registered as ``claim_id``; ``KeyError`` listing the known ids otherwise."""
    claims = _claims_by_id()
    if claim_id not in claims:
        raise KeyError(f"unknown claim {claim_id!r}; known: {sorted(claims)}")
    return claims[claim_id]


def claims_for(case: Case | None) -> list[Claim]:
    """The claims that apply to ``case`` (``None``: the claims about the model alone)."""
    if case is None:
        return [c for c in all_claims() if not c.kinds]
    return [c for c in all_claims() if case.kind in c.kinds]


@functools.cache
def all_properties() -> tuple[Property, ...]:
    """Every falsifiable property, sorted by id (ids unique)."""
    props = sorted((p for d in domains() for p in d.PROPERTIES), key=lambda p: p.id)
    ids = [p.id for p in props]
    if len(set(ids)) != len(ids):
        raise ValueError("a property id is registered twice")
    return tuple(props)


def properties_for(name: str) -> list[Property]:
    """Properties named ``name``: a property id, or a claim id (all its wordings); ``KeyError``
    listing the known names when it matches nothing."""
    chosen = [p for p in all_properties() if name in (p.id, p.claim)]
    if not chosen:
        known = sorted({p.claim for p in all_properties()} | {p.id for p in all_properties()})
        raise KeyError(f"no property or claim named {name!r}; known: {known}")
    return chosen


def certifiers() -> dict[str, tuple[Certifier, ...]]:
    """Case kind → the builders of its certificates, sorted by kind."""
    found: dict[str, tuple[Certifier, ...]] = {}
    for domain in domains():
        for kind, builds in domain.CERTIFIERS.items():
            found[kind] = (*found.get(kind, ()), *builds)
    return dict(sorted(found.items()))


def case_certificates(case: Case, *, seed: int = 0) -> list[dict[str, Any]]:
    """All certificates ``case`` supports, each accepted by ``proofs_check`` (``seed``: of any
    random evaluation point).

    Raises :class:`InconclusiveError` if the kind has no certificate kinds or none could be made
    (giving every reason), :class:`PropertyFails` if the property is decided false.
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
    if not certs:
        raise InconclusiveError(f"no certificate for {case.name}: " + "; ".join(reasons))
    return certs


def certificate_bundle(case: Case, *, seed: int = 0) -> dict[str, Any]:
    """The ``"kind": "bundle"`` document of every certificate of ``case``, re-checked by
    ``proofs_check`` as written (:func:`case_certificates`'s errors; :class:`SolverError` if the
    written document does not pass: a bug)."""
    import proofs_check
    import proofs_check.parse

    document = bundle(case_certificates(case, seed=seed), case=case.name)
    text = json.dumps(document, indent=1, ensure_ascii=False)
    if not proofs_check.check_certificate(proofs_check.parse.loads(text)).valid:
        raise SolverError("the written certificate did not pass proofs_check (a bug)")
    return document
