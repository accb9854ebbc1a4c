"""Coupled Riccati iterations (seed 000 eqs. (5.7)–(5.9), App. C.3) and Lemma 5.2.3."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given

from theory.consensus.case import Order
from theory.consensus.operators import (
    E_map,
    J_matrix,
    closed_loop,
    spectral_radius,
    unvec_tuple,
    vec_tuple,
)
from theory.consensus.riccati import (
    check_averaged_bound,
    check_covariance_bound,
    coupled_riccati,
    riccati_gains,
)
from theory.consensus.s_detectability import decide_s_detectability
from theory.kinds import load_case
from theory.strategies import dkf_problems


def run(name, order, **kw):
    s = load_case(name).spec
    return s, coupled_riccati(s.A, s.C, s.W, s.Q, s.R, 10 * np.eye(s.n), order=order, **kw)


@pytest.mark.parametrize("order", list(Order))
def test_example_1_good_weights_converge_to_a_stabilizing_solution(order):
    s, result = run("ch5-example-1-wg", order)
    assert result.status == "converged" and result.stabilizing
    if order is Order.CONSENSUS_THEN_FILTER:
        Pi = E_map(s.W, result.P)
        gains = riccati_gains(s.A, s.C, s.R, Pi)
        for i in range(s.n_agents):  # footnote 5's fixed-point equation
            Ci, Li = s.C[i], gains[i]
            rhs = s.A @ Pi[i] @ s.A.T + s.Q - Li @ (Ci @ Pi[i] @ Ci.T + s.R[i]) @ Li.T
            assert np.allclose(result.P[i], rhs, rtol=1e-8, atol=1e-8 * np.abs(rhs).max())


@pytest.mark.parametrize("order", list(Order))
@pytest.mark.parametrize("name", ["ch5-example-1-wb", "ch5-example-2-wb"])
def test_bad_weights_diverge(name, order):
    assert run(name, order)[1].status == "diverged"


@pytest.mark.parametrize("order", list(Order))
def test_example_2_good_weights_converge(order):
    assert run("ch5-example-2-wg", order)[1].stabilizing


@given(dkf_problems(max_states=3, max_agents=3, gain_bound=1.5))
def test_lemma_5_2_3_covariance_bound(problem):
    n = problem.A.shape[0]
    Q = np.eye(n) * 0.5
    R = [np.eye(Ci.shape[0]) for Ci in problem.C]
    check = check_covariance_bound(
        problem.A,
        problem.C,
        problem.W,
        Q,
        R,
        problem.L,
        np.eye(n),
        steps=12,
        samples=4000,
        seed=problem.seed % 2**32,
    )
    assert check.holds, check
    assert check.mc_violation <= 12 / np.sqrt(check.samples)


@given(dkf_problems(max_states=2, max_agents=3, a_bound=1.4))
def test_stabilizing_riccati_limit_implies_s_detectable(problem):
    n = problem.A.shape[0]
    R = [np.eye(Ci.shape[0]) for Ci in problem.C]
    result = coupled_riccati(
        problem.A, problem.C, problem.W, np.eye(n), R, np.eye(n), max_iter=2000
    )
    if result.status == "converged" and result.stabilizing and result.radius < 1 - 1e-6:
        assert decide_s_detectability(problem.A, problem.C, problem.W).verdict is not False


@given(dkf_problems(max_states=3, max_agents=4, a_bound=1.0, gain_bound=0.5))
def test_lemma_a_2_1_bounds(problem):
    """Seed 000 Lemma A.2.1: with X > f_1(M, X), f_k → 0 geometrically and P_k stays bounded."""
    W, n, N = problem.W, problem.A.shape[0], problem.W.shape[0]
    M = closed_loop(problem.A, problem.C, problem.L)
    T = J_matrix(W, M)
    assume(spectral_radius(T) < 0.95)
    X = unvec_tuple(
        np.linalg.solve(np.eye(T.shape[0]) - T, vec_tuple(np.stack([np.eye(n)] * N))), N, n
    )
    X = (X + X.transpose(0, 2, 1)) / 2
    check = check_averaged_bound(
        W, M, X, np.stack([np.eye(n)] * N), np.stack([0.5 * np.eye(n)] * N)
    )
    assert check.r < 1 and check.decay_ok and check.bound_ok


@given(dkf_problems(max_states=3, max_agents=3, gain_bound=1.5))
def test_lemma_5_2_3_noise_free_bound(problem):
    """First statement of Lemma 5.2.3: Ξ(k) ≤ P(k) with P(k+1) = L(P(k)) (no noise)."""
    n = problem.A.shape[0]
    zero_R = [np.zeros((Ci.shape[0], Ci.shape[0])) for Ci in problem.C]
    check = check_covariance_bound(
        problem.A,
        problem.C,
        problem.W,
        np.zeros((n, n)),
        zero_R,
        problem.L,
        np.eye(n),
        steps=12,
        samples=500,
        seed=problem.seed % 2**32,
    )
    assert check.holds, check
