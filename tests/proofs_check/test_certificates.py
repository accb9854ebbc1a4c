"""Certificate builders: round trip certify → check, rejection of tampering, no weak certificates.

Witnesses are computed here by the plainest method the papers allow: fixed-point iteration
``P ← I + T(P)`` of the positive operator (it converges to ``Σ_k T^k(I) ≻ 0`` exactly when
``r_σ(T) < 1``, and then ``P − T(P) = I ≻ 0``).
"""

from __future__ import annotations

import copy
import json
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from proofs_check import MalformedError, check_certificate
from theory.consensus.certificates import (
    float_margin,
    mjls_stability_certificate,
    s_detectability_certificate,
)
from theory.core.exact import RationalizationError
from theory.tdoa.estimation.stability import (
    covariance_bound_certificate,
    ekf_covariance_bound_certificate,
)

OPERATORS = ("L", "J", "L-adjoint", "J-adjoint")


def image(operator: str, W: np.ndarray, gammas: list[np.ndarray], P: list[np.ndarray]):
    """``T(P)`` written out from seed 000 eqs. (5.12)–(5.13) and (C.6), loop by loop."""
    N = len(W)
    out = []
    for i in range(N):
        if operator == "L":
            out.append(gammas[i] @ sum(W[i, j] * P[j] for j in range(N)) @ gammas[i].T)
        elif operator == "J":
            out.append(sum(W[i, j] * gammas[j] @ P[j] @ gammas[j].T for j in range(N)))
        elif operator == "L-adjoint":
            out.append(sum(W[j, i] * gammas[j].T @ P[j] @ gammas[j] for j in range(N)))
        else:
            out.append(gammas[i].T @ sum(W[j, i] * P[j] for j in range(N)) @ gammas[i])
    return out


def fixed_point_witness(operator, W, gammas, *, iterations: int = 400):
    n = gammas[0].shape[0]
    P = [np.eye(n) for _ in W]
    for _ in range(iterations):
        P = [np.eye(n) + t for t in image(operator, W, gammas, P)]
    return P


@st.composite
def stable_networks(draw, *, max_agents: int = 4, max_n: int = 3, contraction: float = 0.8):
    """``(W, Γ)`` with ``W`` row-stochastic and ``‖Γ_i‖₂² ≤ contraction``, so ``r_σ(L) ≤ 0.8``.

    ``W`` is supported on a random graph containing the self-loops; entries are drawn from a
    seeded generator (the seed is part of the example), so the matrices are generic.
    """
    N = draw(st.integers(1, max_agents))
    n = draw(st.integers(1, max_n))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    support = rng.random((N, N)) < 0.6
    np.fill_diagonal(support, True)
    W = np.where(support, rng.uniform(0.1, 1.0, (N, N)), 0.0)
    W /= W.sum(axis=1, keepdims=True)
    gammas = []
    for _ in range(N):
        g = rng.standard_normal((n, n))
        gammas.append(g * np.sqrt(contraction) / np.linalg.norm(g, 2) * rng.uniform(0.3, 1.0))
    return W, gammas


@given(stable_networks(), st.sampled_from(OPERATORS))
def test_round_trip_mjls_stability(network, operator) -> None:
    W, gammas = network
    P = fixed_point_witness(operator, W, gammas)
    cert = mjls_stability_certificate(gammas, W, P, operator=operator)
    text = json.dumps(cert)
    assert check_certificate(json.loads(text)).valid
    assert cert["witness"]["operator"] == operator


@given(stable_networks(contraction=0.3))
def test_rate_bound_round_trip_and_refusal_below_the_true_radius(network) -> None:
    """``r_σ(L) < 0.5`` is certified when ``‖Γ_i‖² ≤ 0.3``; ``r_σ(L) < r_σ(L)/2`` never is."""
    W, gammas = network
    P = fixed_point_witness("L", W, gammas)
    cert = mjls_stability_certificate(gammas, W, P, spectral_radius_below=0.5)
    assert check_certificate(cert).valid
    radius = spectral_radius_L(W, gammas)
    if radius > 1e-3:
        with pytest.raises(RationalizationError):
            mjls_stability_certificate(gammas, W, P, spectral_radius_below=radius / 2)


