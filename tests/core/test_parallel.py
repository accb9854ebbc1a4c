"""The task engine: results in item order whatever the workers, failures reported, bad settings
refused (exit 2 from the commands)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import cloudpickle
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.claims import Context, RunCache
from theory.core.errors import CaseError
from theory.core.parallel import SCHEDULER_SETTING, THREAD_SETTINGS, engine, scheduler_address
from theory.sim.simulate import monte_carlo

# Workers unpickle this module's functions by value: the test folder is not importable there.
cloudpickle.register_pickle_by_value(sys.modules[__name__])


def _walk(spec: dict, rng: np.random.Generator) -> np.ndarray:
    """A random walk of ``spec["steps"]`` steps (one Monte Carlo run)."""
    return np.cumsum(rng.normal(size=spec["steps"]))


def _square_or_fail(x: int) -> int:
    if x in (3, 5):
        raise ValueError(f"item {x} fails")
    return x * x


FIRST_LOAD = textwrap.dedent(
    """
    import json, os, sys
    from theory.core.parallel import engine

    def task(_):
        loaded = "scipy.linalg" in sys.modules
        import scipy.linalg  # noqa: F401
        from threadpoolctl import threadpool_info

        return loaded, sorted({pool["num_threads"] for pool in threadpool_info()})

    with engine(1) as serial:
        print(json.dumps(serial.map(task, [0])[0]))
    """
)
"""A serial task that loads SciPy's BLAS itself: whether it was loaded before, the pool sizes."""


@pytest.mark.parametrize("pinned", [True, False])
def test_a_blas_loaded_inside_a_task_runs_one_thread(pinned: bool) -> None:
    """With every THREAD_SETTINGS variable at 1 (as ``trackcert`` sets them) the engine leaves
    SciPy's BLAS unloaded and a task loading it gets one thread; otherwise the engine loads it
    first, so that threadpoolctl pins it. Either way the task sees only one-thread pools."""
    env = {k: v for k, v in os.environ.items() if k not in THREAD_SETTINGS}
    env |= dict.fromkeys(THREAD_SETTINGS, "1") if pinned else {"OPENBLAS_NUM_THREADS": "2"}
    done = subprocess.run(
        [sys.executable, "-c", FIRST_LOAD], capture_output=True, text=True, check=True,
        cwd=Path(__file__).resolve().parents[2], env=env,
    )  # fmt: skip
    loaded, pools = json.loads(done.stdout.splitlines()[-1])
    assert loaded is not pinned
    assert pools == [1]


@pytest.fixture(scope="module")
def cluster():
    """Two single-threaded worker processes, started by the test."""
    from distributed import LocalCluster  # imported here: 0.3 s off the collection

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as started:
        yield started


@given(st.lists(st.integers(-1000, 1000), max_size=30))
def test_serial_map_is_the_list_comprehension(items: list[int]) -> None:
    done: list[int] = []
    with engine(1) as runner:
        assert runner.serial
        assert runner.map(abs, items, progress=done.append) == [abs(i) for i in items]
    assert done == list(range(1, len(items) + 1))


def test_a_task_inside_a_task_runs_pinned_and_pins_once(monkeypatch) -> None:
    """Tasks run with the BLAS pools at one thread, a nested task too (a sweep point's own
    Monte Carlo), without a second threadpoolctl call; the pools are restored afterwards."""
    import scipy.linalg  # noqa: F401 (its BLAS loaded before the pools are read)
    import threadpoolctl

    calls: list[int] = []
    original = threadpoolctl.threadpool_limits

    def counted(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)

    def threads(_: object = None) -> set[int]:
        return {pool["num_threads"] for pool in threadpoolctl.threadpool_info()}

    monkeypatch.setattr(threadpoolctl, "threadpool_limits", counted)
    with original(limits=2), engine(1) as runner:
        before = threads()
        outer = runner.map(lambda _: (threads(), runner.map(threads, [0])[0]), [0])
        after = threads()
    assert outer == [({1}, {1})] and len(calls) == 1
    assert after == before and 2 in before


def test_monte_carlo_is_identical_on_one_and_two_workers(cluster) -> None:
    spec = {"steps": 50}
    serial = monte_carlo(spec, simulate=_walk, runs=12, seed=7, workers=1)
    done: list[int] = []
    with engine(scheduler=cluster.scheduler_address) as runner:
        assert not runner.serial
        spread = monte_carlo(
            spec, simulate=_walk, runs=12, seed=7, runner=runner, progress=done.append
        )
    assert len(serial) == 12
    for a, b in zip(serial, spread, strict=True):
        assert a.tobytes() == b.tobytes()
    assert done == list(range(1, 13))
    assert not np.array_equal(serial[0], serial[1])  # the runs are seeded apart


