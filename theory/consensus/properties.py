"""Falsifiable wordings of seed 000 ch. 5's detectability claims (for ``trackcert falsify``).

Examples are small consensus-filter problems drawn structurally (integer entries, so hypothesis
shrinks them to the smallest counterexample): ``n ≤ 2`` states, ``N ≤ 3`` agents, ``A`` with
entries in {−3, …, 3}, each ``C_i`` with 0 or 1 row of entries in {−1, 0, 1}, ``W`` from integer
weights 1–4 on a random support with a positive diagonal, normalised by rows. Verdicts come from
the exact LMI decision of :mod:`theory.consensus.s_detectability`; an inconclusive decision is
never a
counterexample.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np
from hypothesis import strategies as st

from theory.consensus.conditions import necessary_conditions
from theory.consensus.s_detectability import decide_s_detectability
from theory.core.observability import unobservable_eigenvalues
from theory.core.tolerances import UNIT_CIRCLE_TOL
from theory.falsify import Property, register_property

__all__ = [
    "SmallDkf",
    "dkf_case",
    "jointly_detectable",
    "small_dkf_problems",
    "strongly_connected",
]


@dataclass(frozen=True, eq=False)
class SmallDkf:
    """``A``, the per-agent ``C_i`` and the row-stochastic ``W`` of one example.

    Attributes
    ----------
    A : ndarray, shape (n, n)
        State matrix (integer entries).
    C : tuple of ndarray
        Measurement matrix ``C_i`` of each agent, shape (p_i, n) with ``p_i`` 0 or 1.
    W : ndarray, shape (N, N)
        Row-stochastic consensus weights with a positive diagonal.
    """

    A: np.ndarray
    C: tuple[np.ndarray, ...]
    W: np.ndarray


@st.composite
def small_dkf_problems(draw: st.DrawFn) -> SmallDkf:
    """Small integer consensus-filter problems (see the module docstring)."""
    n = draw(st.integers(1, 2))
    N = draw(st.integers(1, 3))
    entries = st.integers(-3, 3)
    A = np.array([[draw(entries) for _ in range(n)] for _ in range(n)], dtype=float)
    C = []
    for _ in range(N):
        rows = draw(st.integers(0, 1))
        C.append(np.array([[draw(st.integers(-1, 1)) for _ in range(n)] for _ in range(rows)]))
    raw = np.array(
        [
            [draw(st.integers(1, 4)) if i == j else draw(st.integers(0, 4)) for j in range(N)]
            for i in range(N)
        ],
        dtype=float,
    )
    C = [c.reshape(c.shape[0], n).astype(float) for c in C]
    return SmallDkf(A, tuple(C), raw / raw.sum(axis=1, keepdims=True))


def jointly_detectable(problem: SmallDkf) -> bool:
    """Whether ``problem``'s pair ``(A, col(C_1, …, C_N))`` is detectable (PBH, seed 000 §5.2)."""
    stacked = np.vstack(problem.C) if problem.C else np.zeros((0, problem.A.shape[0]))
    lost = unobservable_eigenvalues(problem.A, stacked)
    return all(abs(lam) < 1 - UNIT_CIRCLE_TOL for lam in lost)


def dkf_case(problem: SmallDkf) -> dict[str, Any]:
    """A ready-to-run ``kind: dkf`` case (Q = I, R_i = I) reproducing ``problem`` (a
    :class:`SmallDkf` or a :class:`~theory.consensus.strategies.DkfProblem`)."""
    n = problem.A.shape[0]
    return {
        "name": f"falsify-dkf-n{n}-N{len(problem.C)}",
        "source": "trackcert falsify (shrunk counterexample, seed 000 ch. 5)",
        "kind": "dkf",
        "dkf": {
            "A": problem.A.tolist(),
            "C": [c.tolist() for c in problem.C],
            "W": problem.W.tolist(),
            "Q": np.eye(n).tolist(),
            "R": [np.eye(c.shape[0]).tolist() for c in problem.C],
        },
    }


def _verdict(problem: SmallDkf) -> bool | None:
    return decide_s_detectability(problem.A, list(problem.C), problem.W).verdict


def strongly_connected(problem: SmallDkf) -> bool:
    """Whether the support of ``problem``'s ``W`` is a strongly connected digraph."""
    graph = nx.from_numpy_array((problem.W > 0).astype(int), create_using=nx.DiGraph)
    return nx.is_strongly_connected(graph)


def _detectable_implies_s_detectable(problem: SmallDkf) -> bool:
    if not strongly_connected(problem) or not jointly_detectable(problem):
        return True
    return _verdict(problem) is not False


def _necessary(attribute: str):
    def holds(problem: SmallDkf) -> bool:
        if _verdict(problem) is not True:
            return True
        return (
            getattr(necessary_conditions(problem.A, list(problem.C), problem.W), attribute)
            is not False
        )

    return holds


PROPERTIES = (
    (
        "seed000.sec5.2.detectability/paper",
        "On a strongly connected network, if (A, col(C_i)) is detectable, the consensus filter "
        "is S-detectable.",
        _detectable_implies_s_detectable,
        False,
    ),
    (
        "seed000.thm5.2.10/paper",
        "Every S-detectable consensus filter satisfies Thm 5.2.10's conditions (necessity).",
        _necessary("paper_conditions"),
        True,
    ),
    (
        "seed000.thm5.2.10/corrected",
        "Every S-detectable consensus filter satisfies the blind-set condition "
        "|λ|²·r(W_SS) < 1 (docs/theory/s-detectability.md, Theorem 4), which implies Thm 5.2.10's.",
        _necessary("blind_set_condition"),
        True,
    ),
)

for _id, _statement, _holds, _expected in PROPERTIES:
    register_property(
        Property(
            id=_id,
            claim=_id.split("/")[0],
            wording=_id.split("/")[1],
            statement=_statement,
            examples=small_dkf_problems(),
            holds=_holds,
            to_case=dkf_case,
            expected_to_hold=_expected,
        )
    )
