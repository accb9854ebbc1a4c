"""Writing the report: reproducible bytes, figures and certificates copied, errata linked."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st
from report_fakes import register_standard_fakes, result, write_case

from theory.core.claims import NotApplicable
from theory.core.errors import CaseError
from theory.core.jsonable import canonical, dumps
from theory.kinds import load_case
from theory.report.document import parse_errata
from theory.report.render import markdown_to_html, write_report
from theory.report.runner import run_claims
from theory.report.tasks import check_document, check_with_cli, prechecked

matplotlib.use("Agg")
import matplotlib.pyplot as plt

FILES = ("report.json", "report.md", "index.html")
ERRATA = """# Errata

## Seed 001 (journal)

- **Theorem 1** says every agent observes; `seed001.fake.observable` shows when.
  A second line <script>alert(1)</script> of the same entry.
- Unlinked entry citing `seed001.unknown`.

## Seed 003 (pursuit)

### S(ω) in eq. (4)
Printed inconsistently; see seed003.fake.random.
"""


def _report(tmp_path: Path, name: str, seed: int, **kwargs) -> dict[str, bytes]:
    case = load_case(write_case(tmp_path, "case-a"))
    errata = tmp_path / "errata.md"
    errata.write_text(ERRATA)
    out = tmp_path / name
    write_report(run_claims([case], seed=seed), out, errata_path=errata, **kwargs)
    return {f: (out / f).read_bytes() for f in FILES}


def test_same_inputs_and_seed_give_identical_files(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    first = _report(tmp_path, "one", seed=5)
    second = _report(tmp_path, "two", seed=5)
    assert first == second
    other = _report(tmp_path, "three", seed=6)
    assert other["report.json"] != first["report.json"]


def test_report_json_follows_the_design_contract(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    document = json.loads(_report(tmp_path, "out", seed=1)["report.json"])
    assert {"claims", "environment"} <= set(document)
    for record in document["claims"]:
        assert {"id", "source", "case", "method", "status", "evidence"} <= set(record)
    model = document["claims"][0]
    assert model["id"] == "seed000.fake.model" and model["case"] == "-"
    assert model["evidence"] == {"value": 0.333333333333}
    environment = document["environment"]
    assert environment["seed"] == 1 and environment["packages"]["numpy"] == np.__version__
    assert environment["tolerances"] == {"rank_tol": [1e-09]}
    assert environment["cases"][0]["name"] == "case-a"
    assert len(environment["cases"][0]["sha256"]) == 64
    random_claim = next(c for c in document["claims"] if c["id"] == "seed003.fake.random")
    assert random_claim["probability_bound"] == 1e-12 and random_claim["seed"] is not None
    assert document["summary"]["all_expectations_met"] is True


def test_html_and_markdown_show_every_result(fakes, tmp_path) -> None:
    register_standard_fakes(fakes, crash=True)
    files = _report(tmp_path, "out", seed=0)
    page, text = files["index.html"].decode(), files["report.md"].decode()
    for claim in ("seed000.fake.model", "seed001.fake.observable", "seed003.fake.random"):
        assert f'data-claim="{claim}"' in page and f"`{claim}`" in text
    assert "ZeroDivisionError: division by zero in the fake check" in page
    assert "unchecked" in page and "Not every expectation is met" in text
    assert "<style>" in page and "<link" not in page  # self-contained


def test_each_result_shows_the_seed_it_used(fakes, tmp_path) -> None:
    """The derived seed where the check takes one, else the seed its evidence names."""
    register_standard_fakes(fakes)

    @fakes.register("seed002.fake.own-seed", source="s", statement="t", kinds=("tdoa",))
    def own_seed(case, ctx):
        return [result(evidence={"seed": 2})]

    files = _report(tmp_path, "out", seed=4)
    document = json.loads(files["report.json"])
    derived = next(c["seed"] for c in document["claims"] if c["id"] == "seed003.fake.random")
    text = files["report.md"].decode()
    assert f"seed {derived})" in text
    assert "seed 2 (the check's own; not derived from --seed))" in text
    assert "seed —)" in text  # the model claim uses no randomness


def test_not_applicable_pairs_are_listed_with_their_reason(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)

    @fakes.register("seed002.fake.lemma", source="s", statement="if H then P", kinds=("tdoa",))
    def lemma(case, ctx):
        raise NotApplicable("hypothesis H <fails> here")

    files = _report(tmp_path, "out", seed=0)
    document = json.loads(files["report.json"])
    assert document["not_applicable"] == [
        {"id": "seed002.fake.lemma", "case": "case-a", "reason": "hypothesis H <fails> here"}
    ]
    assert "hypothesis H &lt;fails&gt; here" in files["index.html"].decode()
    assert (
        "| `seed002.fake.lemma` | case-a | hypothesis H <fails> here |"
        in files["report.md"].decode()
    )
    assert all(c["id"] != "seed002.fake.lemma" for c in document["claims"])


def test_a_paper_section_lists_the_claims_that_cite_it(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)

    @fakes.register(
        "seed000.fake.cross", source="seed 000 Lemma 1; seed 002 Lemma 9", statement="t"
    )
    def cross(case, ctx):
        return [result(status="corrected")]

    text = _report(tmp_path, "out", seed=0)["report.md"].decode()
    seed002 = text[text.index("## Seed 002") : text.index("## Seed 003")]
    assert "| `seed000.fake.cross` | seed 000 Lemma 1; seed 002 Lemma 9 | 1 corrected |" in seed002
    seed001 = text[text.index("## Seed 001") : text.index("## Seed 002")]
    assert "seed000.fake.cross" not in seed001


def test_errata_are_linked_to_their_claims_and_escaped(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    files = _report(tmp_path, "out", seed=0)
    document = json.loads(files["report.json"])
    titles = [e["title"] for e in document["errata"]]
    assert titles == [
        "Theorem 1 says every agent observes; seed001.fake.observable shows when.",
        "Unlinked entry citing seed001.unknown.",
        "S(ω) in eq. (4)",
    ]
    first = document["errata"][0]["claims"][0]
    assert first["id"] == "seed001.fake.observable" and first["registered"]
    assert [r["status"] for r in first["results"]] == ["verified"]
    assert document["errata"][1]["claims"][0]["registered"] is False
    page = files["index.html"].decode()
    assert "<script>alert(1)" not in page and "&lt;script&gt;alert(1)" in page


def test_figures_are_copied_hashed_and_embedded(fakes, tmp_path) -> None:
    figure = tmp_path / "made-by-claim" / "error.png"
    figure.parent.mkdir()
    fig, ax = plt.subplots(figsize=(2, 1.5), dpi=50)
    ax.plot([0, 1, 2], [2, 1, 3])
    fig.savefig(figure, metadata={"Software": None})
    plt.close(fig)

    @fakes.register("seed000.figure", source="s", statement="t", kinds=("tdoa",))
    def with_figure(case, ctx):
        return [result(figures=(str(figure), "/no/such/file.png"))]

    files = _report(tmp_path, "out", seed=0)
    (record,) = json.loads(files["report.json"])["claims"]
    copied, missing = record["figures"]
    assert copied["path"] == "figures/seed000.figure/case-a/error.png"
    assert (tmp_path / "out" / copied["path"]).read_bytes() == figure.read_bytes()
    assert len(copied["sha256"]) == 64
    assert missing["sha256"] is None and "missing" in missing["error"]
    assert "data:image/png;base64," in files["index.html"].decode()
    assert "made-by-claim" not in files["report.json"].decode()


def test_certificates_are_copied_and_checked(fakes, tmp_path) -> None:
    certificate = tmp_path / "claim-output" / "cert.json"
    certificate.parent.mkdir()
    certificate.write_text('{"format": "trackcert-certificate/1"}')

    @fakes.register("seed000.cert", source="s", statement="t", kinds=("tdoa",))
    def with_certificate(case, ctx):
        return [result(evidence={"certificate": str(certificate)})]

    seen = []

    def checker(path: Path, out_dir: Path) -> dict:
        seen.append((path, (out_dir / path).read_text()))
        return {"command": f"trackcert check {path} --json", "valid": False, "checks": []}

    files = _report(tmp_path, "out", seed=0, checker=checker)
    (record,) = json.loads(files["report.json"])["claims"]
    assert record["evidence"]["certificate"] == "certificates/seed000.cert/case-a/cert.json"
    assert record["certificates"][0]["check"]["valid"] is False
    assert seen == [(Path(record["evidence"]["certificate"]), certificate.read_text())]
    assert "invalid" in files["index.html"].decode()


def test_certificate_documents_are_written_and_checked(fakes, tmp_path) -> None:
    """A certificate carried in the evidence becomes a file that proofs_check accepts."""
    from theory.tdoa.observability.certificates import generic_rank_certificates

    (document, *_) = generic_rank_certificates(load_case(write_case(tmp_path, "case-a")).spec)

    @fakes.register("seed000.doc", source="s", statement="t", kinds=("tdoa",))
    def with_document(case, ctx):
        evidence = {"certificate_document": document, "rank": 1}
        return [result(evidence=evidence)]

    files = _report(tmp_path, "out", seed=0)
    (record,) = json.loads(files["report.json"])["claims"]
    path = "certificates/seed000.doc/case-a/generic-rank.json"
    assert record["evidence"] == {"certificate": path, "rank": 1}
    ((entry),) = record["certificates"]
    assert entry["path"] == path and entry["check"]["valid"] is True
    assert entry["check"]["command"] == f"python -m proofs_check {path} --json"
    assert json.loads((tmp_path / "out" / path).read_text()) == document


def test_certificate_documents_are_checked_once_where_their_claim_ran(
    fakes, monkeypatch, tmp_path
) -> None:
    """The task's verdict (on the same bytes) is the report's: the checker does not run again."""
    from theory.tdoa.observability.certificates import generic_rank_certificates

    case = load_case(write_case(tmp_path, "case-a"))
    (document, *_) = generic_rank_certificates(case.spec)

    @fakes.register("seed000.doc", source="s", statement="t", kinds=("tdoa",))
    def with_document(case, ctx):
        return [result(evidence={"certificate_document": document})]

    run = run_claims([case], seed=0)
    ((digest, verdict),) = run.certificate_checks.items()
    assert verdict["valid"] is True and digest == check_document(document)[0]

    def never(relative: Path, out_dir: Path) -> dict:
        raise AssertionError("checked twice")

    monkeypatch.setattr("theory.report.tasks.check_with_cli", never)
    write_report(run, tmp_path / "out")
    (record,) = json.loads((tmp_path / "out" / "report.json").read_text())["claims"]
    ((entry),) = record["certificates"]
    assert entry["sha256"] == digest and entry["check"]["valid"] is True
    assert entry["check"]["command"] == f"python -m proofs_check {entry['path']} --json"


def test_prechecked_verdicts_apply_only_to_the_bytes_checked(tmp_path) -> None:
    (tmp_path / "bogus.json").write_text('{"format": "trackcert-certificate/1"}')
    stale = {"0" * 64: {"command": "x", "valid": True, "checks": []}}
    verdict = prechecked(stale)(Path("bogus.json"), tmp_path)
    assert verdict["valid"] is not True
    assert verdict["command"] == "python -m proofs_check bogus.json --json"


def test_cli_checker_never_validates_a_bogus_certificate(tmp_path) -> None:
    (tmp_path / "bogus.json").write_text('{"format": "trackcert-certificate/1"}')
    verdict = check_with_cli(Path("bogus.json"), tmp_path)
    assert verdict["valid"] is not True
    assert verdict["command"] == "python -m proofs_check bogus.json --json"


def test_unwritable_output_is_bad_input(fakes, tmp_path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(CaseError, match="-o"):
        write_report(run_claims([], seed=0), blocker / "sub")


def test_canonical_forms() -> None:
    data = {
        "b": np.array([[1, 2], [3, 4]], dtype=np.int64),
        "a": (np.float32(0.5), Fraction(-3, 7), sp.Rational(1, 3), sp.Symbol("T") ** 2),
        "c": {np.bool_(True), False},
        "d": [float("nan"), float("inf"), 1 + 2j, 0.1 + 0.2],
    }
    assert canonical(data) == {
        "a": [0.5, "-3/7", "1/3", "T**2"],
        "b": [[1, 2], [3, 4]],
        "c": [False, True],
        "d": ["nan", "inf", {"im": 2.0, "re": 1.0}, 0.3],
    }
    with pytest.raises(TypeError, match=r"\$\.x\[1\]: a object"):
        canonical({"x": [1, object()]})


json_like = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=4), inner),
    max_leaves=20,
)


@given(json_like)
def test_dumps_is_json_of_the_canonical_form(value) -> None:
    text = dumps(value)
    assert json.loads(text) == json.loads(json.dumps(canonical(value)))
    assert dumps(json.loads(text)) == text


def test_markdown_subset() -> None:
    html = markdown_to_html("Intro **bold** and `a<b`.\n\n- one\n  more\n- two [x](#y)")
    assert html == (
        "<p>Intro <strong>bold</strong> and <code>a&lt;b</code>.</p>\n"
        '<ul><li>one more</li><li>two <a href="#y">x</a></li></ul>'
    )


def test_errata_parser_reads_the_real_document() -> None:
    path = Path(__file__).resolve().parents[2] / "docs" / "errata.md"
    entries = parse_errata(path.read_text())
    assert all(e.paper in {"000", "001", "002", "003", "other"} for e in entries)
