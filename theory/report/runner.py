"""Run every registered claim on every case, never letting one check stop the others.

:func:`run_claims` is the report's engine: for each case it runs the claims registered for the
case's kind, and it runs the model claims (``kinds=()``) once, on no case (case ``"-"``). Every
exception a check raises, and every malformed answer it returns, becomes a :class:`Record` with
status ``inconclusive``, method ``"none"`` and the error in its message and evidence, so the report
always completes. A claim whose ``run`` accepts a keyword ``seed`` receives one derived from the
report's seed, its id and the case name (:func:`derive_seed`), so reruns are identical. A claim
whose ``run`` accepts a keyword ``figure_dir`` receives, when the caller gives a figure folder,
a fresh sub-folder ``<claim>/<case>`` of it to draw its figures in (it returns their paths in
``figures``); without one it draws nothing. With a
time limit (:mod:`theory.report.time_limit`), a check still running when it expires becomes an
``inconclusive`` record saying so, and the report goes on with the next one.
"""

from __future__ import annotations

import fnmatch
import hashlib
import inspect
import re
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from theory.core.case_file import Case, kind_spec
from theory.core.claims import Claim, ClaimResult, NotApplicable, all_claims
from theory.core.errors import CaseError
from theory.core.expectations import Expectation, evaluate, observations_from
from theory.core.verdicts import expectations_verdict
from theory.report.canonical import canonical
from theory.report.time_limit import TimeLimitExceeded, time_limit

__all__ = [
    "MODEL_CASE",
    "RESULT_FIELDS",
    "Record",
    "RunResult",
    "derive_seed",
    "paper_of",
    "run_claims",
    "select_claims",
    "slug",
]

MODEL_CASE = "-"
"""Case name of results about the model alone (claims registered with ``kinds=()``)."""

ProgressHook = Callable[[str, str], None]


@dataclass(frozen=True)
class Record:
    """One line of the report: a claim's result on a case (or the failure to get one).

    Attributes
    ----------
    result : ClaimResult
        The result, its evidence, margin and tolerances made plain JSON data
        (:func:`theory.report.canonical.canonical`); a check that failed to run is an
        ``inconclusive`` result of method ``none``. Its fields read through the record:
        ``record.status`` is ``record.result.status``, ``record.id`` its ``claim``.
    source, statement : str
        The claim's source and statement.
    paper : str
        The seed paper it belongs to (``"000"`` … or ``"other"``, :func:`paper_of`).
    seed : int or None
        The derived seed (``None`` if the claim takes none).

    Figure files are copied into the report folder when it is written.
    """

    result: ClaimResult
    source: str
    statement: str
    paper: str
    seed: int | None = None

    @property
    def id(self) -> str:
        """The claim id (``result.claim``)."""
        return self.result.claim

    def __getattr__(self, name: str) -> Any:
        if name in RESULT_FIELDS:
            return getattr(self.result, name)
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def with_evidence(self, evidence: dict[str, Any]) -> Record:
        """The same record with ``evidence`` in place of the result's.

        Parameters
        ----------
        evidence : dict
            Plain JSON evidence.

        Returns
        -------
        Record
        """
        return replace(self, result=replace(self.result, evidence=evidence))

    def to_json(self) -> dict[str, Any]:
        """The result's record (:meth:`ClaimResult.to_json`) with statement, paper and seed."""
        return {
            **self.result.to_json(self.source),
            "statement": self.statement,
            "paper": self.paper,
            "seed": self.seed,
        }


RESULT_FIELDS = (
    "case",
    "method",
    "status",
    "message",
    "margin",
    "tolerance",
    "evidence",
    "figures",
)
"""Fields of :class:`~theory.core.claims.ClaimResult` read through a :class:`Record`."""


