"""A wall-clock budget for one check: hostile input is refused in bounded time.

The static limits of :mod:`proofs_check.parse` and the work estimate of :mod:`proofs_check.kinds`
refuse most oversized certificates before any arithmetic; rationals whose denominators do not
share factors can still make exact sums grow, so the arithmetic loops also call :func:`tick`,
which refuses the certificate (exit code 2) once the budget opened by :func:`budget` is spent.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager

from proofs_check.parse import MalformedError

__all__ = ["DEFAULT_SECONDS", "budget", "tick"]

DEFAULT_SECONDS = 60.0
"""Default budget of one ``python -m proofs_check`` run."""

_deadline = [float("inf")]


@contextmanager
def budget(seconds: float) -> Iterator[None]:
    """Allow ``seconds`` of arithmetic inside the ``with`` block; no limit outside it."""
    _deadline[0] = time.monotonic() + seconds
    try:
        yield
    finally:
        _deadline[0] = float("inf")


def tick() -> None:
    """Refuse the certificate if the budget is spent."""
    if time.monotonic() > _deadline[0]:
        raise MalformedError("refused: the exact arithmetic exceeded the time budget")
