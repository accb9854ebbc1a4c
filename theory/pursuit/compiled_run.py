"""Seed 003: the DEC loop's run on the compiled kernels (:mod:`theory.pursuit.kernels`), the
``"numba"`` engine of :func:`theory.pursuit.closed_loop.simulate_dec`; the engine is chosen by
:func:`resolve_engine`.

The run is :func:`closed_loop._run`'s: at each sampling instant the ranges (9)–(10) (the same
draws from ``rng``), one DEKF step (Algorithm 2) and the runaway check; between two sampling
instants one kernel call integrates and records every ``dt``. This module knows nothing of
:mod:`theory.pursuit.closed_loop` (which imports it): it returns the recorded arrays and the stop.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any

import numpy as np

from theory.core.errors import ENVIRONMENT, CaseError

__all__ = ["ENGINES", "ENGINE_SETTING", "Recorded", "loop_arrays", "record", "resolve_engine"]

ENGINES = ("numba", "numpy")
"""The engines: compiled kernels (default) and the NumPy reference (the tests' oracle)."""

ENGINE_SETTING = "TRACKCERT_ENGINE"
"""The environment variable that chooses the engine when the caller does not."""

Recorded = tuple[np.ndarray, np.ndarray, np.ndarray, tuple[int, int], tuple | None]
"""(z, R, estimates, (steps, rejected), stop): the records of :func:`closed_loop._run` and, for a
run stopped early, (time, reason, whether a runaway)."""


def resolve_engine(engine: str | None = None) -> str:
    """The simulation engine: ``engine``, else ``$TRACKCERT_ENGINE``, else ``"numba"``.

    Parameters
    ----------
    engine : {"numba", "numpy"}, optional
        ``"numba"``: the compiled kernels; ``"numpy"``: the NumPy reference.

    Returns
    -------
    str
        One of :data:`ENGINES`.

    Raises
    ------
    CaseError
        If the engine (or the environment variable) names no engine.
    """
    if engine is not None:
        if engine not in ENGINES:
            raise CaseError("engine", " or ".join(map(repr, ENGINES)), repr(engine))
        return engine
    chosen = os.environ.get(ENGINE_SETTING, "").strip() or ENGINES[0]
    if chosen not in ENGINES:
        raise CaseError(ENGINE_SETTING, " or ".join(ENGINES), repr(chosen), file=ENVIRONMENT)
    return chosen


def loop_arrays(loop: Any) -> tuple:
    """The kernels' ``loop`` tuple of a :class:`closed_loop.DecLoop` (:mod:`.kernels`)."""
    maps = loop._frame_maps
    return (
        np.ascontiguousarray(maps.state_map),
        np.ascontiguousarray(maps.state_offset),
        np.ascontiguousarray(maps.estimate_map),
        np.ascontiguousarray(loop.input_gain, dtype=float),
        np.ascontiguousarray(loop.input_offset, dtype=float),
        np.ascontiguousarray(loop.epsilon, dtype=float),
        float(loop.k_gamma),
        float(loop.scale),
    )


def record(
    loop: Any,
    target: np.ndarray,
    state: Any,
    dekf: dict[str, np.ndarray],
    steps: int,
    rng: np.random.Generator,
    settings: Any,
    runaway: Callable[..., str],
) -> Recorded:
    """Sample, then integrate to the next sampling instant in one kernel call, until ``steps``
    records, a runaway (``runaway``: :func:`closed_loop.runaway_reason`) or a step below
    ``settings.min_step`` (seed 003 §V; :func:`closed_loop._run` on the kernels)."""
    from theory.pursuit import kernels

    n, d = loop.n, loop.dim
    every, dt, arrays = round(settings.Ts / settings.dt), settings.dt, loop_arrays(loop)
    z_rec = np.full((steps + 1, state.z.size), np.nan)
    R_rec = np.full((steps + 1, *state.R.shape), np.nan)
    estimates = np.full((steps + 1, n, 2 * d + 1), np.nan)
    filter_arrays = [np.ascontiguousarray(dekf[k], dtype=float) for k in ("fusion", "F", "W")]
    x_pred, Omega = (np.array(dekf[k], dtype=float) for k in ("x_pred", "Omega"))
    z, R, h, counts = state.z.copy(), state.R.copy(), dt, [0, 0]
    tolerances = (float(settings.rtol), float(settings.min_step))
    m = 0
    while True:
        positions, truth = z[: n * d].reshape(n, d), target[m]
        ranges = np.linalg.norm(positions - truth[:d], axis=1)
        ranges = ranges + settings.sigma * rng.standard_normal(n)
        x_hat, _, Omega, x_pred = kernels.dekf_step(
            x_pred, Omega, positions, ranges, *filter_arrays, float(settings.V)
        )
        reason = runaway(loop, positions, x_hat, truth, Omega, settings.runaway_factor)
        z_rec[m], R_rec[m] = z, R
        last = min(m + every, steps)
        if m == steps:
            return z_rec, R_rec, _estimates(estimates, x_hat, m, m, dt), tuple(counts), None
        if reason:
            _estimates(estimates, x_hat, m, m, dt)
            return z_rec, R_rec, estimates, tuple(counts), (m * dt, reason, True)
        z, R, h, accepted, rejected, reached, failed = kernels.advance(
            m, last, dt, z, R, x_hat, m * dt, h, tolerances, arrays, z_rec, R_rec
        )
        counts[0] += accepted
        counts[1] += rejected
        _estimates(estimates, x_hat, m, reached, dt)
        if failed >= 0:
            why = f"integration step below {settings.min_step} s at t = {failed:g} s"
            return z_rec, R_rec, estimates, tuple(counts), (reached * dt, why, False)
        if last == steps and last % every:  # no sampling instant at the last record
            return z_rec, R_rec, estimates, tuple(counts), None
        m = last


def _estimates(estimates: np.ndarray, x_hat: np.ndarray, first: int, last: int, dt: float):
    """Records ``first … last`` of x̂_{k|k} in force and its age t − t_k (sampled at ``first``)."""
    estimates[first : last + 1, :, :-1] = x_hat
    estimates[first : last + 1, :, -1] = (np.arange(first, last + 1) * dt - first * dt)[:, None]
    return estimates
