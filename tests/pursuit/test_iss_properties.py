"""Falsification of seed 003's corrected ISS inequalities (hypothesis) and the printed ones.

Each property samples states, estimation errors, rotations and parameters with bounded
conditioning, evaluates the actual Lyapunov derivative from the closed-loop dynamics (kinematics for
the pursuit loop, γ̇ of (45)–(47) for the coordination loop) and checks the corrected inequality.
The printed inequalities that are false are refuted by explicit counterexamples.
"""

from __future__ import annotations

import math
from dataclasses import replace
from fractions import Fraction

import networkx as nx
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from proofs_check.linalg import positive_definite
from theory.core.errors import PropertyFails
from theory.kinds import load_case, parse_case
from theory.pursuit.certificates import iss_certificate_data, verify_certificate
from theory.pursuit.derivations import (
    eq71_strict_inequality,
    eq72_printed_region,
    eq74_missing_connectivity,
    eq75_missing_norm,
    xi_not_orthogonal_to_ones,
)
from theory.pursuit.iss import (
    coordination_iss,
    eq72_case_search,
    generalized_algebraic_connectivity,
    iss_bound,
    pursuit_iss,
)
from theory.pursuit.model import closed_loop_rates, exp_skew, left_eigenvector, path_derivative
from theory.pursuit.model import path as path_numeric
from theory.strategies import digraph_laplacians, pursuit_cases, tracker_states

REL_TOL = 1e-9
"""Relative tolerance on inequalities evaluated in floating point (scale: the terms' magnitudes)."""

reals = st.floats(min_value=-10, max_value=10, allow_nan=False)
positive_gains = st.floats(min_value=0.05, max_value=5.0)


def vectors(dim: int, elements=reals) -> st.SearchStrategy:
    return st.lists(elements, min_size=dim, max_size=dim).map(np.array)


@given(data=st.data())
def test_corrected_eq72_no_violation(data) -> None:
    """V̇ ≤ −λ_min(K)‖e‖² + c‖e‖‖x̃‖ along the real closed loop, c = √μ + ‖K‖ and c♯ (Thm 1)."""
    case = data.draw(pursuit_cases())
    spec = case.spec
    state = data.draw(tracker_states(spec=spec))
    rates = state.rates(spec)
    pursuit = pursuit_iss(spec)
    e_norm = math.sqrt(float(rates.e_p @ rates.e_p) + rates.e_gamma**2)
    x_norm = math.sqrt(float(state.q_err @ state.q_err + state.v_err @ state.v_err))
    assert np.allclose(rates.e_p, state.e_p, atol=1e-9 * (1 + np.abs(state.e_p).max()))
    scale = pursuit.norm_K * e_norm**2 + pursuit.cross_gain * e_norm * x_norm + 1.0
    for c in (pursuit.cross_gain, pursuit.sharp_cross_gain):  # the paper's c and the sharp c♯
        bound = -pursuit.lambda_min * e_norm**2 + c * e_norm * x_norm
        assert rates.v_dot <= bound + REL_TOL * scale * 1e3
    # the region form of (78): with θ ∈ (0, 1), V̇ ≤ −(1−θ)λ‖e‖² whenever ‖e‖ ≥ c‖x̃‖/(θλ)
    theta = 0.5
    if e_norm >= pursuit.cross_gain * x_norm / (theta * pursuit.lambda_min):
        assert rates.v_dot <= -(1 - theta) * pursuit.lambda_min * e_norm**2 + REL_TOL * scale * 1e3


