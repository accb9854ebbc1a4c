"""A wall-clock limit on one check, so that one slow claim cannot hold up the whole report.

:func:`time_limit` arms a :class:`threading.Timer` for the ``with`` block; when it fires, it raises
:class:`TimeLimitExceeded` in the thread running the block (``PyThreadState_SetAsyncExc``), and the
report records the claim as ``inconclusive``. One mechanism serves every thread: the main thread
of ``--workers 1`` and the worker thread in which a Dask task runs (where ``SIGALRM`` cannot be
used). When the block exits first, the timer is cancelled, and an exception it scheduled in the
meantime is received and dropped before the block is left, so nothing is raised after it.

The exception derives from :class:`BaseException`, like :class:`KeyboardInterrupt`, so that a
check's own ``except Exception`` (a solver failure turned into a verdict) cannot swallow it.
Native code (a solver's inner loop) is interrupted when it next returns to Python.
"""

from __future__ import annotations

import ctypes
import threading
import time
from types import TracebackType

__all__ = ["TimeLimitExceeded", "enforceable", "time_limit"]


class TimeLimitExceeded(BaseException):
    """A check ran past its time limit.

    The exception is raised asynchronously as a class (no arguments), so the limit travels as the
    class attribute ``seconds`` of a subclass made per limit (:func:`_expired`).
    """

    seconds: float = 0.0

    def __init__(self, seconds: float | None = None) -> None:
        if seconds is not None:
            self.seconds = seconds
        super().__init__(f"the check did not finish within its time limit of {self.seconds:g} s")


def _expired(seconds: float) -> type[TimeLimitExceeded]:
    """A subclass of :class:`TimeLimitExceeded` whose instances say ``seconds``."""
    return type("TimeLimitExceeded", (TimeLimitExceeded,), {"seconds": seconds})


def enforceable() -> bool:
    """Whether :func:`time_limit` can interrupt a check (``PyThreadState_SetAsyncExc``)."""
    return hasattr(ctypes, "pythonapi") and hasattr(ctypes.pythonapi, "PyThreadState_SetAsyncExc")


def _set_async_exc(thread_id: int, exception: type[BaseException]) -> int:
    """Schedule ``exception`` in thread ``thread_id``."""
    return ctypes.pythonapi.PyThreadState_SetAsyncExc(
        ctypes.c_ulong(thread_id), ctypes.py_object(exception)
    )


class time_limit:  # noqa: N801 (used as a context manager, like contextlib's)
    """Raise :class:`TimeLimitExceeded` in the ``with`` block after ``seconds`` of wall time.

    Parameters
    ----------
    seconds : float or None
        The limit; ``None`` (or a Python where :func:`enforceable` is false) sets none.
    """

    def __init__(self, seconds: float | None) -> None:
        self.seconds = seconds
        self._lock = threading.Lock()
        self._timer: threading.Timer | None = None
        self._thread_id = 0
        self._open = False
        self._fired = False

    def __enter__(self) -> time_limit:
        if self.seconds is None or not enforceable():
            return self
        self._thread_id = threading.get_ident()
        self._open = True
        self._timer = threading.Timer(self.seconds, self._expire)
        self._timer.daemon = True
        self._timer.start()
        return self

    def _expire(self) -> None:
        with self._lock:
            if self._open:
                self._fired = True
                _set_async_exc(self._thread_id, _expired(float(self.seconds or 0.0)))

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        if self._timer is None:
            return
        with self._lock:
            self._open = False
        delivered = kind is not None and issubclass(kind, TimeLimitExceeded)
        if self._fired and not delivered:
            _absorb_pending()
        self._timer.cancel()
        self._timer.join()  # returns at once: the timer is cancelled or has fired
        self._timer = None


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
