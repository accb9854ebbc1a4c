"""Online model learning (seed 002 §3.2.2, eqs. (3.17)–(3.19)) and its guards."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.particle.case import DcrwParams
from theory.particle.dcrw import (
    movement_samples,
    sample_dcrw_path,
    sample_weibull,
    sample_wrapped_cauchy,
)
from theory.particle.filter import OnlineLearner, UniformMotion
from theory.registry import get_claim


@given(st.integers(0, 2**32 - 1))
def test_movement_samples_invert_eqs_3_3_to_3_5(seed: int):
    params = DcrwParams(0.3, 0.5, 1.5, 2.0)
    path = sample_dcrw_path(params, 30, np.random.default_rng(seed), start=np.zeros(2), heading=0.2)
    replay = np.random.default_rng(seed)
    turns = sample_wrapped_cauchy(replay, 0.3, 0.5, (30,))
    steps = sample_weibull(replay, 1.5, 2.0, (30,))
    got_turns, got_steps = movement_samples(path)
    np.testing.assert_allclose(got_steps, steps, rtol=1e-10)
    np.testing.assert_allclose(got_turns, turns[1:], atol=1e-9)


def test_movement_samples_wrap_turns_and_drop_zero_steps():
    track = np.array([[0.0, 0.0], [1.0, 0.01], [0.0, 0.0], [0.0, 0.0], [1.0, 0.0]])
    turns, steps = movement_samples(track)
    assert np.all(np.abs(turns) <= np.pi)
    assert steps.size == 3 and np.all(steps > 0)


def _feed(learner: OnlineLearner, track: np.ndarray) -> OnlineLearner:
    for point in track:
        learner = learner.observe(point[None])
    return learner


def test_no_fit_before_min_samples_then_switch():
    path = sample_dcrw_path(
        DcrwParams(0, 0.6, 2, 3), 40, np.random.default_rng(0), start=np.zeros(2)
    )
    learner = OnlineLearner(UniformMotion(5.0), min_samples=10, burn_in=0)
    early = _feed(learner, path[:11])  # 11 estimates → 9 turning angles
    assert not early.fitted.any()
    turn, step = early.sample(np.random.default_rng(1), (1, 2000))
    assert step.max() <= 5.0 and abs(turn.mean()) < 0.2  # the uniform prior
    assert _feed(learner, path[:12]).fitted.all()


def test_burn_in_discards_early_estimates():
    learner = OnlineLearner(UniformMotion(5.0), min_samples=3, burn_in=4)
    wild = np.array([[0, 0], [90, 0], [-80, 40], [10, -70]], float)
    steady = np.cumsum(np.tile([[1.0, 0.0], [0.0, 1.0]], (4, 1)), axis=0)
    learned = _feed(learner, np.vstack([wild, steady]))
    assert learned.params[0, 3] == pytest.approx(1.0, rel=1e-6)  # λ from unit steps only


def test_straight_track_fit_is_clamped():
    track = np.stack([np.arange(20.0), 0.5 * np.arange(20.0)], axis=1)
    learned = _feed(OnlineLearner(UniformMotion(5.0), burn_in=0, gamma_max=0.9), track)
    mu, gamma, kappa, lam = learned.params[0]
    assert gamma == 0.9 and mu == pytest.approx(0.0, abs=1e-9)
    assert kappa == 10.0 and lam == pytest.approx(np.hypot(1, 0.5))


def test_learned_sampling_uses_each_nodes_fit():
    rng = np.random.default_rng(3)
    params = np.array([[0.0, 0.8, 2.0, 3.0], [np.nan] * 4])
    learner = OnlineLearner(UniformMotion(1.0), params=params)
    turn, step = learner.sample(rng, (2, 20000))
    assert step[1].max() <= 1.0 and step[0].mean() == pytest.approx(3.0 * 0.886227, rel=0.02)
    assert abs(np.mean(np.exp(1j * turn[0])) - 0.8) < 0.02  # E e^{iφ} = γ e^{iμ}


@pytest.mark.parametrize("claim", ["seed002.eq3.1", "seed002.eq3.2", "seed002.eq3.17"])
def test_model_claims_verified(claim: str):
    (result,) = get_claim(claim).run(None)
    assert result.status == "verified", result.evidence
    assert result.margin > 0 and result.tolerance["z_tol"] == 4.0