def test_particle_monte_carlo_is_identical_on_one_and_two_workers(cluster) -> None:
    """seed 002's runs are tasks too (``theory.particle.experiments.monte_carlo``)."""
    from theory.kinds import load_case
    from theory.particle.experiments import monte_carlo as pf_monte_carlo

    spec = load_case("pf-topology-b").spec
    serial = pf_monte_carlo(spec, runs=3, seed=5, snapshot_steps=(0, 3))
    with engine(scheduler=cluster.scheduler_address) as runner:
        spread = pf_monte_carlo(spec, runs=3, seed=5, snapshot_steps=(0, 3), runner=runner)
    for name in ("errors", "estimates", "paths"):
        assert getattr(serial, name).tobytes() == getattr(spread, name).tobytes()
    assert sorted(spread.snapshots) == [0, 3]
    assert serial.snapshots[3].tobytes() == spread.snapshots[3].tobytes()


def test_completed_reports_each_failure_and_map_raises_the_first(cluster) -> None:
    with engine(scheduler=cluster.scheduler_address) as runner:
        outcomes = sorted(runner.completed(_square_or_fail, list(range(8))), key=lambda o: o.index)
        assert [o.index for o in outcomes] == list(range(8))
        assert [type(o.error) for o in outcomes if o.error] == [ValueError, ValueError]
        assert [o.value for o in outcomes if o.error is None] == [0, 1, 4, 16, 36, 49]
        with pytest.raises(ValueError, match="item 3 fails"):
            runner.map(_square_or_fail, list(range(8)))
    with engine(1) as serial, pytest.raises(ValueError, match="item 3 fails"):
        serial.map(_square_or_fail, list(range(8)))


def test_bad_settings_are_case_errors(monkeypatch) -> None:
    with pytest.raises(CaseError, match="--workers"), engine(0):
        pass
    monkeypatch.setenv(SCHEDULER_SETTING, "tcp://example:8786")
    assert scheduler_address(None) == "tcp://example:8786"
    assert scheduler_address("tcp://other:1") == "tcp://other:1"


def test_unreachable_scheduler_is_a_case_error(monkeypatch) -> None:
    monkeypatch.setattr("theory.core.parallel.CONNECT_TIMEOUT", 1.0)
    with (
        pytest.raises(CaseError, match="--scheduler") as raised,
        engine(scheduler="tcp://127.0.0.1:9") as runner,
    ):
        runner.map(abs, [1, 2])
    assert "dask scheduler" in raised.value.hint


def test_unreachable_scheduler_started_in_the_background_fails_at_the_first_map(
    monkeypatch,
) -> None:
    monkeypatch.setattr("theory.core.parallel.CONNECT_TIMEOUT", 1.0)
    with pytest.raises(CaseError, match="--scheduler"), engine(scheduler="tcp://127.0.0.1:9") as r:
        r.start()
        r.map(abs, [1, 2])


def test_start_on_the_serial_path_starts_nothing() -> None:
    with engine(1) as runner:
        runner.start()
        assert runner.map(abs, [-1, -2]) == [1, 2]
        assert runner.size == 1


def test_local_workers_started_in_the_background_have_the_preload_imported(tmp_path) -> None:
    """A fresh process (so that it starts its own forkserver): its two workers are up before the
    first map and have imported the preload modules, and only those, before any task runs; they
    run with :data:`CLUSTER_CONFIG`'s housekeeping intervals."""
    (tmp_path / "probe.py").write_text(
        "import sys\n\nimport dask\n\n\ndef loaded(name):\n    return name in sys.modules\n"
        "\n\ndef setting(name):\n    return dask.config.get(name)\n"
    )
    script = textwrap.dedent(
        """
        import probe
        from theory.core.parallel import CLUSTER_CONFIG, engine

        if __name__ == "__main__":
            with engine(2, preload=["theory.tdoa.model"]) as runner:
                runner.start()
                print(runner.map(probe.loaded, ["theory.tdoa.model", "theory.pursuit.dekf"]))
                print(runner.size)
                print(runner.map(probe.setting, [k for k in CLUSTER_CONFIG if "admin" in k]))
        """
    )
    root = Path(__file__).resolve().parents[2]
    done = subprocess.run(
        [sys.executable, "-c", script],
        cwd=tmp_path,
        env={"PYTHONPATH": f"{tmp_path}:{root}", "PATH": "/usr/bin:/bin"},
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    loaded, size, settings = done.stdout.splitlines()
    assert (loaded, size) == ("[True, False]", "2")
    assert settings == "['200ms', '5s']"  # the workers run with the cluster's quieter settings


def test_run_cache_computes_once_per_key() -> None:
    calls: list[str] = []
    cache = RunCache()

    def compute(name: str):
        return lambda: calls.append(name) or name.upper()

    assert cache.get("a", compute("a")) == "A"
    assert cache.get("a", compute("again")) == "A"
    assert Context(cache).shared("b", compute("b")) == "B"
    assert Context().shared("a", compute("fresh")) == "FRESH"  # a fresh context: its own cache
    cache.put("c", "given")
    assert Context(cache).shared("c", compute("c")) == "given"
    assert calls == ["a", "b", "fresh"]
    assert (cache.hits, cache.misses) == (2, 2)