@given(data=st.data())
def test_corrected_eq71_no_violation(data) -> None:
    """‖Φ‖² ≤ μ‖x̃‖² with Φ = col(Rᵀṽ, −q̃ᵀr′(γ)) and the case's μ (eq. (71) with ≤)."""
    case = data.draw(pursuit_cases())
    spec = case.spec
    state = data.draw(tracker_states(spec=spec))
    path = spec.trackers[0]
    params = {"r_x": path.r_x, "r_y": path.r_y, "gamma0": path.gamma0}
    if spec.dim == 3:
        params.update({"r_z": path.r_z, "c": path.c})
    r_prime = path_derivative(state.gamma, **params)
    phi_sq = (
        float(np.sum((state.rotation.T @ state.v_err) ** 2)) + float(state.q_err @ r_prime) ** 2
    )
    x_sq = float(state.q_err @ state.q_err + state.v_err @ state.v_err)
    mu = pursuit_iss(spec).mu
    assert phi_sq <= mu * x_sq * (1 + REL_TOL) + REL_TOL


@given(data=st.data())
def test_pursuit_error_independent_of_coordination(data) -> None:
    """Remark 10: e's dynamics do not depend on v̇_c (Type II uses it in γ̈ and cancels it)."""
    case = data.draw(pursuit_cases())
    spec = case.spec
    state = data.draw(tracker_states(spec=spec))
    first = state.rates(spec)
    second = replace(state, omega_d_dot=state.omega_d_dot + 1.0).rates(spec)
    assert np.allclose(first.de_p, second.de_p, rtol=1e-9, atol=1e-9)
    assert math.isclose(first.de_gamma, second.de_gamma, rel_tol=1e-9, abs_tol=1e-9)


@given(L=digraph_laplacians())
def test_lemma1_exact_on_random_digraphs(L) -> None:
    """Lemma 1: r > 0, rᵀL = 0, rᵀ1 = 1, and RL + LᵀR ⪰ 0 (exact rationals)."""
    r = left_eigenvector(L)
    assert r is not None and all(x > 0 for x in r) and sum(r) == 1
    n = len(r)
    assert all(sum(r[i] * int(L[i, j]) for i in range(n)) == 0 for j in range(n))
    M = [[r[i] * int(L[i, j]) + int(L[j, i]) * r[j] for j in range(n)] for i in range(n)]
    assert positive_definite(M, semi=True).positive


@given(L=digraph_laplacians())
def test_connectivity_bounds_the_spectrum(L) -> None:
    """0 < a(L) ≤ Re λ for every non-zero eigenvalue of L (Definition 1 gives a decay rate)."""
    r = np.array([float(x) for x in left_eigenvector(L)])
    a = generalized_algebraic_connectivity(L.astype(float), r)
    eigenvalues = np.linalg.eigvals(L.astype(float))
    nonzero = np.delete(eigenvalues, np.argmin(np.abs(eigenvalues)))
    assert a > 0
    assert a <= float(nonzero.real.min()) + 1e-9 * max(1.0, float(np.abs(L).max()))


@given(n=st.integers(2, 7), data=st.data())
def test_undirected_connectivity_is_fiedler(n, data) -> None:
    """Definition 1: for undirected connected graphs a(L) = λ₂(L)."""
    tree_parent = [data.draw(st.integers(0, i - 1)) for i in range(1, n)]
    adjacency = np.zeros((n, n), dtype=int)
    for child, parent in enumerate(tree_parent, start=1):
        adjacency[child, parent] = adjacency[parent, child] = 1
    for i, j in data.draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)))):
        if i != j:
            adjacency[i, j] = adjacency[j, i] = 1
    L = np.diag(adjacency.sum(axis=1)) - adjacency
    r = np.array([float(x) for x in left_eigenvector(L)])
    assert np.allclose(r, 1.0 / n)
    fiedler = float(np.sort(np.linalg.eigvalsh(L.astype(float)))[1])
    a = generalized_algebraic_connectivity(L.astype(float), r)
    assert math.isclose(a, fiedler, rel_tol=1e-9, abs_tol=1e-9)


