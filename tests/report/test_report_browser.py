"""The report as a person sees it: ``index.html`` rendered by headless Chromium.

Needs Debian's ``chromium`` (``apt-get install -y chromium``); the test installs nothing and is
skipped, saying why, where no browser is present. The screenshot is saved next to the report
(and copied to ``$TRACKCERT_SCREENSHOT`` when that is set, so CI can keep it).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import pytest
from report_fakes import register_standard_fakes, result, write_case

from theory.kinds import load_case
from theory.report.render import write_report
from theory.report.runner import run_claims

CHROMIUM = next(
    (p for p in (shutil.which("chromium"), "/usr/bin/chromium") if p and Path(p).is_file()), None
)
FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--enable-logging=stderr",
    "--window-size=1280,1600",
)

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(
        CHROMIUM is None,
        reason="headless Chromium not found (install Debian's package: apt-get install chromium)",
    ),
]


class _Page(HTMLParser):
    """Collects the body's data attributes, the summary table's rows, a case page's claim rows,
    its figures, and the search results the page's script listed."""

    def __init__(self) -> None:
        super().__init__()
        self.body: dict[str, str | None] = {}
        self.rows: list[tuple[str | None, str | None]] = []
        self.hidden: list[bool] = []
        self.case_rows: list[tuple[str | None, str | None]] = []
        self.images: list[str | None] = []
        self.found: list[str | None] = []
        self._table: str | None = None
        self._in_results = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        attributes = dict(attrs)
        if tag == "body":
            self.body = attributes
        elif tag == "table":
            self._table = attributes.get("id")
        elif tag == "tr" and "data-claim" in attributes and self._table == "summary-table":
            self.rows.append((attributes["data-claim"], attributes.get("data-case")))
            self.hidden.append("hidden" in attributes)
        elif tag == "tr" and "data-claim" in attributes and self._table == "case-claims":
            self.case_rows.append((attributes["data-claim"], attributes.get("data-status")))
        elif tag == "img":
            self.images.append(attributes.get("src"))
        elif tag == "ol" and attributes.get("id") == "search-results":
            self._in_results = True
        elif tag == "a" and self._in_results:
            self.found.append(attributes.get("href"))

    def handle_endtag(self, tag: str) -> None:
        if tag == "table":
            self._table = None
        elif tag == "ol":
            self._in_results = False


def test_index_html_renders_in_chromium(fakes, tmp_path) -> None:
    register_standard_fakes(fakes, crash=True)
    figure = tmp_path / "figure.svg"
    figure.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="120" height="40">'
        '<rect width="120" height="40" fill="#1f5fa8"/></svg>'
    )

    @fakes.register(
        "seed002.fake.figure", source="seed 002 Fig. 3.2", statement="t", kinds=("tdoa",)
    )
    def with_figure(case, ctx):
        return [result(figures=(str(figure),))]

    out = tmp_path / "report"
    cases = [load_case(write_case(tmp_path, "case-a")), load_case(write_case(tmp_path, "case-b"))]
    document = write_report(run_claims(cases, seed=0), out)
    screenshot = out / "screenshot.png"
    done, page = _render(out / "index.html", tmp_path, f"--screenshot={screenshot}")
    assert page.body.get("data-loaded") == "yes", "the page's load event never ran"
    assert page.body.get("data-broken-images") == "0", "an embedded figure did not decode"
    assert "Uncaught" not in done.stderr, done.stderr[-2000:]
    expected = [(c["id"], c["case"]) for c in document["claims"]]
    assert page.rows == expected
    assert {claim for claim, _ in page.rows} == {c["id"] for c in document["registered"]}
    assert screenshot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert screenshot.stat().st_size > 10_000
    if os.environ.get("TRACKCERT_SCREENSHOT"):
        shutil.copyfile(screenshot, os.environ["TRACKCERT_SCREENSHOT"])
    assert json.loads((out / "report.json").read_text()) == document
    assert not any(page.hidden), "the summary filter hides rows by default"


