"""Write a report folder — ``report.json``, ``report.md``, a self-contained ``index.html``, the
claims' figures and certificates, ``timings.json`` — and ``trackcert report`` as one library call.

:func:`build_report` runs the claims (:func:`theory.report.runner.run_claims`) with figures drawn
in a temporary folder, then writes everything into a staging folder that replaces the report
folder whole (:func:`theory.core.atomic_output.replaced_folder`): a failure or a signal leaves the
old report as it was.

Files the claims produce are copied in: figures from :attr:`ClaimResult.figures`, certificates
given as paths in the evidence (``certificate``: one, ``certificates``: a list) or as the
document itself (``certificate_document``). Each goes to ``DIR/figures/<claim>/<case>/`` or
``DIR/certificates/<claim>/<case>/`` with its SHA-256 (so the figures' data is part of the
reproducible ``report.json``), the evidence names the copy, and every certificate is re-verified
by the independent checker (:func:`theory.report.tasks.check_with_cli`, reusing the verdict given
where its claim ran). The three files are rendered from one document
(:func:`theory.report.document.build_document`) with the jinja2 templates of
``theory/report/templates/``; the HTML has its CSS inline and its figures as data URIs, and
renders ``docs/errata.md`` through a small Markdown subset whose input is escaped first.
"""

from __future__ import annotations

import base64
import hashlib
import html
import json
import os
import re
import shutil
import tempfile
import time
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import jinja2
from markupsafe import Markup

from theory.core.atomic_output import check_replaceable, recover, replaced_folder
from theory.core.case_file import Case
from theory.core.claims import DOCUMENT_KEY, Claim, Status
from theory.core.errors import COMMAND_LINE, CaseError
from theory.core.jsonable import dumps, layout
from theory.core.parallel import TaskRunner
from theory.registry import all_claims
from theory.report.case_figures import draw_case
from theory.report.design_section import design_sections, headline
from theory.report.document import (
    Artifacts,
    ErratumEntry,
    build_document,
    default_errata_path,
    environment,
    parse_errata,
)
from theory.report.evidence_table import evidence_rows
from theory.report.glossary import STATUS_LEGEND, margin_table
from theory.report.pages import (
    case_pages,
    page_views,
    result_view,
    results_by_claim,
    search_file,
)
from theory.report.runner import (
    ProgressHook,
    RunResult,
    load_estimates,
    run_claims,
    select_claims,
    timings_document,
    write_timings,
)
from theory.report.search import canonical, script_rules
from theory.report.tasks import (
    CertificateChecker,
    Record,
    certificate_bytes,
    check_with_cli,
    document_name,
    prechecked,
    slug,
)

__all__ = [
    "CERTIFICATE_KEYS",
    "EVIDENCE_LIMIT",
    "MARKER",
    "build_report",
    "check_count",
    "choose_claims",
    "collect",
    "markdown_to_html",
    "render_html",
    "render_markdown",
    "render_pages",
    "write_report",
]

MARKER = "report.json"
"""The file every report folder has: a folder without it is not replaced (unless empty)."""

CERTIFICATE_KEYS = ("certificate", "certificates")
"""Evidence keys whose values are certificate paths (a string, or a list of strings)."""

EVIDENCE_LIMIT = 20_000
"""Characters of a result's evidence shown in HTML/Markdown (``report.json`` has all of it)."""

_TEMPLATES = Path(__file__).with_name("templates")
_IMAGE_TYPES = {
    ".png": "image/png",
    ".svg": "image/svg+xml",
    ".jpg": "image/jpeg",
    ".jpeg": "image/jpeg",
    ".gif": "image/gif",
}


def choose_claims(patterns: Sequence[str] = ()) -> list[Claim]:
    """The registered claims matching ``patterns`` (``--only``; none: all), refusing patterns
    that match nothing (the hint lists the registered ids)."""
    registered = all_claims()
    claims = select_claims(registered, patterns)
    if patterns and not claims:
        known = "Registered claims: " + ", ".join(c.id for c in registered)
        raise CaseError(
            "--only",
            "a pattern matching a registered claim id",
            list(patterns),
            file=COMMAND_LINE,
            hint=known,
        )
    return claims


def check_count(cases: Sequence[Case], claims: Sequence[Claim]) -> int:
    """How many checks :func:`build_report` runs: each model claim once, each claim per case."""
    return sum(1 for c in claims if not c.kinds) + sum(
        1 for case in cases for c in claims if case.kind in c.kinds
    )