@given(L=digraph_laplacians(), data=st.data())
def test_corrected_eq74_no_violation(L, data) -> None:
    """V̇_c ≤ −k_c a(L) ξᵀRξ + ‖ξ‖_R b ‖e_γ‖ with V̇_c from γ̇ = ω̄1 − k_cLγ + e_γ."""
    n = L.shape[0]
    r = np.array([float(x) for x in left_eigenvector(L)])
    k_c = data.draw(positive_gains)
    gamma = data.draw(vectors(n))
    e_gamma = data.draw(vectors(n))
    W = np.eye(n) - np.outer(np.ones(n), r)
    R = np.diag(r)
    xi = W @ gamma
    gamma_dot = data.draw(reals) * np.ones(n) - k_c * L @ gamma + e_gamma
    v_dot = float(xi @ R @ (W @ gamma_dot))
    a = generalized_algebraic_connectivity(L.astype(float), r)
    b = math.sqrt(float(np.linalg.eigvalsh(W.T @ R @ W)[-1]))
    xi_r = math.sqrt(float(xi @ R @ xi))
    bound = -k_c * a * xi_r**2 + xi_r * b * float(np.linalg.norm(e_gamma))
    scale = k_c * float(np.abs(L).max()) * float(xi @ xi) + xi_r * b * np.linalg.norm(e_gamma) + 1
    assert abs(float(r @ xi)) <= 1e-9 * (1 + np.abs(gamma).max())
    assert v_dot <= bound + REL_TOL * scale * 10


def test_printed_inequalities_are_false() -> None:
    """Explicit counterexamples to (71) strict, (72)'s region, (74)'s rate, (75)'s cross term."""
    assert not eq71_strict_inequality()["printed_strict_holds"]
    assert eq71_strict_inequality()["corrected_nonstrict_holds"]
    region = eq72_printed_region()
    assert region["e_norm"] >= region["printed_region_threshold"]
    assert region["v_dot"] > region["printed_bound"] + 0.1
    assert region["e_norm"] < region["corrected_region_threshold"]
    missing = eq74_missing_connectivity()
    assert not missing["printed_holds"] and missing["corrected_holds"]
    assert Fraction(missing["v_dot"]) == -1 and Fraction(missing["printed_bound"]) == -2
    norm = eq75_missing_norm()
    assert not norm["printed_holds"] and norm["corrected_holds"]
    orth = xi_not_orthogonal_to_ones()
    assert orth["r_is_left_eigenvector"] and orth["r_dot_xi"] == "0"
    assert Fraction(orth["ones_dot_xi"]) != 0


def test_eq74_counterexample_agrees_with_definition1() -> None:
    L = np.eye(6, dtype=int) - np.roll(np.eye(6, dtype=int), 1, axis=1)
    r = np.array([float(x) for x in left_eigenvector(L)])
    assert math.isclose(generalized_algebraic_connectivity(L.astype(float), r), 0.5)


@pytest.mark.parametrize("name", ["pursuit-table1-n3", "pursuit-table2-n3", "pursuit-table1-n1"])
def test_certificate_data_verifies_and_tampering_fails(name: str) -> None:
    certificate = iss_certificate_data(load_case(name).spec)
    data, witness = certificate["data"], certificate["witness"]
    assert all(ok for _, ok in verify_certificate(data, witness))
    tampered = dict(witness, **{"lambda": witness["lambda"] * 2})
    assert not dict(verify_certificate(data, tampered))["E2"]
    if "a" in witness:
        tampered = dict(witness, a=witness["a"] * Fraction(11, 10))
        assert not dict(verify_certificate(data, tampered))["C3"]
        tampered = dict(witness, b=witness["b"] * Fraction(9, 10))
        assert not dict(verify_certificate(data, tampered))["C4"]


@given(data=st.data())
def test_certificate_random_cases(data) -> None:
    case = data.draw(pursuit_cases(n_trackers=data.draw(st.integers(1, 4))))
    certificate = iss_certificate_data(case.spec)
    assert all(ok for _, ok in verify_certificate(certificate["data"], certificate["witness"]))


def test_certificate_refused_when_conditions_fail() -> None:
    for name in ("pursuit-not-strongly-connected", "pursuit-singular-epsilon"):
        with pytest.raises(PropertyFails, match="conditions"):
            iss_certificate_data(load_case(name).spec)


