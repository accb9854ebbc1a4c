"""The report read by case and by theorem: a page per case (every claim on it, its verdict, its
figures, its design answers), a contents page by paper and theorem with one verdict line per
claim, and the search index — all rendered from the ``report.json`` document.

Page names are fixed by the case names (:func:`case_pages`), so links between pages, and the
bytes of every page, depend on the document only.
"""

from __future__ import annotations

import re
from collections import Counter
from typing import Any

from theory.core.claims import Status
from theory.report.design_section import headline
from theory.report.evidence_table import evidence_rows
from theory.report.glossary import STATUS_LEGEND, margin_of, margin_table
from theory.report.search import canonical, search_entries, search_script
from theory.report.tasks import slug

__all__ = ["MODEL", "case_pages", "contents_view", "page_views", "result_view", "search_file"]

MODEL = "-"
"""The case name of results about the model itself (claims that take no case)."""


def case_pages(document: dict[str, Any]) -> dict[str, str]:
    """Case name → its page (``cases/<slug>.html``; the model's results: ``cases/model.html``)."""
    pages = {MODEL: "cases/model.html"}
    taken = set(pages.values())
    for case in document["environment"]["cases"]:
        page, index = f"cases/{slug(case['name'])}.html", 2
        while page in taken:
            page, index = f"cases/{slug(case['name'])}-{index}.html", index + 1
        taken.add(page)
        pages[case["name"]] = page
    return pages


def result_view(record: dict[str, Any]) -> dict[str, Any]:
    """A result with what its page shows beside the record: the margin's meaning and the
    evidence as labelled tables."""
    margin = margin_of(record["id"])
    return {
        **record,
        "margin_meaning": None if margin is None else margin.__dict__,
        "evidence_rows": evidence_rows(record["evidence"]),
        "words": canonical(" ".join((record["id"], record["source"], record["case"]))),
    }


def _verdict_line(results: list[dict[str, Any]]) -> str:
    counts = Counter(r["status"] for r in results)
    return ", ".join(f"{counts[s.value]} {s.value}" for s in Status if counts[s.value])


def _worst(results: list[dict[str, Any]]) -> str:
    """The status a contents line is coloured by: refuted, inconclusive, corrected, verified."""
    order = ("refuted", "inconclusive", "corrected", "verified")
    present = {r["status"] for r in results}
    return next((s for s in order if s in present), "none")


def _reading_order(claim: dict[str, Any]) -> tuple:
    """Chapter order within a paper: the section numbers that open the id after ``seedNNN.``
    (``thm4.2.3`` → (4, 2, 3), before ``lem5.2.2``; ``thm2`` before ``thm10``); ids that open
    with none (appendices, ``lemA.1.1``) after them."""
    match = re.match(r"[a-z_]*(\d+(?:\.\d+)*)", claim["id"].split(".", 1)[-1])
    numbers = tuple(int(n) for n in match.group(1).split(".")) if match else ()
    return (not numbers, numbers, claim["id"])


def results_by_claim(document: dict[str, Any]) -> dict[str, list[dict[str, Any]]]:
    """report.json's result records grouped by claim id, in report order."""
    by_id: dict[str, list[dict[str, Any]]] = {}
    for record in document["claims"]:
        by_id.setdefault(record["id"], []).append(record)
    return by_id


def contents_view(document: dict[str, Any], pages: dict[str, str]) -> list[dict[str, Any]]:
    """Per paper, its registered claims with one verdict line each and a link per result."""
    by_id = results_by_claim(document)
    sections = []
    for paper in [*document["papers"], "other"]:
        claims = []
        mine = [c for c in document["registered"] if c["paper"] == paper]
        for claim in sorted(mine, key=_reading_order):
            results = by_id.get(claim["id"], [])
            links = [
                {
                    "case": r["case"],
                    "status": r["status"],
                    "href": f"{pages[r['case']]}#result-{slug(r['id'])}",
                }
                for r in results
            ]
            claims.append(
                {
                    **claim,
                    "verdict": _verdict_line(results) or "no result",
                    "worst": _worst(results),
                    "links": links,
                    "words": canonical(
                        " ".join((claim["id"], claim["source"], claim["statement"]))
                    ),
                }
            )
        if claims:
            title = document["papers"].get(paper, "Other checks (no seed paper cited)")
            sections.append({"paper": paper, "title": title, "claims": claims})
    return sections


def _case_view(document: dict[str, Any], case: dict[str, Any], page: str) -> dict[str, Any]:
    name = case["name"]
    results = [result_view(r) for r in document["claims"] if r["case"] == name]
    design = document["design"].get(name)
    return {
        **case,
        "page": page,
        "results": results,
        "verdict": _verdict_line(results) or "no result",
        "expectations": [e for e in document["expectations"] if e["case"] == name],
        "not_applicable": [n for n in document["not_applicable"] if n["case"] == name],
        "figures": document["case_figures"].get(name, []),
        "design": design,
        "design_headline": [] if design is None else headline(design),
    }


def page_views(document: dict[str, Any]) -> dict[str, Any]:
    """What the case and contents templates need: the case views (model first), the contents,
    the legend and the margin table."""
    pages = case_pages(document)
    model = {
        "name": MODEL,
        "kind": "model",
        "source": "claims about the model, run once",
        "file": "",
        "sha256": None,
        "tolerances": {},
    }
    cases = [model, *document["environment"]["cases"]]
    views = [_case_view(document, case, pages[case["name"]]) for case in cases]
    return {
        "pages": pages,
        "case_views": [v for v in views if v["results"] or v["name"] != MODEL],
        "contents": contents_view(document, pages),
        "legend": STATUS_LEGEND,
        "margins": margin_table(),
    }


def search_file(document: dict[str, Any]) -> str:
    """``search-index.js`` of the document."""
    return search_script(search_entries(document, case_pages(document)))
