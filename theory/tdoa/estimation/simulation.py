"""A ``kind: tdoa-sim`` case simulated: summary, data files, figures, the kind's simulator and
observer, and the claim on the movement threshold ``b`` (seed 000 §4.3–4.4).

Per agent (1-based ``id``): ``final_localization_error`` ``‖p̄_i(K) − p(K)‖`` and
``mean_localization_error`` (the mean over the pings ``k = 1, …, K``, after the first
measurement), in metres; ``final_cov_norm`` and ``mean_cov_norm`` (same ranges, in the case's
norm); ``distance`` travelled; ``mse_to_pcrb``; the NEES/NIS tests and OSPA of
:mod:`theory.core.consistency` (``anees``, ``mean_nis``, verdicts, ``mean_ospa``; the full
records under ``metrics``). Over Monte Carlo runs each number is the mean
over runs. The expect keys: ``bounded_error`` (every agent's final error below ``error_bound``
metres, default ``ERROR_BOUND_SIGMAS · √r``) and ``max_final_error`` (judged ``at_most``).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, status_of
from theory.core.consistency import agent_columns, filter_metrics, nees, nis
from theory.core.consistency import evidence as metrics_evidence
from theory.core.expectations import Observed
from theory.core.tolerances import ERROR_BOUND_SIGMAS
from theory.sim.outputs import write_agents_csv, write_runs_npz, write_timeseries_csv
from theory.sim.simulate import Finished, Simulator
from theory.tdoa.case import TdoaSimSpec
from theory.tdoa.estimation.scenario import (
    TdoaRun,
    hears_at,
    run_tdoa_scenario,
    run_tdoa_scenarios,
)
from theory.tdoa.geometry.crb import pcrb_along
from theory.tdoa.model import cv_discrete, neighbour_lists

__all__ = [
    "B_SWEEP",
    "SWEEP_MAX_STEPS",
    "SWEEP_SEEDS",
    "b_tradeoff_claim",
    "claims",
    "error_bound",
    "observe_tdoa_sim",
    "run_metrics",
    "run_pcrb",
    "sim_observed",
    "summarize_runs",
    "tdoa_filter_metrics",
    "tdoa_simulator",
    "write_data",
    "write_figures",
]

claims = ClaimSet()


def run_pcrb(spec: TdoaSimSpec, run: TdoaRun) -> np.ndarray:
    """Trace of the position block of the posterior CRB at each ping of ``run``, from every
    agent's rows at its recorded position (independent noises, seed 000 eq. (4.2))."""
    A, B = cv_discrete(spec.T, 3)
    positions = run.paths[:: spec.rounds]
    neighbours = [neighbour_lists(hears_at(spec, p)) for p in positions]
    bound = pcrb_along(run.truth, positions, neighbours, A, B @ spec.Q @ B.T, spec.r, spec.P0)
    return np.trace(bound[:, :3, :3], axis1=1, axis2=2)


def run_metrics(run: TdoaRun, pcrb: np.ndarray) -> dict[str, np.ndarray]:
    """Per-agent metrics of one run (module docstring), each of shape (N,).

    ``mse_to_pcrb`` is the mean squared error over the second half of the pings divided by the
    mean PCRB there (≥ 1 on average for any unbiased estimator; the centralized EKF comes
    closest).
    """
    errors = run.localization_errors
    late = errors.shape[0] // 2
    return {
        "mse_to_pcrb": (errors[late:] ** 2).mean(axis=0) / pcrb[late:].mean(),
        "final_localization_error": errors[-1],
        "mean_localization_error": errors[1:].mean(axis=0),
        "final_cov_norm": run.cov_norms[-1],
        "mean_cov_norm": run.cov_norms[1:].mean(axis=0),
        "distance": run.distance[-1],
    }


def summarize_runs(spec: TdoaSimSpec, runs: Sequence[TdoaRun]) -> dict[str, Any]:
    """The Monte Carlo summary: per-agent means over runs (``agents``) and network totals."""
    bounds = [run_pcrb(spec, run) for run in runs]
    per_run = [run_metrics(run, bound) for run, bound in zip(runs, bounds, strict=True)]
    keys = per_run[0].keys()
    means = {key: np.mean([m[key] for m in per_run], axis=0) for key in keys}
    n = means["distance"].shape[0]
    metrics = tdoa_filter_metrics(runs)
    agents = [
        {"id": i + 1, **{key: float(means[key][i]) for key in keys}, **agent_columns(metrics, i)}
        for i in range(n)
    ]
    totals = [float(m["distance"].sum()) for m in per_run]
    return {
        "agents": agents,
        "metrics": metrics,
        "total_distance": float(np.mean(totals)),
        "runs_total_distance": totals,
        "mean_localization_error": float(means["mean_localization_error"].mean()),
        "mean_cov_norm": float(means["mean_cov_norm"].mean()),
        "moving_fraction": float(np.mean([run.moving.mean() for run in runs])),
        "pcrb_position_trace": float(np.mean([bound[1:].mean() for bound in bounds])),
    }


