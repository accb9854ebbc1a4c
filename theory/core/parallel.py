"""Independent tasks on ``dask.distributed``, with results in task order whatever the worker count.

Every embarrassingly parallel piece of trackcert (the report's checks, Monte Carlo runs, sweep
points, falsify examples) goes through :func:`engine`: a context that yields a :class:`TaskRunner`
whose :meth:`~TaskRunner.map` runs ``fn(item)`` for each item and returns the results **in item
order**, so that a caller seeding each item explicitly gets identical results with 1, 2 or 64
workers and whatever the order in which they finish; :meth:`~TaskRunner.completed` yields each
task's :class:`Outcome` (value or exception) as it finishes, for callers that show progress or
must survive a lost task (the report).

Where the tasks run:

* ``workers=1`` (and no scheduler): in this process, one after the other (the debugging path;
  no Dask at all);
* by default: an in-process ``distributed.LocalCluster`` of one single-threaded worker process per
  local core, started on the first :meth:`~TaskRunner.map` of more than one task (or in the
  background from :meth:`~TaskRunner.start`, while the caller prepares its tasks) and closed when
  the context ends. Its workers are forked from a ``forkserver`` that has imported the caller's
  ``preload`` modules once, so no worker imports them again;
* ``scheduler="tcp://host:8786"`` (or the ``TRACKCERT_SCHEDULER`` setting): an existing Dask
  cluster, whose workers must have trackcert installed. The engine waits at most
  ``$TRACKCERT_WORKER_TIMEOUT`` seconds (default :data:`WORKER_TIMEOUT`) for a first worker, and
  as long again whenever the cluster has lost every worker while tasks are pending; then it
  raises :class:`~theory.core.errors.ClusterError` (CLI exit 4) instead of waiting for ever.

Inside a task (on a Dask worker) :func:`engine` always runs serially: nested parallelism would
only oversubscribe the cores.

Every task runs with its BLAS and OpenMP thread pools pinned to one thread (``threadpoolctl``),
wherever it runs — in this process on the serial path, on a local or remote worker — so a
result never depends on how many threads summed a matrix product (:func:`_one_thread`).
"""

from __future__ import annotations

import functools
import logging
import os
import queue
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any, TypeVar

from theory.core.errors import COMMAND_LINE, ENVIRONMENT, CaseError, ClusterError

__all__ = [
    "SCHEDULER_SETTING",
    "THREAD_SETTINGS",
    "WORKER_TIMEOUT_SETTING",
    "Outcome",
    "TaskRunner",
    "default_workers",
    "engine",
    "in_worker",
    "one_thread_pools",
    "scheduler_address",
    "worker_timeout",
]

SCHEDULER_SETTING = "TRACKCERT_SCHEDULER"
"""Environment setting naming a Dask scheduler address (``--scheduler`` overrides it)."""

WORKER_TIMEOUT_SETTING = "TRACKCERT_WORKER_TIMEOUT"
"""Environment setting: seconds to wait for a worker on a scheduler that has none."""

CONNECT_TIMEOUT = 10.0
"""Seconds to wait for a scheduler given by address before reporting it unreachable."""

WORKER_TIMEOUT = 60.0
"""Default seconds to wait for a worker (a ``dask worker`` joins in a few seconds)."""

POLL_SECONDS = 2.0
"""While tasks are pending and none finishes, how often the engine counts the cluster's workers."""

WORKER_MEMORY = "2GiB"
"""Memory limit of each LocalCluster worker (Dask pauses, then restarts, a worker above it)."""

CLUSTER_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.worker.multiprocessing-method": "forkserver",
    "distributed.admin.tick.interval": "200ms",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "500ms",
}
"""Dask settings of the local cluster (its scheduler and nannies in this process, its workers).

* No statistical profiler: it samples the task thread's stack every 10 ms under the GIL and made
  the report's checks cost about 45 % more CPU on 2 workers (2-worker report: 98 s → 76 s wall,
  same report.json). Workers of a cluster started apart take
  ``DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED=False`` (docs/parallel.md).
* Worker processes forked from a ``forkserver`` (Dask's default is ``spawn``) that has imported
  the engine's ``preload`` modules: the imports (about 3 s of CPU for the report's claims) and
  the module-level work they do are paid once, not once per worker. Dask sets its thread-count
  variables (``OMP_NUM_THREADS``…, ``distributed.nanny.pre-spawn-environ``) in this process
  before the first worker starts, so the forkserver, started then, inherits them.
* Fewer housekeeping wake-ups: the event loops' health tick every 200 ms instead of 20 ms (it
  only times the loop, for warnings), the system monitor (metrics for a dashboard we do not
  start) every 5 s instead of 0.5 s, the memory monitor every 0.5 s instead of 0.1 s (a worker
  past its limit is still stopped, half a second later at most). An idle 2-worker cluster took
  4.1 % of a core in this process and 1.9 % in each worker with Dask's defaults, 1.1 % and
  0.4–0.5 % with these: about 3.5 s of CPU less over a one-minute report on cores that the
  checks keep busy."""

