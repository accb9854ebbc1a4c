"""A ``kind: tdoa-sim`` case simulated: the kind's simulator and observer (seed 000 §4.3–4.4).

:func:`tdoa_simulator` is what ``trackcert simulate`` runs (:mod:`theory.simulate`): the closed
loop :func:`theory.tdoa.scenario.run_tdoa_scenario`, summarised by
:func:`theory.tdoa.metrics.summarize_runs`, written by :mod:`theory.tdoa.outputs` and
:mod:`theory.tdoa.figures`. :func:`sim_observed` reads the expect keys off a summary:

- ``bounded_error``: every agent's mean-over-runs final localization error is below
  ``error_bound`` (metres; default :func:`error_bound`);
- ``max_final_error``: the largest such error (judged with the rule ``at_most``: the case states
  an upper bound).

:func:`observe_tdoa_sim` (the kind's observer) runs one seeded run (seed 0), as ``trackcert
simulate`` does by default, so the report's ``case.expect.tdoa-sim`` claim agrees with it.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

from theory.core.case_file import Case
from theory.core.expectations import Observed
from theory.core.tolerances import ERROR_BOUND_SIGMAS
from theory.simulate import Finished, Simulator

__all__ = [
    "ERROR_BOUND_SIGMAS",
    "error_bound",
    "observe_tdoa_sim",
    "sim_observed",
    "tdoa_simulator",
]


def error_bound(case: Case) -> float:
    """The case's ``tolerances.error_bound``, else ``ERROR_BOUND_SIGMAS · √r`` metres.

    Parameters
    ----------
    case : Case
        A ``kind: tdoa-sim`` case (``r`` is its TDOA noise variance).

    Returns
    -------
    float
    """
    return case.tolerances.get("error_bound", ERROR_BOUND_SIGMAS * math.sqrt(case.spec.r))


def sim_observed(summary: dict[str, Any]) -> Observed:
    """The tdoa-sim expect keys in a Monte Carlo summary (module docstring).

    Parameters
    ----------
    summary : dict
        From :func:`theory.tdoa.metrics.summarize_runs`, with ``tolerances.error_bound``.

    Returns
    -------
    Observed
    """
    worst = max(agent["final_localization_error"] for agent in summary["agents"])
    bound = summary["tolerances"]["error_bound"]
    return Observed({"bounded_error": bool(worst < bound), "max_final_error": float(worst)})


def tdoa_simulator(case: Case, steps: int | None = None) -> Simulator:
    """The simulator of ``case`` for :func:`theory.simulate.simulate_case`.

    Parameters
    ----------
    case : Case
        A ``kind: tdoa-sim`` case.
    steps : int, optional
        Overrides the number of pings.

    Returns
    -------
    Simulator
    """
    from theory.tdoa.scenario import run_tdoa_scenario

    spec = case.spec if steps is None else dataclasses.replace(case.spec, steps=steps)
    fields = {"filter": spec.filter, "b": spec.b, "steps": spec.steps, "T": spec.T, "tau": spec.tau}
    return Simulator(spec, run_tdoa_scenario, fields, _finish)


def observe_tdoa_sim(case: Case) -> Observed:
    """The observer of ``kind: tdoa-sim``: one run with seed 0, as ``trackcert simulate`` runs.

    Parameters
    ----------
    case : Case
        A loaded tdoa-sim case.

    Returns
    -------
    Observed
    """
    from theory.sim.runner import monte_carlo

    simulator = tdoa_simulator(case)
    results = monte_carlo(simulator.spec, runs=1, seed=0, workers=1, simulate=simulator.run)
    return sim_observed(_summary(case, simulator.spec, results))


def _summary(case: Case, spec: Any, results: list) -> dict[str, Any]:
    from theory.tdoa.metrics import summarize_runs

    return {"tolerances": {"error_bound": error_bound(case)}, **summarize_runs(spec, results)}


def _finish(case: Case, spec: Any, results: list, folder: Path, figures: bool) -> Finished:
    from theory.tdoa.outputs import write_data

    record = _summary(case, spec, results)
    files = write_data(results, record, folder)
    if figures:
        from theory.tdoa.figures import write_figures  # matplotlib: imported when drawing

        files += write_figures(results, folder)
    return Finished(record, files, sim_observed(record))
