"""Theory ↔ simulation for ch. 5: the exact S-detectability verdict against the coupled Riccati
recursion (5.7)–(5.9), both orders (App. C.3), over random systems and networks.

The statement is in :mod:`theory.consensus.properties` (registered for ``trackcert
falsify`` as ``seed000.fn5/corrected``): S-detectable ⇒ the Riccati iterates stay below the
fixed-gain bound of Lemma 5.2.3 (bounded from every P0 ⪰ 0); not S-detectable ⇒ from P0 = 0 they
are non-decreasing and none of their gains is stabilizing (unbounded).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given

from theory.consensus.case import Order
from theory.consensus.properties import RICCATI_EXAMPLES, riccati_agreement
from theory.consensus.riccati import bound_iteration, coupled_riccati
from theory.consensus.strategies import DkfProblem
from theory.core.tolerances import RICCATI_HORIZON
from theory.falsify import falsify
from theory.kinds import load_case
from theory.registry import properties_for


@given(problem=RICCATI_EXAMPLES)
def test_riccati_agrees_with_the_exact_verdict(problem) -> None:
    for order in Order:
        result = riccati_agreement(problem, order=order)
        assert result.holds, (order, result)


def test_registered_for_falsify_and_survives() -> None:
    [prop] = properties_for("seed000.fn5/corrected")
    assert prop.expected_to_hold
    assert not falsify(prop, examples=10, seed=1).found


@pytest.mark.parametrize("order", list(Order))
@pytest.mark.parametrize(
    ("name", "verdict"),
    [("ch5-example-1-wg", True), ("ch5-example-1-wc", False), ("ch5-example-2-wb", False)],
)
def test_paper_examples_on_both_sides(name: str, verdict: bool, order: str) -> None:
    """Example 1 W_g is bounded below its certified bound; W_c (on the bound) and Example 2's
    W_b are refuted exactly and their Riccati iterates only grow."""
    spec = load_case(name).spec
    problem = DkfProblem(0, spec.A, spec.C, spec.W, spec.L or ())
    result = riccati_agreement(problem, order=order)
    assert result.verdict is verdict and result.holds, result


def test_the_bound_comes_from_the_certified_gains() -> None:
    """The fixed-gain bound is finite only for stabilizing gains: with the zero gain, Example 1's
    bound iteration grows like 4^k while the Riccati iterates stay bounded."""
    spec = load_case("ch5-example-1-wg").spec
    zero = [np.zeros((2, c.shape[0])) for c in spec.C]
    P0 = np.zeros((3, 2, 2))
    order = Order.CONSENSUS_THEN_FILTER
    bound = bound_iteration(
        spec.A, spec.C, spec.W, spec.Q, spec.R, zero, P0, order=order, steps=RICCATI_HORIZON
    )
    run = coupled_riccati(
        spec.A, spec.C, spec.W, spec.Q, spec.R, P0, order=order, max_iter=RICCATI_HORIZON,
        fixed_steps=True,
    )  # fmt: skip
    assert run.norms[-1] < 1e3 < np.linalg.norm(bound[-1], 2, axis=(1, 2)).max()
