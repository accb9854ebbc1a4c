"""Write a report folder: ``report.json``, ``report.md`` and a self-contained ``index.html``.

All three are rendered from one document (:func:`theory.report.document.build_document`) with
jinja2 templates in ``theory/report/templates/``. The HTML has its CSS inline and its figures
embedded as data URIs (the files are also in ``figures/``). Nothing in any of the files depends
on the time of the run: the same inputs and seed give the same bytes.
"""

from __future__ import annotations

import base64
import json
import os
import re
from collections import Counter
from pathlib import Path
from typing import Any

import jinja2
from markupsafe import Markup

from theory.core.claims import Status
from theory.core.errors import CaseError
from theory.report.artifacts import CertificateChecker, collect, prechecked
from theory.report.canonical import dumps, layout
from theory.report.document import build_document
from theory.report.environment import environment
from theory.report.errata import default_errata_path, parse_errata
from theory.report.markup import markdown_to_html
from theory.report.runner import RunResult

__all__ = ["EVIDENCE_LIMIT", "render_html", "render_markdown", "write_report"]

EVIDENCE_LIMIT = 20_000
"""Characters of a result's evidence shown in HTML/Markdown (``report.json`` has all of it)."""

_TEMPLATES = Path(__file__).with_name("templates")
_IMAGE_TYPES = {".png": "image/png", ".svg": "image/svg+xml", ".jpg": "image/jpeg",
                ".jpeg": "image/jpeg", ".gif": "image/gif"}  # fmt: skip


