"""Closed-loop simulation of a case: the kind's simulator run over seeds (``trackcert simulate``).

A kind that ``trackcert simulate`` runs has a simulator (:func:`theory.kinds.simulator_for`):
``simulator(case, steps) -> Simulator`` says what one run is (a picklable
``run(spec, rng)``), which fields the record gets, and how the runs are summarised, written and
observed (:class:`Finished`). :func:`simulate_case` runs it on the engine
(:func:`theory.sim.runner.monte_carlo`: run ``i`` seeded by child ``i`` of
``SeedSequence(seed)``), judges the case's ``expect`` block with
:mod:`theory.core.expectations` when the simulator observes it, and writes the files and
``summary.json`` into a staging folder that replaces the output folder whole
(:func:`theory.core.atomic_output.replaced_folder`): a failure or a signal leaves the old folder as
it was.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from theory.core.atomic_output import check_replaceable, replaced_folder
from theory.core.case_file import Case
from theory.core.expectations import Expectation, Observed, judge
from theory.core.jsonable import plain
from theory.core.verdicts import Verdict, expectations_verdict

__all__ = ["MARKER", "Finished", "Simulation", "Simulator", "simulate_case"]

MARKER = "summary.json"
"""The file every simulation folder has: a folder without it is not replaced (unless empty)."""

SOURCE = "trackcert simulate"
"""The observations' source in the command's verdict records."""


@dataclass(frozen=True)
class Finished:
    """What a simulator makes of its runs.

    Attributes
    ----------
    summary : dict
        Record fields (per-agent ``agents`` rows, tolerances, …).
    files : list of Path
        Data and figure files written.
    observed : Observed or None
        The expect keys the runs decide (``None``: the kind's keys are not about simulation).
    """

    summary: dict[str, Any]
    files: list[Path]
    observed: Observed | None = None


@dataclass(frozen=True)
class Simulator:
    """One kind's simulation, ready for the engine.

    Attributes
    ----------
    spec : object
        What each run receives (the case's spec, steps overridden).
    run : callable
        ``run(spec, rng) -> run record``, picklable (module level or a ``functools.partial``).
    fields : dict
        Record fields naming the settings (filter, steps, …).
    finish : callable
        ``finish(case, spec, runs, folder, figures) -> Finished``.
    """

    spec: Any
    run: Callable[[Any, Any], Any]
    fields: dict[str, Any]
    finish: Callable[[Case, Any, list, Path, bool], Finished]


@dataclass(frozen=True)
class Simulation:
    """The record of one ``trackcert simulate`` call (also written as ``summary.json``).

    Attributes
    ----------
    case : Case
        The case simulated.
    runs, seed, workers : int
        Monte Carlo runs, root seed and the worker processes used.
    fields : dict
        The simulator's settings.
    finished : Finished
        Summary, files and observations.
    expectations : tuple of Expectation
        The case's ``expect`` block judged against ``finished.observed`` (empty when not
        observed).
    """

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
        """The ``summary.json`` record: case, settings, summary, expectations, files.

        ``expectations`` maps each key to its verdict record
        (:meth:`theory.core.expectations.Expectation.to_json`: ``expected``, ``got``, ``met``,
        ``verdict``, …).
        """
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
        From :func:`theory.kinds.simulator_for` (or an interim one).
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
        If ``folder`` holds files but no ``summary.json``
        (:func:`theory.core.atomic_output.replaceable_problem`).
    OutputError
        If writing fails (the folder is left as it was).
    """
    from theory.core.parallel import engine
    from theory.sim.runner import monte_carlo

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
