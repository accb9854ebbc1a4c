"""NEES/NIS and OSPA of seed 003's DEKF (Algorithm 2) in ``trackcert simulate``'s pursuit summary
(theory.pursuit.filter_metrics): the recorded innovations are the EKF's, a filter trusting its
ranges too much fails the NIS band, and a stopped run counts only up to where it stopped."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from theory.core.consistency import Consistency, consistency_test, nis
from theory.core.engines import ENGINE_SETTING
from theory.kinds import load_case
from theory.pursuit import compiled_replay
from theory.pursuit.dekf import encircling_paths, range_dekf, table_target, transition_matrix
from theory.pursuit.filter_metrics import REPLAY_KEY, REPLAY_MIN_STEPS, dekf_metrics, replay_dekf
from theory.pursuit.simulation import dec_arguments, run_pursuit_case, summarize_pursuit

TS = 2.0
Q_TABLE_I = 1e-3 * np.diag([1, 1, 0.1, 0.1])


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), V=st.floats(0.5, 50))
def test_recorded_innovations_are_the_covariance_form_ekf_ones(seed: int, V: float) -> None:
    """ν = y − ‖q̂_{k|k−1} − p‖ and S = C P_{k|k−1} Cᵀ + 1/V with P = Ω⁻¹ (seed 003 (10), (41))."""
    rng = np.random.default_rng(seed)
    steps = 5
    target = table_target("I", TS * np.arange(steps))
    trackers = target[:, None, :2] + rng.uniform(10, 40, (steps, 1, 2))
    x0, P0 = target[0] + np.array([3.0, -2.0, 0.1, 0.0]), 20.0 * np.eye(4)
    run = range_dekf(
        trackers, target, Ts=TS, noise_var=0.25, V=V, Q=Q_TABLE_I, fusion=np.eye(1),
        x0=x0, P0=P0, rng=np.random.default_rng(seed),
    )  # fmt: skip
    noise = 0.5 * np.random.default_rng(seed).standard_normal(steps)
    F = np.block([[np.eye(2), TS * np.eye(2)], [np.zeros((2, 2)), np.eye(2)]])
    x, P = x0, P0
    for k in range(steps):
        diff = x[:2] - trackers[k, 0]
        H = np.concatenate([diff / np.linalg.norm(diff), np.zeros(2)])
        y = np.linalg.norm(trackers[k, 0] - target[k, :2]) + noise[k]
        nu = y - np.linalg.norm(diff)  # the two forms agree to rounding, as in Remark 7's test
        assert run.innovations[k, 0, 0] == pytest.approx(nu, rel=1e-7, abs=1e-7)
        S = H @ P @ H + 1 / V
        assert run.innovation_covariances[k, 0, 0, 0] == pytest.approx(S, rel=1e-7)
        K = P @ H / S
        x, P = x + K * (y - np.linalg.norm(diff)), P - np.outer(K, H @ P)
        x, P = F @ x, F @ P @ F.T + Q_TABLE_I


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), m=st.integers(1, 20))
def test_m_predictions_per_ts_are_one_with_the_accumulated_process_noise(seed: int, m: int) -> None:
    """``predictions = m`` with F(T_s/m) and Q per T_s/m is one prediction (44) with F(T_s) and
    Q_Ts = Σ_{j<m} F(T_s/m)ʲ Q F(T_s/m)ʲᵀ: the covariance recursion P ← FPFᵀ + Q applied m times."""
    rng = np.random.default_rng(seed)
    steps = 6
    target = table_target("I", TS * np.arange(steps))
    trackers = target[:, None, :2] + rng.uniform(10, 40, (steps, 1, 2))
    F = transition_matrix(2, TS / m)
    powers = [np.linalg.matrix_power(F, j) for j in range(m)]
    accumulated = sum(A @ Q_TABLE_I @ A.T for A in powers)
    common = {"Ts": TS, "noise_var": 0.25, "V": 4.0, "fusion": np.eye(1), "P0": 20.0 * np.eye(4),
              "x0": target[0] + np.array([3.0, -2.0, 0.1, 0.0])}  # fmt: skip
    fine = range_dekf(trackers, target, Q=Q_TABLE_I, predictions=m,
                      rng=np.random.default_rng(seed), **common)  # fmt: skip
    coarse = range_dekf(trackers, target, Q=accumulated, rng=np.random.default_rng(seed), **common)
    np.testing.assert_allclose(fine.information, coarse.information, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(fine.estimates, coarse.estimates, rtol=1e-7, atol=1e-7)


@pytest.mark.parametrize("engine", ["numpy", "numba"])
def test_the_replay_is_the_published_loops_filter(engine: str) -> None:
    """Given the closed loop's own range noise, the replay of a published run (the DEKF predicting
    every 0.1 s, ``predict_every``) reproduces the loop's filter: its x̂_{k|k} propagated by F(δ)
    is the loop's recorded prior one record after each sampling instant (its error ‖x̂ − x‖).
    (Before the replay honoured ``predict_every`` it predicted once per T_s with Q per 0.1 s, a
    covariance far too small: ANEES 6.6 against 1.75 on pursuit-published-3d-n1,
    docs/simulation.md.)"""
    spec = load_case("cases/pursuit-published-3d-n1.yaml").spec
    rng = np.random.default_rng(np.random.SeedSequence([REPLAY_KEY, 0]))
    run = run_pursuit_case(spec, rng, steps=200)
    arguments = dec_arguments(spec, 200)
    replay = replay_dekf(run, arguments, 0, engine)
    every = round(spec.dekf.Ts / 0.1)
    step = transition_matrix(3, 0.1)
    after = every * np.arange(len(replay.estimates) - 1) + 1  # the last instant has no next record
    assert arguments["settings"].predictions == every == 20
    errors = np.linalg.norm(replay.estimates[:-1, 0] @ step.T - run.target[after], axis=-1)
    np.testing.assert_allclose(errors, run.estimation_errors[after, 0], rtol=1e-7, atol=1e-9)


def _encircling_nis(V: float, runs: int = 8) -> np.ndarray:
    """NIS of one tracker circling the Table I target at 20 m, ranges with σ = 0.5 m."""
    steps = 120
    times = TS * np.arange(steps)
    target = table_target("I", times)
    trackers = encircling_paths(target, times, 1, (20.0, 20.0), 0.05)
    values = []
    for seed in range(runs):
        run = range_dekf(
            trackers, target, Ts=TS, noise_var=0.25, V=V, Q=Q_TABLE_I, fusion=np.eye(1),
            x0=target[0] + np.array([1.0, -1.0, 0.0, 0.0]), P0=np.eye(4),
            rng=np.random.default_rng(seed),
        )  # fmt: skip
        values.append(nis(run.innovations, run.innovation_covariances)[:, 0])
    return np.array(values)


def test_a_dekf_trusting_its_ranges_too_much_fails_the_nis_band() -> None:
    """With V = 100/σ² the filter assumes a range variance 100 times too small: its NIS lies
    above the band (optimistic, the unsafe side), and far above that of V = 1/σ² on the same
    ranges. (The matched single-tracker filter is not consistent either on this geometry:
    its NIS grows after about 30 s; docs/simulation.md.)"""
    overconfident = consistency_test("NIS", _encircling_nis(100 / 0.25), 1)
    matched = consistency_test("NIS", _encircling_nis(1 / 0.25), 1)
    assert overconfident.verdict is Consistency.OPTIMISTIC
    assert overconfident.value > overconfident.band.upper and overconfident.margin < 0
    assert overconfident.value > 5 * matched.value


@pytest.fixture(scope="module")
def table1_runs() -> tuple:
    case = load_case("cases/pursuit-table1-n3.yaml")
    runs = [run_pursuit_case(case.spec, np.random.default_rng(s), steps=300) for s in range(2)]
    return case.spec, runs


def test_pursuit_summary_reports_every_tracker(table1_runs: tuple) -> None:
    spec, runs = table1_runs
    summary = summarize_pursuit(spec, runs)
    metrics = summary["metrics"]
    every = round(spec.dekf.Ts / 0.1)
    samples = 2 * len(runs[0].times[::every])
    assert len(metrics["nees"]) == len(metrics["nis"]) == len(spec.trackers)
    for test in metrics["nees"]:
        assert test["band"]["dof"] == 4 * samples and test["band"]["samples"] == samples
    for test in metrics["nis"]:
        assert test["band"]["dof"] == samples
    for agent, test in zip(summary["agents"], metrics["nees"], strict=True):
        assert agent["anees"] == test["value"] and agent["nees_verdict"] == test["verdict"]
        assert 0 <= agent["mean_ospa"] <= metrics["positions"]["tolerance"]["ospa_cutoff"]


def test_the_metrics_are_the_same_on_both_engines(table1_runs: tuple) -> None:
    """The compiled replay (theory.pursuit.compiled_replay) gives the NumPy replay's NEES, NIS
    and OSPA, their bands and verdicts, to rounding."""
    spec, runs = table1_runs
    arguments = dec_arguments(spec, len(runs[0].times) - 1)
    fast, slow = (dekf_metrics(runs, arguments, engine) for engine in ("numba", "numpy"))
    for name in ("nees", "nis"):
        for got, want in zip(fast[name], slow[name], strict=True):
            assert got["verdict"] == want["verdict"] and got["band"] == want["band"]
            assert got["value"] == pytest.approx(want["value"], rel=1e-9)
    assert fast["positions"]["mean_ospa"] == pytest.approx(slow["positions"]["mean_ospa"], 1e-9)


def test_a_stopped_run_counts_until_it_stopped(table1_runs: tuple) -> None:
    spec, runs = table1_runs
    positions = runs[1].positions.copy()
    positions[151:] = np.nan  # stopped at t = 15 s: the records after it are NaN
    stopped = [runs[0], dataclasses.replace(runs[1], positions=positions)]
    arguments = dec_arguments(spec, len(runs[0].times) - 1)
    every = round(spec.dekf.Ts / 0.1)
    full = len(runs[0].times[::every])
    kept = len(positions[::every][np.isfinite(positions[::every]).all(axis=(1, 2))])
    metrics = dekf_metrics(stopped, arguments)
    assert metrics["nees"][0]["band"]["samples"] == full + kept < 2 * full


def test_the_replay_is_compiled_from_replay_min_steps_filter_steps(
    table1_runs, monkeypatch
) -> None:
    """Without a choice, the replay's engine follows its filter steps (runs × sampling instants):
    NumPy below REPLAY_MIN_STEPS, the compiled kernel from there; the keyword still wins."""
    spec, runs = table1_runs
    arguments = dec_arguments(spec, len(runs[0].times) - 1)
    instants = (len(runs[0].times) - 1) // round(spec.dekf.Ts / 0.1)
    calls = []
    compiled = compiled_replay.replay_compiled
    monkeypatch.setattr(
        compiled_replay, "replay_compiled", lambda *a, **k: calls.append(1) or compiled(*a, **k)
    )
    monkeypatch.delenv(ENGINE_SETTING, raising=False)
    few = runs[:1] * (REPLAY_MIN_STEPS // instants)
    dekf_metrics(few, arguments)
    assert len(few) * instants < REPLAY_MIN_STEPS and not calls
    many = runs[:1] * (len(few) + 1)
    dekf_metrics(many, arguments)
    assert len(many) * instants >= REPLAY_MIN_STEPS and len(calls) == len(many)
    dekf_metrics(runs[:1], arguments, "numba")
    assert len(calls) == len(many) + 1