THREAD_SETTINGS = ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")
"""The thread-count variables a BLAS or OpenMP pool reads when its library is loaded: Dask's
``distributed.nanny.pre-spawn-environ`` sets them to 1 in every worker, and
:func:`one_thread_pools` in the ``trackcert`` process."""

T = TypeVar("T")
R = TypeVar("R")


def one_thread_pools() -> None:
    """Set every :data:`THREAD_SETTINGS` variable the user has not set to 1, before NumPy loads.

    Every task runs with its pools pinned to one thread anyway (:func:`_one_thread`), as on a
    Dask worker; a pool started at its default size only costs its threads' start-up: OpenBLAS's
    threads spin on load, 0.05 s of CPU for NumPy's and 0.17 s for SciPy's on 2 cores (``python
    -c "import numpy, scipy.linalg"``: 0.38 s of CPU, 0.21 s with these set; the wall time is
    the same). Called by the ``trackcert`` command before any import of NumPy; a library caller's
    process is left as its owner set it.
    """
    for name in THREAD_SETTINGS:
        os.environ.setdefault(name, "1")


def default_workers() -> int:
    """All local cores (``os.cpu_count()``), at least 1."""
    return max(1, os.cpu_count() or 1)


def scheduler_address(option: str | None = None) -> str | None:
    """The scheduler: ``option`` (``--scheduler``), else ``$TRACKCERT_SCHEDULER``, else none."""
    return option or os.environ.get(SCHEDULER_SETTING) or None


def worker_timeout() -> float:
    """Seconds to wait for a worker: ``$TRACKCERT_WORKER_TIMEOUT``, else :data:`WORKER_TIMEOUT`."""
    text = os.environ.get(WORKER_TIMEOUT_SETTING)
    if text is None:
        return WORKER_TIMEOUT
    try:
        seconds = float(text)
    except ValueError:
        seconds = 0.0
    if not 0 < seconds < float("inf"):
        raise CaseError(WORKER_TIMEOUT_SETTING, "a number of seconds > 0", text, file=ENVIRONMENT)
    return seconds


def in_worker() -> bool:
    """Whether this code runs inside a task on a Dask worker (a process that has not imported
    ``distributed`` is none: the question then costs no import of it)."""
    if "distributed" not in sys.modules:
        return False
    try:
        from distributed import get_worker
    except ImportError:  # pragma: no cover - distributed is a dependency
        return False
    try:
        get_worker()
    except ValueError:
        return False
    return True


