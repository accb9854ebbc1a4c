"""One exit-code policy for every command, and the verdict words it maps (DESIGN.md, *CLI*).

A command decides a property — True (holds), False (fails) or None (inconclusive: a margin lies
inside its tolerance, a solver failed) — or judges a case's ``expect`` block
(:mod:`theory.core.expectations`), which reduces to the same three values by
:func:`expectations_verdict`: every expectation met → True, one unmet → False, otherwise (one
inconclusive or unchecked, none unmet) → None. Then

- True → exit 0 (:data:`EXIT_HOLDS`), claim status ``verified``
  (:func:`theory.core.claims.status_of`);
- False → exit 1 (:data:`EXIT_FAILS`), claim status ``refuted``;
- None → exit 3 (:data:`EXIT_INCONCLUSIVE`), claim status ``inconclusive``;
- bad input → exit 2 (:data:`EXIT_BAD_INPUT`).

Bad input is not a verdict: it is a :class:`~theory.core.errors.CaseError` (or another
:class:`~theory.core.errors.TrackcertError` that is not a verdict), reported on stderr.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

__all__ = [
    "EXIT_BAD_INPUT",
    "EXIT_FAILS",
    "EXIT_HOLDS",
    "EXIT_INCONCLUSIVE",
    "Verdict",
    "all_hold",
    "exit_code",
    "expectations_verdict",
]

EXIT_HOLDS, EXIT_FAILS, EXIT_BAD_INPUT, EXIT_INCONCLUSIVE = 0, 1, 2, 3

Verdict = bool | None
"""True holds, False fails, None inconclusive."""

_EXIT = {True: EXIT_HOLDS, False: EXIT_FAILS, None: EXIT_INCONCLUSIVE}


def exit_code(verdict: Verdict) -> int:
    """The exit code of a verdict: True 0, False 1, None 3.

    Parameters
    ----------
    verdict : bool or None
        The property's (or the expectations') verdict.

    Returns
    -------
    int
    """
    return _EXIT[verdict]


def all_hold(verdicts: Iterable[Verdict]) -> Verdict:
    """Three-valued conjunction: False if one fails, else None if one is undecided, else True."""
    seen = set(verdicts)
    if False in seen:
        return False
    return None if None in seen else True


def expectations_verdict(expectations: Iterable[Any]) -> Verdict:
    """The verdict of a set of expectations: False if one is unmet, True if all are met, else None.

    Parameters
    ----------
    expectations : iterable of Expectation
        Judged expectations (anything with a ``verdict`` of
        :data:`theory.core.expectations.VERDICTS`); none at all is True (nothing to meet).

    Returns
    -------
    bool or None
    """
    verdicts = {e.verdict for e in expectations}
    if "unmet" in verdicts:
        return False
    return None if verdicts - {"met"} else True
