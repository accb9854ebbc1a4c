"""``trackcert report``: every registered claim on every case, written as HTML, Markdown, JSON.

:mod:`~theory.report.tasks` is what a worker runs (claims of one case under a CPU-time limit,
their records, their certificates re-checked); :mod:`~theory.report.runner` runs the tasks on the
engine longest first and keeps their timings; :mod:`~theory.report.document` is ``report.json``
as data (results, expectations, errata, design, environment); :mod:`~theory.report.render` writes
the folder whole. The pages read by case and by theorem: :mod:`~theory.report.pages` (case pages,
contents), :mod:`~theory.report.search` (the search over the papers' wording),
:mod:`~theory.report.evidence_table` (evidence as labelled tables), :mod:`~theory.report.glossary`
(the legend, the margin table, units), :mod:`~theory.report.case_figures` (a case's geometry,
graph or eigenvalues) and :mod:`~theory.report.design_section` (the design answers per kind).
See ``docs/report.md`` for the format.
"""

from theory.report.render import build_report, write_report
from theory.report.runner import RunResult, run_claims

__all__ = ["RunResult", "build_report", "run_claims", "write_report"]
