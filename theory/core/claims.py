"""The claim protocol: a check is ``check(case, ctx) -> list[ClaimResult]``, registered once.

A :class:`Claim` has a stable id (``seed000.eq4.20``), its source, a one-line statement and the
case kinds it applies to. Each module of a domain collects its claims in a :class:`ClaimSet`
(``claims = ClaimSet()``, ``@claims.register(...)``); the domain's ``registry.py`` lists those sets
and :mod:`theory.registry` lists the domains. :meth:`Claim.run` stamps the claim id and the case
name on every result, so a check never types its own id.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterator
from dataclasses import dataclass, field, replace
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from hypothesis.strategies import SearchStrategy

    from theory.core.case_file import Case
    from theory.core.parallel import TaskRunner

__all__ = [
    "DOCUMENT_KEY",
    "MODEL_CASE",
    "Claim",
    "ClaimResult",
    "ClaimSet",
    "Context",
    "Finding",
    "FixedInstance",
    "Method",
    "NotApplicable",
    "Property",
    "RunCache",
    "Status",
    "Wording",
    "finding_of",
    "status_of",
]

T = TypeVar("T")


class Status(StrEnum):
    """The verdict vocabulary of a result (its value is what report.json records)."""

    VERIFIED = "verified"  # the claim holds
    REFUTED = "refuted"  # it fails, with a counterexample in the evidence
    CORRECTED = "corrected"  # the paper's wording fails, the corrected statement holds
    INCONCLUSIVE = "inconclusive"  # a margin lies inside tolerance or a solver failed


class Finding(StrEnum):
    """What a result that is not ``verified`` found (report.json's ``finding``; issue 27 part 3).

    ``status`` keeps its four values; the finding tells a reader which of three different things
    a ``refuted`` or ``corrected`` result says.
    """

    COUNTEREXAMPLE = "counterexample"  # the paper's statement is false: hypotheses met, claim fails
    HYPOTHESES_UNMET = "hypotheses-unmet"  # the system fails the hypotheses: the theorem is silent
    PROPERTY_FAILS = "property-fails"  # this system fails the property (evidence says how)


class Wording(StrEnum):
    """Which statement of a claim a property tests: the paper's, or our corrected one."""

    PAPER = "paper"
    CORRECTED = "corrected"


class Method(StrEnum):
    """How a result was reached; ``none`` marks a check that failed to run."""

    SYMBOLIC = "symbolic"
    EXACT_RANDOM = "exact-random"
    NUMERIC = "numeric"
    LMI = "lmi"
    SIMULATION = "simulation"
    EXACT = "exact"
    NONE = "none"


DOCUMENT_KEY = "certificate_document"
"""Evidence key of a certificate carried as a JSON object; the report writes and re-checks it."""

MODEL_CASE = "-"
"""The case name of a claim about the model alone (run once, with ``case=None``)."""

_STATUS_OF = {True: Status.VERIFIED, False: Status.REFUTED, None: Status.INCONCLUSIVE}


def status_of(verdict: bool | None) -> Status:
    """The status of a three-valued verdict: True verified, False refuted, None inconclusive."""
    return _STATUS_OF[verdict]


def finding_of(status: Status, *, about_model: bool) -> Finding | None:
    """The finding a result gets when its check states none: ``corrected`` (the paper's wording
    fails) and ``refuted`` about the model alone are counterexamples to the paper's statement; a
    ``refuted`` result on a case says that this system fails the property; ``verified`` and
    ``inconclusive`` find nothing (``None``)."""
    if status == Status.CORRECTED or (status == Status.REFUTED and about_model):
        return Finding.COUNTEREXAMPLE
    return Finding.PROPERTY_FAILS if status == Status.REFUTED else None


class NotApplicable(Exception):  # noqa: N818 (a verdict, not a failure)
    """Raised by a check whose claim says nothing about the case; the message says why."""


@dataclass(frozen=True)
class ClaimResult:
    """The outcome of one claim on one case (``claim``, ``case`` stamped by :meth:`Claim.run`).

    ``margin`` is the distance of the deciding quantity from its threshold (in the unit the
    evidence states), ``tolerance`` the named tolerances used. ``finding`` says what a result
    that is not verified found (:class:`Finding`); a check that leaves it ``None`` gets
    :func:`finding_of` its status from :meth:`Claim.run`. A ``verified`` result finds nothing.
    """

    status: Status
    method: Method
    evidence: dict[str, Any] = field(default_factory=dict)
    margin: float | None = None
    tolerance: dict[str, float] = field(default_factory=dict)
    message: str = ""
    figures: tuple[str, ...] = ()
    claim: str = ""
    case: str = ""
    finding: Finding | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", Status(self.status))
        object.__setattr__(self, "method", Method(self.method))
        if self.finding is not None:
            object.__setattr__(self, "finding", Finding(self.finding))
            if self.status == Status.VERIFIED:
                raise ValueError(f"a verified result finds nothing; got finding {self.finding!r}")

    def to_json(self, source: str = "") -> dict[str, Any]:
        """The report record ``{"id","source","case","method","status","evidence",…}``."""
        return {
            "id": self.claim,
            "source": source,
            "case": self.case,
            "method": str(self.method),
            "status": str(self.status),
            "finding": None if self.finding is None else str(self.finding),
            "margin": self.margin,
            "tolerance": dict(self.tolerance),
            "message": self.message,
            "evidence": self.evidence,
            "figures": list(self.figures),
        }


class RunCache:
    """Values computed once per case and run, by plain-value key (never object identity).

    ``runner`` is an open engine a computation made of independent runs may spread them on
    (``None``: serially).
    """

    def __init__(self, runner: TaskRunner | None = None) -> None:
        self.runner = runner
        self._values: dict[Hashable, Any] = {}
        self.hits = 0
        self.misses = 0

    def get(self, key: Hashable, compute: Callable[[], T]) -> T:
        """The value stored under ``key``, computed by ``compute()`` the first time."""
        if key in self._values:
            self.hits += 1
            return self._values[key]
        self.misses += 1
        value = compute()
        self._values[key] = value
        return value

    def put(self, key: Hashable, value: Any) -> None:
        """Store a value computed elsewhere (a command's own analysis, shared with its claims)."""
        self._values[key] = value


@dataclass
class Context:
    """What a check receives besides its case: the case's shared cache, a seed, a figure folder.

    ``seed`` is derived per claim and case by the report; ``figure_dir`` is where a drawing check
    may put figures (``None``: do not draw).
    """

    cache: RunCache = field(default_factory=RunCache)
    seed: int = 0
    figure_dir: Path | None = None

    def shared(self, key: Hashable, compute: Callable[[], T]) -> T:
        """``compute()`` once per key for all the checks of one case (:meth:`RunCache.get`)."""
        return self.cache.get(key, compute)

    def figure_folder(self) -> Path | None:
        """:attr:`figure_dir`, created, or ``None`` when figures are off."""
        if self.figure_dir is not None:
            self.figure_dir.mkdir(parents=True, exist_ok=True)
        return self.figure_dir


Check = Callable[["Case | None", Context], list[ClaimResult]]


@dataclass(frozen=True)
class Claim:
    """A registered check.

    ``kinds`` are the case kinds it applies to (empty: a claim about the model alone, run once
    with ``case=None``). ``shares_work``: its check reads work other checks of the case compute
    (:meth:`Context.shared`), so the report runs it in one task with them. ``seeded``: its check
    draws random numbers from :attr:`Context.seed`, which the report records.
    """

    id: str
    source: str
    statement: str
    kinds: tuple[str, ...]
    check: Check
    shares_work: bool = False
    seeded: bool = False

    def run(self, case: Case | None, ctx: Context | None = None) -> list[ClaimResult]:
        """The check's results on ``case``, stamped with this id and the case name; raises
        :class:`NotApplicable` when the claim says nothing about the case, ``TypeError`` when
        the check returns anything but a list of :class:`ClaimResult`."""
        results = self.check(case, Context() if ctx is None else ctx)
        if not isinstance(results, list | tuple):
            returned = type(results).__name__
            raise TypeError(f"{self.id}: the check returned a {returned}, not a list of results")
        for result in results:
            if not isinstance(result, ClaimResult):
                returned = type(result).__name__
                raise TypeError(f"{self.id}: the check returned a {returned}, not a ClaimResult")
        name = MODEL_CASE if case is None else case.name
        return [
            replace(
                r,
                claim=self.id,
                case=name,
                finding=r.finding or finding_of(r.status, about_model=case is None),
            )
            for r in results
        ]

    def results(self, case: Case | None, ctx: Context | None = None) -> list[ClaimResult]:
        """:meth:`run`, with :class:`NotApplicable` read as no result."""
        try:
            return self.run(case, ctx)
        except NotApplicable:
            return []


class ClaimSet:
    """The claims of one module, in the order registered; ids unique within the set."""

    def __init__(self) -> None:
        self._claims: list[Claim] = []

    def register(
        self,
        claim_id: str,
        *,
        source: str,
        statement: str,
        kinds: tuple[str, ...] = (),
        shares_work: bool = False,
        seeded: bool = False,
    ) -> Callable[[Check], Check]:
        """Decorator adding ``check`` as the claim ``claim_id`` (the function is returned as is)."""

        def decorate(check: Check) -> Check:
            if any(c.id == claim_id for c in self._claims):
                raise ValueError(f"claim id {claim_id!r} registered twice")
            claim = Claim(claim_id, source, statement, tuple(kinds), check, shares_work, seeded)
            self._claims.append(claim)
            return check

        return decorate

    def add(self, claim: Claim) -> Claim:
        """Add a claim built elsewhere (e.g. an expectations claim)."""
        if any(c.id == claim.id for c in self._claims):
            raise ValueError(f"claim id {claim.id!r} registered twice")
        self._claims.append(claim)
        return claim

    def __iter__(self) -> Iterator[Claim]:
        return iter(self._claims)

    def __len__(self) -> int:
        return len(self._claims)


@dataclass(frozen=True)
class FixedInstance:
    """A registered claim about one fixed instance (a printed example, a figure's experiment, one
    case's certificate), which no counterexample search can falsify: ``reason`` says which
    instance, and where the claim it instantiates is searched (``trackcert falsify --list``)."""

    claim: str
    reason: str


@dataclass(frozen=True)
class Property:
    """One wording of a claim for a counterexample search (``trackcert falsify``).

    ``id`` is ``<claim id>/<wording>``; ``wording`` is ``paper`` or ``corrected``; ``examples``
    is where to search; ``holds(example)`` must be true on each (vacuously on an example outside
    the statement's hypotheses); ``to_case(example)`` is a case file (plain data) reproducing the
    example, or for a claim about the model alone a record of its data without a ``kind``.
    ``expected_to_hold`` is False for a paper wording known to be wrong: the default budget must
    find its counterexample.
    """

    id: str
    claim: str
    wording: Wording
    statement: str
    examples: SearchStrategy[Any]
    holds: Callable[[Any], bool]
    to_case: Callable[[Any], dict[str, Any]]
    expected_to_hold: bool = True

    def __post_init__(self) -> None:
        if self.wording not in set(Wording):
            raise ValueError(f"wording {self.wording!r} is not 'paper' or 'corrected'")
        object.__setattr__(self, "wording", Wording(self.wording))
