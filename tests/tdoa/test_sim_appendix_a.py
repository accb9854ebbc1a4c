"""Seed 000 App. A, Lemma A.1.2: constants and inequality (A.24) along simulated runs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st
from scipy.linalg import block_diag

from theory.core.case_file import bundled_cases
from theory.core.network import stationary_vector, uniform_weights
from theory.kinds import load_case, parse_case
from theory.registry import get_claim
from theory.tdoa.estimation.scenario import hears_at, run_tdoa_scenario, weights_at
from theory.tdoa.estimation.stability import a24_factor, lemma_a12_along
from theory.tdoa.model import cv_discrete, tdoa_jacobian


def _run(name: str, steps: int = 15):
    spec = dataclasses.replace(load_case(name).spec, tau=1.0, steps=steps)
    return spec, run_tdoa_scenario(spec, np.random.default_rng(4))


def test_constants_of_the_cv_model() -> None:
    """‖A‖ for T = 1 is the golden ratio; λ_max(BBᵀ) = T⁴/4 + T²; BQBᵀ has rank d = 3 of 6."""
    spec, run = _run("sim-ch4-fixed-b0")
    out = lemma_a12_along(spec, run)
    assert np.isclose(out["constants"]["a_bar"], (1 + np.sqrt(5)) / 2)
    assert np.isclose(out["constants"]["delta"], 1.25)
    assert out["bqb_rank"] == 3 and out["bqb_lower_bound"] == 0.0
    c = out["constants"]
    assert c["p_low"] > 0 and c["p_high"] >= 100.0  # P_0 = 100 I is among the P_k


def test_factor_is_the_smallest_constant_in_a24() -> None:
    """c_0 = λ_max(P_0^{1/2} LHS P_0^{1/2}) rebuilt by hand at k = 0, where P_0 = 100 I."""
    spec, run = _run("sim-ch4-range21-b0", steps=3)
    out = lemma_a12_along(spec, run)
    A, B = cv_discrete(1.0)
    positions = run.paths[0]
    hears = hears_at(spec, positions)
    blocks = []
    for i in range(spec.n_agents):
        H = tdoa_jacobian(spec.x0[:3], positions, i, np.flatnonzero(hears[i]))
        K = 100 * H.T @ np.linalg.inv(100 * H @ H.T + spec.r * np.eye(H.shape[0]))
        blocks.append(np.eye(6) - K @ H)
    I_KH = block_diag(*blocks)
    WA = np.kron(weights_at(spec, positions), A)
    P1 = block_diag(*[A @ P @ A.T + B @ spec.Q @ B.T for P in run.covariances[0]])
    lhs = I_KH.T @ WA.T @ np.linalg.inv(P1) @ WA @ I_KH
    expected = 100 * np.linalg.eigvalsh(0.5 * (lhs + lhs.T))[-1]
    assert np.isclose(out["factors"][0], expected, rtol=1e-9)
    assert np.all(out["factors"] > 0) and np.all(out["factors"] < 1)


def test_a24_holds_along_runs_but_alpha_is_tiny() -> None:
    """Finding: (A.24) held at every step of the bundled runs; α of (A.35) is below 1e-9."""
    spec, run = _run("sim-ch4-range21-b0", steps=20)
    out = lemma_a12_along(spec, run)
    assert out["holds"].all()
    assert 0 < 1 - out["one_minus_alpha"] < 1e-9
    assert out["factors"].max() < 1


def test_registered_claim_reports_correction() -> None:
    case = load_case("sim-ch4-fixed-b0")
    result = get_claim("seed000.lemA.1.2").run(case)[0]
    assert result.status == "corrected" and result.margin > 0
    assert result.evidence["bqb_rank"] == 3


def test_refuses_fast_consensus() -> None:
    spec = load_case("sim-ch4-fixed-b0").spec
    run = run_tdoa_scenario(dataclasses.replace(spec, steps=2), np.random.default_rng(0))
    with pytest.raises(ValueError, match="tau = T"):
        lemma_a12_along(dataclasses.replace(spec, steps=2), run)


def test_row_stochastic_weights_refute_a24() -> None:
    """Bundled case ``seed000-lemA12-uniform-weights`` (docs/errata.md): uniform weights, in the
    class of §4.2.2 but not doubly stochastic, give c_0 > 1 in (A.24), so no α in (0, 1) works;
    Metropolis weights on the same network give c_0 = 1 to rounding."""
    case = load_case("seed000-lemA12-uniform-weights")
    result = get_claim("seed000.lemA.1.2").run(case)[0]
    assert result.status == "refuted" and result.evidence["first_failure_step"] == 0
    assert result.evidence["max_factor"] > 1.06
    assert result.evidence["max_weighted_factor"] <= 1 + 1e-12  # the corrected Lemma A.1.2′
    raw = yaml.safe_load(bundled_cases()["seed000-lemA12-uniform-weights"].read_text())
    raw["tdoa-sim"]["weights"] = "metropolis"
    metropolis = parse_case(raw).spec
    out = lemma_a12_along(metropolis, run_tdoa_scenario(metropolis, np.random.default_rng(0)))
    assert abs(out["factors"][0] - 1) < 1e-12


def test_stationary_weighting_restores_a24() -> None:
    """Corrected Lemma A.1.2 (docs/errata.md): on the bundled uniform-weights case the
    π-weighted factor is ≤ 1 at every ping and equals 1 at ping 0, so 1 − α = 1 is sharp;
    π is the stationary vector of W (πᵀW = πᵀ, π > 0)."""
    case = load_case("seed000-lemA12-uniform-weights")
    out = lemma_a12_along(case.spec, run_tdoa_scenario(case.spec, np.random.default_rng(0)))
    assert out["factors"][0] > 1.06
    assert np.all(out["weighted_factors"] <= 1 + 1e-12)
    assert abs(out["weighted_factors"][0] - 1) < 1e-12


def test_stationary_vector_is_left_invariant_per_component() -> None:
    """Two components (a path and an edge), uniform weights: πᵀW = πᵀ, π > 0, unit mass each;
    on the path 1–2–3 the uniform rule gives π ∝ (d_i + 1) = (2, 3, 2)."""
    hears = np.zeros((5, 5), bool)
    for i, j in ((0, 1), (1, 2), (3, 4)):
        hears[i, j] = hears[j, i] = True
    W = uniform_weights(hears)
    pi = stationary_vector(W)
    assert np.allclose(pi @ W, pi, atol=1e-14) and np.all(pi > 0)
    assert np.allclose(pi, [2 / 7, 3 / 7, 2 / 7, 1 / 2, 1 / 2], atol=1e-14)


@st.composite
def _averaging_steps(draw: st.DrawFn) -> dict:
    """One step of (A.2) with random data: N agents, any row-stochastic W on a connected
    undirected support with weights over four decades, invertible A, P_k^i ≻ 0, H^i with 0–3
    rows, R^i ≻ 0, and process noise U = BQBᵀ + qI with q ≥ 0."""
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    N, n = draw(st.integers(2, 5)), draw(st.sampled_from((2, 4)))
    hears = np.zeros((N, N), bool)
    for i in range(1, N):  # a random spanning tree, then extra links
        j = int(rng.integers(0, i))
        hears[i, j] = hears[j, i] = True
    extra = np.triu(rng.random((N, N)) < 0.3, 1)
    hears |= extra | extra.T
    raw = np.where(hears | np.eye(N, dtype=bool), 10.0 ** rng.uniform(-4, 0, (N, N)), 0.0)
    W = raw / raw.sum(axis=1, keepdims=True)
    A = rng.normal(size=(n, n)) + 2 * np.eye(n)
    P = [(lambda G: G @ G.T + 0.1 * np.eye(n))(rng.normal(size=(n, n))) for _ in range(N)]
    H = [rng.normal(size=(int(rng.integers(0, 4)), n)) for _ in range(N)]
    R = [np.diag(10.0 ** rng.uniform(-2, 1, h.shape[0])) for h in H]
    q = draw(st.sampled_from((0.0, 0.1, 1.0)))
    B = rng.normal(size=(n, n // 2))
    return {"W": W, "A": A, "P": P, "H": H, "R": R, "U": B @ B.T + q * np.eye(n), "q": q}


@given(_averaging_steps())
def test_corrected_lemma_a12_on_random_steps(step: dict) -> None:
    """The corrected Lemma A.1.2 (docs/errata.md) on random data, with P_{k+1} rebuilt from (A.2)
    directly: the π-weighted factor is ≤ 1/(1 + q/(ā² p̄)) (≤ 1 when q = 0), and the unweighted
    one is ≤ the largest column sum of W (≤ 1 when W is doubly stochastic)."""
    W, A, P, H, R, U = (step[k] for k in ("W", "A", "P", "H", "R", "U"))
    N, n = len(W), len(A)
    KH = [
        np.linalg.solve(h @ p @ h.T + r, h @ p).T @ h if h.size else np.zeros((n, n))
        for p, h, r in zip(P, H, R, strict=True)
    ]
    posterior = [(np.eye(n) - kh) @ p for kh, p in zip(KH, P, strict=True)]  # (I − KH)P = P⁺
    P_next = [sum(W[i, j] * A @ posterior[j] @ A.T for j in range(N)) + U for i in range(N)]
    I_KH, Pk, Pn = np.eye(n * N) - block_diag(*KH), block_diag(*P), block_diag(*P_next)
    p_bar = max(np.linalg.eigvalsh(p)[-1] for p in P)
    rate = 1 / (1 + step["q"] / (np.linalg.norm(A, 2) ** 2 * p_bar))
    weighted = a24_factor(W, A, I_KH, Pk, Pn, weights=stationary_vector(W))
    assert weighted <= rate * (1 + 1e-9)
    assert a24_factor(W, A, I_KH, Pk, Pn) <= W.sum(axis=0).max() * (1 + 1e-9)
