"""One line of the report (:class:`Record`) and the names and seeds every check is filed under.

Shared by the side that runs checks (:mod:`theory.report.tasks`, on a worker) and the side that
assembles and writes the report (:mod:`theory.report.runner`, :mod:`theory.report.artifacts`).
"""

from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass, replace
from typing import Any

from theory.core.claims import MODEL_CASE, ClaimResult

__all__ = ["MODEL_CASE", "RESULT_FIELDS", "Record", "derive_seed", "paper_of", "slug"]


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
