"""Seed 000 App. A, Lemma A.1.2: constants and inequality (A.24) along simulated runs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import yaml
from scipy.linalg import block_diag

from theory.core.case_file import bundled_cases
from theory.kinds import load_case, parse_case
from theory.registry import get_claim
from theory.tdoa.estimation.scenario import hears_at, run_tdoa_scenario, weights_at
from theory.tdoa.estimation.stability import lemma_a12_along
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
    raw = yaml.safe_load(bundled_cases()["seed000-lemA12-uniform-weights"].read_text())
    raw["tdoa-sim"]["weights"] = "metropolis"
    metropolis = parse_case(raw).spec
    out = lemma_a12_along(metropolis, run_tdoa_scenario(metropolis, np.random.default_rng(0)))
    assert abs(out["factors"][0] - 1) < 1e-12