def spectral_radius_L(W, gammas) -> float:
    """``r_σ`` of ``diag[Γ_i ⊗ Γ_i](W ⊗ I_{n²})`` (seed 000 Lemma 5.2.2)."""
    n = gammas[0].shape[0]
    big = np.zeros((len(W) * n * n, len(W) * n * n))
    for i, g in enumerate(gammas):
        for j in range(len(W)):
            big[i * n * n : (i + 1) * n * n, j * n * n : (j + 1) * n * n] = W[i, j] * np.kron(g, g)
    return float(max(abs(np.linalg.eigvals(big))))


@given(stable_networks(max_n=2))
def test_unstable_systems_get_no_certificate(network) -> None:
    """With ``Γ_i`` scaled so that ``r_σ(L) > 1`` no rounding can pass: an error, never a file."""
    W, gammas = network
    radius = spectral_radius_L(W, gammas)
    if radius < 1e-3:
        return
    scaled = [g * 1.1 / np.sqrt(radius) for g in gammas]
    P = fixed_point_witness("L", W, scaled, iterations=60)
    assert float_margin("L", W, scaled, P) < 0
    with pytest.raises(RationalizationError, match="no certificate"):
        mjls_stability_certificate(scaled, W, P)


@st.composite
def detectable_systems(draw):
    """``(A, C_i, W, L_i)`` with the gains making ``‖A − L_i C_i‖₂² ≤ 0.8``.

    ``A`` is arbitrary (possibly unstable); every agent measures the full state through an
    invertible ``C_i`` (bounded condition number) and ``L_i = (A − Γ_i) C_i⁻¹``.
    """
    W, gammas = draw(stable_networks(max_n=3))
    n = gammas[0].shape[0]
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    A = 1.5 * rng.standard_normal((n, n))
    Cs, gains = [], []
    for g in gammas:
        q, _ = np.linalg.qr(rng.standard_normal((n, n)))
        C = q @ np.diag(rng.uniform(0.5, 2.0, n))
        Cs.append(C)
        gains.append((A - g) @ np.linalg.inv(C))
    return A, Cs, W, gains


@given(
    detectable_systems(),
    st.sampled_from(["consensus-then-filter", "filter-then-consensus"]),
    st.booleans(),
)
def test_round_trip_s_detectability(system, order, dual) -> None:
    """Primal Lyapunov tuple of the order's operator, or the dual tuple of ``L*``."""
    A, Cs, W, gains = system
    gammas = [A - g @ c for g, c in zip(gains, Cs, strict=True)]
    operator = "L-adjoint" if dual else {"consensus-then-filter": "L"}.get(order, "J")
    P = fixed_point_witness(operator, W, gammas)
    cert = s_detectability_certificate(A, Cs, W, order, gains, P, dual=dual)
    assert check_certificate(json.loads(json.dumps(cert))).valid


def test_chapter5_example1_self_weight_threshold() -> None:
    """Seed 000 §5.3.1: with w₁₁ = w₂₂ = 0.24 the gains below certify S-detectability; at 0.25
    the same gains fail (Thm 5.2.10 needs w_ii < 1/r_σ(A_iᵘ)² = 0.25 for *any* gains)."""
    A = 2 * np.eye(2)
    Cs = [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)]
    gains = [np.array([[2.0], [0.0]]), np.array([[0.0], [2.0]]), 2 * np.eye(2)]
    gammas = [A - g @ c for g, c in zip(gains, Cs, strict=True)]
    for w, certifiable in ((0.24, True), (0.25, False)):
        W = np.array([[w, 1 - w, 0], [1 - w, w, 0], [0, 0, 1]])
        P = fixed_point_witness("L", W, gammas, iterations=2000)
        if certifiable:
            cert = s_detectability_certificate(A, Cs, W, "consensus-then-filter", gains, P)
            assert cert["data"]["W"][0][0] == "6/25"
            assert check_certificate(cert).valid
        else:
            with pytest.raises(RationalizationError):
                s_detectability_certificate(A, Cs, W, "consensus-then-filter", gains, P)


