"""The report as one plain-data document, the content of ``report.json``: results, expectations,
the errata linked to their claims, and what a reader needs to reproduce it.

HTML and Markdown are rendered from this same document (:mod:`theory.report.render`), so the
three files never disagree; nothing in it depends on the time of day (docs/report.md).

The errata document (``docs/errata.md``) is split into entries: sections are its ``## Seed NNN
…`` headings, and inside a section each ``### …`` heading, or else each top-level list item, is
one entry; every claim id an entry mentions links it to that claim's results.
"""

from __future__ import annotations

import hashlib
import json
import platform
import re
import subprocess
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path
from typing import Any

import theory
from theory.core.case_file import Case, bundled_case_dir
from theory.core.claims import Status
from theory.core.expectations import ExpectationVerdict
from theory.core.tolerances import table
from theory.registry import all_claims
from theory.report.runner import RunResult
from theory.report.tasks import Record, clock_name, enforceable, paper_of

__all__ = [
    "FORMAT",
    "PACKAGES",
    "PAPERS",
    "PROBABILITY_KEY",
    "SEED_RULE",
    "Artifacts",
    "ErratumEntry",
    "build_document",
    "default_errata_path",
    "environment",
    "parse_errata",
]

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
"""Evidence key of a randomized claim's bound on the chance of a wrong verdict."""

PACKAGES = (
    "numpy",
    "scipy",
    "sympy",
    "networkx",
    "control",
    "cvxpy",
    "clarabel",
    "scs",
    "python-flint",
    "typer",
    "rich",
    "matplotlib",
    "jinja2",
    "pyyaml",
    "hypothesis",
    "threadpoolctl",
)
"""Distributions whose versions the report records (trackcert's runtime dependencies)."""

SEED_RULE = 'claim seed = first 4 bytes (big-endian) of SHA-256("{seed}:{claim id}:{case}")'

_CLAIM_ID = re.compile(r"\bseed\d{3}\.[A-Za-z0-9_.\-]*[A-Za-z0-9_]")
_ENTRY_START = re.compile(r"^(?:###\s+|[-*]\s+|\d+\.\s+)")


@dataclass(frozen=True)
class Artifacts:
    """A record with its files copied into the report folder (``figures`` and ``certificates``
    as report entries)."""

    record: Record
    figures: tuple[dict[str, Any], ...]
    certificates: tuple[dict[str, Any], ...]


@dataclass(frozen=True)
class ErratumEntry:
    """One erratum: its ``paper`` (``000``… or ``other``), the ``section`` heading it stands
    under, its ``title``, Markdown ``text``, the claim ids it cites, and whether it is a ``###``
    ``heading`` (whose title is not part of its text) rather than a list item."""

    paper: str
    section: str
    title: str
    text: str
    claims: tuple[str, ...]
    heading: bool


