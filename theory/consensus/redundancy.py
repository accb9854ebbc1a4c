"""The fewest links (or agents) whose loss breaks S-detectability (seed 000 Def. 5.2.4, issue 25
item 4): ``trackcert design redundancy`` for ``kind: dkf``.

A **link** is a weight ``w_ij > 0`` (``i ≠ j``: agent i receives from agent j). When it is
lost, agent i keeps its own estimate in its place (``w_ii += w_ij``), so ``W`` stays
row-stochastic on the smaller graph. When an **agent** is lost, its row, column and sensor go,
and every agent that received from it keeps its own estimate instead.

Sets are enumerated by size, every removal decided exactly
(:func:`~theory.consensus.s_detectability.decide_s_detectability`): ``k`` is the first size with
a set certified not S-detectable (``s-detectability-infeasible``), and every set of fewer than
``certified_below`` items is certified S-detectable (``s-detectability``, one certificate per
set). An inconclusive decision stops ``certified_below`` at its size; past ``MAX_SETS`` decisions
the answer is the bracket reached.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction
from itertools import combinations
from typing import Any

import numpy as np

from theory.consensus.design import exact_system
from theory.consensus.s_detectability import LmiCache, decide_s_detectability
from theory.core.case_file import Case
from theory.core.exact import Matrix

__all__ = ["MAX_SETS", "DkfRedundancy", "dkf_redundancy", "without"]

MAX_SETS = 400
"""Most removal sets decided before the answer becomes a bracket."""


@dataclass(frozen=True)
class DkfRedundancy:
    """``k`` items (``links`` or ``agents``) whose loss breaks S-detectability (``witness``,
    1-based; None when none was found within the budget), every set of fewer than
    ``certified_below`` items certified S-detectable. ``exact`` when ``k == certified_below``, or
    ``complete``: no removal that leaves an agent breaks it, every one certified."""

    case: str
    items: str
    k: int | None
    witness: tuple
    certified_below: int
    checked: int
    certificates: tuple[dict[str, Any], ...]
    reason: str
    note: str
    complete: bool = False

    @property
    def exact(self) -> bool:
        """Whether the minimum is known (``complete``: every removal is certified harmless)."""
        return self.complete or (self.k is not None and self.k == self.certified_below)

    @property
    def verdict(self) -> bool | None:
        """False when the case is not S-detectable already (``k = 0``), True when every smaller
        set is certified, else None."""
        if self.k == 0:
            return False
        return True if self.exact else None

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert design redundancy --json`` record."""
        return {
            "case": self.case,
            "items": self.items,
            "k": self.k,
            "witness": [list(x) if isinstance(x, tuple) else x for x in self.witness],
            "certified_below": self.certified_below,
            "exact": self.exact,
            "reason": self.reason,
            "sets_checked": self.checked,
            "verdict": self.verdict,
            "note": self.note,
            "tolerances": {"max_sets": MAX_SETS},
            "certificates": list(self.certificates),
        }


def without(
    C: list[np.ndarray], W: Matrix, removed: tuple, links: bool
) -> tuple[list[np.ndarray], Matrix]:
    """``C`` and exact ``W`` after losing ``removed`` (0-based links ``(i, j)`` or agents)."""
    W = [list(row) for row in W]
    if links:
        for i, j in removed:
            W[i][i] += W[i][j]
            W[i][j] = Fraction(0)
        return C, W
    gone = set(removed)
    for i, row in enumerate(W):
        for j in gone:
            row[i] += row[j]
            row[j] = Fraction(0)
    keep = [i for i in range(len(W)) if i not in gone]
    return [C[i] for i in keep], [[W[i][j] for j in keep] for i in keep]


def dkf_redundancy(case: Case, *, links: bool = True, max_sets: int = MAX_SETS) -> DkfRedundancy:
    """The fewest links (``links``) or agents whose loss breaks S-detectability, by exact
    enumeration of every smaller set (module docstring)."""
    A, C, W = exact_system(case)
    N = len(W)
    if links:
        items: list = [(i, j) for i in range(N) for j in range(N) if i != j and W[i][j]]
    else:
        items = list(range(N))
    problems = LmiCache()
    kept: list[dict[str, Any]] = []
    checked, certified_below = 0, 0
    for size in range(min(len(items) + 1, N if not links else len(items) + 1)):
        positives: list[dict[str, Any]] = []
        for removed in combinations(items, size):
            if checked >= max_sets:
                return _answer(case, links, None, (), certified_below, checked, kept,
                               f"budget of {max_sets} sets reached at size {size}")  # fmt: skip
            C_r, W_r = without(C, W, removed, links)
            result = decide_s_detectability(A, C_r, W_r, case=case.name, problems=problems)
            checked += 1
            if result.verdict is False:
                return _answer(case, links, size, removed, certified_below, checked,
                               [*kept, result.certificate], result.reason)  # fmt: skip
            positives.append(result.certificate)
        if certified_below == size and all(c is not None for c in positives):
            kept += positives
            certified_below = size + 1
    answer = _answer(case, links, None, (), certified_below, checked, kept,
                     "no removal that leaves an agent breaks S-detectability")  # fmt: skip
    return replace(answer, complete=certified_below == size + 1)


def _answer(case: Case, links: bool, k: int | None, removed: tuple, certified_below: int,
            checked: int, kept: list, reason: str) -> DkfRedundancy:  # fmt: skip
    """The answer with its witness 1-based and the note on what a loss means."""
    witness = tuple((i + 1, j + 1) for i, j in removed) if links else tuple(a + 1 for a in removed)
    what = "links" if links else "agents"
    note = (
        "a lost link (i, j): agent i keeps its own estimate in place of agent j's "
        "(w_ii += w_ij); a lost agent: every agent that received from it does the same"
    )
    if k is not None and k != certified_below:
        note += f"; bracket: every set of fewer than {certified_below} {what} is certified"
    return DkfRedundancy(
        case.name, what, k, witness, certified_below, checked, tuple(kept), reason, note
    )
