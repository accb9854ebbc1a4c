"""Data files of a simulation: NPZ arrays per run and CSV tables (``trackcert simulate -o``)."""

from __future__ import annotations

import csv
import dataclasses
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from theory.sim.scenario import TdoaRun

__all__ = ["write_data"]


def write_data(runs: Sequence[TdoaRun], summary: dict[str, Any], folder: Path) -> list[Path]:
    """Write ``runs.npz`` (every array, stacked over runs), ``agents.csv`` and ``timeseries.csv``.

    Parameters
    ----------
    runs : sequence of TdoaRun
        The runs.
    summary : dict
        The summary from :func:`theory.sim.metrics.summarize_runs`.
    folder : pathlib.Path
        Output folder (must exist).

    Returns
    -------
    list of pathlib.Path
    """
    arrays = {
        f.name: np.stack([getattr(r, f.name) for r in runs]) for f in dataclasses.fields(TdoaRun)
    }
    arrays["localization_errors"] = np.stack([r.localization_errors for r in runs])
    npz = folder / "runs.npz"
    np.savez_compressed(npz, **arrays)
    agents_csv = folder / "agents.csv"
    columns = list(summary["agents"][0])
    with agents_csv.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns)
        writer.writeheader()
        writer.writerows(summary["agents"])
    series = folder / "timeseries.csv"
    errors = arrays["localization_errors"].mean(axis=0)
    norms = arrays["cov_norms"].mean(axis=0)
    n = errors.shape[1]
    with series.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(
            ["time"]
            + [f"error_{i + 1}" for i in range(n)]
            + [f"cov_norm_{i + 1}" for i in range(n)]
        )
        for t, e, p in zip(runs[0].ping_times, errors, norms, strict=True):
            writer.writerow([f"{t:g}", *(f"{v:.6g}" for v in e), *(f"{v:.6g}" for v in p)])
    return [npz, agents_csv, series]