def build_document(
    run: RunResult,
    artifacts: Sequence[Artifacts],
    environment: dict[str, Any],
    errata: Sequence[ErratumEntry] | None,
    pages: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """The ``report.json`` document: ``format``, ``seed``, ``summary``, ``papers``, ``claims``
    (one per artifact, in ``run.records`` order), ``registered``, ``expectations``,
    ``not_applicable``, ``errata`` (``None`` when no errata document was found), ``design``
    (case → its design answers, :func:`theory.report.design_section.design_sections`),
    ``case_figures`` (case → its own figures), ``environment``; ``pages`` gives ``design`` and
    ``case_figures`` (empty when omitted).
    """
    pages = pages or {}
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
            "expectations": {v.value: verdicts.get(v, 0) for v in ExpectationVerdict},
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
        "design": pages.get("design", {}),
        "case_figures": pages.get("case_figures", {}),
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


# ------------------------------------------------------------------------------- environment
def environment(
    seed: int,
    cases: Sequence[Case],
    records: Sequence[Record],
    time_limit: float | None = None,
) -> dict[str, Any]:
    """The ``environment`` section: ``python``, ``implementation``, ``platform``, ``packages``
    (name → version or ``"not installed"``), ``trackcert`` (version, source revision), ``seed``,
    ``seed_rule``, ``cases`` (name, kind, file, SHA-256, tolerance overrides), ``claim_modules``,
    ``claims_registered``, ``tolerances`` (name → the distinct values the results used),
    ``tolerance_table`` (:func:`theory.core.tolerances.table`), ``time_limit`` (CPU seconds or
    ``None``), ``time_limit_clock`` and ``time_limit_enforced``."""
    return {
        "python": platform.python_version(),
        "implementation": platform.python_implementation(),
        "platform": platform.platform(),
        "packages": {name: _version(name) for name in PACKAGES},
        "trackcert": {"version": theory.__version__, "revision": _revision()},
        "seed": seed,
        "seed_rule": SEED_RULE,
        "cases": [_case(case) for case in cases],
        "claim_modules": sorted({c.check.__module__ for c in all_claims()}),
        "claims_registered": len(all_claims()),
        "tolerances": _tolerances(records),
        "tolerance_table": table(),
        "time_limit": time_limit,
        "time_limit_clock": clock_name(),
        "time_limit_enforced": time_limit is not None and enforceable(),
    }


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def _revision() -> str | None:
    """``git describe --always --dirty`` of a source checkout; ``None`` for an installed copy."""
    root = Path(theory.__file__).resolve().parent.parent
    if not (root / ".git").exists():
        return None
    try:
        done = subprocess.run(
            ["git", "-C", str(root), "describe", "--always", "--dirty", "--abbrev=12"],
            capture_output=True,
            text=True,
            timeout=30,
            check=False,
        )
    except (OSError, subprocess.SubprocessError):
        return None
    text = done.stdout.strip()
    return text if done.returncode == 0 and text else None


def _case(case: Case) -> dict[str, Any]:
    path = Path(case.file)
    digest = hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else None
    return {
        "name": case.name,
        "kind": case.kind,
        "source": case.source,
        "file": _shown_path(path),
        "sha256": digest,
        "tolerances": dict(case.tolerances),
    }


def _shown_path(path: Path) -> str:
    """``bundled:NAME.yaml`` for bundled cases (their folder differs between installs)."""
    folder = bundled_case_dir().resolve()
    resolved = path.resolve()
    return f"bundled:{resolved.name}" if resolved.parent == folder else str(path)


def _tolerances(records: Sequence[Record]) -> dict[str, list[Any]]:
    used: dict[str, dict[str, Any]] = {}
    for record in records:
        for name, value in record.tolerance.items():
            used.setdefault(name, {})[json.dumps(value, sort_keys=True)] = value
    return {name: [values[k] for k in sorted(values)] for name, values in sorted(used.items())}


# ------------------------------------------------------------------------------------ errata
def default_errata_path() -> Path | None:
    """``theory/bundled_docs/errata.md`` of an installed package, else ``docs/errata.md`` of a
    source checkout, else ``None``."""
    package = Path(theory.__file__).resolve().parent
    for candidate in (package / "bundled_docs" / "errata.md", package.parent / "docs/errata.md"):
        if candidate.is_file():
            return candidate
    return None


def parse_errata(text: str) -> list[ErratumEntry]:
    """The entries of an errata document (Markdown with ``## `` section headings), in order."""
    blocks: list[tuple[str, str, list[str]]] = []
    section, paper, current = "", "other", None
    for line in text.splitlines():
        if line.startswith("## "):
            section = line[3:].strip()
            match = re.search(r"seed\s*(\d{3})", section, re.IGNORECASE)
            paper = match.group(1) if match else "other"
            current = None
        elif section and _ENTRY_START.match(line):
            current = [line]
            blocks.append((paper, section, current))
        elif current is not None:
            current.append(line)
    return [_entry(paper, section, "\n".join(lines)) for paper, section, lines in blocks]


def _entry(paper: str, section: str, text: str) -> ErratumEntry:
    lines = text.strip().splitlines()
    title = _ENTRY_START.sub("", lines[0]).strip()
    heading = lines[0].startswith("###")
    if heading:
        body = "\n".join(lines[1:]).strip()
    else:  # a list item: its text, the marker removed and continuation lines dedented
        body = "\n".join([title, *(line.strip() for line in lines[1:])])
    claims = tuple(dict.fromkeys(_CLAIM_ID.findall(text)))
    return ErratumEntry(paper, section, _short(title), body, claims, heading)


def _short(title: str, limit: int = 140) -> str:
    title = re.sub(r"[*`]", "", title)
    return title if len(title) <= limit else title[: limit - 1].rstrip() + "…"
