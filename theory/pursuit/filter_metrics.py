"""NEES, NIS and OSPA/GOSPA of the DEKF (seed 003 Algorithm 2) along simulated pursuit runs.

The closed loop (:mod:`theory.pursuit.closed_loop`) records the trackers' and the target's
trajectories but not the filter's information matrices. The DEKF is replayed here, with the one
implementation :func:`theory.pursuit.dekf.range_dekf` and the run's own priors, fusion weights,
``V``, ``Q`` and prediction rate (``predict_every``: ``Q`` per ``T_s/predictions``, predicted
that many times per ``T_s``, as the loop's filter), on the recorded tracker and target positions
at every sampling instant ``kT_s`` up to where the run stopped; run ``i``'s range noise (σ of
the case) comes from ``SeedSequence([REPLAY_KEY, i])``. The statistics are then those of the
filter on the closed-loop geometry (:mod:`theory.core.consistency`); the range variance the
filter assumes is ``1/V``, so a case whose ``V`` exceeds ``1/σ²`` trusts its ranges more than
their noise allows.
The replay runs on the engine :func:`theory.core.engines.resolve_engine` chooses for
its filter steps (fewer than :data:`REPLAY_MIN_STEPS` on the NumPy reference): compiled
(:mod:`theory.pursuit.compiled_replay`) or the NumPy reference.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from theory.core.consistency import filter_metrics, nees, nis
from theory.core.engines import resolve_engine
from theory.pursuit.closed_loop import DecRun, _filter_setup, build_loop
from theory.pursuit.dekf import RangeDekfRun, range_dekf

__all__ = ["REPLAY_KEY", "REPLAY_MIN_STEPS", "dekf_metrics", "replay_dekf"]

REPLAY_KEY = 3
"""First word of the replays' seed sequences (seed 003)."""

REPLAY_MIN_STEPS = 700
"""Replays of fewer filter steps (runs × sampling instants) than this run on NumPy by default.

Loading the compiled replay's cached kernel costs a process 0.03–0.04 s of CPU, with numba
already imported by the runs; the NumPy replay costs 47–52 µs a filter step more. The
break-even is 560–750 steps on the four Table cases (``benchmarks/bench_replay_engine.py``):
one run of 450 s replays 225 steps, 0.014–0.020 s on NumPy against 0.032–0.046 s compiled."""


def replay_dekf(
    run: DecRun, arguments: dict[str, Any], index: int, engine: str | None = None
) -> RangeDekfRun:
    """Algorithm 2 on run ``index``'s recorded trajectories every ``T_s`` (module docstring;
    ``arguments`` are :func:`theory.pursuit.simulation.dec_arguments`', ``engine`` as
    :func:`~theory.core.engines.resolve_engine`'s); seed 003 (41)–(44)."""
    settings = arguments["settings"]
    every = round(settings.Ts / settings.dt)
    positions, target = run.positions[::every], run.target[::every]
    finite = np.isfinite(positions).all(axis=(1, 2))
    last = len(finite) if finite.all() else int(np.argmin(finite))
    d = positions.shape[-1]
    loop = build_loop(settings, arguments["paths"], arguments["in_neighbours"], d)
    dekf = _filter_setup(loop, settings, arguments["x0"], arguments["P0"], arguments["fusion"])
    if resolve_engine(engine) == "numba":
        from theory.pursuit.compiled_replay import replay_compiled as replay
    else:
        replay = range_dekf
    return replay(
        positions[:last],
        target[:last],
        Ts=settings.Ts,
        noise_var=settings.sigma**2,
        V=settings.V,
        Q=np.linalg.inv(dekf["W"]),
        fusion=dekf["fusion"],
        x0=dekf["x_pred"][0],
        P0=np.linalg.inv(dekf["Omega"][0]),
        rng=np.random.default_rng(np.random.SeedSequence([REPLAY_KEY, index])),
        predictions=settings.predictions,
    )


def dekf_metrics(
    runs: Sequence[DecRun], arguments: dict[str, Any], engine: str | None = None
) -> dict[str, Any]:
    """NEES of ``x̂_{k|k}`` against ``Ω_{k|k}⁻¹``, NIS of every range correction and OSPA/GOSPA
    of ``q̂_{k|k}`` per tracker over the replays (NaN after a run stopped), replayed on
    ``engine`` (default: the one :func:`resolve_engine` chooses for the replays' filter
    steps, :data:`REPLAY_MIN_STEPS`)."""
    settings = arguments["settings"]
    every = round(settings.Ts / settings.dt)
    instants = sum((len(run.times) - 1) // every for run in runs)
    engine = resolve_engine(engine, records=instants, minimum=REPLAY_MIN_STEPS)
    replays = [replay_dekf(run, arguments, i, engine) for i, run in enumerate(runs)]
    truth = np.stack([run.target[::every] for run in runs])
    steps, d = truth.shape[1], truth.shape[2] // 2
    estimates = np.stack([_padded(r.estimates, steps) for r in replays])
    information = np.stack([_padded(r.information, steps, eye=True) for r in replays])
    covariances = np.linalg.inv(information)
    innovations = nis(
        np.stack([_padded(r.innovations, steps) for r in replays]),
        np.stack([_padded(r.innovation_covariances, steps, eye=True) for r in replays]),
    )
    errors = nees(estimates - truth[:, :, None], covariances)
    return filter_metrics(errors, 2 * d, innovations, 1, (estimates[..., :d], truth[..., :d]))


def _padded(values: np.ndarray, steps: int, *, eye: bool = False) -> np.ndarray:
    """``values`` (K, …) extended to ``steps`` records with NaN (identity matrices if ``eye``,
    their vectors being NaN already)."""
    fill = np.broadcast_to(np.eye(values.shape[-1]) if eye else np.nan, values.shape[1:])
    return np.concatenate([values, np.broadcast_to(fill, (steps - len(values), *fill.shape))])
