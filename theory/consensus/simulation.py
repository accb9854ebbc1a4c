"""``trackcert simulate`` for ``kind: dkf`` cases (seed 000 ch. 5): run, summary, files.

A ``dkf`` case gives ``A, C_i, W, Q, R_i`` and the filter order but no initial data; the
simulation uses ``P_i(0) = 10 I`` (Example 1's value), every estimate starting at 0 and the
initial state drawn from ``N(0, P_i(0))`` with the run's generator. The summary reports per
agent the final and mean estimation error ``‖x̂_i − x‖`` (as ``final_localization_error`` /
``mean_localization_error``) and ``cov_growth = ‖P_i(K)‖/‖P_i(K/2)‖`` with the verdict
``bounded`` (``|growth − 1| ≤ CONVERGED_TOL``), ``unbounded`` (``growth > GROWTH``) or
``undecided``.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from theory.consensus.case import DkfSpec
from theory.consensus.kalman_filter import (
    ConsensusKfRun,
    simulate_consensus_kf,
    true_error_covariance,
)
from theory.core.tolerances import CONVERGED_TOL, GROWTH
from theory.sim.outputs import write_agents_csv, write_runs_npz

__all__ = [
    "CONVERGED_TOL",
    "DEFAULT_STEPS",
    "GROWTH",
    "run_dkf_case",
    "summarize_dkf",
    "write_dkf_data",
]

DEFAULT_STEPS = 400
P0_SCALE = 10.0


def run_dkf_case(
    spec: DkfSpec, rng: np.random.Generator, steps: int = DEFAULT_STEPS
) -> ConsensusKfRun:
    """One run of the consensus Kalman filter of a ``dkf`` case.

    Parameters
    ----------
    spec : DkfSpec
        The case.
    rng : numpy.random.Generator
        Source of the initial state and the noises.
    steps : int
        Horizon ``K``.

    Returns
    -------
    ConsensusKfRun
    """
    n = spec.A.shape[0]
    P0 = P0_SCALE * np.eye(n)
    x0 = rng.multivariate_normal(np.zeros(n), P0)
    return simulate_consensus_kf(
        spec.A, spec.C, spec.W, spec.Q, spec.R, x0=x0, estimate0=np.zeros(n), P0=P0,
        steps=steps, rng=rng, order=spec.order,
    )  # fmt: skip


def summarize_dkf(spec: DkfSpec, runs: Sequence[ConsensusKfRun]) -> dict[str, Any]:
    """Per-agent estimation errors and covariance growth (means over runs), and the exact
    network error covariance under the filter's gains.

    Parameters
    ----------
    spec : DkfSpec
        The case.
    runs : sequence of ConsensusKfRun

    Returns
    -------
    dict
        ``{"agents": [{"id", "final_localization_error", "mean_localization_error",
        "final_cov_norm", "cov_growth", "covariance"}], "true_error_trace", "tolerances"}``.
    """
    errors = np.mean([np.linalg.norm(r.errors, axis=-1) for r in runs], axis=0)
    norms = runs[0].cov_norms  # the Riccati recursion does not depend on the data
    half = norms.shape[0] // 2
    growth = norms[-1] / norms[half]
    agents = []
    for i in range(norms.shape[1]):
        g = float(growth[i])
        verdict = (
            "bounded"
            if abs(g - 1) <= CONVERGED_TOL
            else ("unbounded" if g > GROWTH else "undecided")
        )
        agents.append(
            {
                "id": i + 1,
                "final_localization_error": float(errors[-1, i]),
                "mean_localization_error": float(errors[1:, i].mean()),
                "final_cov_norm": float(norms[-1, i]),
                "cov_growth": g,
                "covariance": verdict,
            }
        )
    traces, _ = true_error_covariance(
        spec.A, spec.C, spec.W, spec.Q, spec.R, P0_SCALE * np.eye(spec.A.shape[0]),
        norms.shape[0] - 1, order=spec.order,
    )  # fmt: skip
    return {
        "agents": agents,
        "true_error_trace": {"half": float(traces[half]), "final": float(traces[-1])},
        "tolerances": {"converged_tol": CONVERGED_TOL, "growth": GROWTH},
        "P0": f"{P0_SCALE:g} I",
    }


def write_dkf_data(
    runs: Sequence[ConsensusKfRun], summary: dict[str, Any], folder: Path
) -> list[Path]:
    """``runs.npz`` (errors and covariances stacked over runs) and ``agents.csv``.

    Parameters
    ----------
    runs : sequence of ConsensusKfRun
    summary : dict
        From :func:`summarize_dkf`.
    folder : pathlib.Path
        Existing output folder.

    Returns
    -------
    list of pathlib.Path
    """
    return [
        write_runs_npz(runs, folder / "runs.npz"),
        write_agents_csv(summary["agents"], folder / "agents.csv"),
    ]
