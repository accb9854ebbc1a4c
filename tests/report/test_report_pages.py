"""The report read by case and by theorem (issue 26 item 5): case pages, the contents, the search
over the papers' wording, evidence as labelled tables, the legend and the margin table, the
case figures and the design section (issue 25)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from report_fakes import register_standard_fakes, result, write_case

from theory.core.claims import Status
from theory.kinds import load_case
from theory.registry import all_claims
from theory.report import design_section
from theory.report.case_figures import DRAWINGS, draw_case
from theory.report.evidence_table import evidence_rows, shown_value
from theory.report.glossary import MARGINS, STATUS_LEGEND, margin_of
from theory.report.render import write_report
from theory.report.runner import run_claims
from theory.report.search import canonical

# ------------------------------------------------------------------------------------ search
SAME = [
    ("Theorem 2", "Thm 2", "thm. 2", "THEOREM 2"),
    ("Thm 4.2.3", "Theorem 4.2.3", "theorem  4.2.3"),
    ("seed 003", "seed003", "Seed 003"),
    ("Lemma A.1.1", "Lem. A.1.1"),
    ("eq. (4.20)", "equation 4.20", "Eq (4.20)"),
    ("§4.2.2", "Section 4.2.2", "sec. 4.2.2"),
    ("Cor. 4.2.4", "Corollary 4.2.4"),
    ("Def. 5.2.4", "Definition 5.2.4"),
]


@pytest.mark.parametrize("spellings", SAME)
def test_the_papers_spellings_meet_in_one_form(spellings) -> None:
    assert len({canonical(s) for s in spellings}) == 1


WORDS = st.sampled_from(
    [
        "Theorem",
        "Thm.",
        "Lemma",
        "eq.",
        "(4.20)",
        "§",
        "seed",
        "003",
        "seed002",
        "Fig.",
        "3.2",
        "App.",
        "C.3",
        "ω",
        ";",
        "x_1",
    ]
)


@settings(max_examples=200, deadline=None)
@given(st.lists(WORDS, max_size=8).map(" ".join))
def test_canonical_form_is_idempotent(text: str) -> None:
    once = canonical(text)
    assert canonical(once) == once
    assert once == once.strip() and "  " not in once


# -------------------------------------------------------------------------- evidence tables
def test_evidence_becomes_labelled_rows_with_units() -> None:
    rows = evidence_rows(
        {
            "rank_tol": 1e-9,
            "T": 1.0,
            "gain": "661745/524288",
            "agents": [{"id": 1, "radius": 0.5}, {"id": 2, "radius": 0.25}],
            "nested": {"flag": True},
            "matrix": [[1, 2], [3, 4]],
        }
    )
    by_label = {r["label"]: r for r in rows}
    assert by_label["rank_tol"]["unit"] == "relative to the largest singular value"
    assert by_label["T"]["unit"] == "s"
    assert by_label["gain"]["value"] == "≈ 1.26218 (661745/524288)"
    assert [c["label"] for c in by_label["agents"]["columns"]] == ["id", "radius"]
    assert by_label["agents"]["columns"][1]["unit"] == "m"
    assert by_label["agents"]["records"] == [["1", "0.5"], ["2", "0.25"]]
    assert by_label["nested"]["rows"] == [{"label": "flag", "unit": "", "value": "true"}]
    assert by_label["matrix"]["value"] == "[1, 2]\n[3, 4]"


@given(st.fractions(max_denominator=10**6))
def test_rationals_are_shown_with_their_exact_text(value) -> None:
    text = f"{value.numerator}/{value.denominator}"
    shown = shown_value(text)
    assert shown.endswith(f"({text})")
    assert float(shown.split()[1]) == pytest.approx(float(value), rel=1e-5, abs=1e-300)


# ----------------------------------------------------------------------- legend and margins
def test_the_legend_explains_every_status() -> None:
    assert {s.value for s in Status} <= set(STATUS_LEGEND)


def test_every_margin_pattern_names_registered_claims() -> None:
    ids = [c.id for c in all_claims()]
    for pattern in MARGINS:
        assert any(margin_of(i) is MARGINS[pattern] for i in ids), pattern


# ------------------------------------------------------------------------------- the pages
def _report(fakes, tmp_path: Path) -> tuple[Path, dict]:
    register_standard_fakes(fakes)

    @fakes.register(
        "seed003.fake.thm2", source="seed 003 Thm 2", statement="ISS holds", kinds=("tdoa",)
    )
    def theorem(case, ctx):
        return [result(margin=0.5, evidence={"radius": 0.5, "gain": "1/4"})]

    cases = [load_case(write_case(tmp_path, "case-a")), load_case(write_case(tmp_path, "case-b"))]
    out = tmp_path / "report"
    return out, write_report(run_claims(cases, seed=0), out)


def test_a_page_per_case_with_every_claim_on_it(fakes, tmp_path) -> None:
    out, document = _report(fakes, tmp_path)
    for name in ("case-a", "case-b"):
        page = (out / "cases" / f"{name}.html").read_text()
        mine = [c for c in document["claims"] if c["case"] == name]
        rows = re.findall(r'<tr data-claim="([^"]+)" data-status="([^"]+)">', page)
        assert rows == [(c["id"], c["status"]) for c in mine]
        assert "geometry.png" in page and 'id="design"' in page
        assert "Certified displacement margin ρ" in page
        assert '<details class="evidence"><summary>' in page and "<details open" not in page
        assert '{"radius"' not in page  # evidence as a table, not raw JSON
    model = (out / "cases" / "model.html").read_text()
    assert "seed000.fake.model" in model


def test_contents_has_one_verdict_line_per_claim_linking_the_cases(fakes, tmp_path) -> None:
    for number in (10, 2):  # registered out of the paper's order

        @fakes.register(f"seed003.thm{number}.fake", source=f"seed 003 Thm {number}", statement="t")
        def numbered(case, ctx):
            return [result()]

    out, document = _report(fakes, tmp_path)
    page = (out / "contents.html").read_text()
    lines = re.findall(r'<tr id="claim-([^"]+)" class="line', page)
    assert sorted(lines) == sorted(c["id"] for c in document["registered"])
    assert lines.index("seed003.thm2.fake") < lines.index("seed003.thm10.fake")
    assert [line[:7] for line in lines] == sorted(line[:7] for line in lines)  # by paper
    assert 'href="cases/case-b.html#result-seed003.fake.thm2"' in page
    assert 'id="legend"' in page and 'id="margin-table"' in page


def test_search_index_finds_the_papers_wording(fakes, tmp_path) -> None:
    out, _ = _report(fakes, tmp_path)
    text = (out / "search-index.js").read_text()
    data = json.loads(text.removeprefix("window.TRACKCERT_SEARCH = ").rstrip(";\n"))
    for query in ("Theorem 2", "seed 003", "seed003 thm. 2"):
        hits = [e["href"] for e in data["entries"] if canonical(query) in e["words"]]
        assert "contents.html#claim-seed003.fake.thm2" in hits, query
    assert [e["href"] for e in data["entries"] if e["kind"] == "case"] == [
        "cases/case-a.html",
        "cases/case-b.html",
    ]


def test_case_figures_and_design_are_in_report_json(fakes, tmp_path) -> None:
    out, document = _report(fakes, tmp_path)
    (figure,) = document["case_figures"]["case-a"]
    assert figure["path"] == "figures/cases/case-a/geometry.png"
    assert (out / figure["path"]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    answers = document["design"]["case-a"]["answers"]
    assert answers["margin"]["radius"] > 0 and answers["redundancy_links"]["k"] >= 1


def test_a_failing_design_summary_is_reported_not_fatal(fakes, tmp_path, monkeypatch) -> None:
    def broken(case):
        raise ArithmeticError("no bound")

    summary = design_section.Summary("tests:broken", broken, lambda answers: [])
    monkeypatch.setitem(design_section.SUMMARIES, "tdoa", summary)
    out, document = _report(fakes, tmp_path)
    assert document["design"]["case-a"]["error"] == "ArithmeticError: no bound"
    assert (
        "The design summary failed: ArithmeticError: no bound"
        in (out / "cases" / "case-a.html").read_text()
    )


@pytest.mark.parametrize(
    "name",
    ["fig43-case-d", "sim-ch4-range21-b0", "ch5-example-1-wg", "pursuit-table1-n3", "pf-path3"],
)
def test_case_figures_are_drawn_the_same_twice(name: str, tmp_path: Path) -> None:
    case = load_case(name)
    assert case.kind in DRAWINGS
    first = draw_case(case, tmp_path / "one")
    second = draw_case(case, tmp_path / "two")
    assert first == second and first
    for file, _ in first:
        assert (tmp_path / "one" / file).read_bytes() == (tmp_path / "two" / file).read_bytes()


@pytest.mark.parametrize(
    ("name", "exact"), [("ch5-example-1-wg", "1/4"), ("ch5-example-2-wg", "4000000/11840481")]
)
def test_a_dkf_case_page_gives_the_exact_self_weight_supremum(name: str, exact: str) -> None:
    section = design_section.design_sections([load_case(name)])[name]
    assert section["answers"]["supremum"]["rational"] == exact
    assert f"exactly {exact}" in design_section.headline(section)[0]
