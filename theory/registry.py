"""Everything the suite can check: the claims, properties and certifiers of each domain.

Each domain lists its own in its ``registry`` module; this module lists the domains. A domain's
registry imports all of its analyses, so it is imported only when its claims are needed.
"""

from __future__ import annotations

import functools
from types import ModuleType

from theory.core.case_file import Case
from theory.core.certificate_format import Certifier
from theory.core.claims import Claim, Property

__all__ = [
    "all_claims",
    "all_properties",
    "certifiers",
    "claims_for",
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


@functools.cache
def _claims_by_id() -> dict[str, Claim]:
    found: dict[str, Claim] = {}
    for domain in domains():
        for claim in domain.CLAIMS:
            if claim.id in found:
                raise ValueError(f"claim id {claim.id!r} registered twice")
            found[claim.id] = claim
    return dict(sorted(found.items()))


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
    """Properties named ``name``: a property id, or a claim id (all its wordings).

    Raises
    ------
    KeyError
        Listing the known names when ``name`` matches nothing.
    """
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
