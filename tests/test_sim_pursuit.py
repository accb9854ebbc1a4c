"""Seed 003 §VI, 2-D (Table I): the DEC loop pursues, localizes and coordinates."""

from __future__ import annotations

import numpy as np
import pytest

from theory.sim.pursuit import DecSettings, simulate_dec_2d
from theory.sim.range_dekf import table_target

STEPS = 1500  # 150 s of 0.1 s; the paper's runs are 450 s
START = np.array([[-40.0, -40.0], [-30.0, -45.0], [-45.0, -30.0]])
"""Initial offsets of the trackers from the target (not given in the paper)."""
RING = [[1], [2], [0]]


def _run(n: int, controller: str = "II", seed: int = 0, steps: int = STEPS):
    times = 0.1 * np.arange(steps + 1)
    target = table_target("I", times)
    x0 = np.concatenate([target[0, :2] + [5.0, -5.0], [0.0, 0.0]])
    return simulate_dec_2d(
        target,
        target[0, :2] + START[:n],
        np.zeros(n),
        np.array([0.0, 1.0, 2.0])[:n],
        RING if n == 3 else [[]],
        x0,
        10 * np.eye(4),
        steps,
        np.random.default_rng(seed),
        DecSettings(controller=controller),
    )


def test_three_trackers_pursue_localize_and_coordinate() -> None:
    """Figs VI.2–VI.4: pursuit and localization errors small; γ^[i] agree and γ̇^[i] → ω̄."""
    run = _run(3)
    late = slice(-300, None)
    assert run.pursuit_errors[late].max() < 2.0
    assert run.localization_errors[late].max() < 1.5
    assert np.ptp(run.gammas[-1]) < 0.05
    assert np.abs(run.gamma_rates[-100:] - 0.05).mean() < 0.005  # a neighbourhood of ω̄
    assert np.abs(run.gamma_rates[-1] - 0.05).max() < 0.005


def test_three_trackers_localize_faster_than_one() -> None:
    """Fig. VI.3: convergence is faster with three trackers (mean error over the first 100 s)."""
    one = np.mean([_run(1, seed=s).localization_errors[:1000].mean() for s in range(2)])
    three = np.mean([_run(3, seed=s).localization_errors[:1000].mean() for s in range(2)])
    assert three < one


def test_singular_delta_is_refused() -> None:
    """Eq. (22)/Remark 6: Δ̄ exists only when ε₁ ≠ 0."""
    target = table_target("I", np.zeros(2))
    with pytest.raises(ValueError, match="epsilon"):
        simulate_dec_2d(
            target, START[:1], np.zeros(1), np.zeros(1), [[]], target[0], np.eye(4), 1,
            np.random.default_rng(0), DecSettings(epsilon=(0.0, 0.5)),
        )  # fmt: skip
