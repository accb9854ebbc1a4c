"""``trackcert report``: every registered claim on every case, written as HTML, Markdown, JSON.

- :mod:`theory.report.runner` runs the claims as tasks on the engine (:mod:`theory.core.parallel`)
  and never lets one failing check stop the rest; :mod:`theory.report.tasks` is what a worker
  runs (claims of one case, their shared :class:`~theory.core.claims.RunCache`);
  :mod:`theory.report.records` the records they return; :mod:`theory.report.time_limit` the
  per-check limit; :mod:`theory.report.timings` writes ``timings.json``;
- :mod:`theory.core.expectations` compares each case's ``expect`` block with the claims' values;
- :mod:`theory.report.environment` records what a reader needs to reproduce the report;
- :mod:`theory.report.artifacts` copies figures and certificates and re-checks the certificates;
- :mod:`theory.report.errata` reads ``docs/errata.md``; :mod:`theory.report.markup` renders it;
- :mod:`theory.report.document` assembles ``report.json``; :mod:`theory.report.render` writes
  the three files; :mod:`theory.report.canonical` makes the JSON byte-for-byte reproducible.

See ``docs/report.md`` for the format.
"""

from theory.report.render import write_report
from theory.report.runner import RunResult, run_claims

__all__ = ["RunResult", "run_claims", "write_report"]
