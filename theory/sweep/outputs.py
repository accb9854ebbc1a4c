"""``sweep.csv``, ``sweep.json`` and ``sweep.png``, written all or nothing.

The three files are written into a fresh temporary folder next to the output folder and then
moved into it (``os.replace``), so an error while writing (a full disk, a figure that fails)
leaves the output folder as it was. ``sweep.csv`` is tidy: one row per point, the columns of
:meth:`theory.sweep.run.Sweep.columns`; floats are written with ``repr`` (round-trip exact),
missing values as empty cells, the tolerances as ``name=value`` pairs separated by ``;``.
"""

from __future__ import annotations

import csv
import json
import os
import shutil
import tempfile
from pathlib import Path
from typing import Any

from theory.sweep.figure import write_sweep_figure

__all__ = ["FILES", "csv_cell", "write_sweep", "write_sweep_csv"]

FILES = ("sweep.csv", "sweep.json", "sweep.png")


def csv_cell(value: Any) -> str:
    """One CSV cell: ``repr`` of a float, empty for ``None``, ``a=1;b=2`` for a mapping.

    Parameters
    ----------
    value : object

    Returns
    -------
    str
    """
    if value is None:
        return ""
    if isinstance(value, dict):
        return ";".join(f"{k}={csv_cell(v)}" for k, v in value.items())
    if isinstance(value, float):
        return repr(value)
    return str(value)


def write_sweep_csv(sweep: Any, path: Path) -> Path:
    """Write the tidy table of ``sweep`` to ``path``.

    Parameters
    ----------
    sweep : Sweep
        From :func:`theory.sweep.run.sweep_case`.
    path : pathlib.Path
        The CSV file.

    Returns
    -------
    pathlib.Path
    """
    columns = sweep.columns()
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(columns)
        for record in sweep.records():
            writer.writerow([csv_cell(record[c]) for c in columns])
    return path


def write_sweep(sweep: Any, folder: Path, *, figure: bool = True) -> list[Path]:
    """Write ``sweep.csv``, ``sweep.json`` and (``figure``) ``sweep.png`` into ``folder``.

    Parameters
    ----------
    sweep : Sweep
        From :func:`theory.sweep.run.sweep_case`.
    folder : pathlib.Path
        The output folder (created; other files in it are left alone).
    figure : bool
        Whether to draw ``sweep.png``.

    Returns
    -------
    list of pathlib.Path
        The files written, in :data:`FILES` order.
    """
    folder = Path(folder)
    folder.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{folder.name}-", dir=folder.parent))
    try:
        write_sweep_csv(sweep, staging / FILES[0])
        text = json.dumps(sweep.to_json(), indent=2, ensure_ascii=False) + "\n"
        (staging / FILES[1]).write_text(text, encoding="utf-8")
        if figure:
            write_sweep_figure(sweep, staging / FILES[2])
        folder.mkdir(exist_ok=True)
        written = []
        for name in FILES[: 3 if figure else 2]:
            os.replace(staging / name, folder / name)
            written.append(folder / name)
        return written
    finally:
        shutil.rmtree(staging, ignore_errors=True)
