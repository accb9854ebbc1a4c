"""``sweep.csv``, ``sweep.json`` and ``sweep.png``, written all or nothing.

The three files are written into a staging folder next to the output folder, which then replaces
it whole (:func:`theory.core.atomic_output.replaced_folder`), so an error while writing (a full
disk, a figure that fails) or a signal leaves the output folder as it was. ``sweep.csv`` is
tidy: one row per point, the columns of :meth:`theory.sweep.run.Sweep.columns`; floats are
written with ``repr`` (round-trip exact), missing values as empty cells, the tolerances as
``name=value`` pairs separated by ``;``.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

from theory.core.atomic_output import replaced_folder
from theory.sweep.figure import write_sweep_figure

__all__ = ["FILES", "MARKER", "csv_cell", "write_sweep", "write_sweep_csv"]

FILES = ("sweep.csv", "sweep.json", "sweep.png")

MARKER = "sweep.json"
"""The file every sweep folder has: a folder without it is not replaced (unless empty)."""


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
    """Write ``sweep.csv``, ``sweep.json`` and (``figure``) ``sweep.png`` as the folder ``folder``.

    Parameters
    ----------
    sweep : Sweep
        From :func:`theory.sweep.run.sweep_case`.
    folder : pathlib.Path
        The output folder: created, or replaced whole if it is an earlier sweep's (or empty).
    figure : bool
        Whether to draw ``sweep.png``.

    Returns
    -------
    list of pathlib.Path
        The files written, in :data:`FILES` order.

    Raises
    ------
    CaseError
        If ``folder`` holds files but no ``sweep.json``.
    OutputError
        If writing fails (the folder is left as it was).
    """
    folder = Path(folder)
    names = FILES[: 3 if figure else 2]
    with replaced_folder(folder, MARKER) as staging:
        write_sweep_csv(sweep, staging / FILES[0])
        text = json.dumps(sweep.to_json(), indent=2, ensure_ascii=False) + "\n"
        (staging / FILES[1]).write_text(text, encoding="utf-8")
        if figure:
            write_sweep_figure(sweep, staging / FILES[2])
    return [folder / name for name in names]
