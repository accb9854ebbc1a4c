"""A limit on the CPU time of one check, so that one runaway claim cannot hold up the whole report
— and a busy machine cannot turn a verdict into "inconclusive".

The limit is on **work**, not on the clock on the wall: :func:`time_limit` counts the CPU time
of the thread running the ``with`` block (its POSIX per-thread CPU clock,
``time.pthread_getcpuclockid``; where a platform has none, the CPU time of the whole process,
which can only make the limit stricter). Time spent waiting for a core that other processes
hold is not counted: on a loaded two-core machine a check that needs 40 s of CPU may take
300 s of wall time and still finishes. A watcher thread sleeps for the CPU budget still unspent
(a thread cannot use more CPU than wall time, so it never wakes late), reads the clock again and,
once the budget is spent, raises :class:`TimeLimitExceeded` in the thread running the block
(``PyThreadState_SetAsyncExc``), and the report records the claim as ``inconclusive``. One
mechanism serves every thread: the main thread of ``--workers 1`` and the worker thread in which a
Dask task runs (where ``SIGALRM`` cannot be used). When the block exits first, the watcher is
stopped, and an exception it scheduled in the meantime is received and dropped before the block
is left, so nothing is raised after it.

The work a check hands to other processes (the certificate checker it runs) is not counted; BLAS
runs on the calling thread (:mod:`theory.core.parallel` pins it to one thread). A check that
blocks without working (a deadlock) is not stopped by this limit.

The exception derives from :class:`BaseException`, like :class:`KeyboardInterrupt`, so that a
check's own ``except Exception`` (a solver failure turned into a verdict) cannot swallow it.
Native code (a solver's inner loop) is interrupted when it next returns to Python.
"""

from __future__ import annotations

import ctypes
import threading
import time
from collections.abc import Callable
from types import TracebackType

__all__ = ["TimeLimitExceeded", "clock_name", "enforceable", "time_limit"]


class TimeLimitExceeded(BaseException):
    """A check ran past its time limit.

    The exception is raised asynchronously as a class (no arguments), so the limit travels as the
    class attribute ``seconds`` of a subclass made per limit (:func:`_expired`).
    """

    seconds: float = 0.0

    def __init__(self, seconds: float | None = None) -> None:
        if seconds is not None:
            self.seconds = seconds
        super().__init__(f"the check used up its CPU-time limit of {self.seconds:g} s")


def _expired(seconds: float) -> type[TimeLimitExceeded]:
    """A subclass of :class:`TimeLimitExceeded` whose instances say ``seconds``."""
    return type("TimeLimitExceeded", (TimeLimitExceeded,), {"seconds": seconds})


def enforceable() -> bool:
    """Whether :func:`time_limit` can interrupt a check (``PyThreadState_SetAsyncExc``)."""
    return hasattr(ctypes, "pythonapi") and hasattr(ctypes.pythonapi, "PyThreadState_SetAsyncExc")


def clock_name() -> str:
    """What :func:`time_limit` counts here: ``thread CPU time`` or, lacking a per-thread clock,
    ``process CPU time``."""
    return "thread CPU time" if hasattr(time, "pthread_getcpuclockid") else "process CPU time"


def _cpu_clock(thread_id: int) -> Callable[[], float]:
    """A function reading the CPU seconds of thread ``thread_id`` (readable from any thread)."""
    try:
        clock = time.pthread_getcpuclockid(thread_id)
    except (AttributeError, OSError):
        return time.process_time
    return lambda: time.clock_gettime(clock)


def _set_async_exc(thread_id: int, exception: type[BaseException]) -> int:
    """Schedule ``exception`` in thread ``thread_id``."""
    return ctypes.pythonapi.PyThreadState_SetAsyncExc(
        ctypes.c_ulong(thread_id), ctypes.py_object(exception)
    )


class time_limit:  # noqa: N801 (used as a context manager, like contextlib's)
    """Raise :class:`TimeLimitExceeded` in the ``with`` block once it has used ``seconds`` of CPU.

    Parameters
    ----------
    seconds : float or None
        The limit, in CPU seconds of the thread entering the block; ``None`` (or a Python where
        :func:`enforceable` is false) sets none.
    """

    def __init__(self, seconds: float | None) -> None:
        self.seconds = seconds
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._watcher: threading.Thread | None = None
        self._thread_id = 0
        self._open = False
        self._fired = False

    def __enter__(self) -> time_limit:
        if self.seconds is None or not enforceable():
            return self
        self._thread_id = threading.get_ident()
        clock = _cpu_clock(self._thread_id)
        self._open = True
        self._watcher = threading.Thread(
            target=self._watch, args=(clock, clock()), name="trackcert-time-limit", daemon=True
        )
        self._watcher.start()
        return self

    def _watch(self, clock: Callable[[], float], start: float) -> None:
        budget = float(self.seconds or 0.0)
        while not self._stop.wait(max(budget - (clock() - start), 0.0)):
            if clock() - start >= budget:
                self._expire(budget)
                return

    def _expire(self, budget: float) -> None:
        with self._lock:
            if self._open:
                self._fired = True
                _set_async_exc(self._thread_id, _expired(budget))

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        if self._watcher is None:
            return
        with self._lock:
            self._open = False
        delivered = kind is not None and issubclass(kind, TimeLimitExceeded)
        if self._fired and not delivered:
            _absorb_pending()
        self._stop.set()
        self._watcher.join()  # returns at once: the watcher is stopped or has fired
        self._watcher = None


def _absorb_pending(seconds: float = 0.1) -> None:
    """Receive, here, a :class:`TimeLimitExceeded` scheduled just as the block ended, and drop it.

    An exception scheduled with ``PyThreadState_SetAsyncExc`` is raised at the interpreter's next
    check (every loop iteration), so this loop receives it at once. It is never *withdrawn*
    (``PyThreadState_SetAsyncExc(id, NULL)``): CPython would leave its "asynchronous exception
    pending" signal set with nothing to raise, and every later instruction of the thread would
    take the interpreter's slow path (a hypothesis search after it ran about 1000× slower).
    If the block itself swallowed the exception, the loop simply runs out after ``seconds``.
    """
    end = time.monotonic() + seconds
    try:
        while time.monotonic() < end:
            pass
    except TimeLimitExceeded:
        return
