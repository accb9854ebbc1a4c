"""``trackcert simulate`` for ``kind: pursuit`` cases (seed 003, 2-D and 3-D), and the ISS
estimate of Theorem 2 checked along the simulated trajectories.

Adapts a :class:`~theory.pursuit.case.PursuitSpec` to
:func:`theory.pursuit.closed_loop.simulate_dec`. Defaults where the case leaves the simulation
unspecified (``docs/simulation.md``): tracker ``i`` (0-based) starts at
``q(0) + (−40 + 5i, −40 − 5i[, 0])`` m with zero Euler angles, ``γ^[i](0) = i`` rad and
γ̇(0) = ω_d(0) (a case's ``gamma_dot`` sets e_γ(0) = γ̇(0) − ω_d(0), Type II); estimates start at
``[q(0) + (5, −5[, 0]); 0]`` with ``P = 10 I``. The loop is integrated with error control and
recorded every 0.1 s.

With ``μ = col(ξ, e)``, ``ξ = (I − 1rᵀ)γ`` (eq. (56)), ``e^[i] = [e_p^[i], e_γ^[i]]`` (true
target) and ``x̃`` the stacked estimation errors the controllers use,
:func:`theory.pursuit.iss.iss_bound` gives ``‖μ(t)‖ ≤ β(‖μ(0)‖, t) + γ(sup_{s≤t}‖x̃(s)‖)``;
:func:`simulation_agreement` checks it at every record of a run — the verdict shared by
``trackcert simulate`` and the claim ``seed003.thm2.sim-trajectories``: does the simulated loop
stay within what ``trackcert iss`` certifies? The estimate is conditional on x̃, which the DEKF
produces in closed loop; a run whose estimate runs away stays within it while diverging, so the
verdict also reports how x̃ grew.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, NotApplicable, Status
from theory.core.consistency import agent_columns
from theory.core.consistency import evidence as metrics_evidence
from theory.core.engines import resolve_engine
from theory.core.errors import CaseError, PropertyFails
from theory.core.expectations import Observed
from theory.core.tolerances import ISS_BOUND_RTOL, RUNAWAY_FACTOR
from theory.pursuit.case import PursuitSpec
from theory.pursuit.closed_loop import DecRun, DecSettings, StopCause, simulate_dec
from theory.pursuit.filter_metrics import dekf_metrics
from theory.pursuit.model import desired_speed
from theory.pursuit.published import simulate_published
from theory.sim.outputs import write_agents_csv, write_runs_npz, write_timeseries_csv
from theory.sim.simulate import Finished, Simulator

__all__ = [
    "DEFAULT_DURATION",
    "RECORD_INTERVAL",
    "SIMULATION_SEED",
    "STOPS",
    "IssMargin",
    "check_pursuit_case",
    "claims",
    "dec_arguments",
    "default_run",
    "default_steps",
    "iss_margin_along",
    "pursuit_simulator",
    "run_pursuit_case",
    "runaway_factor_of",
    "simulation_agreement",
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


def default_steps(spec: PursuitSpec | None = None) -> int:
    """Records after the first in the case's ``duration``, else ``DEFAULT_DURATION`` (4500 of
    ``RECORD_INTERVAL``)."""
    duration = DEFAULT_DURATION if spec is None or spec.duration is None else spec.duration
    return round(duration / RECORD_INTERVAL)


def check_pursuit_case(spec: PursuitSpec) -> None:
    """CaseError naming what the simulation cannot run (no ``target``, no ``dekf``); PropertyFails
    for a rank-deficient Δ of (22) (ε₁ = 0): a valid case whose controller (26) does not exist,
    as ``trackcert iss`` and ``certify`` decide (seed 003 Remark 6; docs/errata.md)."""
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
    """The keyword arguments of :func:`theory.pursuit.closed_loop.simulate_dec` but ``rng``.

    ``steps`` records after the first, every :data:`RECORD_INTERVAL` (default
    :func:`default_steps`); a run stops as a runaway beyond ``runaway_factor`` S-T curve sizes of
    localization error.
    """
    steps = default_steps(spec) if steps is None else steps
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
        predictions=dekf.predictions,
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
        "in_neighbours": spec.weighted_adjacency.astype(float),
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
    engine: str | None = None,
) -> DecRun:
    """One run of the DEC loop for a pursuit case (``rng`` draws the range noise; seed 003 §V):
    the analysed laws integrated as an ODE on ``engine`` (:func:`simulate_dec`), or the
    ``published`` variant as the authors' scripts run it
    (:func:`theory.pursuit.published.simulate_published`)."""
    arguments = dec_arguments(spec, steps, runaway_factor=runaway_factor)
    if spec.published is None:
        return simulate_dec(rng=rng, engine=engine, **arguments)
    errors = arguments.pop("initial_gamma_errors")
    omega_d = desired_speed(
        spec.omega_bar, spec.laplacian.astype(float), arguments["initial_gammas"], spec.k_c or 0.0
    )
    rates = omega_d if errors is None else omega_d + errors
    return simulate_published(
        rng=rng, initial_gamma_rates=rates, control=spec.published, **arguments
    )


def summarize_pursuit(
    spec: PursuitSpec,
    runs: Sequence[DecRun],
    *,
    runaway_factor: float = RUNAWAY_FACTOR,
    metrics: bool = True,
) -> dict[str, Any]:
    """Per-tracker means over runs (errors in m, γ in rad) and the coordination outcome.

    ``stopped_at``, ``stop_causes`` and ``stop_reasons`` per run are ``None`` when it completed;
    ``iss_agreement`` is run 0 against the certified estimate (:func:`simulation_agreement`), or
    ``None`` when ``trackcert iss`` certifies nothing; ``metrics`` the DEKF's NEES/NIS and OSPA
    (:func:`theory.pursuit.filter_metrics.dekf_metrics`) and their per-tracker columns, or
    ``None`` and no columns when ``metrics`` is false (a sweep point's summary: its row shows none).
    """
    loc = np.mean([r.localization_errors for r in runs], axis=0)
    pur = np.mean([r.pursuit_errors for r in runs], axis=0)
    replayed = dekf_metrics(runs, dec_arguments(spec, len(runs[0].times) - 1)) if metrics else None
    agents = [
        {
            "id": i + 1,
            "final_localization_error": float(loc[-1, i]),
            "mean_localization_error": float(loc[:, i].mean()),
            "final_pursuit_error": float(pur[-1, i]),
            "mean_pursuit_error": float(pur[:, i].mean()),
            **(agent_columns(replayed, i) if replayed is not None else {}),
        }
        for i in range(loc.shape[1])
    ]
    return {
        "agents": agents,
        "metrics": replayed,
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
    from theory.pursuit.iss import ConditionStatus, iss_conditions

    statuses = {c.status for c in iss_conditions(spec)} - {ConditionStatus.NOT_APPLICABLE}
    if statuses != {ConditionStatus.HOLDS}:
        return None
    return simulation_agreement(spec, run)


def simulation_observed(summary: dict[str, Any]) -> Observed:
    """``simulation_bounded`` as run 0 of a :func:`summarize_pursuit` decides it (undecided when
    ``trackcert iss`` certifies nothing: there is no estimate to stay within); ``runaways`` (runs
    stopped as runaways), and per tracker the ``final_localization_error`` and
    ``mean_pursuit_error`` averaged over the runs (m), the statistics a published case bands."""
    agreement = summary["iss_agreement"]
    got = None if agreement is None else agreement["simulation_bounded"]
    undecided = frozenset() if got is not None else frozenset({"simulation_bounded"})
    values = {
        "simulation_bounded": got,
        "runaways": sum(cause == StopCause.RUNAWAY for cause in summary["stop_causes"]),
        "final_localization_error": [a["final_localization_error"] for a in summary["agents"]],
        "mean_pursuit_error": [a["mean_pursuit_error"] for a in summary["agents"]],
    }
    return Observed(values, undecided)


def pursuit_simulator(case: Case, steps: int | None = None, runs: int | None = None) -> Simulator:
    """The simulator of a ``kind: pursuit`` case (:func:`theory.sim.simulate.simulate_case`).

    ``steps`` recorded 0.1 s steps (default :func:`default_steps`); ``runs`` the Monte Carlo runs
    planned, which with ``steps`` choose the default engine (a short job runs on the NumPy
    engine: :func:`theory.core.engines.resolve_engine`); CaseError naming the file if
    the case cannot be simulated, or naming ``TRACKCERT_ENGINE`` if it names no engine (checked
    here, before any run).
    """
    steps = steps or default_steps(case.spec)
    engine = resolve_engine(records=None if runs is None else runs * steps)
    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise error.in_file(case.file) from None
    fields = {
        "controller": case.spec.controller,
        "variant": "analysed" if case.spec.published is None else "published",
        "dim": case.spec.dim,
        "steps": steps,
        "dt": RECORD_INTERVAL,
    }
    run = functools.partial(
        run_pursuit_case, steps=steps, runaway_factor=runaway_factor_of(case), engine=engine
    )
    return Simulator(case.spec, run, fields, _finish)


def runaway_factor_of(case: Case) -> float:
    """The case's ``tolerances.runaway_factor``, else the tolerance table's."""
    return float(case.tolerances.get("runaway_factor", RUNAWAY_FACTOR))


def _finish(case: Case, spec: Any, results: list, folder: Path | None, figures: bool) -> Finished:
    """The summary, files and observations; without a ``folder`` (a sweep point) the summary
    skips the DEKF metrics, which only the written summary and the command's table show."""
    factor = runaway_factor_of(case)
    summary = summarize_pursuit(spec, results, runaway_factor=factor, metrics=folder is not None)
    files = [] if folder is None else write_pursuit_data(results, summary, folder)
    if figures and folder is not None:
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
    if cause == StopCause.RUNAWAY:
        return f"run {run} stopped at t = {stopped:g} s, {reason}"
    return f"a run's integration stopped at t = {stopped:g} s (step below the floor)"


def write_pursuit_data(runs: Sequence[DecRun], summary: dict[str, Any], folder: Path) -> list[Path]:
    """``runs.npz`` (every array stacked over runs), ``agents.csv``, ``timeseries.csv``."""
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
    """``trajectories.png`` (run 0), ``errors.png`` and ``coordination.png`` in ``folder``.

    Drawn without pyplot and with fixed margins (:func:`theory.sim.outputs.new_figure`): the
    automatic layout would draw every tick label twice.
    """
    from theory.sim.outputs import save_figure

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
    from theory.sim.outputs import new_figure

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
    from theory.sim.outputs import new_figure

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
    from theory.sim.outputs import new_figure

    fig, axes = new_figure(2, 1, figsize=(7, 6), sharex=True, margins=_STACKED)
    axes[0].plot(run.times, run.gammas - run.gammas.mean(axis=1, keepdims=True), lw=1)
    axes[0].set_ylabel("γ_i − mean γ (rad)")
    axes[1].plot(run.times, run.gamma_rates, lw=1)
    axes[1].set_ylabel("dγ_i/dt (rad/s)")
    axes[1].set_xlabel("time (s)")
    return fig


# ---------------------------------------------------------------------------------------------
# the ISS estimate of Theorem 2 along a run


@dataclass(frozen=True, eq=False)
class IssMargin:
    """Both sides of the Theorem 2 estimate at the completed records of a run.

    ``mu`` is ‖μ(t)‖, ``bound`` β + γ, ``x_tilde`` ‖x̃(t)‖; ``margin`` = min(bound − mu),
    ``relative_margin`` = min((bound − mu)/bound) (at ``worst_time``), ``holds`` within the
    table's ``iss_bound_rtol``; ``gain`` and ``constants`` are the estimate's.
    """

    mu: np.ndarray
    bound: np.ndarray
    margin: float
    relative_margin: float
    holds: bool
    worst_time: float
    gain: float
    constants: dict[str, float]
    x_tilde: np.ndarray


def iss_margin_along(spec: PursuitSpec, run: DecRun) -> IssMargin:
    """Both sides of the seed 003 Theorem 2 estimate along ``run`` (its completed records).

    ValueError if the analysis' conditions fail (from :func:`theory.pursuit.iss.iss_bound`).
    """
    from theory.pursuit.iss import coordination_iss, iss_bound

    estimate = iss_bound(spec)
    done = np.isfinite(run.pursuit_errors).all(axis=1)
    done &= np.isfinite(run.estimation_errors).all(axis=1)
    times, gammas = run.times[done], run.gammas[done]
    if spec.n_trackers > 1:
        r = np.array([float(v) for v in coordination_iss(spec).r])
        xi_sq = ((gammas - (gammas @ r)[:, None]) ** 2).sum(axis=1)
    else:
        xi_sq = np.zeros(len(times))
    e_sq = (run.pursuit_errors[done] ** 2).sum(axis=1) + (run.gamma_errors[done] ** 2).sum(axis=1)
    mu = np.sqrt(xi_sq + e_sq)
    x_tilde = np.sqrt((run.estimation_errors[done] ** 2).sum(axis=1))
    sup_error = np.maximum.accumulate(x_tilde)
    bound = estimate.beta(mu[0], times) + estimate.gamma(sup_error)
    slack = bound - mu
    worst = int(np.argmin(slack / bound))
    return IssMargin(
        mu=mu,
        bound=bound,
        margin=float(slack.min()),
        relative_margin=float(slack[worst] / bound[worst]),
        holds=bool(np.all(mu <= bound * (1 + ISS_BOUND_RTOL))),
        worst_time=float(times[worst]),
        gain=estimate.gain,
        constants=estimate.constants,
        x_tilde=x_tilde,
    )


STOPS = {
    StopCause.RUNAWAY: "a runaway: the DEKF lost the target",
    StopCause.STEP_FLOOR: "the integrator's step fell below its floor",
}
"""How a stopped run's message names its cause (the full reason is in the run's warning)."""


def simulation_agreement(spec: PursuitSpec, run: DecRun) -> dict[str, Any]:
    """Whether a run of a certified case stays within the certified estimate (and finite).

    ``simulation_bounded`` is true when the integration reached the last record and ‖μ(t)‖ stays
    within β(‖μ(0)‖, t) + γ(sup‖x̃‖) at every record (slack: ``iss_bound_rtol``). ``status`` is
    ``verified`` then, ``refuted`` when μ leaves the estimate, ``inconclusive`` when the run
    stopped early inside it (the loop ran away with its estimate, docs/theory/pursuit-iss.md §11:
    the certificate, which takes x̃ as its input, is not contradicted). ValueError if the
    analysis' conditions fail (seed 003 Theorem 2).
    """
    along = iss_margin_along(spec, run)
    x_tilde = along.x_tilde
    numbers = {
        "margin": along.margin,
        "relative_margin": along.relative_margin,
        "iss_bound_rtol": ISS_BOUND_RTOL,
        "worst_time": along.worst_time,
        "gain": along.gain,
        "final_mu": float(along.mu[-1]),
        "final_bound": float(along.bound[-1]),
        "x_tilde_initial": float(x_tilde[0]),
        "x_tilde_max": float(x_tilde.max()),
        "x_tilde_final": float(x_tilde[-1]),
        "completed": run.completed,
        "stopped_at": None if run.completed else run.stopped_at,
        "stop_cause": None if run.completed else run.stop_cause,
    }
    if not along.holds:
        status = "refuted"
        message = (
            f"‖μ‖ leaves the certified estimate at t = {along.worst_time:g} s (relative "
            f"margin {along.relative_margin:.3g})"
        )
    elif not run.completed:
        status = "inconclusive"
        stop = STOPS.get(run.stop_cause, run.stop_reason)
        message = (
            f"within the estimate until the run stopped at t = {run.stopped_at:g} s ({stop}); "
            f"‖x̃‖ grew from {x_tilde[0]:.3g} to {x_tilde.max():.3g}"
        )
    else:
        status = "verified"
        message = (
            f"within the certified estimate at every record (relative margin "
            f"{along.relative_margin:.3g}); ‖x̃‖ from {x_tilde[0]:.3g} to {x_tilde[-1]:.3g}"
        )
    bounded = status == "verified"
    return {"simulation_bounded": bounded, "status": status, "message": message, **numbers}


# ---------------------------------------------------------------------------------------------
# claim: `trackcert iss` and `trackcert simulate` agree

claims = ClaimSet()

SIMULATION_SEED = 0
"""Root seed of the claim's run (``trackcert simulate``'s default)."""


def default_run(case: Case) -> DecRun:
    """The run ``trackcert simulate CASE`` makes by default (one run, root seed 0, 450 s)."""
    from theory.sim.simulate import run_seeds

    (sequence,) = run_seeds(SIMULATION_SEED, 1)
    rng = np.random.default_rng(sequence)
    return run_pursuit_case(case.spec, rng, runaway_factor=runaway_factor_of(case))


def _certified(case: Case) -> None:
    """Raise :class:`NotApplicable` unless ``trackcert iss`` certifies the case and it simulates."""
    from theory.pursuit.iss import ConditionStatus, iss_conditions

    tol = case.tolerances.get("margin_tol")
    options = {} if tol is None else {"margin_tol": float(tol)}
    undecided = [
        c.name for c in iss_conditions(case.spec, **options) if c.status != ConditionStatus.HOLDS
    ]
    if case.spec.n_trackers == 1:  # graph conditions are not applicable to one tracker
        undecided = [name for name in undecided if name != "graph_strongly_connected"]
    if undecided:
        raise NotApplicable(f"trackcert iss certifies nothing here (conditions {undecided})")
    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise NotApplicable(f"nothing to simulate: {error.field} is not {error.expected}") from None


@claims.register(
    "seed003.thm2.sim-trajectories",
    source="seed 003, Theorem 2 (corrected constants of theory.pursuit.iss) against the simulator",
    statement="When trackcert iss certifies a case, its simulated trajectory (trackcert simulate, "
    "seed 0) stays finite and within the certified estimate ‖μ(t)‖ ≤ β(‖μ(0)‖, t) + "
    "γ(sup‖x̃‖) at every record.",
    kinds=("pursuit",),
)
def check_simulation_agrees(case: Case, ctx: Context) -> list[ClaimResult]:
    """One run of a certified case (seed 0) against the certified estimate (seed 003 Theorem 2).

    ``verified`` (agreement), ``refuted`` (μ leaves the estimate) or ``inconclusive`` (stopped
    early inside it); not applicable when a condition does not hold or nothing simulates. Draws
    ‖μ(t)‖ against the estimate (``mu_bound.png``) when figures are on.
    """
    _certified(case)
    run = default_run(case)
    verdict = simulation_agreement(case.spec, run)
    folder = ctx.figure_folder()
    figures = ()
    if folder is not None:
        figures = (_figure(run.times, iss_margin_along(case.spec, run), folder),)
    evidence = {k: v for k, v in verdict.items() if k not in ("status", "message")}
    evidence |= {"seed": SIMULATION_SEED, "records": len(run.times), "steps": run.steps}
    arguments = dec_arguments(case.spec, len(run.times) - 1)
    evidence["filter_metrics"] = metrics_evidence(dekf_metrics([run], arguments))
    evidence["expectations"] = {"simulation_bounded": verdict["simulation_bounded"]}
    return [
        ClaimResult(
            verdict["status"], "simulation", evidence, margin=verdict["relative_margin"],
            tolerance={"iss_bound_rtol": verdict["iss_bound_rtol"]}, message=verdict["message"],
            figures=figures,
        )
    ]  # fmt: skip


PUBLISHED_RUNS = 10
"""Runs of the claim ``seed003.sec6.published-statistics``: children 0–9 of
``SeedSequence(SIMULATION_SEED)``, as ``trackcert simulate --runs 10``."""

PUBLISHED_KEYS = ("runaways", "final_localization_error", "mean_pursuit_error")
"""The expect keys a published-variant case bands (:func:`simulation_observed`)."""


@claims.register(
    "seed003.sec6.published-statistics",
    source="seed 003 §VI as the authors' scripts run it (github.com/hungrepo/"
    "cooperative-distributed-range-based-SLAP, SLAP_*.m; docs/simulation.md)",
    statement="A case of the published variant, simulated over 10 seeds (trackcert simulate "
    "--runs 10), never runs away, and its per-tracker run-mean final localization and mean "
    "pursuit errors lie in the bands its expect block states (measured on the authors' code).",
    kinds=("pursuit",),
)
def check_published_statistics(case: Case, ctx: Context) -> list[ClaimResult]:
    """The published statistics of seed 003 §VI reproduced (issue 27): ``verified`` when no run
    runs away and every stated band holds, else ``refuted``; the margin is the smallest distance
    of a statistic inside its band (m; negative outside). Not applicable to the analysed laws."""
    from theory.core.expectations import judge
    from theory.sim.simulate import run_seeds

    if case.spec.published is None:
        raise NotApplicable("the case runs the analysed laws, not the published scripts")
    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise NotApplicable(f"nothing to simulate: {error.field} is not {error.expected}") from None
    factor = runaway_factor_of(case)
    runs = [
        run_pursuit_case(case.spec, np.random.default_rng(sequence), runaway_factor=factor)
        for sequence in run_seeds(SIMULATION_SEED, PUBLISHED_RUNS)
    ]
    values = simulation_observed(summarize_pursuit(case.spec, runs, runaway_factor=factor)).values
    observed = Observed({key: values[key] for key in PUBLISHED_KEYS})
    verdicts = judge(case, observed, source="seed003.sec6.published-statistics")
    failed = [v.describe() for v in verdicts if not v.met] + (
        [f"{values['runaways']} of {PUBLISHED_RUNS} runs ran away"] if values["runaways"] else []
    )
    return [
        ClaimResult(
            Status.REFUTED if failed else Status.VERIFIED, Method.SIMULATION,
            {**observed.evidence(), "runs": PUBLISHED_RUNS, "seed": SIMULATION_SEED},
            margin=_band_margin(case.expect, values), tolerance={"runaway_factor": factor},
            message="; ".join(failed) or f"no runaway in {PUBLISHED_RUNS} runs, every band met",
        )
    ]  # fmt: skip


def _band_margin(expect: dict[str, Any], values: dict[str, Any]) -> float | None:
    """The smallest distance (m) of a banded statistic to its band's nearer edge (negative
    outside); ``None`` when the case states no band."""
    distances = [
        min(value - band[0], band[1] - value)
        for key in PUBLISHED_KEYS[1:]
        if isinstance(band := expect.get(key), list)
        for value in values[key]
    ]
    return float(min(distances)) if distances else None


def _figure(times: np.ndarray, along: IssMargin, folder: Path) -> str:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from theory.sim.outputs import save_figure

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.semilogy(times[: len(along.mu)], along.mu, lw=1, label="‖μ(t)‖ (simulated)")
    ax.semilogy(times[: len(along.bound)], along.bound, lw=1, label="β + γ (certified)")
    ax.set_xlabel("time (s)")
    ax.legend(fontsize=7)
    return str(save_figure(fig, folder / "mu_bound.png"))
