"""Search over the papers' wording: claim ids, sources ("Theorem 2", "Thm 4.2.3", "seed 003"),
statements and cases, as a small static index the report's pages filter in the browser.

Text is compared in one canonical form (:func:`canonical`): lower case, the papers'
abbreviations (``Theorem``/``Thm.``, ``Lemma``/``Lem.``, ``eq.``/``equation``, ``§``/``Section`` …)
folded to one spelling, ``seed003`` read as ``seed 003``, punctuation dropped. The pages' script
applies the same rules (:data:`RULES`, written into the page) to what the reader types.
"""

from __future__ import annotations

import json
import re
from typing import Any

__all__ = ["RULES", "canonical", "script_rules", "search_entries", "search_script"]

RULES: tuple[tuple[str, str], ...] = (
    (r"§\s*", "sec "),
    (r"\btheorems?\b|\bthms?\b", "thm"),
    (r"\blemmas?\b|\blems?\b", "lem"),
    (r"\bcorollar(?:y|ies)\b|\bcors?\b", "cor"),
    (r"\bdefinitions?\b|\bdefs?\b", "def"),
    (r"\bpropositions?\b|\bprops?\b", "prop"),
    (r"\bremarks?\b|\brems?\b", "rem"),
    (r"\bexamples?\b|\bexs?\b", "ex"),
    (r"\bequations?\b|\beqs?\b", "eq"),
    (r"\bfigures?\b|\bfigs?\b", "fig"),
    (r"\bsections?\b|\bsecs?\b", "sec"),
    (r"\bappendix\b|\bapp\b", "app"),
    (r"\bseed\s*(\d{3})\b", r"seed \1"),
    (r"[^a-z0-9_.\s]|(?<!\d)\.|\.(?!\d)", " "),
    (r"\s+", " "),
)
"""(regular expression, replacement) applied in order to lower-cased text; the JavaScript of the
pages applies the same list (JSON-encoded; ``\\1`` read as ``$1``)."""


def canonical(text: str) -> str:
    """``text`` in the search's canonical form (``"Theorem 4.2.3"`` → ``"thm 4.2.3"``)."""
    out = text.lower()
    for pattern, replacement in RULES:
        out = re.sub(pattern, replacement, out)
    return out.strip()


def search_entries(document: dict[str, Any], case_pages: dict[str, str]) -> list[dict[str, Any]]:
    """The index: one entry per registered claim (to its line of the contents) and one per case
    (to its page), each with the ``text`` shown and the canonical ``words`` searched."""
    entries = []
    for claim in document["registered"]:
        shown = f"{claim['id']} — {claim['source']}"
        words = " ".join((claim["id"], claim["source"], claim["statement"]))
        entries.append(
            {
                "kind": "claim",
                "text": shown,
                "detail": claim["statement"],
                "href": f"contents.html#claim-{claim['id']}",
                "words": canonical(words),
            }
        )
    for case in document["environment"]["cases"]:
        words = " ".join((case["name"], case["kind"], case["source"]))
        entries.append(
            {
                "kind": "case",
                "text": case["name"],
                "detail": case["source"],
                "href": case_pages[case["name"]],
                "words": canonical(words),
            }
        )
    return entries


def script_rules() -> list[list[str]]:
    """:data:`RULES` for JavaScript's ``String.replace`` (``\\1`` written ``$1``)."""
    return [[pattern, replacement.replace("\\1", "$1")] for pattern, replacement in RULES]


def search_script(entries: list[dict[str, Any]]) -> str:
    """``search-index.js``: the index and the rules, for the pages' search boxes."""
    data = {"rules": script_rules(), "entries": entries}
    text = json.dumps(data, ensure_ascii=False, sort_keys=True, separators=(",", ":"))
    return f"window.TRACKCERT_SEARCH = {text};\n"
