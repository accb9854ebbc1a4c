"""Seed 003: information-form DEKF (Algorithms 1–2), range model, Tables I–II trajectories."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.pursuit.dekf import encircling_paths, range_dekf, st_curve, table_target
from theory.tdoa.estimation.filters import ekf_update

TS = 2.0
Q_TABLE_I = 1e-3 * np.diag([1, 1, 0.1, 0.1])
RING = 0.5 * np.eye(3) + 0.5 * np.roll(np.eye(3), -1, axis=1)
"""Fusion weights π = 0.5 on a directed ring 1←2←3←1 (Fig. VI.1 is not reproduced in the text)."""


@given(seed=st.integers(0, 2**32 - 1))
def test_algorithm_1_equals_covariance_form_ekf(seed: int) -> None:
    """Remark 7 and §IV: the information form is the EKF; compare with (4.13)–(4.15)-style steps."""
    rng = np.random.default_rng(seed)
    steps = 6
    times = TS * np.arange(steps)
    target = table_target("I", times)
    trackers = target[:, None, :2] + rng.uniform(10, 40, (steps, 1, 2))
    x0 = target[0] + np.array([3.0, -2.0, 0.1, 0.0])
    P0 = 20.0 * np.eye(4)
    run = range_dekf(
        trackers, target, Ts=TS, noise_var=0.25, V=4.0, Q=Q_TABLE_I, fusion=np.eye(1),
        x0=x0, P0=P0, rng=np.random.default_rng(seed),
    )  # fmt: skip
    noise = np.sqrt(0.25) * np.random.default_rng(seed).standard_normal((steps, 1))
    F = np.block([[np.eye(2), TS * np.eye(2)], [np.zeros((2, 2)), np.eye(2)]])
    x, P = x0, P0
    for k in range(steps):
        y = np.linalg.norm(trackers[k, 0] - target[k, :2]) + noise[k]
        diff = x[:2] - trackers[k, 0]
        H = np.concatenate([diff / np.linalg.norm(diff), np.zeros(2)])[None, :]
        x, P = ekf_update(x, P, y - np.linalg.norm(diff), H, np.eye(1) / 4.0)
        assert np.allclose(run.estimates[k, 0], x, atol=1e-8 * (1 + np.abs(x).max()))
        assert np.allclose(np.linalg.inv(run.information[k, 0]), P, rtol=1e-7, atol=1e-10)
        x, P = F @ x, F @ P @ F.T + Q_TABLE_I


def test_fusion_of_agreeing_trackers_changes_nothing() -> None:
    """(43) with row-stochastic π maps identical (z̃, Ω̃) to themselves."""
    steps = 3
    target = table_target("I", TS * np.arange(steps))
    same = np.repeat(target[:, None, :2] + np.array([30.0, 0.0]), 3, axis=1)
    args = dict(Ts=TS, noise_var=0.0, V=4.0, Q=Q_TABLE_I, x0=target[0], P0=np.eye(4))
    alone = range_dekf(same[:, :1], target, fusion=np.eye(1), rng=np.random.default_rng(0), **args)
    fused = range_dekf(same, target, fusion=RING, rng=np.random.default_rng(0), **args)
    assert np.allclose(fused.estimates, alone.estimates[:, [0, 0, 0]])


@pytest.mark.parametrize("table", ["I", "II"])
def test_table_velocities_are_derivatives(table: str) -> None:
    t = np.array([0.0, 50.0, 123.0])
    h = 1e-5
    d = 2 if table == "I" else 3
    derivative = (table_target(table, t + h)[:, :d] - table_target(table, t - h)[:, :d]) / (2 * h)
    assert np.allclose(derivative, table_target(table, t)[:, d:], atol=1e-8)


def test_st_curve_phases_form_the_formation() -> None:
    """γ0^[i] = 2π(i−1)/N puts three trackers at 120° around the target (§V-A)."""
    target = table_target("I", np.zeros(1))
    paths = encircling_paths(target, np.zeros(1), 3, (30.0, 30.0), 0.05)[0] - target[0, :2]
    angles = np.sort(np.mod(np.arctan2(paths[:, 1], paths[:, 0]), 2 * np.pi))
    assert np.allclose(np.diff(angles), 2 * np.pi / 3)
    assert np.allclose(np.linalg.norm(st_curve(np.linspace(0, 6, 5), (30, 30), 0.3), axis=1), 30)


def test_three_trackers_localize_faster_than_one() -> None:
    """§VI: localization errors converge to a small neighbourhood, faster with N = 3 (Table I)."""
    steps = 160
    times = TS * np.arange(steps)
    target = table_target("I", times)
    x0 = target[0] + np.array([10.0, 10.0, -0.2, -0.3])
    reach = {}
    for n, fusion in ((1, np.eye(1)), (3, RING)):
        trackers = encircling_paths(target, times, n, (30.0, 30.0), 0.05)
        errors = np.mean(
            [
                range_dekf(
                    trackers, target, Ts=TS, noise_var=0.25, V=10.0, Q=Q_TABLE_I, fusion=fusion,
                    x0=x0, P0=100 * np.eye(4), rng=np.random.default_rng(seed),
                ).errors(target).mean(axis=1)
                for seed in range(3)
            ],
            axis=0,
        )  # fmt: skip
        below = np.flatnonzero(errors < 1.0)
        reach[n] = int(below[0]) if below.size else steps
        assert errors[-20:].max() < 1.5, (n, errors[-20:])
    assert reach[3] < reach[1], reach