class TaskRunner:
    """Runs independent tasks; made by :func:`engine`.

    ``workers`` local processes (1: the serial path; ignored with a ``scheduler`` address),
    ``preload`` the modules the local cluster's forkserver imports, ``named`` the (field, file)
    the scheduler's address came from (for messages), ``wait`` the seconds to wait for a worker.
    """

    def __init__(
        self,
        workers: int,
        scheduler: str | None,
        preload: Sequence[str] = (),
        *,
        named: tuple[str, str] = ("--scheduler", COMMAND_LINE),
        wait: float = WORKER_TIMEOUT,
    ) -> None:
        self.workers = workers
        self.scheduler = scheduler
        self.preload = tuple(preload)
        self.named = named
        self.wait = wait
        self._client: Any = None
        self._cluster: Any = None
        self._starting: threading.Thread | None = None
        self._start_error: BaseException | None = None

    @property
    def serial(self) -> bool:
        """Whether tasks run in this process, one after the other."""
        return (self.workers == 1 and self.scheduler is None) or in_worker()

    def map(
        self,
        fn: Callable[[T], R],
        items: Sequence[T],
        *,
        progress: Callable[[int], None] | None = None,
    ) -> list[R]:
        """``[fn(item) for item in items]``, the calls spread over the workers, in item order.

        ``fn`` is picklable (module level, or a ``functools.partial`` of one) and depends only
        on its argument; ``progress`` is called with the number of tasks finished. The first
        exception (in item order) a task raised is re-raised here.
        """
        results: list[Any] = [None] * len(items)
        errors: dict[int, BaseException] = {}
        for done, outcome in enumerate(self.completed(fn, items), start=1):
            if outcome.error is None:
                results[outcome.index] = outcome.value
            elif self.serial:
                raise outcome.error  # the first in item order: no need to run the rest
            else:
                errors[outcome.index] = outcome.error
            if progress is not None:
                progress(done)
        if errors:
            raise errors[min(errors)]
        return results

    def completed(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[Outcome]:
        """The outcome of ``fn(item)`` for each item, in completion order (item order on the
        serial path); a task that raised, or whose worker died, yields its exception."""
        if self.serial or (len(items) <= 1 and self.scheduler is None):
            yield from _serial(fn, items)  # one task is not worth starting a local cluster
            return
        client = self._connect()
        futures = client.map(functools.partial(_one_thread, fn), list(items), pure=False)
        index = {future.key: i for i, future in enumerate(futures)}
        finished: queue.SimpleQueue = queue.SimpleQueue()
        for future in futures:
            future.add_done_callback(finished.put)
        remaining, idle_since = len(futures), None
        try:
            while remaining:
                try:
                    future = finished.get(timeout=POLL_SECONDS)
                except queue.Empty:
                    idle_since = self._check_workers(client, idle_since)
                    continue
                remaining -= 1
                yield _outcome(index[future.key], future)
        finally:
            client.cancel(futures)

    def _check_workers(self, client: Any, idle_since: float | None) -> float | None:
        """``None`` while the cluster has a worker, else when it lost the last; raise once that
        is :attr:`wait` seconds ago (the tasks would wait for ever)."""
        if client.nthreads():
            return None
        now = time.monotonic()
        if idle_since is None:
            return now
        if now - idle_since >= self.wait:
            raise ClusterError(self._no_worker(f"has had no worker for {self.wait:g} s"))
        return idle_since

    def _no_worker(self, what: str) -> str:
        return (
            f"the Dask scheduler at {self.scheduler} {what} (the wait is "
            f"${WORKER_TIMEOUT_SETTING}); start one with `dask worker {self.scheduler}`"
        )

    @property
    def size(self) -> int:
        """How many workers ran (or would run) the tasks: 1 on the serial path, the cluster's
        worker count once connected, else :attr:`workers`."""
        if self.serial:
            return 1
        if self._client is not None:
            return len(self._client.scheduler_info().get("workers", {}))
        return self.workers

    def start(self) -> None:
        """Begin connecting in the background: the local cluster's workers start (or the
        scheduler is reached) while the caller prepares its tasks; the first :meth:`map` waits
        for it. Nothing happens on the serial path or once connected.

        A failure (an unreachable scheduler) is raised by the first :meth:`map`.
        """
        if self.serial or self._client is not None or self._starting is not None:
            return
        self._starting = threading.Thread(
            target=self._start_in_background, name="trackcert-engine-start", daemon=True
        )
        self._starting.start()

    def _start_in_background(self) -> None:
        try:
            self._open()
        except BaseException as error:  # re-raised in the caller's thread by _connect
            self._start_error = error

    def _connect(self) -> Any:
        if self._starting is not None:
            self._starting.join()
            self._starting = None
            if self._start_error is not None:
                error, self._start_error = self._start_error, None
                raise error
        if self._client is None:
            self._open()
        return self._client

    def _open(self) -> None:
        """Connect to the scheduler, or start the local cluster and connect to it."""
        from distributed import Client, LocalCluster

        if self.scheduler is not None:
            try:
                self._client = Client(self.scheduler, timeout=CONNECT_TIMEOUT)
            except (OSError, ValueError) as error:
                field, file = self.named
                raise CaseError(
                    field,
                    "the address of a running Dask scheduler",
                    self.scheduler,
                    file=file,
                    hint=f"{error}; start one with `dask scheduler` and `dask worker ADDRESS`",
                ) from None
            try:
                self._client.wait_for_workers(1, timeout=self.wait)
            except TimeoutError:
                raise ClusterError(
                    self._no_worker(f"has no worker after {self.wait:g} s")
                ) from None
            return
        import dask

        with dask.config.set(CLUSTER_CONFIG):  # the cluster's processes start with it
            _preload_forkserver(self.preload)
            self._cluster = LocalCluster(
                n_workers=self.workers,
                threads_per_worker=1,
                processes=True,
                memory_limit=WORKER_MEMORY,
                dashboard_address=":0",  # the health server on a free port (8787 may be taken)
                scheduler_kwargs={"dashboard": False},
            )
        self._client = Client(self._cluster)

    def close(self) -> None:
        """Close the client and the local cluster, if they were started.

        Dask's shutdown chatter (a worker killed after a few seconds of closing) is not shown:
        the results are in by then.
        """
        if self._starting is not None:
            self._starting.join()
            self._starting = None
        logger = logging.getLogger("distributed")
        level = logger.level
        logger.setLevel(logging.ERROR)
        try:
            if self._client is not None:
                self._client.close()
            if self._cluster is not None:
                self._cluster.close()
        finally:
            logger.setLevel(level)
        self._client = self._cluster = None


def _preload_forkserver(modules: Sequence[str]) -> None:
    """Have the forkserver import ``modules`` (and ``distributed``) before it forks any worker.

    Called under :data:`CLUSTER_CONFIG`. Dask's ``get_mp_context`` sets its own preload list (its
    required packages) on first use; ours, set after it, replaces that list. A forkserver that is
    already running (an earlier cluster of this process) keeps the modules it has.
    """
    if not modules:
        return
    from distributed.utils import get_mp_context

    get_mp_context().set_forkserver_preload(["distributed", *modules])


@dataclass(frozen=True)
class Outcome:
    """One finished task of :meth:`TaskRunner.completed`: the item's ``index``, and ``fn(item)``
    or the exception it raised (or the worker's failure, e.g. ``KilledWorker``)."""

    index: int
    value: Any = None
    error: BaseException | None = None


def _serial(fn: Callable[[T], R], items: Sequence[T]) -> Iterator[Outcome]:
    for i, item in enumerate(items):
        try:
            value = _one_thread(fn, item)
        except Exception as error:
            yield Outcome(i, error=error)
        else:
            yield Outcome(i, value)


def _one_thread(fn: Callable[[T], R], item: T) -> R:
    """``fn(item)`` with the BLAS and OpenMP pools of this process at one thread.

    The same on every path: a multi-threaded BLAS sums a product in another order than a
    single-threaded one, and the last digit of a result would then depend on where its task ran.
    SciPy's BLAS is loaded first (numpy's is loaded with numpy), so that a task importing
    ``scipy.linalg`` for the first time does not get an unpinned pool — unless every
    :data:`THREAD_SETTINGS` variable is 1 (as ``trackcert`` sets them, :func:`one_thread_pools`):
    a BLAS loaded later then starts with one thread. A task inside a task (a
    sweep point's own one-run Monte Carlo) finds the pools pinned already and pins nothing:
    threadpoolctl's search of the loaded libraries costs a few ms a call.
    """
    if getattr(_PINNED, "active", False):
        return fn(item)
    if not _loads_with_one_thread():
        import scipy.linalg  # noqa: F401 (loads SciPy's BLAS, so that it is pinned too)
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1):
        _PINNED.active = True
        try:
            return fn(item)
        finally:
            _PINNED.active = False


