"""One exit-code rule for every command, and the verdict words it maps (docs/cli.md, *Exit codes*).

A command decides a property — True (holds), False (fails) or None (inconclusive: a margin lies
inside its tolerance, a solver failed) — and judges the keys of the case's ``expect`` block that
it observes (:mod:`theory.core.expectations`), which reduce to the same three values by
:func:`expectations_verdict`: every expectation met → True, one unmet → False, otherwise (one
inconclusive or unchecked, none unmet) → None. :func:`command_verdict` is the rule: **when the
command judged at least one expectation, the expectations' verdict decides; otherwise the
property's** (a command with no property of its own — ``simulate``, ``pf``, ``report`` — has
True: it ran). Then

- True → exit 0 (:data:`EXIT_HOLDS`), claim status ``verified``
  (:func:`theory.core.claims.status_of`);
- False → exit 1 (:data:`EXIT_FAILS`), claim status ``refuted``;
- None → exit 3 (:data:`EXIT_INCONCLUSIVE`), claim status ``inconclusive``;
- bad input → exit 2 (:data:`EXIT_BAD_INPUT`);
- a fault of the machine → exit 4 (:data:`EXIT_FAULT`): writing an output failed, no worker
  joined the cluster in time, memory ran out;
- interrupted by a signal → 128 + its number (:func:`interrupted_code`: SIGINT 130, SIGTERM 143).

Bad input and faults are not verdicts: a :class:`~theory.core.errors.CaseError` (or another
:class:`~theory.core.errors.TrackcertError` that is not a verdict) and a
:class:`~theory.core.errors.FaultError`, reported on stderr.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

__all__ = [
    "EXIT_BAD_INPUT",
    "EXIT_FAILS",
    "EXIT_FAULT",
    "EXIT_HOLDS",
    "EXIT_INCONCLUSIVE",
    "Verdict",
    "all_hold",
    "command_verdict",
    "exit_code",
    "expectations_verdict",
    "interrupted_code",
]

EXIT_HOLDS, EXIT_FAILS, EXIT_BAD_INPUT, EXIT_INCONCLUSIVE, EXIT_FAULT = 0, 1, 2, 3, 4

Verdict = bool | None
"""True holds, False fails, None inconclusive."""

_EXIT = {True: EXIT_HOLDS, False: EXIT_FAILS, None: EXIT_INCONCLUSIVE}


def exit_code(verdict: Verdict) -> int:
    """The exit code of a verdict: True 0, False 1, None 3."""
    return _EXIT[verdict]


def all_hold(verdicts: Iterable[Verdict]) -> Verdict:
    """Three-valued conjunction: False if one fails, else None if one is undecided, else True."""
    seen = set(verdicts)
    if False in seen:
        return False
    return None if None in seen else True


def expectations_verdict(expectations: Iterable[Any]) -> Verdict:
    """The expectations' verdict: False if one is unmet, True if all (or none) met, else None."""
    verdicts = {e.verdict for e in expectations}
    if "unmet" in verdicts:
        return False
    return None if verdicts - {"met"} else True


def command_verdict(property_verdict: Verdict, expectations: Sequence[Any]) -> Verdict:
    """The verdict a command exits with: its expectations' if it judged any, else its property's."""
    return expectations_verdict(expectations) if expectations else property_verdict


def interrupted_code(signum: int) -> int:
    """The exit code of a command stopped by signal ``signum``: 128 + ``signum``, as shells do."""
    return 128 + signum
