"""A wall-clock limit on one check, so that one slow claim cannot hold up the whole report.

:func:`time_limit` arms ``SIGALRM`` for the ``with`` block; when it fires,
:class:`TimeLimitExceeded` is raised in the check's Python code, and the report records the claim
as ``inconclusive``. The
exception derives from :class:`BaseException`, like :class:`KeyboardInterrupt`, so that a
check's own ``except Exception`` (a solver failure turned into a verdict) cannot swallow it.
Native code (a solver's inner loop) is interrupted when it next returns to Python. The limit
needs ``SIGALRM`` and the main thread; elsewhere (Windows, a worker thread) :func:`enforceable`
is false and checks run unlimited.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["TimeLimitExceeded", "enforceable", "time_limit"]


class TimeLimitExceeded(BaseException):
    """A check ran past its time limit."""

    def __init__(self, seconds: float) -> None:
        super().__init__(f"the check did not finish within its time limit of {seconds:g} s")
        self.seconds = seconds


def enforceable() -> bool:
    """Whether :func:`time_limit` can interrupt a check here (``SIGALRM``, main thread)."""
    return hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()


@contextmanager
def time_limit(seconds: float | None) -> Iterator[None]:
    """Raise :class:`TimeLimitExceeded` in the ``with`` block after ``seconds`` of wall time.

    Parameters
    ----------
    seconds : float or None
        The limit; ``None`` (or a place where :func:`enforceable` is false) sets none.
    """
    if seconds is None or not enforceable():
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise TimeLimitExceeded(seconds)

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