def write_report(
    run: RunResult,
    out_dir: str | Path,
    *,
    errata_path: str | Path | None = None,
    checker: CertificateChecker | None = None,
) -> dict[str, Any]:
    """Write ``out_dir/report.json``, ``report.md``, ``index.html`` (and the claims' files).

    Parameters
    ----------
    run : RunResult
        From :func:`theory.report.runner.run_claims`.
    out_dir : str or Path
        The report folder; created if needed; other files in it are left alone.
    errata_path : str or Path, optional
        The errata document; defaults to :func:`theory.report.errata.default_errata_path`.
    checker : callable, optional
        Certificate checker (default: the verdicts the checks' tasks gave,
        :attr:`RunResult.certificate_checks`, and ``python -m proofs_check FILE --json`` on any
        other certificate).

    Returns
    -------
    dict
        The document written to ``report.json``.

    Raises
    ------
    CaseError
        If ``out_dir`` cannot be a folder or ``errata_path`` cannot be read.
    """
    out = Path(out_dir)
    errata = _read_errata(errata_path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise CaseError("-o", "a folder that can be created", str(out), hint=str(error)) from None
    artifacts = collect(
        run.records, out, checker=prechecked(run.certificate_checks) if checker is None else checker
    )
    env = environment(run.seed, run.cases, run.records, run.time_limit)
    text = dumps(build_document(run, artifacts, env, errata))
    document = json.loads(text)
    files = {
        "report.json": text,
        "report.md": render_markdown(document),
        "index.html": render_html(document, out),
    }
    for name, content in files.items():
        partial = out / f".{name}.partial"
        partial.write_text(content, encoding="utf-8")
        os.replace(partial, out / name)
    return document


def _read_errata(errata_path: str | Path | None):
    path = default_errata_path() if errata_path is None else Path(errata_path)
    if path is None:
        return None
    try:
        return parse_errata(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise CaseError(
            "--errata", "a readable Markdown file", str(path), hint=str(error.strerror)
        ) from None


def render_html(document: dict[str, Any], out_dir: Path) -> str:
    """The self-contained ``index.html`` for ``document``.

    Parameters
    ----------
    document : dict
        The ``report.json`` document.
    out_dir : Path
        The report folder, where the figures to embed were copied.

    Returns
    -------
    str
    """
    env = _environment(autoescape=True)
    env.filters["datauri"] = lambda path: _data_uri(out_dir / path)
    env.filters["md"] = lambda text: Markup(markdown_to_html(text))
    return env.get_template("index.html.j2").render(doc=document, **_views(document))


def render_markdown(document: dict[str, Any]) -> str:
    """``report.md`` for ``document``.

    Parameters
    ----------
    document : dict
        The ``report.json`` document.

    Returns
    -------
    str
    """
    env = _environment(autoescape=False)
    env.filters["cell"] = lambda text: str(text).replace("|", "\\|").replace("\n", " ")
    return env.get_template("report.md.j2").render(doc=document, **_views(document))


def _environment(*, autoescape: bool) -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(_TEMPLATES),
        autoescape=autoescape,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
    )
    env.filters["num"] = _number
    env.filters["pretty"] = _pretty
    env.filters["seed"] = _seed
    env.filters["image"] = lambda path: Path(path).suffix.lower() in _IMAGE_TYPES
    return env


def _views(document: dict[str, Any]) -> dict[str, Any]:
    """Groupings the templates need: per paper, each registered claim with its results."""
    by_id: dict[str, list[dict[str, Any]]] = {}
    for record in document["claims"]:
        by_id.setdefault(record["id"], []).append(record)
    papers = [*document["papers"], "other"]
    sections = []
    for paper in papers:
        claims = [
            {**claim, "results": by_id.get(claim["id"], [])}
            for claim in document["registered"]
            if claim["paper"] == paper
        ]
        title = document["papers"].get(paper, "Other checks (no seed paper cited)")
        cited = [
            {**claim, "statuses": _status_counts(by_id.get(claim["id"], []))}
            for claim in document["registered"]
            if claim["paper"] != paper and _cites(claim["source"], paper)
        ]
        if claims or paper != "other":
            sections.append({"paper": paper, "title": title, "claims": claims, "cited": cited})
    errata = document["errata"] or []
    return {
        "sections": sections,
        "errata_sections": _errata_sections(errata),
        "status_order": tuple(s.value for s in Status),
    }


def _cites(source: str, paper: str) -> bool:
    """Whether a claim's source names seed ``paper`` (``"seed 000 Thm 4.2.3; seed 001 Thm 1"``)."""
    return paper != "other" and re.search(rf"\bseed\s*{paper}\b", source) is not None


def _status_counts(results: list[dict[str, Any]]) -> str:
    counts = Counter(r["status"] for r in results)
    return ", ".join(f"{n} {s}" for s, n in sorted(counts.items())) or "no result"


def _errata_sections(errata: list[dict[str, Any]]) -> list[dict[str, Any]]:
    sections: dict[str, list[dict[str, Any]]] = {}
    for entry in errata:
        sections.setdefault(entry["section"], []).append(entry)
    return [{"section": s, "entries": e} for s, e in sections.items()]


def _number(value: Any) -> str:
    if value is None:
        return "—"
    if isinstance(value, float):
        return f"{value:.3g}"
    return str(value)


def _seed(record: dict[str, Any]) -> str:
    """The seed a result used: the report's derived one, else the one its evidence names (a
    case's own Monte Carlo seed, a command's fixed default), else none."""
    if record["seed"] is not None:
        return str(record["seed"])
    own = record["evidence"].get("seed")
    return "—" if own is None else f"{own} (the check's own; not derived from --seed)"


def _pretty(value: Any) -> str:
    text = layout(value, width=96)
    if len(text) <= EVIDENCE_LIMIT:
        return text
    return (
        text[:EVIDENCE_LIMIT] + f"\n… ({len(text) - EVIDENCE_LIMIT} more characters in report.json)"
    )


def _data_uri(path: Path) -> str:
    kind = _IMAGE_TYPES.get(path.suffix.lower())
    if kind is None or not path.is_file():
        return ""
    return f"data:{kind};base64," + base64.b64encode(path.read_bytes()).decode("ascii")
