"""Seed 003: the DEC loop's run on the compiled kernels (:mod:`theory.pursuit.kernels`), the
``"numba"`` engine of :func:`theory.pursuit.closed_loop.simulate_dec`; the engine is chosen by
:func:`theory.core.engines.resolve_engine` (a short job runs on the NumPy engine).

The run is :func:`closed_loop._run`'s: at each sampling instant the ranges (9)–(10) (the same
draws from ``rng``), one DEKF step (Algorithm 2) and the runaway check; between two sampling
instants one kernel call integrates and records every ``dt``. This module knows nothing of
:mod:`theory.pursuit.closed_loop` (which imports it): it returns the recorded arrays and the stop.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["Recorded", "loop_arrays", "record"]

Recorded = tuple[np.ndarray, np.ndarray, np.ndarray, tuple[int, int], tuple | None]
"""(z, R, estimates, (steps, rejected), stop): the records of :func:`closed_loop._run` and, for a
run stopped early, (time, reason, whether a runaway)."""


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
    """The run of :func:`closed_loop._run` in one kernel call (:func:`kernels.run`): ``steps``
    records, or until a runaway (its reason from ``runaway``, :func:`closed_loop.runaway_reason`)
    or a step below ``settings.min_step`` (seed 003 §V).

    The range noise of every sampling instant is drawn from ``rng`` first, in the order the NumPy
    engine draws it (one standard normal a tracker an instant), so both engines see the same
    noise; ``rng`` ends after the last instant of the horizon even if the run stops early.
    """
    from theory.pursuit import kernels

    n, d = loop.n, loop.dim
    every, dt = round(settings.Ts / settings.dt), settings.dt
    noise = settings.sigma * rng.standard_normal((steps // every + 1, n))
    records = (
        np.full((steps + 1, state.z.size), np.nan),
        np.full((steps + 1, *state.R.shape), np.nan),
        np.full((steps + 1, n, 2 * d + 1), np.nan),
    )
    filter_arrays = tuple(
        np.array(dekf[k], dtype=float) for k in ("x_pred", "Omega", "fusion", "F", "W")
    )
    numbers = (
        dt, every, float(settings.V), int(settings.predictions),
        settings.runaway_factor * loop.scale, float(settings.rtol), float(settings.min_step),
    )  # fmt: skip
    accepted, rejected, stop, cause, failed, x_hat, Omega = kernels.run(
        np.ascontiguousarray(target, dtype=float), noise, state.z.copy(), state.R.copy(),
        filter_arrays, numbers, loop_arrays(loop), records,
    )  # fmt: skip
    if cause == 0:
        return *records, (accepted, rejected), None
    if cause == 1:
        positions = records[0][stop, : n * d].reshape(n, d)
        why = runaway(loop, positions, x_hat, target[stop], Omega, settings.runaway_factor)
        return *records, (accepted, rejected), (stop * dt, why, True)
    why = f"integration step below {settings.min_step} s at t = {failed:g} s"
    return *records, (accepted, rejected), (stop * dt, why, False)
