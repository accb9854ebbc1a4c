"""``timings.json``: how long each check took, where it ran and how much memory it used.

Wall times differ from run to run, so they are kept out of ``report.json`` (which is byte-for-byte
reproducible) and written beside it. The document::

    {"format": "trackcert-timings/1", "workers": 2, "scheduler": null,
     "wall_seconds": 81.2, "cpu_seconds": 150.3,
     "parent_peak_rss": 412000000, "worker_peak_rss": {"host:1234": 623000000, ...},
     "checks": [{"id", "case", "wall_seconds", "cpu_seconds", "worker", "started_seconds"}, ...]}

``wall_seconds`` is the whole run's (claims only, not writing the report); ``cpu_seconds`` the sum
over checks. ``checks`` keeps the report's check order; :func:`slowest` sorts them.
``started_seconds`` is when a check began, after the run began (``null`` for a lost task): with
``worker`` and ``wall_seconds`` it draws each worker's timeline (on a cluster, as far as the
machines' clocks agree).
"""

from __future__ import annotations

import json
import resource
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from theory.report.tasks import process_name

if TYPE_CHECKING:  # the runner orders its tasks by timings (theory.report.schedule)
    from theory.report.runner import RunResult, Timing

__all__ = ["FORMAT", "slowest", "timings_document", "write_timings"]

FORMAT = "trackcert-timings/1"


def slowest(timings: Sequence[Timing], count: int = 10) -> list[Timing]:
    """The ``count`` checks of longest wall time, slowest first (ties: report order).

    Parameters
    ----------
    timings : sequence of Timing
        From :attr:`RunResult.timings`.
    count : int
        How many.

    Returns
    -------
    list of Timing
    """
    return sorted(timings, key=lambda t: -t.wall_seconds)[:count]


def timings_document(
    run: RunResult, *, wall_seconds: float, workers: int, scheduler: str | None
) -> dict[str, Any]:
    """The ``timings.json`` document of ``run`` (see the module docstring).

    Parameters
    ----------
    run : RunResult
        The finished run.
    wall_seconds : float
        Wall time of the whole run.
    workers : int
        Local workers used (1: serial).
    scheduler : str or None
        The scheduler's address, if one was used.

    Returns
    -------
    dict
    """
    workers_rss: dict[str, int] = {}
    for t in run.timings:
        if t.worker and t.worker != process_name():
            workers_rss[t.worker] = max(workers_rss.get(t.worker, 0), t.peak_rss)
    return {
        "format": FORMAT,
        "workers": workers,
        "scheduler": scheduler,
        "wall_seconds": round(wall_seconds, 3),
        "cpu_seconds": round(sum(t.cpu_seconds for t in run.timings), 3),
        "parent_peak_rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
        "worker_peak_rss": dict(sorted(workers_rss.items())),
        "checks": [
            {
                "id": t.claim,
                "case": t.case,
                "wall_seconds": round(t.wall_seconds, 4),
                "cpu_seconds": round(t.cpu_seconds, 4),
                "worker": t.worker,
                "started_seconds": None if t.started is None else round(t.started, 3),
            }
            for t in run.timings
        ],
    }


def write_timings(document: dict[str, Any], out_dir: Path) -> Path:
    """Write ``document`` as ``out_dir/timings.json``.

    Parameters
    ----------
    document : dict
        From :func:`timings_document`.
    out_dir : Path
        The report folder (it exists).

    Returns
    -------
    Path
        The file written.
    """
    path = Path(out_dir) / "timings.json"
    path.write_text(json.dumps(document, indent=1) + "\n", encoding="utf-8")
    return path