def build_report(
    cases: Sequence[Case],
    out_dir: Path,
    *,
    claims: Sequence[Claim] | None = None,
    seed: int = 0,
    seconds: float | None = None,
    errata_path: Path | None = None,
    progress: ProgressHook | None = None,
    runner: TaskRunner | None = None,
) -> tuple[RunResult, dict[str, Any]]:
    """Run every claim on every case; write ``index.html``, ``report.md``, ``report.json`` and
    ``timings.json`` into ``out_dir``, replaced whole.

    Parameters
    ----------
    cases : sequence of Case
        The cases (distinct names).
    out_dir : Path
        The report folder.
    claims : sequence of Claim, optional
        Default: every registered claim.
    seed : int
        Seed of every randomized check (:func:`theory.report.tasks.derive_seed`).
    seconds : float, optional
        CPU-time limit of each check (``None``: none).
    errata_path : Path, optional
        The errata document (default ``docs/errata.md``).
    progress : callable, optional
        :data:`~theory.report.runner.ProgressHook`, as checks complete.
    runner : TaskRunner, optional
        An open engine to run the checks on (default: serially in this process).

    Returns
    -------
    (RunResult, dict)
        What the claims returned, and the ``report.json`` document.

    Raises
    ------
    CaseError
        If ``errata_path`` is not a readable file, ``out_dir`` is not a report folder
        (:func:`theory.core.atomic_output.replaceable_problem`) or the engine's scheduler cannot
        be reached.
    OutputError
        If writing fails (the folder is left as it was).
    """
    if errata_path is not None and not Path(errata_path).is_file():
        raise CaseError("--errata", "a readable Markdown file", str(errata_path), file=COMMAND_LINE)
    recover(out_dir)  # a report killed while swapping folders: its old folder comes back first
    check_replaceable(out_dir, MARKER)
    with tempfile.TemporaryDirectory(prefix="trackcert-figures-") as figures:
        started = time.perf_counter()
        run = run_claims(
            cases,
            seed=seed,
            claims=claims,
            progress=progress,
            seconds=seconds,
            figure_dir=Path(figures),
            runner=runner,
            estimates=load_estimates(Path(out_dir)),
        )
        wall = time.perf_counter() - started
        timings = timings_document(
            run,
            wall_seconds=wall,
            workers=1 if runner is None else runner.size,
            scheduler=None if runner is None else runner.scheduler,
        )
        with replaced_folder(out_dir, MARKER) as staging:
            document = write_report(run, staging, errata_path=errata_path)
            write_timings(timings, staging)
    return run, document