@dataclass(frozen=True)
class RunResult:
    """Everything the claims returned, ready to be rendered.

    Attributes
    ----------
    records : tuple of Record
        Sorted by paper, claim id, case order.
    expectations : tuple of Expectation
        One per key of every case's ``expect`` block.
    not_applicable : tuple of (claim id, case name, reason)
        Claims that returned no result for a case (they do not apply to it); ``reason`` is the
        message of the :class:`~theory.core.claims.NotApplicable` the check raised, or ``""`` when
        it
        returned an empty list.
    cases : tuple of Case
        The cases, in the order given.
    claims : tuple of Claim
        The claims that were run, sorted by id.
    seed : int
        The report's seed.
    time_limit : float or None
        Seconds allowed to each check (``None``: no limit).
    """

    records: tuple[Record, ...]
    expectations: tuple[Expectation, ...]
    not_applicable: tuple[tuple[str, str, str], ...]
    cases: tuple[Case, ...]
    claims: tuple[Claim, ...]
    seed: int
    time_limit: float | None = None

    @property
    def all_expectations_met(self) -> bool:
        """Whether every expectation of every case is met (the report's exit code 0)."""
        return all(e.verdict == "met" for e in self.expectations)

    @property
    def verdict(self) -> bool | None:
        """The expectations' verdict: False if one is unmet, True if all are met, else None
        (:func:`theory.core.verdicts.expectations_verdict`; the report's exit code)."""
        return expectations_verdict(self.expectations)


def paper_of(claim_id: str, source: str) -> str:
    """The seed paper a claim belongs to.

    Parameters
    ----------
    claim_id : str
        Registered id; ``seed000.…`` names paper ``000``.
    source : str
        The claim's source, used when the id names no paper (``"seed 003, eq. (4)"``).

    Returns
    -------
    str
        ``"000"``, ``"001"``, ``"002"``, ``"003"`` or ``"other"``.
    """
    match = re.match(r"seed(\d{3})\b", claim_id) or re.search(r"seed\s*(\d{3})", source)
    return match.group(1) if match else "other"


def derive_seed(seed: int, claim_id: str, case: str) -> int:
    """The seed one claim receives on one case.

    Parameters
    ----------
    seed : int
        The report's seed.
    claim_id : str
        Registered claim id.
    case : str
        Case name (``"-"`` for model claims).

    Returns
    -------
    int
        The first 4 bytes (big-endian) of SHA-256 of ``"{seed}:{claim_id}:{case}"``: stable
        across runs, platforms and the order in which claims run.
    """
    digest = hashlib.sha256(f"{seed}:{claim_id}:{case}".encode()).digest()
    return int.from_bytes(digest[:4], "big")


def select_claims(claims: Sequence[Claim], patterns: Sequence[str]) -> list[Claim]:
    """The claims whose id matches one of ``patterns``.

    Parameters
    ----------
    claims : sequence of Claim
        Candidates.
    patterns : sequence of str
        Shell-style patterns (``seed000.*``); none given selects every claim.

    Returns
    -------
    list of Claim
    """
    if not patterns:
        return list(claims)
    return [c for c in claims if any(fnmatch.fnmatchcase(c.id, p) for p in patterns)]


def run_claims(
    cases: Sequence[Case],
    *,
    seed: int = 0,
    claims: Sequence[Claim] | None = None,
    progress: ProgressHook | None = None,
    seconds: float | None = None,
    figure_dir: Path | None = None,
) -> RunResult:
    """Run each claim on each case it applies to, and the model claims once.

    Parameters
    ----------
    cases : sequence of Case
        Validated cases (their names must be distinct).
    seed : int
        The report's seed; each claim accepting ``seed`` gets :func:`derive_seed` of it.
    claims : sequence of Claim, optional
        Defaults to every registered claim (:func:`theory.core.claims.all_claims`).
    progress : callable, optional
        Called as ``progress(claim_id, case_name)`` before each run.
    seconds : float, optional
        Time limit of each check (one claim on one case); ``None``: none.
    figure_dir : Path, optional
        Folder under which claims accepting ``figure_dir`` draw (``None``: no figures).

    Returns
    -------
    RunResult
    """
    claims = sorted(all_claims() if claims is None else claims, key=lambda c: c.id)
    _check_distinct_names(cases)
    rows: list[tuple[int, Record]] = []
    skipped: list[tuple[str, str, str]] = []
    tasks = [(c, None) for c in claims if not c.kinds] + [
        (c, case) for case in cases for c in claims if case.kind in c.kinds
    ]
    order = {MODEL_CASE: -1} | {case.name: i for i, case in enumerate(cases)}
    for claim, case in tasks:
        name = MODEL_CASE if case is None else case.name
        if progress is not None:
            progress(claim.id, name)
        try:
            records = _run_one(claim, case, seed, seconds, figure_dir)
        except NotApplicable as reason:
            records = []
            skipped.append((claim.id, name, str(reason)))
        else:
            if not records:
                skipped.append((claim.id, name, ""))
        rows.extend((order[name], r) for r in records)
    rows.sort(key=lambda row: (row[1].paper, row[1].id, row[0]))
    records = tuple(r for _, r in rows)
    expectations = _expectations(cases, records)
    return RunResult(
        records, expectations, tuple(skipped), tuple(cases), tuple(claims), seed, seconds
    )


