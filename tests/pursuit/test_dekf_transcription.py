"""trackcert's DEKF step against Algorithms 1–2 of seed 003, transcribed here line by line.

The transcription follows the paper's listing for one tracker i at a time (loops, no
vectorization, nothing imported from the filter under test): Correction (lines 7–10, eq. (41);
without a range z̃ = z_{k|k−1}, Ω̃ = Ω_{k|k−1}), Fusion (43), Prediction (44). It runs on a
recorded range sequence (tests/data/seed003_dekf_ranges.json: three trackers around the Table I
target, σ = 0.5 m, a range every 2 s) and must agree with :func:`theory.pursuit.dekf.dekf_step`
at every instant to 1e-9 (relative).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from theory.pursuit.dekf import dekf_step

DATA = json.loads((Path(__file__).parents[1] / "data" / "seed003_dekf_ranges.json").read_text())
POSITIONS = np.asarray(DATA["positions"])
RANGES = np.asarray(DATA["ranges"])
TS = DATA["Ts"]
Q = np.diag([1e-3, 1e-3, 1e-4, 1e-4])
X0 = np.array([[5.0, -5.0, 0.0, 0.0], [-3.0, 4.0, 0.1, 0.2], [2.0, 2.0, -0.1, 0.3]])
P0 = 10.0 * np.eye(4)
RING = np.array([[0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5]])  # 1←2, 2←3, 3←1


def model_matrix(step: float) -> np.ndarray:
    """F of seed 003 eq. (8) in 2-D."""
    return np.block([[np.eye(2), step * np.eye(2)], [np.zeros((2, 2)), np.eye(2)]])


def correction(x_prior, Omega_prior, p, y, V):
    """Algorithm 2 lines 7–10: (z̃, Ω̃) of one tracker; ``y`` None when no range came."""
    z_prior = Omega_prior @ x_prior
    if y is None:
        return z_prior, Omega_prior
    q_hat = x_prior[:2]
    d_hat = np.sqrt((q_hat[0] - p[0]) ** 2 + (q_hat[1] - p[1]) ** 2)
    C = np.array([[(q_hat[0] - p[0]) / d_hat, (q_hat[1] - p[1]) / d_hat, 0.0, 0.0]])
    y_tilde = y - d_hat + (C @ x_prior)[0]
    return z_prior + C[0] * V * y_tilde, Omega_prior + V * (C.T @ C)


def fusion(i, z_tilde, Omega_tilde, weights):
    """Eq. (43) at tracker i: z_{k|k}, Ω_{k|k}, x̂_{k|k} = Ω⁻¹z."""
    z = sum(weights[i, j] * z_tilde[j] for j in range(len(z_tilde)) if weights[i, j] > 0)
    Omega = sum(weights[i, j] * Omega_tilde[j] for j in range(len(z_tilde)) if weights[i, j] > 0)
    return z, Omega, np.linalg.solve(Omega, z)


def prediction(x_post, Omega_post, F, W):
    """Eq. (44): x̂_{k+1|k} = F x̂_{k|k}, Ω_{k+1|k} = W − WF(Ω_{k|k} + FᵀWF)⁻¹FᵀW."""
    return F @ x_post, W - W @ F @ np.linalg.inv(Omega_post + F.T @ W @ F) @ F.T @ W


def algorithm(x0, P0, positions, ranges, weights, V, step, every):
    """Algorithm 2 at every discrete time of period ``step``, a range every ``every`` times
    (the recorded ones); returns x̂_{k|k} and Ω_{k+1|k} at the instants with a range."""
    n = len(x0)
    F, W = model_matrix(step), np.linalg.inv(Q)
    x = [np.array(x0[i], float) for i in range(n)]
    Omega = [np.linalg.inv(P0) for _ in range(n)]
    posteriors, informations = [], []
    for k in range(len(ranges) * every):
        sample = k // every if k % every == 0 else None
        corrected = [
            correction(x[i], Omega[i], positions[sample][i] if sample is not None else None,
                       ranges[sample][i] if sample is not None else None, V)
            for i in range(n)
        ]  # fmt: skip
        fused = [fusion(i, *zip(*corrected, strict=True), weights) for i in range(n)]
        predicted = [prediction(fused[i][2], fused[i][1], F, W) for i in range(n)]
        x, Omega = [p[0] for p in predicted], [p[1] for p in predicted]
        if sample is not None:
            posteriors.append(np.array([f[2] for f in fused]))
        if (k + 1) % every == 0:
            informations.append(np.array(Omega))
    return np.array(posteriors), np.array(informations)


def trackcert(x0, P0, positions, ranges, weights, V, predictions):
    """The same run through ``dekf_step`` (one call per range, ``predictions`` per T_s)."""
    x = np.array(x0, float)
    Omega = np.tile(np.linalg.inv(P0), (len(x0), 1, 1))
    F, W = model_matrix(TS / predictions), np.linalg.inv(Q)
    posteriors, informations = [], []
    for p, y in zip(positions, ranges, strict=True):
        x_hat, _, Omega, x = dekf_step(
            x, Omega, p, y, fusion=weights, F=F, W=W, V=V, predictions=predictions
        )
        posteriors.append(x_hat)
        informations.append(Omega)
    return np.array(posteriors), np.array(informations)


def assert_agree(ours, theirs) -> None:
    for mine, reference in zip(ours, theirs, strict=True):
        scale = np.max(np.abs(reference), axis=(-2, -1), keepdims=True)
        assert np.max(np.abs(mine - reference) / scale) < 1e-9


@pytest.mark.parametrize("V", [0.1, 1.0, 10.0])
def test_three_trackers_one_prediction_per_range_is_algorithm_2(V: float) -> None:
    """N = 3 on the ring, a range at every discrete time (T_s = 2 s): the paper's Algorithm 2."""
    reference = algorithm(X0, P0, POSITIONS, RANGES, RING, V, TS, every=1)
    assert_agree(trackcert(X0, P0, POSITIONS, RANGES, RING, V, predictions=1), reference)


def test_one_tracker_predicting_every_tenth_of_a_second_is_algorithm_1() -> None:
    """N = 1 (Remark 7), discrete time 0.1 s and a range every 2 s (lines 10–11: no range, no
    innovation), as the authors' scripts run it: ``predictions = 20``."""
    positions, ranges = POSITIONS[:, :1], RANGES[:, :1]
    one = np.ones((1, 1))
    reference = algorithm(X0[:1], P0, positions, ranges, one, 0.1, TS / 20, every=20)
    assert_agree(trackcert(X0[:1], P0, positions, ranges, one, 0.1, predictions=20), reference)


def test_the_prediction_rate_changes_the_filter() -> None:
    """The comparison can fail: predicting once per 2 s is not Algorithm 1 at 0.1 s (the process
    noise W per step differs), so the two must disagree well beyond 1e-9."""
    positions, ranges = POSITIONS[:, :1], RANGES[:, :1]
    one = np.ones((1, 1))
    reference = algorithm(X0[:1], P0, positions, ranges, one, 0.1, TS / 20, every=20)
    ours = trackcert(X0[:1], P0, positions, ranges, one, 0.1, predictions=1)
    with pytest.raises(AssertionError):
        assert_agree(ours, reference)
