"""Closed-loop simulation of a case (``trackcert simulate``): Monte Carlo of the kind's simulator
on the task engine, deterministic by seed, its expectations judged and its files written whole.

A simulated kind has a simulator (:func:`theory.kinds.simulator_for`): ``simulator(case, steps)
-> Simulator`` says what one run is (a picklable ``run(spec, rng)``), which fields the record gets
and how the runs are summarised, written and observed (:class:`Finished`). :func:`monte_carlo`
runs ``run`` ``runs`` times on the engine (:mod:`theory.core.parallel`), run ``i`` seeded by child
``i`` of ``SeedSequence(seed)``, so nothing depends on the number of workers nor on the order they
finish; it knows no model. :func:`simulate_case` judges the case's ``expect`` block with
:mod:`theory.core.expectations` when the simulator observes it, and writes the files and
``summary.json`` into a staging folder that replaces the output folder whole
(:func:`theory.core.atomic_output.replaced_folder`).
"""

from __future__ import annotations

import functools
import itertools
import json
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from theory.core.atomic_output import check_replaceable, replaced_folder
from theory.core.case_file import Case
from theory.core.expectations import Expectation, Observed, judge
from theory.core.jsonable import plain
from theory.core.parallel import TaskRunner, default_workers, engine
from theory.core.verdicts import Verdict, expectations_verdict

__all__ = [
    "MARKER",
    "Finished",
    "Simulation",
    "Simulator",
    "monte_carlo",
    "run_seeds",
    "simulate_case",
]

MARKER = "summary.json"
"""The file every simulation folder has: a folder without it is not replaced (unless empty)."""

SOURCE = "trackcert simulate"
"""The observations' source in the command's verdict records."""


def run_seeds(seed: int, runs: int) -> list[np.random.SeedSequence]:
    """The seed sequences of runs ``0 … runs−1``: the children of ``SeedSequence(seed)``."""
    return np.random.SeedSequence(seed).spawn(runs)


TASKS_PER_WORKER = 4
"""Monte Carlo runs go to the engine in about this many batches per worker: a task per run cost
Dask's per-task work (and the BLAS pinning) per run; a few batches a worker still balance runs
of unequal length (a runaway stops early)."""


def _batch(simulate: Callable, spec: Any, sequences: list[np.random.SeedSequence]) -> list:
    """Runs of one task, in order (run ``i`` seeded by its own child sequence)."""
    return [simulate(spec, np.random.default_rng(sequence)) for sequence in sequences]


def _batches(runs: int, workers: int) -> list[range]:
    """Consecutive ranges of run indices, about :data:`TASKS_PER_WORKER` per worker (one run each
    on a single worker, the serial path's progress per run)."""
    count = runs if workers <= 1 else min(runs, TASKS_PER_WORKER * workers)
    edges = np.linspace(0, runs, count + 1).round().astype(int)
    return [range(a, b) for a, b in itertools.pairwise(edges)]


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
    """``simulate(spec, rng)`` ``runs`` times as tasks on the engine, in run order.

    ``simulate`` is a picklable module-level function (or a ``functools.partial`` of one); run
    ``i`` draws from child ``i`` of ``SeedSequence(seed)``. It runs on ``runner`` if given, else on
    ``workers`` local processes (default all cores; 1: this process), in batches of consecutive
    runs (about :data:`TASKS_PER_WORKER` a worker); ``progress`` is called with the number of runs
    finished. ``ValueError`` if ``runs < 1``.
    """
    if runs < 1:
        raise ValueError(f"runs must be ≥ 1, got {runs}")
    if runner is not None:
        return _batched(runner, spec, simulate, run_seeds(seed, runs), progress)
    with engine(min(default_workers() if workers is None else workers, runs)) as local:
        return _batched(local, spec, simulate, run_seeds(seed, runs), progress)


def _batched(runner: TaskRunner, spec, simulate, sequences, progress) -> list[Any]:
    """The runs in batches (:func:`_batches`) on ``runner``, flattened in run order; ``progress``
    gets 1, 2, … up to the runs finished as each batch finishes (a lower bound while the batches
    differ in size: the smallest ones counted)."""
    batches = _batches(len(sequences), runner.size)
    bounds = list(itertools.accumulate(sorted(len(b) for b in batches)))
    reported = [0]

    def finished(count: int) -> None:
        for done in range(reported[0] + 1, bounds[count - 1] + 1):
            progress(done)
        reported[0] = max(reported[0], bounds[count - 1])

    task = functools.partial(_batch, simulate, spec)
    results = runner.map(
        task, [sequences[b.start : b.stop] for b in batches],
        progress=None if progress is None else finished,
    )  # fmt: skip
    return [run for batch in results for run in batch]


