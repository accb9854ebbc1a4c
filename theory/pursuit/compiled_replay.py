"""Seed 003: the DEKF replay of :mod:`theory.pursuit.filter_metrics` as one compiled call (the
``"numba"`` engine of :func:`theory.pursuit.dekf.range_dekf`).

The replay is Algorithm 2 on a run's recorded geometry every ``T_s``: the ranges (9)–(10), the
innovations ``ν = y − ‖q̂_{k|k−1} − p‖`` and ``S = C Ω_{k|k−1}⁻¹ Cᵀ + 1/V`` of (10), (41), and one
correction, fusion and prediction (41)–(44) by the compiled :func:`kernels.dekf_step`. The NumPy
loop of :func:`range_dekf` makes a few dozen NumPy calls on 4–6-number arrays per instant; a
summary of a 450 s run replays 226 instants per run, which cost more than the run itself.
The range noise is drawn from ``rng`` first, in the order :func:`range_dekf` draws it (one
standard normal a tracker an instant), so both engines see the same noise.
"""

from __future__ import annotations

import math

import numpy as np

from theory.core.engines import compiled
from theory.pursuit.dekf import RangeDekfRun, transition_matrix
from theory.pursuit.kernels import dekf_step

__all__ = ["replay_compiled"]


@compiled
def _replay(trackers, target, noise, x0, Omega0, fusion, F, W, V, predictions, out):
    """Fill ``out`` = (x̂_{k|k}, Ω_{k|k}, ν, S) at every instant (module docstring)."""
    estimates, information, innovations, variances = out
    steps, n, d = trackers.shape
    x, Omega = np.empty((n, 2 * d)), np.empty((n, 2 * d, 2 * d))
    for i in range(n):
        x[i] = x0
        Omega[i] = Omega0
    ranges = np.empty(n)
    for k in range(steps):
        for i in range(n):
            diff = x[i, :d] - trackers[k, i]
            predicted = math.sqrt(np.sum(diff * diff))
            ranges[i] = math.sqrt(np.sum((trackers[k, i] - target[k, :d]) ** 2)) + noise[k, i]
            C = np.zeros(2 * d)
            C[:d] = diff / predicted
            innovations[k, i, 0] = ranges[i] - predicted
            variances[k, i, 0, 0] = np.sum(C * np.linalg.solve(Omega[i], C)) + 1 / V
        x_hat, Omega_post, Omega, x = dekf_step(
            x, Omega, trackers[k], ranges, fusion, F, W, V, predictions
        )
        estimates[k] = x_hat
        information[k] = Omega_post


def replay_compiled(
    trackers: np.ndarray,
    target: np.ndarray,
    *,
    Ts: float,
    noise_var: float,
    V: float,
    Q: np.ndarray,
    fusion: np.ndarray,
    x0: np.ndarray,
    P0: np.ndarray,
    rng: np.random.Generator,
    predictions: int = 1,
) -> RangeDekfRun:
    """:func:`theory.pursuit.dekf.range_dekf` (same arguments, same noise from ``rng``) compiled.

    Parameters
    ----------
    trackers, target : numpy.ndarray
        Tracker positions (K, N, d) and target states (K, 2d) at the sampling instants.
    Ts, noise_var, V : float
        Sampling period, variance of the range noise drawn, the filter's ``V``.
    Q, fusion, x0, P0 : numpy.ndarray
        Process covariance (W = Q⁻¹), fusion weights π^[i,j], every tracker's x̂_{1|0}, P_{1|0}.
    rng : numpy.random.Generator
        Draws the range noise, K × N standard normals.
    predictions : int
        Predictions (44) per ``Ts``, with F(Ts/predictions) and ``Q`` per Ts/predictions.

    Returns
    -------
    RangeDekfRun
    """
    steps, n, d = trackers.shape
    noise = math.sqrt(noise_var) * rng.standard_normal((steps, n))
    out = (
        np.empty((steps, n, 2 * d)),
        np.empty((steps, n, 2 * d, 2 * d)),
        np.empty((steps, n, 1)),
        np.empty((steps, n, 1, 1)),
    )
    _replay(
        np.ascontiguousarray(trackers, dtype=float), np.ascontiguousarray(target, dtype=float),
        noise, np.asarray(x0, dtype=float), np.linalg.inv(P0), np.asarray(fusion, dtype=float),
        transition_matrix(d, Ts / predictions), np.linalg.inv(Q), float(V), int(predictions), out,
    )  # fmt: skip
    return RangeDekfRun(*out)