def _check_distinct_names(cases: Sequence[Case]) -> None:
    names = [case.name for case in cases]
    duplicated = sorted({n for n in names if names.count(n) > 1})
    if duplicated:
        raise CaseError("name", "distinct case names in one report", duplicated[0])


def _run_one(
    claim: Claim, case: Case | None, seed: int, seconds: float | None, figure_dir: Path | None
) -> list[Record]:
    name = MODEL_CASE if case is None else case.name
    claim_seed = derive_seed(seed, claim.id, name) if _takes(claim.run, "seed") else None
    options: dict[str, Any] = {} if claim_seed is None else {"seed": claim_seed}
    if figure_dir is not None and _takes(claim.run, "figure_dir"):
        options["figure_dir"] = figure_dir / slug(claim.id) / slug(name)
        options["figure_dir"].mkdir(parents=True, exist_ok=True)
    try:
        with time_limit(seconds):
            results = claim.run(case, **options)
        return [_record(claim, name, result, claim_seed) for result in _checked(results)]
    except NotApplicable:
        raise
    except (Exception, SystemExit, TimeLimitExceeded) as error:  # one check never stops the report
        return [_failure(claim, name, error, claim_seed)]


def _takes(run: Callable[..., Any], keyword: str) -> bool:
    try:
        parameters = inspect.signature(run).parameters
    except (TypeError, ValueError):
        return False
    return keyword in parameters


def slug(text: str) -> str:
    """``text`` as one safe path component (runs of other characters become ``_``).

    Parameters
    ----------
    text : str
        A claim id or case name.

    Returns
    -------
    str
    """
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("_") or "_"


def _checked(results: object) -> list[ClaimResult]:
    if not isinstance(results, list | tuple):
        raise TypeError(f"the check returned a {type(results).__name__}, not a list of results")
    for result in results:
        if not isinstance(result, ClaimResult):
            raise TypeError(f"the check returned a {type(result).__name__}, not a ClaimResult")
    return list(results)


def _record(claim: Claim, case: str, result: ClaimResult, seed: int | None) -> Record:
    evidence = canonical(result.evidence, "evidence")
    if not isinstance(evidence, dict):
        raise TypeError(f"evidence is a {type(result.evidence).__name__}, not a mapping")
    plain = replace(
        result,
        claim=claim.id,
        case=case,
        evidence=evidence,
        margin=canonical(result.margin, "margin"),
        tolerance=canonical(dict(result.tolerance), "tolerance"),
        figures=tuple(str(f) for f in result.figures),
    )
    return _wrap(claim, plain, seed)


def _wrap(claim: Claim, result: ClaimResult, seed: int | None) -> Record:
    paper = paper_of(claim.id, claim.source)
    return Record(result, claim.source, claim.statement, paper, seed)


def _failure(claim: Claim, case: str, error: BaseException, seed: int | None) -> Record:
    kind = type(error).__name__
    message = (
        str(error)
        if isinstance(error, TimeLimitExceeded)
        else f"the check failed to run: {kind}: {error}"
    )
    evidence = {"error": {"type": kind, "message": str(error), "where": _where(error)}}
    result = ClaimResult(claim.id, case, "none", "inconclusive", evidence, message=message)
    return _wrap(claim, result, seed)


def _where(error: BaseException) -> str:
    """``file:line in function`` of the innermost frame, the file relative to the package root."""
    frames = traceback.extract_tb(error.__traceback__)
    if not frames:
        return ""
    frame = frames[-1]
    root = Path(__file__).resolve().parents[2]
    path = Path(frame.filename).resolve()
    shown = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.name
    return f"{shown}:{frame.lineno} in {frame.name}"


def _expectations(cases: Sequence[Case], records: Sequence[Record]) -> tuple[Expectation, ...]:
    verdicts: list[Expectation] = []
    for case in cases:
        observations = [
            found
            for r in records
            if r.case == case.name
            for found in observations_from(r.id, r.evidence, r.status)
        ]
        rules = kind_spec(case.kind).expect_rules
        verdicts.extend(evaluate(case.name, canonical(case.expect), observations, rules))
    return tuple(verdicts)
