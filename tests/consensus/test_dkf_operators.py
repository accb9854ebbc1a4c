"""Operators of seed 000 §5.2 / App. C.3: explicit matrices agree with the maps; spectral facts."""

from __future__ import annotations

import numpy as np
from hypothesis import given

from theory.consensus.operators import (
    B2_matrix,
    B_matrix,
    E_map,
    E_matrix,
    J_map,
    J_matrix,
    L_adjoint_map,
    L_map,
    L_matrix,
    closed_loop,
    spectral_radius,
    unvec_tuple,
    vec_tuple,
)
from theory.strategies import dkf_problems


def test_vec_stacks_columns_then_agents():
    V = np.array([[[1.0, 2.0], [3.0, 4.0]], [[5.0, 6.0], [7.0, 8.0]]])
    assert vec_tuple(V).tolist() == [1, 3, 2, 4, 5, 7, 6, 8]
    assert np.array_equal(unvec_tuple(vec_tuple(V), 2, 2), V)


def test_vec_identity_gamma_x_gamma_transpose():
    rng = np.random.default_rng(0)
    G, X = rng.normal(size=(3, 3)), rng.normal(size=(3, 3))
    lhs = (G @ X @ G.T).reshape(-1, order="F")
    assert np.allclose(lhs, np.kron(G, G) @ X.reshape(-1, order="F"), rtol=1e-12, atol=1e-12)


def _random_tuple(problem, rng):
    N, n = problem.W.shape[0], problem.A.shape[0]
    return rng.normal(size=(N, n, n))


@given(dkf_problems())
def test_kronecker_matrices_apply_the_maps(problem):
    rng = np.random.default_rng(problem.seed)
    Gamma = closed_loop(problem.A, problem.C, problem.L)
    V = _random_tuple(problem, rng)
    N, n = V.shape[0], V.shape[1]
    pairs = [
        (L_matrix(problem.W, Gamma), L_map(problem.W, Gamma, V)),
        (J_matrix(problem.W, Gamma), J_map(problem.W, Gamma, V)),
        (E_matrix(problem.W, n), E_map(problem.W, V)),
        (L_matrix(problem.W, Gamma).T, L_adjoint_map(problem.W, Gamma, V)),
    ]
    for matrix, mapped in pairs:
        scale = np.linalg.norm(matrix) * np.linalg.norm(V) + 1.0
        assert np.allclose(matrix @ vec_tuple(V), vec_tuple(mapped), atol=1e-12 * scale)
    assert unvec_tuple(vec_tuple(V), N, n).shape == V.shape


@given(dkf_problems())
def test_adjoint_for_the_trace_inner_product(problem):
    rng = np.random.default_rng(problem.seed + 1)
    Gamma = closed_loop(problem.A, problem.C, problem.L)
    V, Y = _random_tuple(problem, rng), _random_tuple(problem, rng)
    lhs = np.sum(L_map(problem.W, Gamma, V) * Y)
    rhs = np.sum(V * L_adjoint_map(problem.W, Gamma, Y))
    assert abs(lhs - rhs) <= 1e-10 * (1 + abs(lhs))


@given(dkf_problems(max_states=3, max_agents=5))
def test_radius_L_equals_radius_J_and_B_equals_B2(problem):
    Gamma = closed_loop(problem.A, problem.C, problem.L)
    rL = spectral_radius(L_matrix(problem.W, Gamma))
    rJ = spectral_radius(J_matrix(problem.W, Gamma))
    rB = spectral_radius(B_matrix(problem.W, Gamma))
    rB2 = spectral_radius(B2_matrix(problem.W, Gamma))
    assert abs(rL - rJ) <= 1e-8 * max(1.0, rL)
    assert abs(rB - rB2) <= 1e-8 * max(1.0, rB)


@given(dkf_problems(max_states=3, max_agents=4))
def test_s_detectable_gains_make_B_stable(problem):
    """Seed 000 after Def. 5.2.4: r(L) < 1 implies r(B) < 1; more precisely r(B)² ≤ r(L)."""
    Gamma = closed_loop(problem.A, problem.C, problem.L)
    rL = spectral_radius(L_matrix(problem.W, Gamma))
    rB = spectral_radius(B_matrix(problem.W, Gamma))
    assert rB**2 <= rL * (1 + 1e-8) + 1e-12


def test_paper_counterexample_weights():
    """Seed 000 §5.2: n=1, N=2, A=C=1, L=(0.3, −0.25); W = ½·11' gives r(B)=0.975, r(L)=1.026."""
    A, C = np.array([[1.0]]), [np.array([[1.0]])] * 2
    Gamma = closed_loop(A, C, [np.array([[0.3]]), np.array([[-0.25]])])
    W = np.full((2, 2), 0.5)
    assert round(spectral_radius(B_matrix(W, Gamma)), 3) == 0.975
    assert round(spectral_radius(L_matrix(W, Gamma)), 3) == 1.026
