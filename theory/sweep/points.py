"""One sweep point: set its values, re-validate the case, judge it, simulate it, compare.

:func:`evaluate_point` is pure in its arguments (the case data, the targets, the values, the
settings), so a point gives the same row in any process and any order; :func:`evaluate_batch`
runs a batch of points as one engine task (:mod:`theory.core.parallel`).

A point whose data the case loader rejects (:func:`theory.kinds.parse_case`), or whose
analysis refuses it (a :class:`~theory.core.errors.CaseError`), is a row with status
``invalid`` and the loader's message. A solver failure makes the verdict inconclusive. The
simulation is one run (``runs = 1``) with root seed ``sim_seed`` (run 0 uses child 0 of
``SeedSequence(sim_seed)``, as ``trackcert simulate --seed sim_seed`` does), summarised by the
kind's own simulator (:func:`theory.kinds.simulator_for`, its ``finish`` with no figures).
"""

from __future__ import annotations

import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import status_of
from theory.core.errors import CaseError, InconclusiveError, PropertyFails, SolverError
from theory.core.expectations import Observed, judge
from theory.core.verdicts import (
    EXIT_BAD_INPUT,
    exit_code,
    expectations_verdict,
)
from theory.kinds import SIMULATED, parse_case
from theory.sweep.kinds import Judgement, agreement, analysis_for
from theory.sweep.paths import Target, apply_values

__all__ = ["INVALID", "Row", "SweepSetup", "evaluate_batch", "evaluate_point", "simulate_point"]

INVALID = "invalid"
"""The status of a point the case loader (or its analysis) rejects."""

SOURCE = "trackcert sweep"
"""The observations' source when a point is judged by its simulation."""


@dataclass(frozen=True)
class SweepSetup:
    """What every point shares (sent once with each task).

    Attributes
    ----------
    data : dict
        The case file's parsed YAML.
    file : str
        Where it came from (named in messages).
    targets : tuple of Target
        Where each swept path lands (:func:`theory.sweep.paths.resolve_target`).
    steps : int or None
        Simulation steps (``None``: the kind's default).
    simulate : bool
        Whether to simulate each point (when the kind has a simulator).
    seed : int
        Simulation root seed when ``seed`` is not swept.
    """

    data: dict[str, Any]
    file: str
    targets: tuple[Target, ...]
    steps: int | None = None
    simulate: bool = True
    seed: int = 0


@dataclass(frozen=True)
class Row:
    """One point's result (one row of ``sweep.csv``).

    Attributes
    ----------
    point : int
        0-based index in grid order.
    values : tuple
        The swept values, in ``--param`` order.
    status : str
        ``verified``, ``refuted``, ``inconclusive`` (the verdict, :mod:`theory.core.verdicts`) or
        ``invalid``.
    margin : float or None
        The verdict's margin (:mod:`theory.sweep.kinds`).
    tolerances : dict
        The tolerances the verdict used.
    sim_seed : int or None
        The simulation's root seed (``None``: not simulated).
    simulated : dict
        Worst agent's value of every ``*_error`` field of the simulation summary, and every
        key the simulation observes (``simulation_bounded``, …), each prefixed ``sim_``.
    agreement : str
        One of :data:`theory.sweep.kinds.AGREEMENTS`.
    message : str
        Why (the loader's message for an invalid point).
    """

    point: int
    values: tuple[Any, ...]
    status: str
    margin: float | None = None
    tolerances: dict[str, float] = field(default_factory=dict)
    sim_seed: int | None = None
    simulated: dict[str, Any] = field(default_factory=dict)
    agreement: str = "n/a"
    message: str = ""

    @property
    def exit_code(self) -> int:
        """0 verified, 1 refuted, 3 inconclusive, 2 invalid (:mod:`theory.core.verdicts`)."""
        if self.status == INVALID:
            return EXIT_BAD_INPUT
        return exit_code({"verified": True, "refuted": False, "inconclusive": None}[self.status])


def _judge(case: Case) -> Judgement | None:
    analysis = analysis_for(case.kind)
    if analysis is None:
        return None
    try:
        return analysis(case)
    except (SolverError, InconclusiveError, np.linalg.LinAlgError) as error:
        return Judgement(None, None, {}, f"inconclusive: {error}")


