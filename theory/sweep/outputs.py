"""``sweep.csv``, ``sweep.json`` and ``sweep.png``, written all or nothing.

The files go into a staging folder that replaces the output folder whole
(:func:`theory.core.atomic_output.replaced_folder`), so an error while writing (a full disk, a
figure that fails) or a signal leaves the folder as it was. ``sweep.csv`` is tidy — one row per
point, the columns of :meth:`theory.sweep.run.Sweep.columns`, floats written with ``repr``
(round-trip exact), missing values empty, the tolerances as ``name=value`` pairs separated by
``;``.

``sweep.png`` shows where the analysis verdict and the simulation part: its x-axis is the first
``--param`` (logarithmic for a ``log`` spec), every combination of the other parameters is one
series, and its panels are (1) the verdict, one strip per series, each point coloured by status,
crossed when its simulation disagrees and circled when the comparison is inconclusive (with two
parameters, a heat map); (2) the verdict's margin; (3) the worst agent's simulated final error
(:data:`ERROR_COLUMNS`), one line per series, or the median and min–max band of more than
:data:`MAX_LINES` series. A y-axis is logarithmic when its values span more than a decade.
"""

from __future__ import annotations

import csv
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from theory.core.atomic_output import replaced_folder
from theory.sim.outputs import save_figure
from theory.sweep.points import Agreement, PointStatus

__all__ = [
    "AGREEMENT_MARKERS",
    "ERROR_COLUMNS",
    "FILES",
    "MARKER",
    "MAX_LINES",
    "STATUS_COLOURS",
    "csv_cell",
    "error_column",
    "write_sweep",
    "write_sweep_csv",
    "write_sweep_figure",
]

FILES = ("sweep.csv", "sweep.json", "sweep.png")

MARKER = "sweep.json"
"""The file every sweep folder has: a folder without it is not replaced (unless empty)."""

ERROR_COLUMNS = ("sim_final_pursuit_error", "sim_final_localization_error")
"""The simulated error drawn, the first one present."""

MAX_LINES = 12
"""More series than this are drawn as a median line and a min–max band."""

STATUS_COLOURS = {
    PointStatus.VERIFIED: "tab:green",
    PointStatus.REFUTED: "tab:red",
    PointStatus.INCONCLUSIVE: "tab:orange",
    PointStatus.INVALID: "tab:gray",
}

AGREEMENT_MARKERS = {Agreement.DISAGREE: "x", Agreement.INCONCLUSIVE: "o"}
"""How a point's agreement is marked on its verdict square (``agree`` and ``n/a`` unmarked)."""

AGREEMENT_LABELS = {
    Agreement.DISAGREE: "simulation disagrees",
    Agreement.INCONCLUSIVE: "comparison inconclusive",
}
MARKER_STYLE = {
    Agreement.DISAGREE: {"c": "black"},
    Agreement.INCONCLUSIVE: {"facecolors": "none", "edgecolors": "black"},
}


def write_sweep(sweep: Any, folder: Path, *, figure: bool = True) -> list[Path]:
    """Write ``sweep.csv``, ``sweep.json`` and (``figure``) ``sweep.png`` as the folder ``folder``
    (created, or replaced whole if it is an earlier sweep's or empty); the files in
    :data:`FILES` order.

    Raises :class:`CaseError` if ``folder`` holds files but no ``sweep.json``,
    :class:`OutputError` if writing fails (the folder is left as it was).
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


def csv_cell(value: Any) -> str:
    """One CSV cell: ``repr`` of a float, empty for ``None``, ``a=1;b=2`` for a mapping."""
    if value is None:
        return ""
    if isinstance(value, dict):
        return ";".join(f"{k}={csv_cell(v)}" for k, v in value.items())
    if isinstance(value, float):
        return repr(value)
    return str(value)


def write_sweep_csv(sweep: Any, path: Path) -> Path:
    """Write the tidy table of ``sweep`` (:class:`theory.sweep.run.Sweep`) to ``path``."""
    columns = sweep.columns()
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(columns)
        for record in sweep.records():
            writer.writerow([csv_cell(record[c]) for c in columns])
    return path


def error_column(columns: Sequence[str]) -> str | None:
    """The simulated-error column the figure draws (``None``: no simulation)."""
    chosen = [c for c in ERROR_COLUMNS if c in columns]
    chosen += [c for c in columns if c.startswith("sim_final_")]
    return chosen[0] if chosen else None


def write_sweep_figure(sweep: Any, path: Path) -> Path:
    """Draw ``sweep.png`` of ``sweep`` (:class:`theory.sweep.run.Sweep`) to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    records, columns = sweep.records(), sweep.columns()
    paths = [p.path for p in sweep.params]
    groups, x, error = _series(records, paths), paths[0], error_column(columns)
    panels = 3 if error else 2
    strip = min(2.0, 0.5 + 0.15 * len(groups))
    fig, axes = plt.subplots(
        panels,
        1,
        figsize=(7, 1.5 + strip + 2.2 * (panels - 1)),
        sharex=True,
        gridspec_kw={"height_ratios": [strip] + [2.2] * (panels - 1)},
    )
    _verdict_strip(axes[0], groups, x)
    _lines(axes[1], groups, x, "margin")
    _scale(axes[1], [_number(r["margin"]) for r in records])
    axes[1].set_ylabel("verdict margin")
    if error:
        _lines(axes[2], groups, x, error)
        _scale(axes[2], [_number(r[error]) for r in records])
        axes[2].set_ylabel(error.removeprefix("sim_").replace("_", " ") + " (worst agent)")
    if sweep.params[0].scale == "log":
        axes[-1].set_xscale("log")
    axes[-1].set_xlabel(x)
    axes[0].set_title(f"{sweep.case}: {len(records)} points", fontsize=9, pad=22)
    return save_figure(fig, path)


