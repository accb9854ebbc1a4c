"""Summary metrics of closed-loop runs (what ``trackcert simulate --json`` prints).

Per agent (1-based ``id``): ``final_localization_error`` ``‖p̄_i(K) − p(K)‖`` and
``mean_localization_error`` (the mean of ``‖p̄_i(k) − p(k)‖`` over the pings ``k = 1, …, K``,
i.e. after the first measurement), in metres; ``final_cov_norm`` and ``mean_cov_norm`` (same
ranges, in the case's norm); ``distance`` travelled. Over Monte Carlo runs each number is the
mean over runs, and ``runs_*`` lists keep the per-run values.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from theory.tdoa.crb import pcrb_along
from theory.tdoa.measurements import neighbour_lists
from theory.tdoa.model import cv_discrete
from theory.tdoa.scenario import TdoaRun, hears_at
from theory.tdoa.sim_case import TdoaSimSpec

__all__ = ["run_metrics", "run_pcrb", "summarize_runs"]


def run_pcrb(spec: TdoaSimSpec, run: TdoaRun) -> np.ndarray:
    """Trace of the position block of the posterior CRB at each ping of ``run``, shape (K+1,).

    Uses every agent's TDOA rows at the agents' recorded positions (seed 000 eq. (4.2): the rows
    of different agents have independent noise) along the run's true trajectory.

    Parameters
    ----------
    spec : TdoaSimSpec
        The scenario of the run.
    run : TdoaRun
        The run.

    Returns
    -------
    ndarray, shape (K+1,)
    """
    A, B = cv_discrete(spec.T, 3)
    positions = run.paths[:: spec.rounds]
    neighbours = [neighbour_lists(hears_at(spec, p)) for p in positions]
    bound = pcrb_along(run.truth, positions, neighbours, A, B @ spec.Q @ B.T, spec.r, spec.P0)
    return np.trace(bound[:, :3, :3], axis1=1, axis2=2)


def run_metrics(run: TdoaRun, pcrb: np.ndarray) -> dict[str, np.ndarray]:
    """Per-agent metrics of one run, each an array of shape (N,).

    Parameters
    ----------
    run : TdoaRun
        The run.
    pcrb : ndarray, shape (K+1,)
        Trace of the position block of the posterior CRB at each ping (see :func:`run_pcrb`).

    Returns
    -------
    dict of str to ndarray
        ``final_localization_error``, ``mean_localization_error``, ``final_cov_norm``,
        ``mean_cov_norm`` and ``distance`` (see the module docstring), and ``mse_to_pcrb``: the
        mean over the second half of the pings (past the initial transient) of
        ``‖p̄_i(k) − p(k)‖²`` divided by the mean there of ``pcrb`` (≥ 1 on average over runs for
        any unbiased estimator; the centralized EKF should come closest).
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
    """The Monte Carlo summary: per-agent means over runs and network totals.

    Parameters
    ----------
    spec : TdoaSimSpec
        The scenario the runs come from.
    runs : sequence of TdoaRun
        One or more runs of the same scenario.

    Returns
    -------
    dict
        ``{"agents": [{"id", "final_localization_error", "mean_localization_error",
        "final_cov_norm", "mean_cov_norm", "distance", "mse_to_pcrb"}], "total_distance",
        "runs_total_distance", "mean_cov_norm", "mean_localization_error", "moving_fraction",
        "pcrb_position_trace"}`` (the last: mean over runs and pings ``k ≥ 1``, m²).
    """
    bounds = [run_pcrb(spec, run) for run in runs]
    per_run = [run_metrics(run, bound) for run, bound in zip(runs, bounds, strict=True)]
    keys = per_run[0].keys()
    means = {key: np.mean([m[key] for m in per_run], axis=0) for key in keys}
    n = means["distance"].shape[0]
    agents = [{"id": i + 1, **{key: float(means[key][i]) for key in keys}} for i in range(n)]
    totals = [float(m["distance"].sum()) for m in per_run]
    return {
        "agents": agents,
        "total_distance": float(np.mean(totals)),
        "runs_total_distance": totals,
        "mean_localization_error": float(means["mean_localization_error"].mean()),
        "mean_cov_norm": float(means["mean_cov_norm"].mean()),
        "moving_fraction": float(np.mean([run.moving.mean() for run in runs])),
        "pcrb_position_trace": float(np.mean([bound[1:].mean() for bound in bounds])),
    }
