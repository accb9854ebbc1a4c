"""Soundness near the S-detectability boundary (issue 17 item 1): every verdict is correct or
inconclusive, never wrong.

The truth comes from exact arguments (docs/theory/s-detectability.md, "Boundary sweeps"): seed 000
Example 1 with self-weight w on agents 1 and 2 is S-detectable iff w < 1/4, Example 2 with
self-weight w on agent 3 iff w · 1.7205² < 1 (blind-set necessity, Theorem 4; sufficiency with the
projection gains). The sweeps toward both thresholds, and the radius of fixed gains through 1, are
the registered properties of :mod:`theory.consensus.properties`
(``tests/consensus/test_dkf_boundary_properties.py``); here: the weights of issue 17, the
self-weight bisection and the scaling invariances.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.consensus.riccati import coupled_riccati
from theory.consensus.s_detectability import decide_s_detectability, max_self_weight
from theory.consensus.strategies import (
    SELF_WEIGHT_THRESHOLDS,
    dkf_problems,
    self_weight_examples,
)


@pytest.mark.parametrize("w", [0.249999999, 0.2499999999, 0.25, 0.2500000001])
def test_issue_17_weights_are_decided_correctly(w: float) -> None:
    """The weights of issue 17: both sides of 1/4 get the right, exactly certified verdict."""
    A, C, W = self_weight_examples("example 1", w)
    result = decide_s_detectability(A, C, W)
    assert result.verdict is (w < 0.25)
    assert result.certificate["kind"] == (
        "s-detectability" if w < 0.25 else "s-detectability-infeasible"
    )


@pytest.mark.parametrize("example", sorted(SELF_WEIGHT_THRESHOLDS))
def test_bisection_brackets_the_exact_threshold(example: str) -> None:
    """The self-weight search rests on exact verdicts, so its bracket holds the true threshold."""
    A, C, W = self_weight_examples(example, 0.0)
    agents = [0, 1] if example == "example 1" else [2]
    search = max_self_weight(A, C, W, agents, weight_tol=1e-3)
    assert search.status == "found"
    assert search.low < SELF_WEIGHT_THRESHOLDS[example] <= search.high


@given(
    problem=dkf_problems(max_states=2, max_agents=3, integer_data=True, a_bound=2.0),
    power=st.sampled_from([-2, -1, 1, 2]),
)
def test_scaled_data_give_the_same_verdict(problem, power: int) -> None:
    """Scaling invariances: r_σ(L) is homogeneous of degree 2 in A (Γ_i → sΓ_i), so
    (sA, C, W) at ρ equals (A, C, W) at ρ/s²; C_i → c C_i with L_i → L_i / c, and a diagonal
    change of state coordinates, leave the question unchanged; Q and R only change the Riccati
    gains offered as candidates. Decided verdicts must agree."""
    A, C, W, s = problem.A, list(problem.C), problem.W, 2.0**power
    base = decide_s_detectability(A, C, W, rho=s * s).verdict
    T = np.diag([2.0**k for k in range(A.shape[0])])
    Ti = np.linalg.inv(T)
    n = A.shape[0]
    Q, R = np.eye(n), [np.eye(c.shape[0]) for c in C]
    run = coupled_riccati(
        A,
        C,
        W,
        s * Q,
        [s * r for r in R],
        np.eye(n),
        order="consensus-then-filter",
        max_iter=30,
        fixed_steps=True,
    )
    variants = [
        decide_s_detectability(s * A, C, W, rho=s**4).verdict,
        decide_s_detectability(A, [s * c for c in C], W, rho=s * s).verdict,
        decide_s_detectability(T @ A @ Ti, [c @ Ti for c in C], W, rho=s * s).verdict,
        decide_s_detectability(
            A, C, W, rho=s * s, candidate_gains=[("Riccati gains, scaled Q and R", run.gains)]
        ).verdict,
    ]
    decided = {v for v in (base, *variants) if v is not None}
    assert len(decided) <= 1, (base, variants)
