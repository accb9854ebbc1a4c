"""The errata document (``docs/errata.md``) split into entries and linked to claims.

Sections are the ``## Seed NNN …`` headings; inside a section each ``### …`` heading, or else
each top-level list item, is one entry. Every claim id an entry mentions (``seed000.thm4.2.3``)
links it to that claim's results in the report, which are its evidence.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import theory

__all__ = ["ErratumEntry", "default_errata_path", "parse_errata"]

_CLAIM_ID = re.compile(r"\bseed\d{3}\.[A-Za-z0-9_.\-]*[A-Za-z0-9_]")
_ENTRY_START = re.compile(r"^(?:###\s+|[-*]\s+|\d+\.\s+)")


@dataclass(frozen=True)
class ErratumEntry:
    """One erratum of ``docs/errata.md``.

    Attributes
    ----------
    paper : str
        ``"000"`` … ``"003"``, or ``"other"``.
    section : str
        The heading of the paper's section it stands under.
    title : str
        The erratum's own heading.
    text : str
        Its Markdown text.
    claims : tuple of str
        Claim ids the text cites (their results are shown beside it).
    heading : bool
        Whether the entry is a ``###`` section (its title is then not part of its text) rather
        than a list item (whose text starts with its title).
    """

    paper: str
    section: str
    title: str
    text: str
    claims: tuple[str, ...]
    heading: bool


def default_errata_path() -> Path | None:
    """The errata document to report by default.

    Returns
    -------
    Path or None
        ``theory/bundled_docs/errata.md`` of an installed package, else ``docs/errata.md`` of a
        source checkout, else ``None``.
    """
    package = Path(theory.__file__).resolve().parent
    for candidate in (package / "bundled_docs" / "errata.md", package.parent / "docs/errata.md"):
        if candidate.is_file():
            return candidate
    return None


def parse_errata(text: str) -> list[ErratumEntry]:
    """The entries of an errata document, in document order.

    Parameters
    ----------
    text : str
        Markdown with ``## `` section headings (``## Seed 000 (…)``).

    Returns
    -------
    list of ErratumEntry
    """
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
