"""The claim registry: every check the suite can run, registered once (DESIGN.md).

A :class:`Claim` has a stable id (``seed000.eq4.20``), the source it comes from, a one-line
statement and the case kinds it applies to. Running it on a case returns a :class:`ClaimResult`
in the closed verdict vocabulary :data:`STATUSES` and method vocabulary :data:`METHODS`. The CLI
and the report consume these objects; nothing prints its own verdicts outside them.

Modules register their claims at import time with :func:`register`. A module registers claims
iff its file name is ``claims.py`` or ends in ``_claims.py`` (:mod:`theory.core.discovery`);
:func:`all_claims` imports every such module first (:func:`claim_modules`), so the registry is
complete without a hand-kept list.
"""

from __future__ import annotations

import importlib
import inspect
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from theory.core.discovery import role_modules

__all__ = [
    "DOCUMENT_KEY",
    "METHODS",
    "STATUSES",
    "Claim",
    "ClaimResult",
    "NotApplicable",
    "accepts",
    "all_claims",
    "applicable_results",
    "claim_modules",
    "get_claim",
    "register",
]

STATUSES = ("verified", "refuted", "corrected", "inconclusive")
"""verified: the claim holds; refuted: it fails (with a counterexample in the evidence);
corrected: the paper's wording fails but the corrected statement in the evidence holds;
inconclusive: a margin lies inside tolerance or a solver failed (the evidence says which)."""

METHODS = ("symbolic", "exact-random", "numeric", "lmi", "simulation", "exact", "none")
"""How a result was reached; ``none`` marks a check that failed to run (the report's record of
the failure, always ``inconclusive``)."""

DOCUMENT_KEY = "certificate_document"
"""Evidence key of a certificate a result carries as a JSON object; the report writes it as a file
and re-checks it with ``proofs_check`` (:mod:`theory.report.artifacts`)."""

_REGISTRY: dict[str, Claim] = {}


class NotApplicable(Exception):  # noqa: N818 (a verdict, not a failure)
    """Raised by a check whose claim says nothing about the case, with the reason as message.

    For example a lemma whose hypothesis the case does not meet, or a certificate of a property
    another claim has decided false. The report lists the pair under ``not_applicable`` with the
    reason; :func:`applicable_results` reads it as "no result". A check that merely returns an
    empty list says the same without a reason (the claim's kind fits, its subject is absent).
    """


@dataclass(frozen=True)
class ClaimResult:
    """The outcome of running one claim on one case.

    Attributes
    ----------
    claim : str
        Claim id.
    case : str
        Case name (or ``"-"`` for a claim about the model alone).
    method : str
        One of :data:`METHODS`.
    status : str
        One of :data:`STATUSES`.
    evidence : dict
        JSON-serialisable numbers, factorizations, counterexamples, file paths.
    margin : float or None
        Distance of the deciding quantity from its threshold, in the unit the evidence states.
    tolerance : dict
        Named tolerances used (e.g. ``{"rank_tol": 1e-9}``).
    message : str
        One human sentence.
    figures : tuple of str
        Paths of figures produced.
    """

    claim: str
    case: str
    method: str
    status: str
    evidence: dict[str, Any] = field(default_factory=dict)
    margin: float | None = None
    tolerance: dict[str, float] = field(default_factory=dict)
    message: str = ""
    figures: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise ValueError(f"status {self.status!r} is not one of {STATUSES}")
        if self.method not in METHODS:
            raise ValueError(f"method {self.method!r} is not one of {METHODS}")

    def to_json(self, source: str = "") -> dict[str, Any]:
        """The DESIGN.md report record ``{"id","source","case","method","status","evidence"}``."""
        return {
            "id": self.claim,
            "source": source,
            "case": self.case,
            "method": self.method,
            "status": self.status,
            "margin": self.margin,
            "tolerance": dict(self.tolerance),
            "message": self.message,
            "evidence": self.evidence,
            "figures": list(self.figures),
        }


