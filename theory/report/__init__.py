"""``trackcert report``: every registered claim on every case, written as HTML, Markdown, JSON.

:mod:`~theory.report.tasks` is what a worker runs (claims of one case under a CPU-time limit,
their records, their certificates re-checked); :mod:`~theory.report.runner` runs the tasks on the
engine longest first and keeps their timings; :mod:`~theory.report.document` is ``report.json``
as data (results, expectations, errata, environment); :mod:`~theory.report.render` writes the
folder whole. See ``docs/report.md`` for the format.
"""

from theory.report.render import build_report, write_report
from theory.report.runner import RunResult, run_claims

__all__ = ["RunResult", "build_report", "run_claims", "write_report"]
