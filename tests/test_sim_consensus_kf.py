"""Seed 000 §5.3: the consensus Kalman filter's covariances, Examples 1–2, both orders.

The condition the text states before Figs 5.2–5.3 is ``w_ii < (1/r_σ(A_i^u))²`` for each agent
``i`` whose pair ``(A, C_i)`` is not detectable (``A_i^u``: its unobservable part). It is computed
here from the matrices (PBH test), not copied from the text.
"""

from __future__ import annotations

import numpy as np
import pytest

from theory.observability import unobservable_eigenvalues
from theory.sim.consensus_kf import ORDERS, simulate_consensus_kf

EXAMPLE_1 = {
    "A": 2.0 * np.eye(2),
    "C": [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)],
    "R": [0.1 * np.eye(1), 0.1 * np.eye(1), 0.1 * np.eye(2)],
    "Q": 0.1 * np.eye(2),
    "x0": np.array([-15.0, 15.0]),
    "P0": 10.0 * np.eye(2),
    "W": {
        "W_g": [[0.24, 0.76, 0], [0.76, 0.24, 0], [0, 0, 1]],
        "W_c": [[0.25, 0.75, 0], [0.75, 0.25, 0], [0, 0, 1]],
        "W_b": [[0.26, 0.74, 0], [0.74, 0.26, 0], [0, 0, 1]],
    },
}
EXAMPLE_2 = {
    "A": np.array([[0.8147, 0.8147, 0.2785], [0.9058, 0.9058, 0.5469], [0, 0, 0.9575]]),
    "C": [np.eye(3)[[i]] for i in range(3)],
    "R": [np.eye(1)] * 3,
    "Q": np.eye(3),
    "x0": np.array([-2.2691, -2.0143, 1.6173]),
    "P0": 100.0 * np.eye(3),
    "W": {
        "W_g": [[1, 0, 0], [0, 1, 0], [0.34, 0.34, 0.32]],
        "W_b": [[1, 0, 0], [0, 1, 0], [0.33, 0.33, 0.34]],
    },
}
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


CASES = [
    (example, name) for example in (EXAMPLE_1, EXAMPLE_2) for name in example["W"] if name != "W_c"
]


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize(("example", "name"), CASES, ids=lambda v: v if isinstance(v, str) else "")
def test_covariances_bounded_iff_self_weight_condition(example: dict, name: str, order: str):
    """Figs 5.2–5.3: P bounded for W_g, unbounded for W_b, in both orders (App. C.3)."""
    W = np.array(example["W"][name], dtype=float)
    norms = _run(example, example["W"][name], order).cov_norms
    mid, end = norms[STEPS // 2], norms[-1]
    for i, condition in enumerate(_self_weight_condition(example, W)):
        if condition is None or condition:
            assert abs(end[i] - mid[i]) <= CONVERGED_TOL * mid[i], (name, i, mid[i], end[i])
        else:
            assert end[i] > GROWTH * mid[i], (name, i, mid[i], end[i])
    assert (name == "W_g") == all(c is not False for c in _self_weight_condition(example, W))


@pytest.mark.parametrize("order", ORDERS)
def test_boundary_weight_grows_linearly(order: str) -> None:
    """Example 1 with W_c (w_ii = 1/r_σ² exactly): ‖P_1‖ grows without bound, linearly."""
    norms = _run(EXAMPLE_1, EXAMPLE_1["W"]["W_c"], order).cov_norms[:, 0]
    quarter, half, end = norms[STEPS // 4], norms[STEPS // 2], norms[-1]
    assert end > 1.5 * half
    assert abs((end - half) - 2 * (half - quarter)) <= 0.01 * (end - half)


def test_unknown_order_is_refused() -> None:
    with pytest.raises(ValueError, match="order"):
        _run(EXAMPLE_1, EXAMPLE_1["W"]["W_g"], "sideways")
