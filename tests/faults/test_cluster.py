"""Faults of the cluster: no worker, an unreachable scheduler, a killed worker; and the BLAS
threads every task runs with, wherever it runs."""

from __future__ import annotations

import functools
import os
import signal
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from theory.cli import app
from theory.core.errors import ClusterError
from theory.core.parallel import TaskRunner, engine
from theory.core.verdicts import EXIT_BAD_INPUT, EXIT_FAULT

runner = CliRunner()


@pytest.fixture(scope="module")
def two_workers():
    from distributed import LocalCluster  # imported here: 0.3 s off the collection

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        yield cluster.scheduler_address


def test_a_scheduler_without_workers_is_a_fault_after_the_wait(tmp_path, monkeypatch) -> None:
    from distributed import LocalCluster

    monkeypatch.setenv("TRACKCERT_WORKER_TIMEOUT", "1")
    out = tmp_path / "sim"
    with LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        started = time.monotonic()
        done = runner.invoke(
            app,
            ["simulate", "pursuit-table1-n1", "--steps", "20", "-o", str(out),
             "--scheduler", cluster.scheduler_address],
        )  # fmt: skip
    assert done.exit_code == EXIT_FAULT, done.output
    assert time.monotonic() - started < 60
    message = done.stderr.strip().splitlines()[-1]
    assert message.startswith("fault: the Dask scheduler at ")
    assert "has no worker after 1 s" in message
    assert "TRACKCERT_WORKER_TIMEOUT" in message and "dask worker" in message
    assert not out.exists()


def test_a_bad_wait_setting_is_bad_input(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("TRACKCERT_WORKER_TIMEOUT", "soon")
    done = runner.invoke(
        app, ["simulate", "pursuit-table1-n1", "-o", str(tmp_path / "o"), "--scheduler", "tcp://127.0.0.1:9"]
    )
    assert done.exit_code == EXIT_BAD_INPUT
    assert "<environment>: field 'TRACKCERT_WORKER_TIMEOUT'" in done.stderr


@pytest.mark.parametrize("where", ["option", "environment"])
def test_an_unreachable_scheduler_names_where_its_address_came_from(
    tmp_path, monkeypatch, where
) -> None:
    monkeypatch.setattr("theory.core.parallel.CONNECT_TIMEOUT", 0.5)
    args = ["simulate", "pursuit-table1-n1", "--steps", "20", "-o", str(tmp_path / "o")]
    if where == "option":
        args += ["--scheduler", "tcp://127.0.0.1:9"]
        named = "<command line>: field '--scheduler'"
    else:
        monkeypatch.setenv("TRACKCERT_SCHEDULER", "tcp://127.0.0.1:9")
        named = "<environment>: field 'TRACKCERT_SCHEDULER'"
    done = runner.invoke(app, args)
    assert done.exit_code == EXIT_BAD_INPUT and named in done.stderr, done.stderr
    assert "Traceback" not in done.output


def test_a_malformed_scheduler_address_is_bad_input(tmp_path) -> None:
    done = runner.invoke(
        app, ["simulate", "pursuit-table1-n1", "-o", str(tmp_path / "o"), "--scheduler", "nowhere"]
    )
    assert done.exit_code == EXIT_BAD_INPUT and "'--scheduler'" in done.stderr


class _Gone:
    """A client whose cluster has lost every worker."""

    def nthreads(self) -> dict:
        return {}


def test_losing_every_worker_is_a_fault_after_the_wait() -> None:
    engine_runner = TaskRunner(2, "tcp://example:8786", wait=0.05)
    idle = engine_runner._check_workers(_Gone(), None)
    assert idle is not None
    time.sleep(0.1)
    with pytest.raises(ClusterError, match=r"has had no worker for 0\.05 s"):
        engine_runner._check_workers(_Gone(), idle)


def _square_killing_once(marker: str, x: int) -> int:
    """x², but the first call anywhere kills its own worker process first (SIGKILL)."""
    try:
        os.close(os.open(marker, os.O_CREAT | os.O_EXCL))
    except FileExistsError:
        return x * x
    os.kill(os.getpid(), signal.SIGKILL)
    raise AssertionError("unreachable")


def test_a_killed_worker_changes_no_result(two_workers, tmp_path) -> None:
    """Dask reruns the task of a worker that died (its nanny starts another): the results are
    those of the serial path."""
    task = functools.partial(_square_killing_once, str(tmp_path / "killed"))
    with engine(scheduler=two_workers) as cluster:
        results = cluster.map(task, list(range(12)))
    assert Path(tmp_path / "killed").exists()
    assert results == [x * x for x in range(12)]


def _blas_threads(_: int) -> list[int]:
    from threadpoolctl import threadpool_info

    return sorted({pool["num_threads"] for pool in threadpool_info()})


def test_every_task_runs_with_one_blas_thread_wherever_it_runs(two_workers) -> None:
    """Serial (in this process, even when its BLAS runs more threads) and on workers alike: a
    result never depends on how many threads summed a product."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=2), engine(1) as serial:
        assert serial.map(_blas_threads, [0, 1]) == [[1], [1]]
    with engine(scheduler=two_workers) as cluster:
        assert cluster.map(_blas_threads, [0, 1, 2]) == [[1], [1], [1]]