def tdoa_filter_metrics(runs: Sequence[TdoaRun]) -> dict[str, Any]:
    """NEES of ``x̄_i(k) − x(k)`` against ``P̄_i(k)`` at every ping, NIS of every update (the
    centralized filter's one update counted for every agent, who all hold its estimate), OSPA and
    GOSPA of the estimated positions (:func:`theory.core.consistency.filter_metrics`)."""
    truth = np.stack([r.truth for r in runs])
    estimates = np.stack([r.estimates for r in runs])
    errors = nees(estimates - truth[:, :, None], np.stack([r.covariances for r in runs]))
    innovations = nis(
        np.stack([r.innovations for r in runs]),
        np.stack([r.innovation_covariances for r in runs]),
    )
    dims = np.stack([r.innovation_dims for r in runs])
    shape = errors.shape
    return filter_metrics(
        errors,
        6,
        np.broadcast_to(innovations, shape),
        np.broadcast_to(dims, shape),
        (estimates[..., :3], truth[..., :3]),
    )


def write_data(runs: Sequence[TdoaRun], summary: dict[str, Any], folder: Path) -> list[Path]:
    """Write ``runs.npz`` (every array, stacked over runs), ``agents.csv``, ``timeseries.csv``."""
    errors = np.stack([r.localization_errors for r in runs])
    npz = write_runs_npz(runs, folder / "runs.npz", localization_errors=errors)
    series = write_timeseries_csv(
        folder / "timeseries.csv",
        runs[0].ping_times,
        {
            "error": errors.mean(axis=0),
            "cov_norm": np.mean([r.cov_norms for r in runs], axis=0),
        },
    )
    return [npz, write_agents_csv(summary["agents"], folder / "agents.csv"), series]


def write_figures(runs: Sequence[TdoaRun], folder: Path) -> list[Path]:
    """``trajectories.png`` (run 0), ``errors.png``, ``covariance.png``, ``distance.png`` (means
    over runs): seed 000 §4.4, Figs. 4.7–4.10."""
    per_ping = (
        ("localization_errors", "localization error ‖p̄ᵢ − p‖ (m)", "errors.png"),
        ("cov_norms", "covariance norm ‖P̄ᵢ‖", "covariance.png"),
    )
    return [
        _trajectories(runs[0], folder / "trajectories.png"),
        *(
            _per_agent(
                runs[0].ping_times,
                np.mean([getattr(r, name) for r in runs], axis=0),
                label,
                folder / file,
                log=True,
            )
            for name, label, file in per_ping
        ),
        _per_agent(
            runs[0].fine_times,
            np.mean([r.distance for r in runs], axis=0).sum(axis=1, keepdims=True),
            "distance travelled by the network (m)",
            folder / "distance.png",
        ),
    ]


def _drawing() -> tuple[Any, Any]:
    """pyplot on the Agg backend and :func:`theory.sim.outputs.save_figure` (imported to draw)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from theory.sim.outputs import save_figure

    return plt, save_figure


def _trajectories(run: TdoaRun, path: Path) -> Path:
    plt, save_figure = _drawing()
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    ax.plot(*run.truth[:, :3].T, "k-", lw=2, label="target")
    for i in range(run.paths.shape[1]):
        ax.plot(*run.paths[:, i].T, lw=1, label=f"agent {i + 1}")
        ax.scatter(*run.paths[-1, i], s=12)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.legend(fontsize=6, loc="upper left")
    return save_figure(fig, path)


def _per_agent(
    times: np.ndarray, values: np.ndarray, label: str, path: Path, *, log: bool = False
) -> Path:
    plt, save_figure = _drawing()
    fig, ax = plt.subplots(figsize=(7, 4))
    for i in range(values.shape[1]):
        name = f"agent {i + 1}" if values.shape[1] > 1 else "network"
        ax.plot(times, values[:, i], lw=1, label=name)
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(label)
    ax.legend(fontsize=6, ncol=2)
    ax.grid(True, alpha=0.3)
    return save_figure(fig, path)


def error_bound(case: Case) -> float:
    """The case's ``tolerances.error_bound``, else ``ERROR_BOUND_SIGMAS · √r`` metres."""
    return case.tolerances.get("error_bound", ERROR_BOUND_SIGMAS * math.sqrt(case.spec.r))


