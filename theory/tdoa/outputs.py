"""Data files of TDOA closed-loop runs (``trackcert simulate -o`` on ``kind: tdoa-sim``).

``runs.npz`` (every array of :class:`~theory.tdoa.scenario.TdoaRun`, stacked over runs),
``agents.csv`` (the per-agent summary) and ``timeseries.csv`` (mean error and covariance norm per
agent and ping), written with the generic writers of :mod:`theory.sim.outputs`.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from theory.sim.outputs import write_agents_csv, write_runs_npz, write_timeseries_csv
from theory.tdoa.scenario import TdoaRun

__all__ = ["write_data"]


def write_data(runs: Sequence[TdoaRun], summary: dict[str, Any], folder: Path) -> list[Path]:
    """Write ``runs.npz`` (every array, stacked over runs), ``agents.csv`` and ``timeseries.csv``.

    Parameters
    ----------
    runs : sequence of TdoaRun
        The runs.
    summary : dict
        The summary from :func:`theory.tdoa.metrics.summarize_runs`.
    folder : pathlib.Path
        Output folder (must exist).

    Returns
    -------
    list of pathlib.Path
    """
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
