"""Calibration of the NEES/NIS spread check (theory.core.consistency.spread_interval): how often
it calls a consistent filter inconsistent, and how often it detects an overconfident one, with
the batch rule of today and the one before 7 December 2026, on the same draws.

The statistics are those of a 4-state filter whose errors are Gaussian AR(1) in time with
correlation time τ (e(t) = φ e(t−1) + √(1−φ²) w(t), φ = e^(−1/τ)) and whose reported covariance
is the truth (``scale`` 1: consistent) or half of it (``scale`` 0.5: optimistic), for one run of
225 steps (a Table case's replay), 3 runs of 400 and one of 2 000. Per row: the seeds (of
``--seeds``) called ``optimistic`` or ``pessimistic`` (consistent filter: nominal 5 % of the
seeds) or ``optimistic`` (overconfident filter: the more the better), for τ = 1, 5, 20, 50, 100.

* ``adaptive``: today's rule: batches of 10 integrated autocorrelation times (estimated, plus
  one standard error), one unit a run from 10 runs;
* ``ten batches``: the rule before: ⌈10/runs⌉ batches a run whatever the correlation.

Usage: ``python benchmarks/bench_spread_check.py [--seeds 200]``
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from unittest import mock

import numpy as np
from scipy.signal import lfilter

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from theory.core import consistency

TAUS = (1, 5, 20, 50, 100)
SHAPES = ((1, 225), (3, 400), (1, 2000))
DIMENSION = 4


def statistics(seed: int, runs: int, steps: int, tau: float, scale: float) -> np.ndarray:
    """NEES of AR(1) errors with correlation time ``tau``, reported covariance ``scale``·I."""
    phi = math.exp(-1 / tau)
    noise = np.random.default_rng(seed).standard_normal((runs, DIMENSION, steps))
    noise[..., 0] /= math.sqrt(1 - phi**2)  # the stationary start
    errors = lfilter([math.sqrt(1 - phi**2)], [1, -phi], noise, axis=-1)
    return (errors**2).sum(axis=1) / scale


def ten_batches(values, dims, valid, probability):
    """The spread check before 7 December 2026: ⌈10/runs⌉ batches a run."""
    runs = values.shape[0]
    batches = 1 if runs >= consistency.SPREAD_UNITS else -(-consistency.SPREAD_UNITS // runs)
    ratios = np.asarray(
        [
            values[r, p].sum() / dims[r, p].sum()
            for r in range(runs)
            for p in np.array_split(np.flatnonzero(valid[r]), batches)
            if p.size
        ]
    )
    if len(ratios) < 2 or not np.isfinite(ratios).all():
        return None
    half = consistency._t_quantile((1 + probability) / 2, len(ratios) - 1) * ratios.std(ddof=1)
    half /= math.sqrt(len(ratios))
    mean = float(ratios.mean())
    return consistency.Spread(len(ratios), "batch means", mean, mean - half, mean + half)


def counts(seeds: int, runs: int, steps: int, scale: float) -> list[int]:
    """Per τ: seeds called inconsistent (scale 1) or optimistic (scale < 1)."""
    wanted = {"optimistic", "pessimistic"} if scale == 1 else {"optimistic"}
    row = []
    for tau in TAUS:
        verdicts = [
            consistency.consistency_test("NEES", statistics(s, runs, steps, tau, scale), DIMENSION)
            for s in range(seeds)
        ]
        row.append(sum(v.verdict.value in wanted for v in verdicts))
    return row


def main() -> None:
    """One row per rule, shape and scale."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=200)
    args = parser.parse_args()
    print(f"seeds per cell: {args.seeds}; τ = {', '.join(map(str, TAUS))} steps")
    for runs, steps in SHAPES:
        for scale, what in ((1.0, "consistent: called inconsistent"), (0.5, "half: detected")):
            adaptive = counts(args.seeds, runs, steps, scale)
            with mock.patch.object(consistency, "spread_interval", ten_batches):
                before = counts(args.seeds, runs, steps, scale)
            label = f"{runs} × {steps}, {what}"
            print(f"{label:48} adaptive {adaptive}  ten batches {before}", flush=True)


if __name__ == "__main__":
    main()
