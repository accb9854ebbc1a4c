"""``trackcert simulate`` for ``kind: pursuit`` cases (seed 003, 2-D and 3-D): run, summary, files.

Adapts a :class:`~theory.pursuit.case.PursuitSpec` to
:func:`theory.pursuit.closed_loop.simulate_dec`.
Defaults where the case leaves the simulation unspecified (documented in
``docs/simulation.md``): tracker ``i`` (0-based) starts at ``q(0) + (−40 + 5i, −40 − 5i[, 0])``
m with zero Euler angles, ``γ^[i](0) = i`` rad and γ̇(0) = ω_d(0) (a case's ``gamma_dot``
sets e_γ(0) = γ̇(0) − ω_d(0), Type II); estimates start at ``[q(0) + (5, −5[, 0]); 0]`` with
``P = 10 I``. The loop is integrated with error control and recorded every 0.1 s.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.errors import CaseError, PropertyFails
from theory.core.expectations import Observed
from theory.core.tolerances import RUNAWAY_FACTOR
from theory.pursuit.case import PursuitSpec
from theory.pursuit.closed_loop import DecRun, DecSettings, simulate_dec
from theory.pursuit.model import desired_speed
from theory.sim.outputs import write_agents_csv, write_runs_npz, write_timeseries_csv
from theory.simulate import Finished, Simulator

__all__ = [
    "DEFAULT_DURATION",
    "RECORD_INTERVAL",
    "check_pursuit_case",
    "dec_arguments",
    "default_steps",
    "pursuit_simulator",
    "run_pursuit_case",
    "runaway_factor_of",
    "simulation_observed",
    "summarize_pursuit",
    "write_pursuit_data",
    "write_pursuit_figures",
]

DEFAULT_DURATION = 450.0
"""Seconds simulated by default (the paper's runs; 4501 samples of 0.1 s in 2-D)."""


RECORD_INTERVAL = 0.1
"""Seconds between recorded samples (both dimensions): the integrator adapts its own steps
(:mod:`theory.pursuit.closed_loop`) and lands on every record."""


def default_steps() -> int:
    """Records after the first in ``DEFAULT_DURATION``: 4500 of ``RECORD_INTERVAL``."""
    return round(DEFAULT_DURATION / RECORD_INTERVAL)


def check_pursuit_case(spec: PursuitSpec) -> None:
    """Refuse what the simulation cannot run: bad input (a missing block), or a case whose
    controller does not exist.

    Parameters
    ----------
    spec : PursuitSpec

    Raises
    ------
    CaseError
        Missing ``target`` or ``dekf`` blocks.
    PropertyFails
        A rank-deficient ``Δ`` of (22) (ε₁ = 0): a valid case on which Remark 6's hypothesis
        fails, so the controller (26) does not exist — as ``trackcert iss`` and ``certify``
        decide (exit 1), not bad input (seed 003 Remark 6; docs/errata.md).
    """
    if spec.target is None:
        raise CaseError("pursuit.target", "a target motion to simulate", "nothing")
    if spec.dekf is None:
        raise CaseError("pursuit.dekf", "DEKF settings (Ts, sigma, V, Q) to simulate", "nothing")
    if spec.epsilon[0] == 0:
        raise PropertyFails(
            f"pursuit.epsilon = {[float(e) for e in spec.epsilon]}: ε₁ = 0, so Δ of eq. (22) is "
            "not of full row rank and the controller (26) does not exist (seed 003 Remark 6 "
            "needs ε₁ ≠ 0, docs/errata.md): there is nothing to simulate"
        )


def _target_states(spec: PursuitSpec, steps: int) -> np.ndarray:
    times = RECORD_INTERVAL * np.arange(steps + 1)[:, None]  # the motion broadcasts over times
    motion = spec.target
    return np.hstack([motion.position(times), motion.velocity_at(times)])


def _initial_trackers(spec: PursuitSpec, start: np.ndarray) -> dict[str, np.ndarray]:
    """Initial positions, headings, γ and e_γ = γ̇(0) − ω_d(0) (defaults: module docstring)."""
    d, laplacian = spec.dim, spec.laplacian.astype(float)
    positions, headings, gammas, rates = [], [], [], []
    for i, tracker in enumerate(spec.trackers):
        initial = tracker.initial
        default = start + np.array([-40.0 + 5 * i, -40.0 - 5 * i, 0.0][:d])
        positions.append(initial.get("position", default))
        euler = np.asarray(initial.get("euler", np.zeros(1 if d == 2 else 3)), dtype=float)
        headings.append(euler[0] if d == 2 else euler)
        gammas.append(initial.get("gamma", float(i)))
        rates.append(initial.get("gamma_dot"))
    gammas = np.array(gammas, float)
    omega_d = desired_speed(spec.omega_bar, laplacian, gammas, spec.k_c or 0.0)
    e_gamma = np.array([0.0 if r is None else r - w for r, w in zip(rates, omega_d, strict=True)])
    return {
        "initial_positions": np.array(positions, float),
        "initial_headings": np.array(headings),
        "initial_gammas": gammas,
        "initial_gamma_errors": e_gamma if spec.controller == "II" else None,
    }


def dec_arguments(
    spec: PursuitSpec, steps: int | None = None, *, runaway_factor: float = RUNAWAY_FACTOR
) -> dict[str, Any]:
    """The keyword arguments of :func:`theory.pursuit.closed_loop.simulate_dec` for a case
    (all but ``rng``).

    Parameters
    ----------
    spec : PursuitSpec
        A case accepted by :func:`check_pursuit_case`.
    steps : int, optional
        Number of records after the first, every :data:`RECORD_INTERVAL` (default
        :func:`default_steps`).
    runaway_factor : float
        A run stops as a runaway beyond this many S-T curve sizes of localization error (the
        tolerance table's ``runaway_factor``; a case's ``tolerances:`` may set it).

    Returns
    -------
    dict
    """
    steps = default_steps() if steps is None else steps
    dekf, d = spec.dekf, spec.dim
    target = _target_states(spec, steps)
    offset = np.array([5.0, -5.0, 0.0][:d])
    x0 = dekf.x0 if dekf.x0 is not None else np.concatenate([target[0, :d] + offset, np.zeros(d)])
    settings = DecSettings(
        omega_bar=spec.omega_bar,
        epsilon=tuple(float(e) for e in spec.epsilon),
        Kp=spec.K_p,
        k_gamma=spec.k_gamma if spec.k_gamma is not None else 0.0,
        k_c=spec.k_c if spec.k_c is not None else 0.0,
        controller=spec.controller,
        V=dekf.V,
        Q=dekf.Q,
        Ts=dekf.Ts,
        dt=RECORD_INTERVAL,
        sigma=dekf.sigma,
        runaway_factor=runaway_factor,
    )
    paths = np.array(
        [
            [t.r_x, t.r_y, t.gamma0] if d == 2 else [t.r_x, t.r_y, t.r_z, t.c, t.gamma0]
            for t in spec.trackers
        ]
    )
    return {
        "target": target,
        **_initial_trackers(spec, target[0, :d]),
        "in_neighbours": [list(np.flatnonzero(row)) for row in spec.adjacency],
        "x0": x0,
        "P0": dekf.P0 if dekf.P0 is not None else 10.0 * np.eye(2 * d),
        "steps": steps,
        "settings": settings,
        "paths": paths,
        "fusion": dekf.weights,
    }


def run_pursuit_case(
    spec: PursuitSpec,
    rng: np.random.Generator,
    steps: int | None = None,
    *,
    runaway_factor: float = RUNAWAY_FACTOR,
) -> DecRun:
    """One run of the DEC loop (2-D or 3-D) for a pursuit case.

    Parameters
    ----------
    spec : PursuitSpec
        A case accepted by :func:`check_pursuit_case`.
    rng : numpy.random.Generator
        Source of the range noise.
    steps : int, optional
        Number of records after the first, every :data:`RECORD_INTERVAL` (default
        :func:`default_steps`).
    runaway_factor : float
        The runaway threshold in S-T curve sizes (:func:`dec_arguments`).

    Returns
    -------
    DecRun
    """
    return simulate_dec(rng=rng, **dec_arguments(spec, steps, runaway_factor=runaway_factor))


def summarize_pursuit(
    spec: PursuitSpec, runs: Sequence[DecRun], *, runaway_factor: float = RUNAWAY_FACTOR
) -> dict[str, Any]:
    """Per-tracker means over runs and the coordination outcome.

    Parameters
    ----------
    spec : PursuitSpec
    runs : sequence of DecRun
    runaway_factor : float
        The runaway threshold the runs used (reported under ``tolerances``).

    Returns
    -------
    dict
        ``{"agents": [{"id", "final_localization_error", "mean_localization_error",
        "final_pursuit_error", "mean_pursuit_error"}], "final_gamma_spread",
        "final_gamma_rate_error", "omega_bar", "integration_steps", "stopped_at",
        "stop_causes", "stop_reasons", "tolerances", "iss_agreement"}`` (means over runs; errors
        in m, γ in rad; ``stopped_at``, ``stop_causes`` (``"runaway"`` or ``"step_floor"``,
        :class:`~theory.pursuit.closed_loop.DecRun`) and ``stop_reasons`` per run, ``None`` when
        the run completed; ``tolerances``: the ``runaway_factor`` used; ``iss_agreement``: run 0
        against the certified estimate, :func:`theory.pursuit.iss_check.simulation_agreement`,
        or ``None`` when ``trackcert iss`` certifies nothing).
    """
    loc = np.mean([r.localization_errors for r in runs], axis=0)
    pur = np.mean([r.pursuit_errors for r in runs], axis=0)
    agents = [
        {
            "id": i + 1,
            "final_localization_error": float(loc[-1, i]),
            "mean_localization_error": float(loc[:, i].mean()),
            "final_pursuit_error": float(pur[-1, i]),
            "mean_pursuit_error": float(pur[:, i].mean()),
        }
        for i in range(loc.shape[1])
    ]
    return {
        "agents": agents,
        "final_gamma_spread": float(np.mean([np.ptp(r.gammas[-1]) for r in runs])),
        "final_gamma_rate_error": float(
            np.mean([np.abs(r.gamma_rates[-1] - spec.omega_bar).max() for r in runs])
        ),
        "omega_bar": spec.omega_bar,
        "integration_steps": [r.steps for r in runs],
        "stopped_at": [None if r.completed else r.stopped_at for r in runs],
        "stop_causes": [None if r.completed else r.stop_cause for r in runs],
        "stop_reasons": [None if r.completed else r.stop_reason for r in runs],
        "tolerances": {"runaway_factor": runaway_factor},
        "iss_agreement": _agreement(spec, runs[0]),
    }


def _agreement(spec: PursuitSpec, run: DecRun) -> dict[str, Any] | None:
    from theory.pursuit.iss import iss_conditions
    from theory.pursuit.iss_check import simulation_agreement

    statuses = {c.status for c in iss_conditions(spec)} - {"not-applicable"}
    if statuses != {"holds"}:
        return None
    return simulation_agreement(spec, run)


def simulation_observed(summary: dict[str, Any]) -> Observed:
    """The ``simulation_bounded`` key as run 0 of ``summary`` decides it.

    Parameters
    ----------
    summary : dict
        From :func:`summarize_pursuit`.

    Returns
    -------
    Observed
        ``simulation_bounded`` (undecided when ``trackcert iss`` certifies nothing, so there is
        no certified estimate to stay within).
    """
    agreement = summary["iss_agreement"]
    got = None if agreement is None else agreement["simulation_bounded"]
    undecided = frozenset() if got is not None else frozenset({"simulation_bounded"})
    return Observed({"simulation_bounded": got}, undecided)


def pursuit_simulator(case: Case, steps: int | None = None) -> Simulator:
    """The simulator of a ``kind: pursuit`` case for :func:`theory.simulate.simulate_case`.

    Parameters
    ----------
    case : Case
        A pursuit case with ``target`` and ``dekf`` blocks.
    steps : int, optional
        Recorded 0.1 s steps (default :func:`default_steps`).

    Returns
    -------
    Simulator

    Raises
    ------
    CaseError
        If the case cannot be simulated (no target or DEKF block), naming its file.
    """
    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise error.in_file(case.file) from None
    steps = steps or default_steps()
    fields = {
        "controller": case.spec.controller,
        "dim": case.spec.dim,
        "steps": steps,
        "dt": RECORD_INTERVAL,
    }
    run = functools.partial(run_pursuit_case, steps=steps, runaway_factor=runaway_factor_of(case))
    return Simulator(case.spec, run, fields, _finish)


def runaway_factor_of(case: Case) -> float:
    """The case's ``tolerances.runaway_factor``, else the tolerance table's."""
    return float(case.tolerances.get("runaway_factor", RUNAWAY_FACTOR))


def _finish(case: Case, spec: Any, results: list, folder: Path, figures: bool) -> Finished:
    summary = summarize_pursuit(spec, results, runaway_factor=runaway_factor_of(case))
    files = write_pursuit_data(results, summary, folder)
    if figures:
        files += write_pursuit_figures(results, folder)
    summary["warnings"] = [
        _stop_warning(i, stopped, cause, reason)
        for i, (stopped, cause, reason) in enumerate(
            zip(summary["stopped_at"], summary["stop_causes"], summary["stop_reasons"], strict=True)
        )
        if stopped is not None
    ]
    return Finished(summary, files, simulation_observed(summary))


def _stop_warning(run: int, stopped: float, cause: str, reason: str) -> str:
    """The warning for run ``run`` (0-based) stopped at ``stopped`` s."""
    if cause == "runaway":
        return f"run {run} stopped at t = {stopped:g} s, {reason}"
    return f"a run's integration stopped at t = {stopped:g} s (step below the floor)"


def write_pursuit_data(runs: Sequence[DecRun], summary: dict[str, Any], folder: Path) -> list[Path]:
    """``runs.npz`` (every array stacked over runs), ``agents.csv``, ``timeseries.csv``.

    Parameters
    ----------
    runs : sequence of DecRun
    summary : dict
        From :func:`summarize_pursuit`.
    folder : pathlib.Path
        Existing output folder.

    Returns
    -------
    list of pathlib.Path
    """
    every = slice(None, None, 10)
    series = write_timeseries_csv(
        folder / "timeseries.csv",
        runs[0].times[every],
        {
            "localization_error": np.mean([r.localization_errors for r in runs], axis=0)[every],
            "pursuit_error": np.mean([r.pursuit_errors for r in runs], axis=0)[every],
        },
    )
    return [
        write_runs_npz(runs, folder / "runs.npz"),
        write_agents_csv(summary["agents"], folder / "agents.csv"),
        series,
    ]


def write_pursuit_figures(runs: Sequence[DecRun], folder: Path) -> list[Path]:
    """``trajectories.png`` (run 0), ``errors.png`` and ``coordination.png``.

    Drawn without pyplot and with fixed margins (:func:`theory.sim.figures.new_figure`): the
    automatic layout would draw every tick label twice.

    Parameters
    ----------
    runs : sequence of DecRun
    folder : pathlib.Path
        Existing output folder.

    Returns
    -------
    list of pathlib.Path
    """
    from theory.sim.figures import save_figure

    drawn = (
        (_trajectory_figure(runs[0]), "trajectories.png"),
        (_error_figure(runs), "errors.png"),
        (_coordination_figure(runs[0]), "coordination.png"),
    )
    return [save_figure(fig, folder / name, layout=False) for fig, name in drawn]


_STACKED = {"left": 0.12, "right": 0.97, "bottom": 0.09, "top": 0.98, "hspace": 0.08}
"""Margins of the two-panel figures (fractions of the figure)."""


def _trajectory_figure(run: DecRun) -> Any:
    """The target's and the trackers' paths in the horizontal plane."""
    from theory.sim.figures import new_figure

    margins = {"left": 0.13, "right": 0.97, "bottom": 0.09, "top": 0.98}
    fig, ax = new_figure(figsize=(6, 6), margins=margins)
    ax.plot(*run.target[:, :2].T, "k-", lw=2, label="target")
    for i in range(run.positions.shape[1]):
        ax.plot(*run.positions[:, i, :2].T, lw=1, label=f"tracker {i + 1}")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=7, loc="upper right")
    return fig


