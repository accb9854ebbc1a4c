"""Seed 000 §5.3: the consensus Kalman filter's covariances, Examples 1–2, both orders.

The condition the text states before Figs 5.2–5.3 is ``w_ii < (1/r_σ(A_i^u))²`` for each agent
``i`` whose pair ``(A, C_i)`` is not detectable (``A_i^u``: its unobservable part). It is computed
here from the matrices (PBH test), not copied from the text.
"""

from __future__ import annotations

import numpy as np
import pytest

from theory.consensus.case import Order, ch5_examples
from theory.consensus.kalman_filter import simulate_consensus_kf, true_error_covariance
from theory.core.observability import unobservable_eigenvalues
from theory.registry import get_claim

EXAMPLES = ch5_examples()
EXAMPLE_1, EXAMPLE_2 = EXAMPLES["example 1"], EXAMPLES["example 2"]
STEPS = 400
CONVERGED_TOL = 1e-3
"""Relative change of ‖P_i‖ between k = K/2 and K under which it counts as converged."""
GROWTH = 2.0
"""Factor by which ‖P_i‖ must grow between K/2 and K to count as unbounded."""


def _run(example: dict, W: list, order: str):
    return simulate_consensus_kf(
        example["A"],
        example["C"],
        np.array(W, dtype=float),
        example["Q"],
        example["R"],
        x0=example["x0"],
        estimate0=np.zeros_like(example["x0"]),
        P0=example["P0"],
        steps=STEPS,
        rng=np.random.default_rng(0),
        order=order,
    )


def _self_weight_condition(example: dict, W: np.ndarray) -> list[bool | None]:
    """``w_ii r_σ(A_i^u)² < 1`` per agent (``None`` where ``(A, C_i)`` is detectable)."""
    out = []
    for i, C in enumerate(example["C"]):
        lost = [abs(lam) for lam in unobservable_eigenvalues(example["A"], C) if abs(lam) >= 1]
        out.append(None if not lost else bool(W[i, i] * max(lost) ** 2 < 1))
    return out


CASES = [(example, name) for example in (EXAMPLE_1, EXAMPLE_2) for name in ("W_g", "W_b")]


@pytest.mark.parametrize("order", list(Order))
@pytest.mark.parametrize(("example", "name"), CASES, ids=lambda v: v if isinstance(v, str) else "")
def test_covariances_bounded_iff_self_weight_condition(example: dict, name: str, order: str):
    """Figs 5.2–5.3: P bounded for W_g, unbounded for W_b, in both orders (App. C.3)."""
    W = np.array(example[name], dtype=float)
    norms = _run(example, example[name], order).cov_norms
    mid, end = norms[STEPS // 2], norms[-1]
    for i, condition in enumerate(_self_weight_condition(example, W)):
        if condition is None or condition:
            assert abs(end[i] - mid[i]) <= CONVERGED_TOL * mid[i], (name, i, mid[i], end[i])
        else:
            assert end[i] > GROWTH * mid[i], (name, i, mid[i], end[i])
    assert (name == "W_g") == all(c is not False for c in _self_weight_condition(example, W))


@pytest.mark.parametrize("order", list(Order))
def test_boundary_weight_grows_linearly(order: str) -> None:
    """Example 1 with W_c (w_ii = 1/r_σ² exactly): ‖P_1‖ grows without bound, linearly."""
    norms = _run(EXAMPLE_1, EXAMPLE_1["W_c"], order).cov_norms[:, 0]
    quarter, half, end = norms[STEPS // 4], norms[STEPS // 2], norms[-1]
    assert end > 1.5 * half
    assert abs((end - half) - 2 * (half - quarter)) <= 0.01 * (end - half)


def test_unknown_order_is_refused() -> None:
    with pytest.raises(ValueError, match="order"):
        _run(EXAMPLE_1, EXAMPLE_1["W_g"], "sideways")


def test_registered_claim_verifies_both_examples() -> None:
    result = get_claim("seed000.sec5.3.sim-examples").run(None)[0]
    assert result.status == "verified", result.evidence


@pytest.mark.parametrize("order", list(Order))
@pytest.mark.parametrize("example", [EXAMPLE_1, EXAMPLE_2], ids=["example 1", "example 2"])
def test_diverging_p_does_not_mean_diverging_error(example: dict, order: str) -> None:
    """Finding (docs/errata.md): with W_b the P_i of (5.9) diverge, yet the exact error
    covariance under the filter's own gains stays bounded and within 2 % of W_g's."""
    results = {}
    for name in ("W_g", "W_b"):
        traces, p_norms = true_error_covariance(
            example["A"], example["C"], np.array(example[name], float), example["Q"],
            example["R"], example["P0"], 600, order=order,
        )  # fmt: skip
        results[name] = (traces, p_norms)
    g_traces, _ = results["W_g"]
    b_traces, b_norms = results["W_b"]
    assert b_norms[-1].max() > GROWTH * b_norms[300].max()  # P unbounded
    assert abs(b_traces[-1] - b_traces[300]) <= 1e-6 * b_traces[300]  # the error is not
    assert abs(b_traces[-1] / g_traces[-1] - 1) < 0.02


def test_error_covariance_matches_monte_carlo() -> None:
    """The exact recursion against the sample covariance of 400 simulated runs (Example 1,
    W_g): agreement within 4 standard errors of the Monte Carlo mean."""
    W = np.array(EXAMPLE_1["W_g"], float)
    traces, _ = true_error_covariance(
        EXAMPLE_1["A"], EXAMPLE_1["C"], W, EXAMPLE_1["Q"], EXAMPLE_1["R"], EXAMPLE_1["P0"], 30
    )
    rng = np.random.default_rng(7)
    samples = []
    for _ in range(400):
        x0 = rng.multivariate_normal(np.zeros(2), EXAMPLE_1["P0"])
        run = simulate_consensus_kf(
            EXAMPLE_1["A"], EXAMPLE_1["C"], W, EXAMPLE_1["Q"], EXAMPLE_1["R"], x0=x0,
            estimate0=np.zeros(2), P0=EXAMPLE_1["P0"], steps=30, rng=rng,
        )  # fmt: skip
        samples.append((run.errors[-1] ** 2).sum())
    mean, stderr = np.mean(samples), np.std(samples) / np.sqrt(len(samples))
    assert abs(mean - traces[-1]) < 4 * stderr, (mean, traces[-1], stderr)
