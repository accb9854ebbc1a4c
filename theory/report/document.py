"""The report as one plain-data document: the content of ``report.json``.

HTML and Markdown are rendered from this same document (STYLE.md, *Adopt* 12), so the three
files never disagree. See ``docs/report.md`` for the format.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from typing import Any

from theory.core.claims import Status
from theory.core.expectations import VERDICTS
from theory.report.artifacts import Artifacts
from theory.report.errata import ErratumEntry
from theory.report.runner import RunResult, paper_of

__all__ = ["FORMAT", "PAPERS", "PROBABILITY_KEY", "build_document"]

FORMAT = "trackcert-report/1"

PAPERS = {
    "000": "Seed 000 — Ennasr, dissertation (ch. 4 TDOA localization, ch. 5 consensus Kalman "
    "filters, appendices)",
    "001": "Seed 001 — distributed TDOA localization, journal version of ch. 4",
    "002": "Seed 002 — distributed TDOA particle filter, thesis",
    "003": "Seed 003 — range-based cooperative pursuit with ISS analysis",
}
"""Section titles, one per seed paper (claims citing no paper go to ``other``)."""

PROBABILITY_KEY = "probability_bound"
"""Evidence key of a randomized claim's bound on the chance of a wrong verdict (shown in the
summary's margin/probability column when the result has no margin)."""


def build_document(
    run: RunResult,
    artifacts: Sequence[Artifacts],
    environment: dict[str, Any],
    errata: Sequence[ErratumEntry] | None,
) -> dict[str, Any]:
    """The ``report.json`` document.

    Parameters
    ----------
    run : RunResult
        What the claims returned.
    artifacts : sequence of Artifacts
        The records with their copied figures and checked certificates (same order as
        ``run.records``).
    environment : dict
        From :func:`theory.report.environment.environment`.
    errata : sequence of ErratumEntry, or None
        The errata entries (``None`` when no errata document was found).

    Returns
    -------
    dict
        Keys ``format``, ``seed``, ``summary``, ``papers``, ``claims``, ``registered``,
        ``expectations``, ``not_applicable``, ``errata``, ``environment``.
    """
    claims = [_claim_entry(a) for a in artifacts]
    statuses = Counter(c["status"] for c in claims)
    verdicts = Counter(e.verdict for e in run.expectations)
    known = {c.id for c in run.claims}
    return {
        "format": FORMAT,
        "seed": run.seed,
        "summary": {
            "results": len(claims),
            "statuses": {s.value: statuses.get(s.value, 0) for s in Status},
            "expectations": {v: verdicts.get(v, 0) for v in VERDICTS},
            "all_expectations_met": run.all_expectations_met,
        },
        "papers": dict(PAPERS),
        "claims": claims,
        "registered": [
            {
                "id": c.id,
                "source": c.source,
                "statement": c.statement,
                "kinds": list(c.kinds),
                "paper": paper_of(c.id, c.source),
            }
            for c in run.claims
        ],
        "expectations": [e.to_json() for e in run.expectations],
        "not_applicable": [{"id": i, "case": c, "reason": r} for i, c, r in run.not_applicable],
        "errata": None if errata is None else [_erratum(e, claims, known) for e in errata],
        "environment": environment,
    }


def _claim_entry(artifact: Artifacts) -> dict[str, Any]:
    record = artifact.record
    return {
        **record.to_json(),
        "probability_bound": record.evidence.get(PROBABILITY_KEY),
        "figures": list(artifact.figures),
        "certificates": list(artifact.certificates),
    }


def _erratum(
    entry: ErratumEntry, claims: Sequence[dict[str, Any]], known: set[str]
) -> dict[str, Any]:
    linked = []
    for claim_id in entry.claims:
        results = [
            {"case": c["case"], "status": c["status"], "message": c["message"]}
            for c in claims
            if c["id"] == claim_id
        ]
        linked.append({"id": claim_id, "registered": claim_id in known, "results": results})
    return {
        "paper": entry.paper,
        "section": entry.section,
        "title": entry.title,
        "heading": entry.heading,
        "text": entry.text,
        "claims": linked,
    }