def _error_figure(runs: Sequence[DecRun]) -> Any:
    """Pursuit and localization errors per tracker (means over runs), log scale."""
    from theory.sim.figures import new_figure

    fig, axes = new_figure(2, 1, figsize=(7, 6), sharex=True, margins=_STACKED)
    times = runs[0].times
    for name, ax in zip(("pursuit_errors", "localization_errors"), axes, strict=True):
        values = np.mean([getattr(r, name) for r in runs], axis=0)
        for i in range(values.shape[1]):
            ax.plot(times, values[:, i], lw=1, label=f"tracker {i + 1}")
        _plain_log_axis(ax)
        ax.set_ylabel(name.replace("_", " ") + " (m)")
        ax.legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("time (s)")
    return fig


def _plain_log_axis(ax: Any) -> None:
    """A log-scale y axis labelled ``0.1, 1, 10`` at the decades, without minor ticks: the
    default ``10ⁿ`` labels need matplotlib's mathtext parser, which costs more to build than
    the rest of the figure."""
    from matplotlib.ticker import FuncFormatter, NullLocator

    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    ax.yaxis.set_minor_locator(NullLocator())
    ax.grid(True, which="major", axis="y", lw=0.3)


def _coordination_figure(run: DecRun) -> Any:
    """γ^[i] about their mean and γ̇^[i] (run 0)."""
    from theory.sim.figures import new_figure

    fig, axes = new_figure(2, 1, figsize=(7, 6), sharex=True, margins=_STACKED)
    axes[0].plot(run.times, run.gammas - run.gammas.mean(axis=1, keepdims=True), lw=1)
    axes[0].set_ylabel("γ_i − mean γ (rad)")
    axes[1].plot(run.times, run.gamma_rates, lw=1)
    axes[1].set_ylabel("dγ_i/dt (rad/s)")
    axes[1].set_xlabel("time (s)")
    return fig