def test_not_strongly_connected_has_no_left_vector() -> None:
    coordination = coordination_iss(load_case("pursuit-not-strongly-connected").spec)
    assert not coordination.strongly_connected and coordination.r is None
    graph = nx.DiGraph([(0, 2), (1, 2)])
    assert not nx.is_strongly_connected(graph)


# ---------------------------------------------------------------------------------------------
# the ISS bound along closed-loop trajectories of the full DEC (N = 3, 2D, Type II)


def _dec_rhs(spec, x_tilde):
    n, path = spec.n_trackers, spec.trackers
    L = spec.laplacian.astype(float)
    target = spec.target

    def rhs(t, state):
        s = state.reshape(n, 5)  # p (2), ψ, γ, γ̇
        q, v = target.position(t), target.velocity_at(t)
        gamma, gamma_dot = s[:, 3], s[:, 4]
        v_c = -spec.k_c * L @ gamma
        v_c_dot = -spec.k_c * L @ gamma_dot
        q_err, v_err = x_tilde(t)
        out = np.zeros_like(s)
        for i in range(n):
            params = {"r_x": path[i].r_x, "r_y": path[i].r_y, "gamma0": path[i].gamma0}
            rotation = exp_skew([s[i, 2]])
            rates = closed_loop_rates(
                position=s[i, :2], rotation=rotation, gamma=gamma[i], gamma_dot=gamma_dot[i],
                target_position=q, target_velocity=v, estimate_position=q + q_err[i],
                estimate_velocity=v + v_err[i], epsilon=spec.epsilon, K_p=spec.K_p,
                k_gamma=spec.k_gamma, controller="II", omega_d=spec.omega_bar + v_c[i],
                omega_d_dot=v_c_dot[i], path_params=params,
            )  # fmt: skip
            out[i, :2] = rotation @ np.array([rates.u[0], 0.0])
            out[i, 2] = rates.u[1]
            out[i, 3] = gamma_dot[i]
            out[i, 4] = rates.de_gamma + v_c_dot[i]
        return out.reshape(-1)

    return rhs


def _mu_norm(spec, t, state):
    n, path = spec.n_trackers, spec.trackers
    s = state.reshape(n, 5)
    L = spec.laplacian.astype(float)
    r = np.array([float(x) for x in coordination_iss(spec).r])
    xi = s[:, 3] - r @ s[:, 3]
    e_gamma = s[:, 4] - (spec.omega_bar - spec.k_c * L @ s[:, 3])
    q = spec.target.position(t)
    total = float(xi @ xi + e_gamma @ e_gamma)
    for i in range(n):
        params = {"r_x": path[i].r_x, "r_y": path[i].r_y, "gamma0": path[i].gamma0}
        rotation = exp_skew([s[i, 2]])
        e_p = rotation.T @ (s[i, :2] - path_numeric(s[i, 3], **params) - q) - spec.epsilon
        total += float(e_p @ e_p)
    return math.sqrt(total)


