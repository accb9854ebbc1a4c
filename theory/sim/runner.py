"""Monte Carlo over local cores, deterministic by seed.

Run ``i`` of ``runs`` uses the ``i``-th child of ``numpy.random.SeedSequence(seed)``, so its
result does not depend on the number of worker processes nor on the order they finish.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from typing import Any

import numpy as np

from theory.tdoa.scenario import run_tdoa_scenario

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
    runs: int = 1,
    seed: int = 0,
    workers: int | None = None,
    progress: Callable[[int], None] | None = None,
    simulate: Callable[[Any, np.random.Generator], Any] = run_tdoa_scenario,
) -> list[Any]:
    """Run the scenario ``runs`` times, in parallel over ``workers`` processes.

    Parameters
    ----------
    spec : object
        The scenario (e.g. a ``TdoaSimSpec``), passed to ``simulate``.
    runs : int
        Number of independent runs (≥ 1).
    seed : int
        Root seed; run ``i`` uses ``SeedSequence(seed).spawn(runs)[i]``.
    workers : int, optional
        Worker processes; default all local cores; 1 runs in this process.
    progress : callable, optional
        Called with the number of runs finished so far, after each run.
    simulate : callable
        ``simulate(spec, rng) -> run``, a picklable module-level function (default: the TDOA
        closed loop :func:`~theory.tdoa.scenario.run_tdoa_scenario`).

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