def sim_observed(summary: dict[str, Any]) -> Observed:
    """The tdoa-sim expect keys in a summary carrying ``tolerances.error_bound``."""
    worst = max(agent["final_localization_error"] for agent in summary["agents"])
    bound = summary["tolerances"]["error_bound"]
    return Observed({"bounded_error": bool(worst < bound), "max_final_error": float(worst)})


def tdoa_simulator(case: Case, steps: int | None = None) -> Simulator:
    """The simulator of a tdoa-sim ``case`` (``steps`` overrides its pings)."""
    spec = case.spec if steps is None else dataclasses.replace(case.spec, steps=steps)
    fields = {"filter": spec.filter, "b": spec.b, "steps": spec.steps, "T": spec.T, "tau": spec.tau}
    return Simulator(spec, run_tdoa_scenario, fields, _finish)


def observe_tdoa_sim(case: Case, ctx: Context) -> Observed:
    """The observer of ``kind: tdoa-sim``: one run with seed 0, as ``trackcert simulate`` runs."""
    from theory.sim.simulate import monte_carlo

    simulator = tdoa_simulator(case)
    results = monte_carlo(simulator.spec, runs=1, seed=0, workers=1, simulate=simulator.run)
    return sim_observed(_summary(case, simulator.spec, results))


def _summary(case: Case, spec: TdoaSimSpec, results: list) -> dict[str, Any]:
    return {"tolerances": {"error_bound": error_bound(case)}, **summarize_runs(spec, results)}


def _finish(
    case: Case, spec: TdoaSimSpec, results: list, folder: Path | None, figures: bool
) -> Finished:
    record = _summary(case, spec, results)
    files = [] if folder is None else write_data(results, record, folder)
    if figures and folder is not None:
        files += write_figures(results, folder)
    return Finished(record, files, sim_observed(record))


B_SWEEP = (0.0, 3.0, 15.0, math.inf)
SWEEP_SEEDS = (0, 1, 2)
SWEEP_MAX_STEPS = 60


@claims.register(
    "seed000.sec4.4.b-tradeoff",
    source="seed 000, §4.4, Figs 4.9-4.10",
    statement="As b increases, total distance travelled decreases and covariance norms increase.",
    kinds=("tdoa-sim",),
)
def b_tradeoff_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """Sweep ``b`` over :data:`B_SWEEP` with the case's other settings; means over 3 seeds (the
    12 runs in lock step, each as it would run alone)."""
    steps = min(case.spec.steps, SWEEP_MAX_STEPS)
    specs = [dataclasses.replace(case.spec, b=b, steps=steps) for b in B_SWEEP]
    sweep = run_tdoa_scenarios(
        [spec for spec in specs for _ in SWEEP_SEEDS],
        [np.random.default_rng(s) for _ in specs for s in SWEEP_SEEDS],
    )
    distance, norms = [], []
    for i in range(len(B_SWEEP)):
        runs = sweep[i * len(SWEEP_SEEDS) : (i + 1) * len(SWEEP_SEEDS)]
        distance.append(float(np.mean([r.distance[-1].sum() for r in runs])))
        norms.append(float(np.mean([r.cov_norms[steps // 5 :].mean() for r in runs])))
    falls = all(a > b for a, b in itertools.pairwise(distance))
    grows = all(a < b for a, b in itertools.pairwise(norms))
    folder = ctx.figure_folder()
    evidence = {
        "b": [str(b) for b in B_SWEEP],
        "mean_total_distance": distance,
        "mean_cov_norm": norms,
        "seeds": list(SWEEP_SEEDS),
        "steps": steps,
        "filter_metrics": metrics_evidence(tdoa_filter_metrics(sweep)),
    }
    return [
        ClaimResult(
            status_of(falls and grows),
            Method.SIMULATION,
            evidence,
            message="mean over seeded runs; single runs may break the distance ordering",
            figures=() if folder is None else (_tradeoff_figure(distance, norms, folder),),
        )
    ]


def _tradeoff_figure(distance: list[float], norms: list[float], folder: Path) -> str:
    """Seed 000 Figs 4.9–4.10 in one plot: total distance against mean ‖P̄ᵢ‖, one point per b."""
    plt, save_figure = _drawing()
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(norms, distance, "o-")
    for b, x, y in zip(B_SWEEP, norms, distance, strict=True):
        ax.annotate(f"b = {b:g}", (x, y), textcoords="offset points", xytext=(5, 5), fontsize=8)
    ax.set(xlabel="mean covariance norm ‖P̄ᵢ‖", ylabel="total distance travelled (m)", xscale="log")
    ax.grid(True, alpha=0.3)
    return str(save_figure(fig, folder / "b-tradeoff.png"))