def _scale(ax: Any, values: list[float]) -> None:
    """A log y-axis when the positive values span more than a decade."""
    finite = [v for v in values if np.isfinite(v) and v > 0]
    if finite and max(finite) > 10 * min(finite):
        ax.set_yscale("log")


def _series(records: list[dict[str, Any]], paths: Sequence[str]) -> dict[str, list[dict]]:
    groups: dict[str, list[dict]] = {}
    for r in records:
        label = ", ".join(f"{p}={r[p]}" for p in paths[1:]) or "all points"
        groups.setdefault(label, []).append(r)
    return groups


def _number(value: Any) -> float:
    return (
        float(value) if isinstance(value, int | float) and not isinstance(value, bool) else np.nan
    )


def _lines(ax: Any, groups: dict[str, list[dict]], x: str, y: str) -> None:
    if len(groups) <= MAX_LINES:
        for label, rows in groups.items():
            ax.plot([r[x] for r in rows], [_number(r[y]) for r in rows], ".-", lw=1, label=label)
        if len(groups) > 1:
            ax.legend(fontsize=6, ncol=2)
        return
    xs = sorted({r[x] for rows in groups.values() for r in rows})
    table = {v: [_number(r[y]) for rows in groups.values() for r in rows if r[x] == v] for v in xs}
    with np.errstate(all="ignore"):
        low, mid, high = (
            np.array([f(table[v]) for v in xs]) for f in (np.nanmin, np.nanmedian, np.nanmax)
        )
    ax.fill_between(xs, low, high, alpha=0.3, label=f"min–max over {len(groups)} series")
    ax.plot(xs, mid, ".-", lw=1, label="median")
    ax.legend(fontsize=6)


def _verdict_strip(ax: Any, groups: dict[str, list[dict]], x: str) -> None:
    for level, rows in enumerate(groups.values()):
        xs = [r[x] for r in rows]
        colours = [STATUS_COLOURS[r["status"]] for r in rows]
        ax.scatter(xs, [level] * len(rows), c=colours, s=18, marker="s")
        for word, marker in AGREEMENT_MARKERS.items():
            marked = [r[x] for r in rows if r["agreement"] == word]
            ax.scatter(marked, [level] * len(marked), s=42, marker=marker, **MARKER_STYLE[word])
    labels = list(groups)
    ax.set_ylim(-0.6, len(labels) - 0.4)
    ax.set_yticks(range(len(labels)) if len(labels) <= MAX_LINES else [])
    if len(labels) <= MAX_LINES:
        ax.set_yticklabels(labels, fontsize=6)
    for status, colour in STATUS_COLOURS.items():
        ax.scatter([], [], c=colour, marker="s", label=status)
    for word, marker in AGREEMENT_MARKERS.items():
        ax.scatter([], [], marker=marker, label=AGREEMENT_LABELS[word], **MARKER_STYLE[word])
    ax.legend(fontsize=6, ncol=6, loc="lower center", bbox_to_anchor=(0.5, 1.0))
    ax.set_ylabel("verdict")
