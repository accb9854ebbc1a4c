"""Monte Carlo on the task engine (:mod:`theory.core.parallel`), deterministic by seed.

Run ``i`` of ``runs`` uses the ``i``-th child of ``numpy.random.SeedSequence(seed)``, so its
result does not depend on the number of Dask workers nor on the order they finish. The
engine knows no model: it calls ``simulate(spec, rng)`` — e.g. the TDOA closed loop
:func:`theory.tdoa.estimation.scenario.run_tdoa_scenario`, the consensus filter or the pursuit
loop — and returns what it returns.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import numpy as np

from theory.core.parallel import TaskRunner, default_workers, engine

__all__ = ["monte_carlo", "run_seeds"]


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
    runner: TaskRunner | None = None,
    progress: Callable[[int], None] | None = None,
) -> list[Any]:
    """Run ``simulate(spec, rng)`` ``runs`` times, as tasks on the engine.

    Parameters
    ----------
    spec : object
        The scenario, passed unchanged to ``simulate`` (picklable when run on workers).
    simulate : callable
        ``simulate(spec, rng) -> run``: one run from a ``numpy.random.Generator``; a picklable
        module-level function (or ``functools.partial`` of one).
    runs : int
        Number of independent runs (≥ 1).
    seed : int
        Root seed; run ``i`` uses ``SeedSequence(seed).spawn(runs)[i]``.
    workers : int, optional
        Local Dask workers when no ``runner`` is given; default all local cores; 1 runs in this
        process.
    runner : TaskRunner, optional
        An open engine (:func:`theory.core.parallel.engine`) to run on.
    progress : callable, optional
        Called with the number of runs finished so far, after each run.

    Returns
    -------
    list
        The runs, in run order.

    Raises
    ------
    ValueError
        If ``runs < 1``.
    """
    if runs < 1:
        raise ValueError(f"runs must be ≥ 1, got {runs}")
    task = functools.partial(_one, simulate, spec)
    sequences = run_seeds(seed, runs)
    if runner is not None:
        return runner.map(task, sequences, progress=progress)
    with engine(min(default_workers() if workers is None else workers, runs)) as local:
        return local.map(task, sequences, progress=progress)
