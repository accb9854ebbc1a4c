"""A wall-clock budget for one check: hostile input is refused in bounded time.

The static limits of :mod:`proofs_check.parse` and the work estimate of :mod:`proofs_check.kinds`
refuse most oversized certificates before any arithmetic; rationals whose denominators do not
share factors can still make exact sums grow, so the arithmetic loops also call :func:`tick`,
which refuses the certificate (exit code 2) once the budget set by :func:`start` is spent.
"""

from __future__ import annotations

import time

from proofs_check.parse import MalformedError

__all__ = ["DEFAULT_SECONDS", "start", "tick"]

DEFAULT_SECONDS = 60.0
"""Default budget of one ``python -m proofs_check`` run."""

_deadline = [float("inf")]


def start(seconds: float) -> None:
    """Allow ``seconds`` of arithmetic from now on."""
    _deadline[0] = time.monotonic() + seconds


def tick() -> None:
    """Refuse the certificate if the budget is spent."""
    if time.monotonic() > _deadline[0]:
        raise MalformedError("refused: the exact arithmetic exceeded the time budget")