@dataclass(frozen=True)
class Claim:
    """A registered check.

    Attributes
    ----------
    id : str
        Stable id, e.g. ``seed000.eq4.20``.
    source : str
        Where it comes from, e.g. ``seed 000 eq. (4.20)``.
    statement : str
        The claim in one line (the paper's wording, or ours for a correction).
    kinds : tuple of str
        Case kinds it applies to; empty for claims about the model alone (run once, case ``-``).
    run : callable
        ``run(case) -> list[ClaimResult]`` (``case`` is ``None`` for model claims).
    """

    id: str
    source: str
    statement: str
    kinds: tuple[str, ...]
    run: Callable[[Any], list[ClaimResult]]


def register(
    claim_id: str, *, source: str, statement: str, kinds: tuple[str, ...] = ()
) -> Callable[[Callable[[Any], list[ClaimResult]]], Callable[[Any], list[ClaimResult]]]:
    """Decorator registering ``run`` as the check for ``claim_id`` (ids must be unique).

    Parameters
    ----------
    claim_id : str
        Stable id, e.g. ``seed000.eq4.20``.
    source : str
        Where the claim comes from, e.g. ``seed 000 eq. (4.20)``.
    statement : str
        The claim in one line.
    kinds : tuple of str
        Case kinds it applies to; empty for claims about the model alone.

    Returns
    -------
    callable
        The decorator; it stores a :class:`Claim` with these fields and returns ``run``
        unchanged.

    Raises
    ------
    ValueError
        From the decorator, if ``claim_id`` is already registered.
    """

    def decorate(run: Callable[[Any], list[ClaimResult]]) -> Callable[[Any], list[ClaimResult]]:
        if claim_id in _REGISTRY:
            raise ValueError(f"claim id {claim_id!r} registered twice")
        _REGISTRY[claim_id] = Claim(claim_id, source, statement, tuple(kinds), run)
        return run

    return decorate


def accepts(run: Callable[..., Any], keyword: str) -> bool:
    """Whether a claim's ``run`` takes the keyword argument ``keyword`` (``seed``, ``cache``…).

    Parameters
    ----------
    run : callable
        The check.
    keyword : str
        The keyword.

    Returns
    -------
    bool
        ``False`` also when the signature cannot be read; a ``**kwargs`` does not count.
    """
    try:
        parameters = inspect.signature(run).parameters
    except (TypeError, ValueError):
        return False
    return keyword in parameters


def applicable_results(claim: Claim, case: Any, *, cache: Any = None) -> list[ClaimResult]:
    """``claim.run(case)``, with :class:`NotApplicable` read as no result.

    Parameters
    ----------
    claim : Claim
        A registered claim.
    case : Case or None
        The case (``None`` for a claim about the model alone).
    cache : RunCache, optional
        The case's :class:`~theory.core.run_cache.RunCache`, passed to a check that accepts
        ``cache`` (so that checks of one case share their work).

    Returns
    -------
    list of ClaimResult
    """
    options = {"cache": cache} if cache is not None and accepts(claim.run, "cache") else {}
    try:
        return claim.run(case, **options)
    except NotApplicable:
        return []


def claim_modules() -> tuple[str, ...]:
    """The modules that register claims: every ``claims.py`` / ``*_claims.py`` of the domain
    packages (:func:`theory.core.discovery.role_modules`).

    Returns
    -------
    tuple of str
        Dotted module names.
    """
    return tuple(role_modules("claims"))


def all_claims() -> list[Claim]:
    """Every registered claim, sorted by id (imports :func:`claim_modules` first)."""
    for module in claim_modules():
        importlib.import_module(module)
    return sorted(_REGISTRY.values(), key=lambda c: c.id)


def get_claim(claim_id: str) -> Claim:
    """The claim registered as ``claim_id``; ``KeyError`` listing the known ids otherwise."""
    claims = {c.id: c for c in all_claims()}
    if claim_id not in claims:
        raise KeyError(f"unknown claim {claim_id!r}; known: {sorted(claims)}")
    return claims[claim_id]