def simulate_point(
    case: Case, steps: int | None, seed: int
) -> tuple[dict[str, Any], Observed | None]:
    """One run of ``case``'s simulator and its summary.

    Parameters
    ----------
    case : Case
        A loaded case whose kind has a simulator.
    steps : int or None
        Simulation steps (``None``: the kind's default).
    seed : int
        Root seed.

    Returns
    -------
    (dict, Observed or None)
        The simulator's summary and what it observes.

    Raises
    ------
    CaseError
        If the simulator refuses the case (e.g. a pursuit case without a target).
    PropertyFails
        If the case's controller does not exist (a pursuit case with ε₁ = 0).
    """
    from theory.kinds import simulator_for
    from theory.sim.runner import monte_carlo

    simulator = simulator_for(case, steps)
    runs = monte_carlo(simulator.spec, runs=1, seed=seed, workers=1, simulate=simulator.run)
    with tempfile.TemporaryDirectory(prefix="trackcert-sweep-") as folder:
        finished = simulator.finish(case, simulator.spec, runs, Path(folder), False)
    return finished.summary, finished.observed


def _simulated(summary: Mapping[str, Any], observed: Observed | None) -> dict[str, Any]:
    agents = summary.get("agents") or []
    keys = [k for k in (agents[0] if agents else {}) if k.endswith("_error")]
    out = {f"sim_{k}": float(np.max([a[k] for a in agents])) for k in keys}
    if observed is not None:
        out |= {f"sim_{k}": v for k, v in observed.values.items()}
    return out


def _by_simulation(case: Case, observed: Observed | None, summary: Mapping[str, Any]) -> Judgement:
    """``trackcert simulate``'s verdict: the case's expectations against the simulation."""
    if observed is None:
        return Judgement(None, None, {}, "no analysis verdict and no simulated observation")
    expectations = judge(case, observed, source=SOURCE)
    unmet = [e.describe() for e in expectations if not e.met]
    return Judgement(
        expectations_verdict(expectations),
        None,
        dict(summary.get("tolerances") or {}),
        "; ".join(unmet) or f"{len(expectations)} simulated expectation(s) met",
    )


def _seed(setup: SweepSetup, values: Sequence[Any]) -> int:
    chosen = [v for t, v in zip(setup.targets, values, strict=True) if t.is_seed]
    return int(chosen[0]) if chosen else setup.seed


def evaluate_point(setup: SweepSetup, point: int, values: Sequence[Any]) -> Row:
    """The row of one point (module docstring).

    Parameters
    ----------
    setup : SweepSetup
        What every point shares.
    point : int
        The point's index in grid order.
    values : sequence
        One value per target.

    Returns
    -------
    Row
    """
    values = tuple(values)
    try:
        case = parse_case(apply_values(setup.data, setup.targets, values), file=setup.file)
        judgement = _judge(case)
    except CaseError as error:
        return Row(point, values, INVALID, message=str(error))
    simulate = setup.simulate and case.kind in SIMULATED
    seed = _seed(setup, values) if simulate else None
    summary: dict[str, Any] = {}
    observed: Observed | None = None
    notes = []
    if simulate:
        try:
            summary, observed = simulate_point(case, setup.steps, seed)
        except CaseError as error:
            seed, notes = None, [f"not simulated: {error.expected} at {error.field}"]
        except PropertyFails as error:  # e.g. ε₁ = 0: the controller does not exist
            seed, notes = None, [f"not simulated: {error}"]
        notes += list(summary.get("warnings") or [])
    if judgement is None:
        judgement = _by_simulation(case, observed, summary)
    agrees, why = agreement(case.kind, judgement.verdict, summary if seed is not None else None)
    return Row(
        point,
        values,
        status_of(judgement.verdict).value,
        judgement.margin,
        judgement.tolerances,
        seed,
        _simulated(summary, observed),
        agrees,
        "; ".join(m for m in [judgement.message, why, *notes] if m),
    )


def evaluate_batch(setup: SweepSetup, batch: Sequence[tuple[int, Sequence[Any]]]) -> list[Row]:
    """The rows of a batch of points (one engine task).

    Parameters
    ----------
    setup : SweepSetup
        What every point shares.
    batch : sequence of (int, sequence)
        Each point's index and values.

    Returns
    -------
    list of Row
        In batch order.
    """
    return [evaluate_point(setup, point, values) for point, values in batch]