@given(stable_networks(max_n=2, contraction=0.35), st.integers(1, 2))
def test_round_trip_covariance_bound_with_a_common_witness(network, n_modes) -> None:
    """Lemma A.2.1 for several modes at once (each mode's ``‖M^j‖² ≤ 0.35``)."""
    W, first = network
    modes = [first] + [[0.5 * g[::-1] for g in first] for _ in range(n_modes - 1)]
    n = first[0].shape[0]
    X = [np.eye(n) for _ in W]
    for _ in range(300):
        images = [image("J", W, m, X) for m in modes]
        X = [np.eye(n) + sum(t[i] for t in images) for i in range(len(W))]
    cert = covariance_bound_certificate(W, modes, X)
    assert check_certificate(json.loads(json.dumps(cert))).valid
    assert len(cert["witness"]["decrease"]) == n_modes


def test_ekf_covariance_bound_takes_gains_and_jacobians_as_data() -> None:
    """Cor. A.2.2 with ``M^j = A (I − K^j H^j)``: the checker forms ``M`` itself from A, K, H."""
    A = np.array([[1.0, 0.5], [0.0, 1.0]])
    Hs = [[np.eye(2), np.array([[1.0, 1.0], [0.0, 1.0]])]]
    Ks = [[0.8 * np.linalg.inv(h) for h in Hs[0]]]
    W = np.array([[0.5, 0.5], [0.5, 0.5]])
    modes = [[A @ (np.eye(2) - k @ h) for k, h in zip(Ks[0], Hs[0], strict=True)]]
    X = [np.eye(2), np.eye(2)]
    for _ in range(200):
        X = [np.eye(2) + t for t in image("J", W, modes[0], X)]
    cert = ekf_covariance_bound_certificate(A, Ks, Hs, W, X)
    assert set(cert["data"]["modes"][0]) == {"K", "H"}
    assert check_certificate(cert).valid


# --- tampering -------------------------------------------------------------------------------


def numeric_leaves(cert: dict) -> list[tuple]:
    """Paths of every rational string in claim, data and witness (statement text excluded)."""
    out = []

    def walk(value, path):
        if isinstance(value, dict):
            for key, item in value.items():
                if key != "statement":
                    walk(item, (*path, key))
        elif isinstance(value, list):
            for index, item in enumerate(value):
                walk(item, (*path, index))
        elif isinstance(value, str) and path[0] in ("claim", "data", "witness"):
            try:
                Fraction(value)
            except ValueError:
                return
            out.append(path)

    walk(cert, ())
    return out


def rejected(cert: dict) -> bool:
    try:
        return not check_certificate(json.loads(json.dumps(cert))).valid
    except MalformedError:
        return True


def changed(cert: dict, path: tuple, delta: Fraction) -> dict:
    out = copy.deepcopy(cert)
    node = out
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = str(Fraction(node[path[-1]]) + delta)
    return out


@settings(max_examples=15)
@given(
    stable_networks(max_agents=3, max_n=2),
    st.data(),
    st.fractions(min_value=Fraction(-1), max_value=1).filter(lambda x: x != 0),
)
def test_changing_any_number_is_rejected(network, data, delta) -> None:
    """Every rational of claim, data and witness enters an exact equality or inequality."""
    W, gammas = network
    cert = mjls_stability_certificate(gammas, W, fixed_point_witness("L", W, gammas))
    path = data.draw(st.sampled_from(numeric_leaves(cert)))
    assert rejected(changed(cert, path, delta)), path


def test_changing_any_number_of_the_paper_example_is_rejected() -> None:
    """Every leaf of the S-detectability certificate of seed 000 §5.3.1, zeros included."""
    A = 2 * np.eye(2)
    Cs = [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)]
    gains = [np.array([[2.0], [0.0]]), np.array([[0.0], [2.0]]), 2 * np.eye(2)]
    W = np.array([[0.24, 0.76, 0], [0.76, 0.24, 0], [0, 0, 1]])
    gammas = [A - g @ c for g, c in zip(gains, Cs, strict=True)]
    cert = s_detectability_certificate(
        A,
        Cs,
        W,
        "consensus-then-filter",
        gains,
        fixed_point_witness("L", W, gammas, iterations=2000),
    )
    survivors = [p for p in numeric_leaves(cert) if not rejected(changed(cert, p, Fraction(1, 3)))]
    assert survivors == []


