"""Data files of a simulation: NPZ arrays per run and CSV tables (``trackcert simulate -o``).

:func:`write_data` writes the files of a TDOA scenario; the three writers it is built from serve
the ``pursuit`` and ``dkf`` simulations too.
"""

from __future__ import annotations

import csv
import dataclasses
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from theory.tdoa.scenario import TdoaRun

__all__ = ["write_agents_csv", "write_data", "write_runs_npz", "write_timeseries_csv"]


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


def write_runs_npz(runs: Sequence[Any], path: Path, **extra: np.ndarray) -> Path:
    """Write every field of the run dataclasses, stacked over runs, to an NPZ file; return ``path``.

    Parameters
    ----------
    runs : sequence of dataclass instances
        Runs of one type.
    path : pathlib.Path
        The file to write.
    **extra : ndarray
        Further arrays to store under their keyword names.
    """
    arrays = {
        f.name: np.stack([getattr(r, f.name) for r in runs]) for f in dataclasses.fields(runs[0])
    }
    np.savez_compressed(path, **arrays, **extra)
    return path


def write_agents_csv(agents: Sequence[Mapping[str, Any]], path: Path) -> Path:
    """Write one CSV row per agent of a summary (columns: the first agent's keys); return ``path``.

    Parameters
    ----------
    agents : sequence of dict
        The summary's ``agents`` list.
    path : pathlib.Path
        The file to write.
    """
    with path.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(agents[0]))
        writer.writeheader()
        writer.writerows(agents)
    return path


def write_timeseries_csv(path: Path, times: np.ndarray, columns: Mapping[str, np.ndarray]) -> Path:
    """Write per-agent time series as CSV (``time``, then ``{name}_{i}``); return ``path``.

    Parameters
    ----------
    path : pathlib.Path
        The file to write.
    times : ndarray, shape (K,)
        Time of each row (written with ``:g``).
    columns : mapping of str to ndarray, shape (K, N)
        One block of columns per name, agent ``i`` (1-based) in column ``i − 1`` (``:.6g``).
    """
    blocks = list(columns.values())
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(
            ["time"]
            + [f"{name}_{i + 1}" for name, block in columns.items() for i in range(block.shape[1])]
        )
        for k, t in enumerate(times):
            writer.writerow([f"{t:g}", *(f"{v:.6g}" for block in blocks for v in block[k])])
    return path