@dataclass(frozen=True)
class Finished:
    """What a simulator makes of its runs: the record's ``summary`` fields (per-agent
    ``agents`` rows, tolerances, …), the ``files`` written, and the expect keys the runs decide
    (``None``: the kind's keys are not about simulation)."""

    summary: dict[str, Any]
    files: list[Path]
    observed: Observed | None = None


@dataclass(frozen=True)
class Simulator:
    """One kind's simulation, ready for the engine: the ``spec`` each run receives, the picklable
    ``run(spec, rng)``, the record ``fields`` naming the settings, and ``finish(case, spec, runs,
    folder, figures) -> Finished`` (``folder`` ``None``: the summary alone, no file written, as a
    sweep point needs it)."""

    spec: Any
    run: Callable[[Any, Any], Any]
    fields: dict[str, Any]
    finish: Callable[[Case, Any, list, Path | None, bool], Finished]


@dataclass(frozen=True)
class Simulation:
    """The record of one ``trackcert simulate`` call (written as ``summary.json``): the case, the
    Monte Carlo runs, root seed and workers used, the simulator's settings, what it finished with,
    and the case's ``expect`` block judged against its observations."""

    case: Case
    runs: int
    seed: int
    workers: int
    fields: dict[str, Any]
    finished: Finished
    expectations: tuple[Expectation, ...] = field(default_factory=tuple)

    @property
    def verdict(self) -> Verdict:
        """The expectations' verdict (:func:`theory.core.verdicts.expectations_verdict`)."""
        return expectations_verdict(self.expectations)

    def to_json(self) -> dict[str, Any]:
        """The ``summary.json`` record: case, settings, summary, each expectation's verdict record
        by key, files."""
        case = self.case
        return {
            "case": case.name,
            "source": case.source,
            "kind": case.kind,
            **self.fields,
            "runs": self.runs,
            "seed": self.seed,
            "workers": self.workers,
            **self.finished.summary,
            "expectations": {e.key: e.to_json() for e in self.expectations},
            "files": [str(f) for f in self.finished.files],
        }


def simulate_case(
    case: Case,
    simulator: Simulator,
    *,
    folder: Path,
    runs: int = 1,
    seed: int = 0,
    workers: int = 1,
    scheduler: str | None = None,
    figures: bool = True,
    progress: Callable[[int], None] | None = None,
) -> Simulation:
    """Run ``simulator`` ``runs`` times, summarise, judge the expectations, write the files.

    Parameters
    ----------
    case : Case
        The case.
    simulator : Simulator
        From :func:`theory.kinds.simulator_for`.
    folder : Path
        Where data, figures and ``summary.json`` go: created, or replaced whole if it is an
        earlier simulation's (or empty).
    runs, seed, workers : int
        Monte Carlo runs, root seed (run ``i`` uses child ``i``) and local worker processes.
    scheduler : str, optional
        Address of a Dask scheduler to run on instead (default ``$TRACKCERT_SCHEDULER``).
    figures : bool
        Whether to draw PNG figures.
    progress : callable, optional
        Called with the number of runs finished.

    Returns
    -------
    Simulation

    Raises
    ------
    CaseError
        If ``folder`` holds files but no ``summary.json``.
    OutputError
        If writing fails (the folder is left as it was).
    """
    check_replaceable(folder, MARKER)
    with engine(min(workers, runs), scheduler) as runner:
        results = monte_carlo(
            simulator.spec,
            runs=runs,
            seed=seed,
            runner=runner,
            progress=progress,
            simulate=simulator.run,
        )
    folder = Path(folder)
    with replaced_folder(folder, MARKER) as staging:
        finished = simulator.finish(case, simulator.spec, results, staging, figures)
        files = [folder / Path(f).relative_to(staging) for f in finished.files]
        finished = replace(finished, files=files)
        expectations = (
            () if finished.observed is None else judge(case, finished.observed, source=SOURCE)
        )
        simulation = Simulation(
            case, runs, seed, min(workers, runs), simulator.fields, finished, tuple(expectations)
        )
        (staging / MARKER).write_text(json.dumps(plain(simulation.to_json()), indent=2))
    return simulation