@given(stable_networks(max_agents=3, max_n=2).filter(lambda nw: len(nw[0]) >= 2), st.data())
def test_swapping_two_agents_in_one_place_is_rejected(network, data) -> None:
    W, gammas = network
    cert = mjls_stability_certificate(gammas, W, fixed_point_witness("L", W, gammas))
    i, j = data.draw(st.lists(st.integers(0, len(W) - 1), min_size=2, max_size=2, unique=True))
    where = data.draw(st.sampled_from([("data", "Gamma"), ("witness", "P"), ("data", "W")]))
    tampered = copy.deepcopy(cert)
    block = tampered[where[0]][where[1]]
    block[i], block[j] = block[j], block[i]
    if block[i] == block[j]:
        return
    assert rejected(tampered)


@given(stable_networks(max_agents=3, max_n=2).filter(lambda nw: len(nw[0]) >= 2), st.data())
def test_dropping_a_block_is_refused(network, data) -> None:
    W, gammas = network
    cert = mjls_stability_certificate(gammas, W, fixed_point_witness("L", W, gammas))
    where = data.draw(
        st.sampled_from([("data", "Gamma"), ("witness", "P"), ("witness", "decrease")])
    )
    tampered = copy.deepcopy(cert)
    del tampered[where[0]][where[1]][data.draw(st.integers(0, len(W) - 1))]
    with pytest.raises(MalformedError):
        check_certificate(tampered)


def test_corollary_a22_needs_a_uniform_margin() -> None:
    """Erratum (seed 000 Cor. A.2.2): ``Xⁱ ≻ f₁ⁱ(M_k, X)`` for every k ≥ 0 does not bound P_k.

    N = 1, w = 1, X = 1, U = 1 and M_k = √m_k with m_k = 1 − 1/(k+2)² < 1: each step satisfies
    the strict inequality (X − f₁ = 1/(k+2)² > 0), yet P_{k+1} = m_k P_k + 1 from P_0 = 0 obeys
    P_k ≥ k·Π_{j<k} m_j ≥ k/2 (the product telescopes to (k+2)/(2(k+1)) > 1/2), so P_k → ∞.
    Checked exactly for the first 300 steps.
    """
    P, product = Fraction(0), Fraction(1)
    for k in range(300):
        assert product == Fraction(k + 2, 2 * (k + 1))
        assert P >= k * product >= Fraction(k, 2)
        m = 1 - Fraction(1, (k + 2) ** 2)
        assert 1 - m * 1 > 0
        P, product = m * P + 1, product * m
    assert P >= 150


@given(stable_networks(max_agents=3, max_n=3), st.sampled_from(OPERATORS))
def test_checker_operators_match_the_paper_formulas(network, operator) -> None:
    """``proofs_check.operators`` (exact) agrees with eqs. (5.12)–(5.13), (C.6) written out here,
    and the adjoints satisfy ``⟨T(V), S⟩ = ⟨V, T*(S)⟩``."""
    from proofs_check.operators import apply_operator
    from theory.core.exact import exact_matrix

    W, gammas = network
    rng = np.random.default_rng(len(W) * 7 + gammas[0].shape[0])
    V = [(lambda m: m + m.T)(rng.standard_normal(gammas[0].shape)) for _ in W]
    exact = apply_operator(
        operator, exact_matrix(W), [exact_matrix(g) for g in gammas], [exact_matrix(v) for v in V]
    )
    for got, want in zip(exact, image(operator, W, gammas, V), strict=True):
        assert np.allclose(np.array(got, dtype=float), want, rtol=1e-12, atol=1e-12)
    if operator.endswith("adjoint"):
        S = [(lambda m: m @ m.T)(rng.standard_normal(gammas[0].shape)) for _ in W]
        forward = image(operator.removesuffix("-adjoint"), W, gammas, V)
        backward = image(operator, W, gammas, S)
        left = sum(np.trace(t @ s) for t, s in zip(forward, S, strict=True))
        right = sum(np.trace(v @ b) for v, b in zip(V, backward, strict=True))
        assert np.isclose(left, right, rtol=1e-10, atol=1e-10)
