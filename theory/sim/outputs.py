"""Data files of a simulation: NPZ arrays per run and CSV tables (``trackcert simulate -o``).

Generic writers for any simulation's runs (dataclasses of arrays) and summaries; the TDOA,
pursuit and consensus simulations build their files from them (e.g.
:func:`theory.tdoa.estimation.simulation.write_data`).
"""

from __future__ import annotations

import csv
import dataclasses
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["write_agents_csv", "write_runs_npz", "write_timeseries_csv"]


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
