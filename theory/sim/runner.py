"""Monte Carlo over local cores, deterministic by seed, for any simulation.

Run ``i`` of ``runs`` uses the ``i``-th child of ``numpy.random.SeedSequence(seed)``, so its
result does not depend on the number of worker processes nor on the order they finish. The
engine knows no model: it calls ``simulate(spec, rng)`` — e.g. the TDOA closed loop
:func:`theory.tdoa.scenario.run_tdoa_scenario`, the consensus filter or the pursuit loop — and
returns what it returns.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from typing import Any

import numpy as np

__all__ = ["default_workers", "monte_carlo", "run_seeds"]


def default_workers() -> int:
    """All local cores (``os.cpu_count()``), at least 1."""
    return max(1, os.cpu_count() or 1)


def run_seeds(seed: int, runs: int) -> list[np.random.SeedSequence]:
    """The seed sequences of runs ``0 … runs−1`` (children of ``SeedSequence(seed)``).

    Parameters
    ----------
    seed : int
        Base seed of the Monte Carlo.
    runs : int
        Number of runs.

    Returns
    -------
    list of numpy.random.SeedSequence
        Item ``i`` seeds run ``i``.
    """
    return np.random.SeedSequence(seed).spawn(runs)


def _one(simulate: Callable, spec: Any, sequence: np.random.SeedSequence) -> Any:
    return simulate(spec, np.random.default_rng(sequence))


def monte_carlo(
    spec: Any,
    *,
    simulate: Callable[[Any, np.random.Generator], Any],
    runs: int = 1,
    seed: int = 0,
    workers: int | None = None,
    progress: Callable[[int], None] | None = None,
) -> list[Any]:
    """Run ``simulate(spec, rng)`` ``runs`` times, in parallel over ``workers`` processes.

    Parameters
    ----------
    spec : object
        The scenario, passed unchanged to ``simulate`` (picklable when ``workers > 1``).
    simulate : callable
        ``simulate(spec, rng) -> run``: one run from a ``numpy.random.Generator``; a picklable
        module-level function (or ``functools.partial`` of one) when ``workers > 1``.
    runs : int
        Number of independent runs (≥ 1).
    seed : int
        Root seed; run ``i`` uses ``SeedSequence(seed).spawn(runs)[i]``.
    workers : int, optional
        Worker processes; default all local cores; 1 runs in this process.
    progress : callable, optional
        Called with the number of runs finished so far, after each run.

    Returns
    -------
    list
        The runs, in run order.

    Raises
    ------
    ValueError
        If ``runs < 1`` or ``workers < 1``.
    """
    if runs < 1:
        raise ValueError(f"runs must be ≥ 1, got {runs}")
    workers = min(default_workers() if workers is None else workers, runs)
    if workers < 1:
        raise ValueError(f"workers must be ≥ 1, got {workers}")
    sequences = run_seeds(seed, runs)
    results: list[Any] = []
    if workers == 1:
        for sequence in sequences:
            results.append(_one(simulate, spec, sequence))
            if progress:
                progress(len(results))
        return results
    with ProcessPoolExecutor(max_workers=workers) as pool:
        for run in pool.map(_one, [simulate] * runs, [spec] * runs, sequences):
            results.append(run)
            if progress:
                progress(len(results))
    return results
