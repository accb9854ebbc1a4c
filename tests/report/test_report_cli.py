"""``trackcert report``: exit codes follow the expectations; bad input exits 2 writing nothing."""

from __future__ import annotations

import json

from report_fakes import register_standard_fakes, write_case
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases

runner = CliRunner()


def _report(*args: str):
    """The command in this process (``--workers 1``): the fake claims exist only here."""
    return runner.invoke(app, ["report", "--workers", "1", *args])


def test_met_expectations_exit_0(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    out = tmp_path / "out"
    done = _report(str(write_case(tmp_path)), "-o", str(out), "--seed", "3")
    assert done.exit_code == 0, done.output
    assert sorted(p.name for p in out.iterdir()) == [
        "cases",
        "contents.html",
        "figures",
        "index.html",
        "report.json",
        "report.md",
        "search-index.js",
        "timings.json",
    ]
    # cases named: no model claims, so no model page
    assert sorted(p.name for p in (out / "cases").iterdir()) == ["four-path.html"]
    assert "every expectation is met" in done.stdout
    assert json.loads((out / "report.json").read_text())["seed"] == 3


def test_unmet_expectation_exits_1(fakes, tmp_path) -> None:
    register_standard_fakes(fakes, observable=(True, True, False, True))
    done = _report(str(write_case(tmp_path)), "-o", str(tmp_path / "out"))
    assert done.exit_code == 1
    (expectation,) = json.loads((tmp_path / "out" / "report.json").read_text())["expectations"]
    assert expectation["verdict"] == "unmet"
    assert expectation["observations"][0]["matches"] is False
    shown = " ".join(done.stdout.split())
    assert "unmet: four-path expect.observable" in shown
    assert "seed001.fake.observable │ 1" in shown  # one row per claim, results counted


def test_crashing_check_is_reported_and_exits_3(fakes, tmp_path) -> None:
    """The only observer of ``observable`` crashed: the expectation is unchecked, which the
    exit-code policy (theory.core.verdicts) reports as inconclusive, not as failed."""
    register_standard_fakes(fakes, crash=True)
    done = _report(str(write_case(tmp_path)), "-o", str(tmp_path / "out"), "--model-claims")
    assert done.exit_code == 3
    document = json.loads((tmp_path / "out" / "report.json").read_text())
    assert [e["verdict"] for e in document["expectations"]] == ["unchecked"]
    statuses = {c["id"]: c["status"] for c in document["claims"]}
    assert statuses == {
        "seed000.fake.model": "verified",
        "seed001.fake.observable": "inconclusive",
        "seed003.fake.random": "verified",
    }


def test_a_case_without_expectations_exits_0(fakes, tmp_path) -> None:
    register_standard_fakes(fakes, crash=True)
    case = write_case(tmp_path, expect={})
    assert _report(str(case), "-o", str(tmp_path / "out")).exit_code == 0


def test_bad_case_exits_2_and_writes_nothing(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    good = write_case(tmp_path)
    bad = write_case(tmp_path, "bad", expect={"colour": "red"})
    out = tmp_path / "out"
    done = _report(str(good), str(bad), "-o", str(out))
    assert done.exit_code == 2
    assert "bad.yaml: field 'expect.colour'" in " ".join(done.output.split())
    assert "Traceback" not in done.output
    assert not out.exists()
    assert _report("no-such-case", "-o", str(out)).exit_code == 2
    assert _report(str(good), "--only", "nothing.*", "-o", str(out)).exit_code == 2
    missing = str(tmp_path / "none.md")
    assert _report(str(good), "--errata", missing, "-o", str(out)).exit_code == 2
    assert not out.exists()


def test_default_is_every_bundled_case_with_the_real_registry(tmp_path) -> None:
    out = tmp_path / "out"
    done = _report("-o", str(out), "--only", "seed000.eq4.6", "--only", "*.metropolis", "--json")
    document = json.loads(done.stdout)
    assert document == json.loads((out / "report.json").read_text())
    assert [c["name"] for c in document["environment"]["cases"]] == list(bundled_cases())
    assert {c["id"] for c in document["claims"]} == {
        "seed000.eq4.6",
        "seed000.sec4.2.2.metropolis",
    }
    verdicts = {e["verdict"] for e in document["expectations"]}
    assert verdicts == {"unchecked"}  # the two claims selected observe no expect key
    assert done.exit_code == 3, done.output


def test_a_report_of_named_cases_runs_the_model_claims_only_when_asked(fakes, tmp_path) -> None:
    """A case named: its own claims (``seed001.fake.observable``, ``seed003.fake.random``), the
    case-independent ``seed000.fake.model`` only with --model-claims or an --only selecting it;
    the full bundled report runs them by default (test above)."""
    register_standard_fakes(fakes)
    case = str(write_case(tmp_path))

    def ran(*options: str) -> set[str]:
        out = tmp_path / "-".join(("out", *options)).replace("*", "x")
        done = _report(case, "-o", str(out), *options)
        assert done.exit_code in (0, 3), done.output  # 3: no claim left observes the expect key
        return {c["id"] for c in json.loads((out / "report.json").read_text())["claims"]}

    own = {"seed001.fake.observable", "seed003.fake.random"}
    assert ran() == own
    assert ran("--model-claims") == own | {"seed000.fake.model"}
    assert ran("--only", "seed000.*") == {"seed000.fake.model"}
    assert ran("--only", "*", "--no-model-claims") == own