def test_summary_filter_presets_from_the_address(fakes, tmp_path) -> None:
    """``#status=inconclusive&text=case-b`` shows exactly the inconclusive rows of case-b."""
    register_standard_fakes(fakes, crash=True)
    out = tmp_path / "report"
    cases = [load_case(write_case(tmp_path, "case-a")), load_case(write_case(tmp_path, "case-b"))]
    document = write_report(run_claims(cases, seed=0), out)
    url = (out / "index.html").as_uri() + "#status=inconclusive&text=case-b"
    _, page = _render(url, tmp_path)
    shown = [row for row, hidden in zip(page.rows, page.hidden, strict=True) if not hidden]
    expected = [
        (c["id"], c["case"])
        for c in document["claims"]
        if c["status"] == "inconclusive" and c["case"] == "case-b"
    ]
    assert shown == expected and len(expected) == 1


def test_case_page_renders_in_chromium(fakes, tmp_path) -> None:
    """A case page as its reader sees it: every claim on the case with its verdict, the case's
    geometry figure and the claims' figures loaded, the design answers, no script error."""
    register_standard_fakes(fakes)
    figure = tmp_path / "figure.png"
    figure.write_bytes(_png())

    @fakes.register("seed003.fake.thm2", source="seed 003 Thm 2", statement="t", kinds=("tdoa",))
    def with_figure(case, ctx):
        return [result(margin=0.5, figures=(str(figure),), evidence={"radius": 0.5})]

    out = tmp_path / "report"
    cases = [load_case(write_case(tmp_path, "case-a")), load_case(write_case(tmp_path, "case-b"))]
    document = write_report(run_claims(cases, seed=0), out)
    screenshot = out / "case-a.png"
    done, page = _render(out / "cases" / "case-a.html", tmp_path, f"--screenshot={screenshot}")
    assert page.body.get("data-loaded") == "yes", "the page's load event never ran"
    assert "Uncaught" not in done.stderr, done.stderr[-2000:]
    assert page.body.get("data-broken-images") == "0", "a figure of the case page did not load"
    expected = [(c["id"], c["status"]) for c in document["claims"] if c["case"] == "case-a"]
    assert page.case_rows == expected and len(expected) == 3
    assert "../figures/cases/case-a/geometry.png" in page.images
    assert "../figures/seed003.fake.thm2/case-a/figure.png" in page.images
    assert "Certified displacement margin" in done.stdout
    assert screenshot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_search_finds_the_papers_wording_in_chromium(fakes, tmp_path) -> None:
    """``contents.html#q=Theorem 2`` lists the claim whose source says ``Thm 2``; the overview's
    filter ``#text=Theorem 2`` shows its rows only."""
    register_standard_fakes(fakes)

    @fakes.register("seed003.fake.thm2", source="seed 003 Thm 2", statement="t", kinds=("tdoa",))
    def theorem(case, ctx):
        return [result()]

    @fakes.register("seed003.fake.thm23", source="seed 003 Thm 23", statement="t", kinds=("tdoa",))
    def other(case, ctx):
        return [result()]

    out = tmp_path / "report"
    document = write_report(run_claims([load_case(write_case(tmp_path, "case-a"))], seed=0), out)
    _, page = _render((out / "contents.html").as_uri() + "#q=Theorem%202", tmp_path)
    assert page.found == ["contents.html#claim-seed003.fake.thm2"]
    _, page = _render((out / "index.html").as_uri() + "#text=Theorem%202", tmp_path)
    shown = [row for row, hidden in zip(page.rows, page.hidden, strict=True) if not hidden]
    assert shown == [
        (c["id"], c["case"]) for c in document["claims"] if c["id"] == "seed003.fake.thm2"
    ]


def _png() -> bytes:
    """A small PNG drawn by matplotlib."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(2, 1.5), dpi=50)
    ax.plot([0, 1, 2], [2, 1, 3])
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", metadata={"Software": None})
    plt.close(fig)
    return buffer.getvalue()


def _render(
    target: Path | str, tmp_path: Path, *extra: str
) -> tuple[subprocess.CompletedProcess, _Page]:
    """Load ``target`` (a file or an address) in headless Chromium; the run and the parsed DOM."""
    url = target.as_uri() if isinstance(target, Path) else target
    done = subprocess.run(
        [CHROMIUM, *FLAGS, f"--user-data-dir={tmp_path / 'profile'}", *extra, "--dump-dom", url],
        capture_output=True,
        text=True,
        timeout=180,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    page = _Page()
    page.feed(done.stdout)
    return done, page
