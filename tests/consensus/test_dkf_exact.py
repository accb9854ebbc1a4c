"""The exact decisions behind ch. 5 verdicts: radii below ρ, M-matrices, detectability, and the
two certificate builders, checked against floats away from the boundary and against each other.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from proofs_check import check_certificate
from theory.consensus.case import Order
from theory.consensus.certificates import (
    exact_gain_certificate,
    primal_certificate,
    projection_gains,
)
from theory.consensus.conditions import detectable_exact
from theory.consensus.infeasibility import blind_set_witness, infeasibility_certificate
from theory.consensus.operators import (
    closed_loop,
    covariance_operator_matrix,
    exact_lyapunov,
    gains_stabilize,
    nonnegative_radius_below,
    spectral_radius,
)
from theory.consensus.strategies import dkf_problems, self_weight_examples
from theory.core.exact import RationalizationError
from theory.core.observability import unobservable_eigenvalues

SMALL = dkf_problems(max_states=2, max_agents=3, integer_data=True, a_bound=2.0)


@pytest.mark.parametrize("order", list(Order))
@given(problem=dkf_problems(max_states=2, max_agents=3, gain_bound=1.5))
def test_exact_radius_agrees_with_floats_away_from_one(problem, order: str) -> None:
    T = covariance_operator_matrix(problem.W, closed_loop(problem.A, problem.C, problem.L), order)
    radius = spectral_radius(T)
    assume(abs(radius - 1) > 1e-6)
    assert gains_stabilize(problem.A, problem.C, problem.W, problem.L, order=order) is (radius < 1)


@given(
    entries=st.lists(st.integers(0, 4), min_size=9, max_size=9),
    scale=st.sampled_from([Fraction(1, 8), Fraction(1, 4), Fraction(1, 2)]),
)
def test_m_matrix_test_agrees_with_the_perron_root(entries, scale) -> None:
    M = [[scale * entries[3 * r + c] for c in range(3)] for r in range(3)]
    radius = max(abs(np.linalg.eigvals(np.array(M, dtype=float))))
    assume(abs(radius - 1) > 1e-9)
    assert nonnegative_radius_below(M) is bool(radius < 1)


def test_m_matrix_test_is_exact_on_the_boundary() -> None:
    """A stochastic matrix has r_σ = 1 exactly: not below 1, below any ρ > 1."""
    W = [[Fraction(1, 4), Fraction(3, 4)], [Fraction(3, 4), Fraction(1, 4)]]
    assert not nonnegative_radius_below(W)
    assert nonnegative_radius_below(W, Fraction(10**12 + 1, 10**12))


@given(problem=SMALL)
def test_exact_detectability_agrees_with_pbh_away_from_the_circle(problem) -> None:
    for C in problem.C:
        lost = [abs(x) for x in unobservable_eigenvalues(problem.A, C)]
        assume(all(abs(x - 1) > 1e-9 for x in lost))
        assert detectable_exact(problem.A, C) is all(x < 1 for x in lost)


@given(problem=SMALL)
def test_never_both_certificates(problem) -> None:
    """An exact Farkas witness and an exact Lyapunov witness cannot both exist: whenever the
    blind-set construction succeeds, no candidate gains (projection, the problem's own) can be
    certified, and the infeasibility certificate passes proofs_check."""
    A, C, W = problem.A, list(problem.C), problem.W
    try:
        cert = infeasibility_certificate(A, C, W)
    except RationalizationError:
        return
    assert check_certificate(cert).valid
    found, reasons = primal_certificate(
        A, C, W, order=Order.CONSENSUS_THEN_FILTER, candidates=[("drawn", problem.L)]
    )
    assert found is None and reasons


def test_issue_17_certificate_is_the_projection_gains() -> None:
    """Example 1 at w = 0.249999999: the projection gains are [2; 0], [0; 2], 2I and their exact
    Lyapunov tuple has P_1 ≈ diag(1, 1e9) (it grows like 1/(1 − 4w))."""
    A, C, W = self_weight_examples("example 1", 0.249999999)
    gains = projection_gains(A, C)
    assert gains == [
        [[Fraction(2)], [Fraction(0)]],
        [[Fraction(0)], [Fraction(2)]],
        [[Fraction(2), Fraction(0)], [Fraction(0), Fraction(2)]],
    ]
    cert = exact_gain_certificate(A, C, W, gains, order=Order.CONSENSUS_THEN_FILTER)
    assert check_certificate(cert).valid
    P1 = np.array([[float(Fraction(x)) for x in row] for row in cert["witness"]["P"][0]])
    assert P1[0, 0] == pytest.approx(1.0) and 1e8 < P1[1, 1] < 1e10


def test_exact_lyapunov_is_none_for_a_singular_operator() -> None:
    """Γ = 1, W = 1: I − T is singular, so there is no solution (r_σ = 1)."""
    one = [[Fraction(1)]]
    assert exact_lyapunov("L", one, [one]) is None


def test_blind_set_witness_needs_a_rational_eigenvector() -> None:
    A = [[Fraction(6, 5), Fraction(6, 5)], [Fraction(6, 5), Fraction(0)]]
    assert blind_set_witness(A, [[]], [[Fraction(1)]]) is None


def test_a_misspelt_order_is_refused_not_read_as_the_other() -> None:
    """``order`` names one of two operators: a typo used to select J silently (and answer True
    here, r_σ(J) = 4w = 0.96 with Example 1's projection gains); it must raise."""
    A, C, W = self_weight_examples("example 1", 0.24)
    gains = [np.array([[2.0], [0.0]]), np.array([[0.0], [2.0]]), 2 * np.eye(2)]
    assert gains_stabilize(A, C, W, gains, order="consensus-then-filter") is True
    with pytest.raises(ValueError, match="consensus-then-filtr"):
        gains_stabilize(A, C, W, gains, order="consensus-then-filtr")
    with pytest.raises(ValueError, match="consensus-then-filtr"):
        exact_gain_certificate(A, C, W, projection_gains(A, C), order="consensus-then-filtr")