def _loads_with_one_thread() -> bool:
    return all(os.environ.get(name) == "1" for name in THREAD_SETTINGS)


_PINNED = threading.local()
"""``active`` while this thread runs a task under :func:`_one_thread`."""


def _outcome(i: int, future: Any) -> Outcome:
    if future.status == "finished":
        return Outcome(i, future.result())
    try:
        future.result()
    except Exception as error:
        return Outcome(i, error=error)
    return Outcome(i, error=RuntimeError(f"task {i} ended as {future.status!r}"))


@contextmanager
def engine(
    workers: int | None = None, scheduler: str | None = None, *, preload: Sequence[str] = ()
) -> Iterator[TaskRunner]:
    """A :class:`TaskRunner` for the ``with`` block; its cluster (if any) is closed at the end.

    Parameters
    ----------
    workers : int, optional
        Local worker processes; default all local cores; 1 runs every task in this process.
    scheduler : str, optional
        Address of an existing Dask scheduler (default ``$TRACKCERT_SCHEDULER``); its workers
        run the tasks and ``workers`` is ignored.
    preload : sequence of str, optional
        Modules the local workers' forkserver imports before forking them (what the tasks will
        import); none: Dask's default list.

    Yields
    ------
    TaskRunner

    Raises
    ------
    CaseError
        If ``workers < 1`` (field ``--workers``), the scheduler cannot be reached (its first
        use; field ``--scheduler`` or ``TRACKCERT_SCHEDULER``), or ``$TRACKCERT_WORKER_TIMEOUT``
        is not a number of seconds.
    ClusterError
        If the scheduler has no worker for ``$TRACKCERT_WORKER_TIMEOUT`` seconds while tasks
        wait (its first use).
    """
    count = default_workers() if workers is None else workers
    if count < 1:
        raise CaseError("--workers", "an integer ≥ 1", workers, file=COMMAND_LINE)
    address = scheduler_address(scheduler)
    named = ("--scheduler", COMMAND_LINE) if scheduler else (SCHEDULER_SETTING, ENVIRONMENT)
    wait = worker_timeout() if address is not None else WORKER_TIMEOUT
    runner = TaskRunner(count, address, preload, named=named, wait=wait)
    try:
        yield runner
    finally:
        runner.close()