def write_report(
    run: RunResult,
    out_dir: str | Path,
    *,
    errata_path: str | Path | None = None,
    checker: CertificateChecker | None = None,
) -> dict[str, Any]:
    """Write ``out_dir/report.json``, ``report.md``, ``index.html`` and the claims' files; return
    the ``report.json`` document.

    ``out_dir`` is created if needed (other files in it are left alone); ``errata_path``
    defaults to :func:`theory.report.document.default_errata_path`; ``checker`` defaults to the
    verdicts the checks' tasks gave, else ``python -m proofs_check FILE --json``. Raises
    :class:`CaseError` if ``out_dir`` cannot be a folder or the errata cannot be read.
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
    pages = {"design": design_sections(run.cases), "case_figures": _case_figures(run.cases, out)}
    text = dumps(build_document(run, artifacts, env, errata, pages))
    document = json.loads(text)
    files = {
        "report.json": text,
        "report.md": render_markdown(document),
        "index.html": render_html(document, out),
        **render_pages(document),
    }
    for name, content in files.items():
        (out / name).parent.mkdir(parents=True, exist_ok=True)
        partial = (out / name).with_name(f".{Path(name).name}.partial")
        partial.write_text(content, encoding="utf-8")
        os.replace(partial, out / name)
    return document


def _case_figures(cases: Sequence[Case], out_dir: Path) -> dict[str, list[dict[str, Any]]]:
    """Each case's own figures (:func:`theory.report.case_figures.draw_case`) written under
    ``out_dir/figures/cases/<case>/``, as report entries (path, SHA-256, caption)."""
    figures = {}
    for case in cases:
        folder = f"figures/cases/{slug(case.name)}"
        drawn = draw_case(case, out_dir / folder)
        figures[case.name] = [
            {
                "path": f"{folder}/{name}",
                "caption": caption,
                "sha256": hashlib.sha256((out_dir / folder / name).read_bytes()).hexdigest(),
            }
            for name, caption in drawn
        ]
    return figures


def _read_errata(errata_path: str | Path | None) -> list[ErratumEntry] | None:
    path = default_errata_path() if errata_path is None else Path(errata_path)
    if path is None:
        return None
    try:
        return parse_errata(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise CaseError(
            "--errata", "a readable Markdown file", str(path), hint=str(error.strerror)
        ) from None


# ---------------------------------------------------------------------------------- artifacts
def collect(
    records: tuple[Record, ...], out_dir: Path, *, checker: CertificateChecker | None = None
) -> list[Artifacts]:
    """Copy every record's figures and certificates into ``out_dir`` and check the certificates
    (``checker`` defaults to :func:`~theory.report.tasks.check_with_cli`); each record's evidence
    names the copies, relative to ``out_dir``."""
    checker = check_with_cli if checker is None else checker
    taken: set[str] = set()
    collected = []
    for record in records:
        figures = tuple(_copy(Path(f), "figures", record, out_dir, taken) for f in record.figures)
        evidence = dict(record.evidence)
        certificates: list[dict[str, Any]] = []
        document = evidence.pop(DOCUMENT_KEY, None)
        for key in CERTIFICATE_KEYS:
            paths = _certificate_paths(evidence.get(key))
            if paths is None:
                continue
            copies = [_copy(Path(p), "certificates", record, out_dir, taken) for p in paths]
            for copy in copies:
                if copy["sha256"] is not None:
                    copy["check"] = checker(Path(copy["path"]), out_dir)
            certificates.extend(copies)
            relative = [c["path"] for c in copies]
            evidence[key] = relative[0] if isinstance(evidence[key], str) else relative
        if isinstance(document, dict):
            written = _write(document, record, out_dir, taken)
            written["check"] = checker(Path(written["path"]), out_dir)
            certificates.append(written)
            evidence["certificate"] = written["path"]
        collected.append(Artifacts(record.with_evidence(evidence), figures, tuple(certificates)))
    return collected


def _certificate_paths(value: object) -> list[str] | None:
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return list(value)
    return None


def _copy(source: Path, folder: str, record: Record, out_dir: Path, taken: set[str]) -> dict:
    """Copy ``source`` under ``out_dir/folder/<claim>/<case>/`` with a name not used before."""
    name = _reserve(folder, record, slug(source.name), taken)
    if not source.is_file():
        return {"path": name, "sha256": None, "error": f"the claim's file {source.name} is missing"}
    target = out_dir / name
    target.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(source, target)
    return {"path": name, "sha256": hashlib.sha256(target.read_bytes()).hexdigest()}


def _write(document: dict, record: Record, out_dir: Path, taken: set[str]) -> dict:
    """Write a certificate ``document`` as ``DIR/certificates/<claim>/<case>/<kind>.json``."""
    path = _reserve("certificates", record, document_name(document), taken)
    target = out_dir / path
    target.parent.mkdir(parents=True, exist_ok=True)
    content = certificate_bytes(document)
    target.write_bytes(content)
    return {"path": path, "sha256": hashlib.sha256(content).hexdigest()}


def _reserve(folder: str, record: Record, name: str, taken: set[str]) -> str:
    """``folder/<claim>/<case>/name``, prefixed ``2-``, ``3-`` … until unused; marks it used."""
    base = f"{folder}/{slug(record.id)}/{slug(record.case)}"
    path, index = f"{base}/{name}", 2
    while path in taken:
        path, index = f"{base}/{index}-{name}", index + 1
    taken.add(path)
    return path


# -------------------------------------------------------------------------------- renderings
def render_html(document: dict[str, Any], out_dir: Path) -> str:
    """The self-contained ``index.html`` of ``document`` (figures embedded from ``out_dir``)."""
    env = _environment(autoescape=True)
    env.filters["md"] = lambda text: Markup(markdown_to_html(text))
    views = _views(document)
    return env.get_template("index.html.j2").render(
        doc=document,
        **views,
        legend=STATUS_LEGEND,
        margins=margin_table(),
        search_rules=script_rules(),
        figure_src=lambda path: _data_uri(out_dir / path),
    )


def render_pages(document: dict[str, Any]) -> dict[str, str]:
    """The pages read by case and by theorem: ``contents.html``, ``cases/<case>.html`` and
    ``search-index.js`` (:mod:`theory.report.pages`), relative path → text."""
    env = _environment(autoescape=True)
    views = page_views(document)
    common = {"doc": document, **views}
    files = {
        "contents.html": env.get_template("contents.html.j2").render(root="", **common),
        "search-index.js": search_file(document),
    }
    template = env.get_template("case.html.j2")
    for case in views["case_views"]:
        design = case["design"]
        rows = evidence_rows(design["answers"]) if design and "answers" in design else []
        files[case["page"]] = template.render(
            root="../",
            case=case,
            design_rows=rows,
            figure_src=lambda path: f"../{path}",
            **common,
        )
    return files


def render_markdown(document: dict[str, Any]) -> str:
    """``report.md`` of ``document``."""
    env = _environment(autoescape=False)
    env.filters["cell"] = lambda text: str(text).replace("|", "\\|").replace("\n", " ")
    design = {case: headline(section) for case, section in document["design"].items()}
    return env.get_template("report.md.j2").render(
        doc=document, design_lines=design, **_views(document)
    )


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
    env.filters["slug"] = slug
    return env


def _views(document: dict[str, Any]) -> dict[str, Any]:
    """Groupings the templates need: per paper, each registered claim with its results."""
    by_id = results_by_claim(document)
    sections = []
    for paper in [*document["papers"], "other"]:
        claims = [
            {**claim, "results": [result_view(r) for r in by_id.get(claim["id"], [])]}
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
        "pages": case_pages(document),
        "row_words": {
            (r["id"], r["case"]): canonical(f"{r['id']} {r['case']} {r['source']}")
            for r in document["claims"]
        },
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


# ------------------------------------------------------------------------- Markdown subset
_LIST_ITEM = re.compile(r"^\s*(?:[-*]|\d+\.)\s+")
_INLINE = (
    (re.compile(r"\*\*(.+?)\*\*"), r"<strong>\1</strong>"),
    (re.compile(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])"), r"<em>\1</em>"),
    (re.compile(r"\[([^\]]+)\]\(((?:https?://|#|\.{0,2}/)?[^)\s]*)\)"), r'<a href="\2">\1</a>'),
)


def markdown_to_html(text: str) -> str:
    """HTML of a safe Markdown subset: paragraphs, ``-``/``*``/``1.`` lists, fenced code,
    headings, inline code, bold, italics and links; everything else is escaped text, so no markup
    in a document can inject HTML into the report."""
    out: list[str] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("```"):
            end = next((j for j in range(i + 1, len(lines)) if lines[j].startswith("```")), None)
            end = len(lines) if end is None else end
            out.append(f"<pre>{html.escape(chr(10).join(lines[i + 1 : end]))}</pre>")
            i = end + 1
        elif heading := re.match(r"^(#{1,6})\s+(.*)", line):
            level = min(len(heading.group(1)) + 2, 6)
            out.append(f"<h{level}>{_inline(heading.group(2))}</h{level}>")
            i += 1
        elif _LIST_ITEM.match(line):
            items, i = _block(lines, i, lambda s: bool(_LIST_ITEM.match(s)))
            out.append("<ul>" + "".join(f"<li>{_inline(item)}</li>" for item in items) + "</ul>")
        elif line.strip():
            paragraph, i = _block(lines, i, lambda s: False)
            out.append(f"<p>{_inline(' '.join(paragraph))}</p>")
        else:
            i += 1
    return "\n".join(out)


def _block(lines: list[str], start: int, starts_item) -> tuple[list[str], int]:
    """Items (or one paragraph) from ``start`` until a blank line, heading or fence."""
    items: list[str] = []
    i = start
    while i < len(lines) and lines[i].strip() and not re.match(r"^(#{1,6}\s|```)", lines[i]):
        line = lines[i]
        if starts_item(line) or not items:
            items.append(_LIST_ITEM.sub("", line, count=1).strip())
        else:
            items[-1] += " " + line.strip()
        i += 1
    return items, i


def _inline(text: str) -> str:
    parts = re.split(r"(`[^`]+`)", text)
    rendered = []
    for part in parts:
        if part.startswith("`") and part.endswith("`") and len(part) > 1:
            rendered.append(f"<code>{html.escape(part[1:-1])}</code>")
            continue
        escaped = html.escape(part, quote=False)
        for pattern, replacement in _INLINE:
            escaped = pattern.sub(replacement, escaped)
        rendered.append(escaped)
    return "".join(rendered)
