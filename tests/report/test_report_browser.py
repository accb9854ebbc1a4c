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
    """Collects the body's data attributes and the summary table's rows."""

    def __init__(self) -> None:
        super().__init__()
        self.body: dict[str, str | None] = {}
        self.rows: list[tuple[str | None, str | None]] = []
        self.hidden: list[bool] = []
        self._in_summary = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        attributes = dict(attrs)
        if tag == "body":
            self.body = attributes
        elif tag == "table":
            self._in_summary = attributes.get("id") == "summary-table"
        elif tag == "tr" and self._in_summary and "data-claim" in attributes:
            self.rows.append((attributes["data-claim"], attributes.get("data-case")))
            self.hidden.append("hidden" in attributes)

    def handle_endtag(self, tag: str) -> None:
        if tag == "table":
            self._in_summary = False


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
