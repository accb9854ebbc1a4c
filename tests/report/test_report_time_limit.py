"""A check that uses up the report's CPU-time limit becomes inconclusive; the others still run;
a check that waits (a busy machine) is not stopped by it."""

from __future__ import annotations

import contextlib
import json
import threading
import time

import pytest
from report_fakes import register_standard_fakes, result, write_case
from typer.testing import CliRunner

from theory.cli import app
from theory.kinds import load_case
from theory.report.runner import run_claims
from theory.report.tasks import TimeLimitExceeded, clock_name, enforceable, time_limit

pytestmark = pytest.mark.skipif(not enforceable(), reason="needs PyThreadState_SetAsyncExc")
runner = CliRunner()


def _spin(seconds: float) -> None:
    """Busy Python code (a check that never returns in time)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        pass


def _timers() -> list[threading.Thread]:
    return [t for t in threading.enumerate() if t.name == "trackcert-time-limit" and t.is_alive()]


def test_the_limit_interrupts_python_code_and_leaves_no_timer() -> None:
    started = time.monotonic()
    with pytest.raises(TimeLimitExceeded, match=r"0\.05 s"), time_limit(0.05):
        _spin(5.0)
    assert time.monotonic() - started < 2.0
    assert _timers() == []


def test_waiting_is_not_work_so_it_does_not_count() -> None:
    """Wall time spent without the CPU — a sleep, or a core held by other processes on a loaded
    machine — leaves the budget as it was: a verdict never turns inconclusive from load."""
    with time_limit(0.1):
        time.sleep(0.4)  # four times the limit in wall time, almost no CPU
        _spin(0.02)
    assert _timers() == []


def test_the_cpu_of_other_threads_does_not_count() -> None:
    """The clock is the checking thread's: another thread's work (another task, the progress
    line, Dask's event loop) does not use its budget."""
    other = threading.Thread(target=_spin, args=(0.4,))
    other.start()
    try:
        with time_limit(0.15):
            time.sleep(0.4)
    finally:
        other.join()
    assert clock_name() == "thread CPU time"


def test_no_limit_and_a_check_that_finishes_in_time() -> None:
    with time_limit(None):
        _spin(0.01)
    with time_limit(5.0):
        _spin(0.01)
    assert _timers() == []
    _spin(0.05)  # nothing is raised after the block


def test_a_check_cannot_swallow_the_limit() -> None:
    """``except Exception`` in a check (a solver failure turned into a verdict) lets it through."""
    with pytest.raises(TimeLimitExceeded), time_limit(0.05):
        try:
            _spin(5.0)
        except Exception:  # pragma: no cover - the point is that this never runs
            pytest.fail("the time limit was caught as an Exception")


def test_the_limit_fires_in_a_worker_thread() -> None:
    """Dask runs a task in a worker thread, where SIGALRM cannot reach it."""
    seen: list[BaseException | None] = []

    def task() -> None:
        try:
            with time_limit(0.05):
                _spin(5.0)
        except TimeLimitExceeded as error:
            seen.append(error)
        else:  # pragma: no cover - the point is that this never runs
            seen.append(None)

    worker = threading.Thread(target=task)
    started = time.monotonic()
    worker.start()
    worker.join(10.0)
    assert not worker.is_alive() and time.monotonic() - started < 2.0
    (error,) = seen
    assert isinstance(error, TimeLimitExceeded) and error.seconds == 0.05
    assert threading.current_thread() is threading.main_thread()  # the main thread ran on


def test_an_expiry_racing_the_exit_raises_nothing_afterwards() -> None:
    """A limit that expires as the block ends raises nothing afterwards."""
    for _ in range(50):
        try:
            with time_limit(0.001):
                _spin(0.001)
        except TimeLimitExceeded:
            pass  # it fired inside the block: fine
        _spin(0.003)  # an exception scheduled and not received in the block would surface here
    assert _timers() == []


def test_after_a_fired_limit_a_failing_hypothesis_search_still_ends() -> None:
    """Regression: withdrawing a delivered exception (``SetAsyncExc(id, NULL)``) left CPython's
    pending-exception signal set, and a failing hypothesis search afterwards never ended."""
    from hypothesis import given, settings
    from hypothesis import strategies as st

    with pytest.raises(TimeLimitExceeded), time_limit(0.01):
        _spin(5.0)
    for _ in range(20):  # expiries racing the exit, received inside the block
        with contextlib.suppress(TimeLimitExceeded), time_limit(0.001):
            _spin(0.001)

    namespace: dict = {}
    exec(SMALL_IS_SMALL, namespace)  # not rewritten by pytest, like docs/property-based.md's
    search = settings(max_examples=25, derandomize=True, database=None, deadline=None)
    with pytest.raises(AssertionError):
        search(given(st.integers())(namespace["small"]))()


SMALL_IS_SMALL = """
def small(x):
    assert x < 10**6
"""


def _register_slow(fakes) -> None:
    @fakes.register("seed002.fake.slow", source="seed 002 §9", statement="slow", kinds=("tdoa",))
    def slow(case, ctx):
        _spin(5.0)
        return [result()]


def test_a_slow_check_is_inconclusive_and_the_report_goes_on(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    _register_slow(fakes)
    run = run_claims([load_case(write_case(tmp_path))], seed=0, seconds=0.2)
    statuses = {r.id: r.status for r in run.records}
    assert statuses == {
        "seed000.fake.model": "verified",
        "seed001.fake.observable": "verified",
        "seed002.fake.slow": "inconclusive",
        "seed003.fake.random": "verified",
    }
    (slow,) = [r for r in run.records if r.id == "seed002.fake.slow"]
    assert slow.method == "none" and "CPU-time limit of 0.2 s" in slow.message
    assert slow.evidence["error"]["type"] == "TimeLimitExceeded"
    assert run.all_expectations_met and run.time_limit == 0.2


def test_cli_time_limit_is_recorded(fakes, tmp_path) -> None:
    register_standard_fakes(fakes)
    _register_slow(fakes)
    out = tmp_path / "out"
    done = runner.invoke(
        app,
        ["report", str(write_case(tmp_path)), "-o", str(out), "--time-limit", "0.2",
         "--workers", "1"],
    )  # fmt: skip
    assert done.exit_code == 0, done.output
    document = json.loads((out / "report.json").read_text())
    assert document["environment"]["time_limit"] == 0.2
    assert document["environment"]["time_limit_enforced"] is True
    assert "Time limit per check: 0.2 s" in (out / "report.md").read_text()
    done = runner.invoke(
        app,
        ["report", str(write_case(tmp_path)), "-o", str(out), "--time-limit", "-1",
         "--workers", "1"],
    )  # fmt: skip
    assert done.exit_code == 2 and "Traceback" not in done.output