@pytest.mark.slow
@pytest.mark.parametrize("amplitude", [0.0, 0.5])
def test_iss_bound_along_closed_loop(amplitude: float) -> None:
    """‖μ(t)‖ ≤ β(‖μ(0)‖, t) + γ(sup_{[0,t]}‖x̃‖) on the Table I gains (k_γ = 5, less stiff)."""
    from scipy.integrate import solve_ivp

    case = load_case("pursuit-table1-n3")
    spec = case.spec
    spec = type(spec)(**{**spec.__dict__, "k_gamma": 5.0})
    rng = np.random.default_rng(3)
    phases = rng.uniform(0, 2 * np.pi, size=(3, 4))

    def x_tilde(t):
        values = amplitude * np.sin(0.3 * t + phases)
        return values[:, :2], values[:, 2:]

    initial = np.column_stack(
        [rng.uniform(-40, 40, (3, 2)), rng.uniform(-np.pi, np.pi, 3), rng.uniform(-1, 1, 3),
         rng.uniform(-0.2, 0.2, 3)]
    ).reshape(-1)  # fmt: skip
    times = np.linspace(0, 40, 81)
    solution = solve_ivp(_dec_rhs(spec, x_tilde), (0, 40), initial, t_eval=times, rtol=1e-9,
                         atol=1e-9)  # fmt: skip
    assert solution.success, solution.message
    bound = iss_bound(spec)
    mu0 = _mu_norm(spec, 0.0, solution.y[:, 0])
    sup_x = 0.0
    for k, t in enumerate(solution.t):
        sup_x = max(sup_x, float(np.linalg.norm(np.concatenate(x_tilde(t), axis=1))))
        mu = _mu_norm(spec, t, solution.y[:, k])
        assert mu <= bound.beta(mu0, t) + bound.gamma(sup_x) + 1e-6 * (1 + mu0)
    if amplitude == 0.0:
        assert _mu_norm(spec, 40.0, solution.y[:, -1]) < mu0


def test_eq72_case_search_finds_the_counterexample_family() -> None:
    """The per-case search agrees with the explicit counterexample and with the Table cases."""
    small = parse_case(
        {
            "name": "small-gains",
            "kind": "pursuit",
            "pursuit": {
                "dim": 2, "controller": "II", "omega_bar": 0.05, "epsilon": [1, 0],
                "K_p": [0.1, 0.1], "k_gamma": 0.1, "trackers": [{"r_x": 1, "r_y": 1}],
            },
        }
    )  # fmt: skip
    assert eq72_case_search(small.spec)["violation_found"]
    for name in ("pursuit-table1-n1", "pursuit-table2-n1"):
        search = eq72_case_search(load_case(name).spec)
        assert not search["violation_found"] and search["minimum"] > 0


@given(data=st.data())
def test_lemma2_equality_along_the_kinematics(data) -> None:
    """Lemma 2 numerically: with q̃ = ṽ = 0, V̇ = −eᵀKe at every state (not just ≤)."""
    case = data.draw(pursuit_cases())
    spec = case.spec
    state = data.draw(tracker_states(spec=spec))
    zero = np.zeros(spec.dim)
    rates = replace(state, q_err=zero, v_err=zero).rates(spec)
    e = np.append(rates.e_p, rates.e_gamma) if spec.controller == "II" else rates.e_p
    K = pursuit_iss(spec).K
    expected = -float(e @ K @ e)
    assert math.isclose(rates.v_dot, expected, rel_tol=1e-8, abs_tol=1e-8 * (1 + e @ e))


# ---------------------------------------------------------------------------------------------
# Theorem 2 against the simulator (the agreement property of trackcert falsify)


def test_simulator_agrees_with_the_certificate_on_random_cases() -> None:
    """``seed003.thm2.sim-trajectories/corrected``: no counterexample within the CI budget (25
    derandomized examples of :func:`theory.strategies.simulated_pursuit_cases`)."""
    from theory.falsify import falsify, properties_for

    (prop,) = properties_for("seed003.thm2.sim-trajectories/corrected")
    result = falsify(prop, examples=25, seed=0)
    assert not result.found, result.case


def test_agreement_counterexample_case_reloads() -> None:
    """The case an example becomes is a valid case that ``trackcert iss`` certifies."""
    from hypothesis import Phase, find, settings

    from theory.pursuit.properties import agreement_case, agreement_examples, agreement_verdict

    # Any 3-D example will do: not shrinking it saves 9 s of CPU.
    first = settings(settings.default, phases=[Phase.generate])
    example = find(agreement_examples(), lambda e: e.block["dim"] == 3, settings=first)
    case = parse_case(agreement_case(example))
    assert case.expect == {"iss": True, "simulation_bounded": True}
    assert agreement_verdict(example)["simulation_bounded"]
