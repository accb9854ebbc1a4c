"""The report on the task engine: the same bytes whatever the workers, lost tasks and failing
checks recorded as inconclusive, an unreachable scheduler refused with exit 2."""

from __future__ import annotations

import json

import pytest
from report_fakes import register_standard_fakes, write_case
from typer.testing import CliRunner

from theory.cli import app
from theory.core.parallel import Outcome, engine
from theory.kinds import load_case
from theory.registry import all_claims
from theory.report.runner import run_claims
from theory.report.tasks import plan_tasks

runner = CliRunner()

CASES = ("fig43-case-d", "topology-coplanar-mirror", "ch5-example-1-wb")
"""Two tdoa cases and a dkf case (whose claims share one task and its cache)."""

ONLY = (
    "seed000.thm4.2.3",
    "seed000.lem4.2.2",
    "seed000.def5.2.4",
    "seed000.lem5.2.*",
    "seed002.eq3.1",
    "case.expect.tdoa",
)
"""Cheap claims: exact-random (seeded), numeric and LMI checks, a model claim, an expectation."""


def _report(out, *options: str):
    args = ["report", *CASES, "-o", str(out)]
    for pattern in ONLY:
        args += ["--only", pattern]
    return runner.invoke(app, [*args, *options])


def _files(out) -> dict[str, bytes]:
    """Every file of a report folder but timings.json (which records the run's own times)."""
    files = {p.relative_to(out).as_posix(): p for p in out.rglob("*") if p.is_file()}
    return {name: p.read_bytes() for name, p in sorted(files.items()) if name != "timings.json"}


@pytest.fixture(scope="module")
def serial_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("serial")
    done = _report(out, "--workers", "1")
    assert done.exit_code in (0, 3), done.output
    return out, done.exit_code


def test_two_workers_write_the_same_report(serial_report, tmp_path) -> None:
    serial, code = serial_report
    done = _report(tmp_path, "--workers", "2")
    assert done.exit_code == code, done.output
    assert _files(tmp_path) == _files(serial)
    assert {"index.html", "contents.html", "search-index.js", "cases/fig43-case-d.html"} <= set(
        _files(serial)
    )
    timings = json.loads((tmp_path / "timings.json").read_text())
    assert timings["workers"] == 2 and len(timings["worker_peak_rss"]) >= 1
    seen = {(c["id"], c["case"]) for c in timings["checks"]}
    starts = [c["started_seconds"] for c in timings["checks"]]
    assert all(0 <= s <= timings["wall_seconds"] for s in starts)  # each worker's timeline
    document = json.loads((tmp_path / "report.json").read_text())
    assert {(c["id"], c["case"]) for c in document["claims"]} <= seen
    assert "wall_seconds" not in (tmp_path / "report.json").read_text()


def test_a_cluster_started_apart_writes_the_same_report(serial_report, tmp_path) -> None:
    """``--scheduler ADDRESS``: worker processes that share nothing with this one but the files."""
    from distributed import LocalCluster  # imported here: 0.3 s off the collection

    serial, code = serial_report
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        done = _report(tmp_path, "--scheduler", cluster.scheduler_address)
    assert done.exit_code == code, done.output
    assert (tmp_path / "report.json").read_bytes() == (serial / "report.json").read_bytes()
    timings = json.loads((tmp_path / "timings.json").read_text())
    assert timings["scheduler"] == cluster.scheduler_address


def test_claims_taking_cache_share_one_task_per_case() -> None:
    claims = [c for c in all_claims() if c.id.startswith(("seed000.def5.2.4", "seed000.lem5.2"))]
    case = load_case("ch5-example-1-wb")
    tasks = plan_tasks([(c, case) for c in claims], seed=0, seconds=None, figures=False)
    shared = [t for t in tasks if len(t.claims) > 1]
    assert len(shared) == 1 and set(shared[0].claims) >= {"seed000.def5.2.4", "seed000.lem5.2.2"}


def test_a_check_missing_on_the_workers_is_inconclusive(fakes, tmp_path) -> None:
    """Fake claims exist only in this process: the workers cannot run them, the report goes on."""
    register_standard_fakes(fakes)
    with engine(2) as two:
        run = run_claims([load_case(write_case(tmp_path))], seed=0, runner=two)
    assert {r.status for r in run.records} == {"inconclusive"}
    assert all("unknown claim" in r.message for r in run.records)
    assert len(run.records) == 3


class _LosingRunner:
    """An engine whose every task is lost (a worker killed, a payload that did not travel)."""

    serial = False

    def completed(self, fn, items):
        for i, _ in enumerate(items):
            yield Outcome(i, error=RuntimeError("worker lost"))


def test_a_lost_task_is_inconclusive(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    run = run_claims([load_case(write_case(tmp_path))], seed=5, runner=_LosingRunner())
    assert [r.status for r in run.records] == ["inconclusive"] * 3
    assert all(r.method == "none" and "worker lost" in r.message for r in run.records)
    (seeded,) = [r for r in run.records if r.id == "seed003.fake.random"]
    assert seeded.seed is not None  # the derived seed is still stated


def test_unreachable_scheduler_exits_2(monkeypatch, tmp_path) -> None:
    monkeypatch.setattr("theory.core.parallel.CONNECT_TIMEOUT", 1.0)
    done = runner.invoke(
        app,
        [
            "report",
            "fig43-case-d",
            "-o",
            str(tmp_path / "out"),
            "--only",
            "seed000.eq4.6",
            "--scheduler",
            "tcp://127.0.0.1:9",
        ],
    )
    assert done.exit_code == 2, done.output
    assert "--scheduler" in done.output and "Traceback" not in done.output
    assert not (tmp_path / "out" / "report.json").exists()


def _missing_worker_modules() -> list[str]:
    import sys

    from theory.report.tasks import worker_modules

    return [m for m in worker_modules() if m not in sys.modules]


def test_a_worker_started_with_the_preload_has_every_claim_module_before_its_first_task() -> None:
    """``dask worker ADDRESS --preload theory.report.tasks``: a spawned worker (Dask's
    default, as ``dask worker`` starts them) imports the claim modules as it starts."""
    import dask
    from distributed import Client, LocalCluster

    with (
        dask.config.set({"distributed.worker.multiprocessing-method": "spawn"}),
        LocalCluster(
            n_workers=1,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            preload=["theory.report.tasks"],
        ) as cluster,
        Client(cluster) as client,
    ):
        (missing,) = client.run(_missing_worker_modules).values()
    assert missing == []
