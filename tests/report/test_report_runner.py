"""The report's runner: every claim runs, failures become inconclusive records, seeds derive."""

from __future__ import annotations

import numpy as np
import pytest
from report_fakes import register_standard_fakes, result, write_case

from theory.core.claims import NotApplicable
from theory.core.errors import CaseError
from theory.kinds import load_case
from theory.registry import all_claims
from theory.report.runner import run_claims, select_claims
from theory.report.tasks import MODEL_CASE, derive_seed, paper_of


def test_every_claim_runs_on_every_case_of_its_kind(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    cases = [load_case(write_case(tmp_path, "a")), load_case(write_case(tmp_path, "b"))]
    run = run_claims(cases, seed=7)
    pairs = [(r.id, r.case) for r in run.records]
    assert pairs == [
        ("seed000.fake.model", MODEL_CASE),
        ("seed001.fake.observable", "a"),
        ("seed001.fake.observable", "b"),
        ("seed003.fake.random", "a"),
        ("seed003.fake.random", "b"),
    ]
    assert [r.paper for r in run.records] == ["000", "001", "001", "003", "003"]
    assert run.all_expectations_met


def test_a_crashing_claim_never_stops_the_report(fakes, tmp_path) -> None:
    register_standard_fakes(fakes, crash=True)
    run = run_claims([load_case(write_case(tmp_path))], seed=0)
    crashed = [r for r in run.records if r.id == "seed001.fake.observable"]
    assert len(crashed) == 1
    record = crashed[0]
    assert record.status == "inconclusive" and record.method == "none"
    assert "ZeroDivisionError: division by zero in the fake check" in record.message
    assert record.evidence["error"]["type"] == "ZeroDivisionError"
    assert record.evidence["error"]["where"].startswith("tests/report/report_fakes.py:")
    assert {r.id for r in run.records} == {
        "seed000.fake.model",
        "seed001.fake.observable",
        "seed003.fake.random",
    }
    assert [e.verdict for e in run.expectations] == ["unchecked"]
    assert not run.all_expectations_met


@pytest.mark.parametrize(
    ("returned", "message"),
    [
        ("verified", "returned a str, not a list"),
        (["verified"], "returned a str, not a ClaimResult"),
        (None, "returned a NoneType"),
    ],
)
def test_malformed_answers_become_inconclusive(fakes, returned, message) -> None:
    fakes.register("seed000.bad", source="s", statement="t")(lambda case, ctx: returned)
    (record,) = run_claims([], seed=0).records
    assert record.status == "inconclusive" and message in record.message


def test_evidence_without_json_form_is_inconclusive(fakes) -> None:
    @fakes.register("seed000.opaque", source="s", statement="t")
    def opaque(case, ctx):
        return [result(evidence={"solver": object()})]

    (record,) = run_claims([], seed=0).records
    assert record.status == "inconclusive"
    assert "evidence.solver: a object has no JSON form" in record.message


def test_an_empty_answer_means_not_applicable(fakes, tmp_path) -> None:
    never = fakes.register("seed000.never", source="s", statement="t", kinds=("tdoa",))
    never(lambda case, ctx: [])
    run = run_claims([load_case(write_case(tmp_path))], seed=0)
    assert run.records == () and run.not_applicable == (("seed000.never", "four-path", ""),)


def test_not_applicable_carries_its_reason(fakes, tmp_path) -> None:
    @fakes.register("seed000.lemma", source="s", statement="if H then P", kinds=("tdoa",))
    def lemma(case, ctx):
        raise NotApplicable("hypothesis H fails on this case")

    run = run_claims([load_case(write_case(tmp_path))], seed=0, seconds=5.0)
    assert run.records == ()
    assert run.not_applicable == (
        ("seed000.lemma", "four-path", "hypothesis H fails on this case"),
    )
    assert all_claims()[0].results(None) == []


def test_claims_of_other_kinds_do_not_run(fakes, tmp_path) -> None:
    calls = []
    dkf = fakes.register("seed000.dkf", source="s", statement="t", kinds=("dkf",))
    dkf(lambda case, ctx: calls.append(case))
    run = run_claims([load_case(write_case(tmp_path))], seed=0)
    assert calls == [] and run.records == ()


def test_seeds_are_derived_per_claim_and_case(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    cases = [load_case(write_case(tmp_path, "a")), load_case(write_case(tmp_path, "b"))]
    first, again, other = (run_claims(cases, seed=s).records for s in (3, 3, 4))
    seeded = [r for r in first if r.id == "seed003.fake.random"]
    assert [r.seed for r in seeded] == [derive_seed(3, "seed003.fake.random", c) for c in "ab"]
    assert seeded[0].seed != seeded[1].seed
    assert first == again
    assert [r.evidence for r in first] != [r.evidence for r in other]
    draw = np.random.default_rng(seeded[0].seed).normal(size=3)
    np.testing.assert_allclose(seeded[0].evidence["draw"], draw, rtol=1e-11)
    assert [r.seed for r in first if r.id != "seed003.fake.random"] == [None, None, None]


def test_duplicate_case_names_are_refused(fakes, tmp_path) -> None:
    case = load_case(write_case(tmp_path))
    with pytest.raises(CaseError, match="distinct case names"):
        run_claims([case, case])


def test_progress_hook_sees_every_run(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    seen = []
    run_claims([load_case(write_case(tmp_path))], progress=lambda d, k: seen.append((d, k)))
    assert seen == [
        (1, "seed000.fake.model on model"),
        (2, "seed001.fake.observable on four-path"),
        (3, "seed003.fake.random on four-path"),
    ]


def test_select_claims_by_pattern(fakes) -> None:
    register_standard_fakes(fakes)
    ids = [c.id for c in select_claims(all_claims(), ["seed00[01].*"])]
    assert ids == ["seed000.fake.model", "seed001.fake.observable"]
    assert len(select_claims(all_claims(), [])) == 3


def test_paper_of() -> None:
    assert paper_of("seed002.eq3.1", "") == "002"
    assert paper_of("network.metropolis", "see seed 003, eq. (4)") == "003"
    assert paper_of("design.rule", "docs/topology.md") == "other"


def test_claims_that_draw_get_their_own_figure_folder(fakes, tmp_path) -> None:
    seen = []

    @fakes.register("seed002.fake.draws", source="s", statement="t", kinds=("tdoa",))
    def draws(case, ctx):
        folder = ctx.figure_folder()
        seen.append(folder)
        if folder is None:
            return [result()]
        (folder / "plot.png").write_bytes(b"png")
        return [result(figures=(str(folder / "plot.png"),))]

    case = load_case(write_case(tmp_path, "a b"))
    run_claims([case], seed=0)
    run = run_claims([case], seed=0, figure_dir=tmp_path / "figures")
    assert seen[0] is None and seen[1].parts[-2:] == ("seed002.fake.draws", "a_b")
    (record,) = run.records
    assert record.figures == (
        str(tmp_path / "figures" / "seed002.fake.draws" / "a_b" / "plot.png"),
    )
