"""Benchmark: what the report's pages by case and theorem cost beside the checks they show.

Run from the repository root: ``python -m benchmarks.bench_report_pages [CASE …]``.

In one process, on the same cases (default: two tdoa cases, a dkf case and a pursuit case), it
measures the CPU seconds of

* ``checks``: every claim of the cases' kinds on the cases (``run_claims``, serially, with the
  certificate checker's subprocesses), the baseline;
* ``design``: the design section (``theory.report.design_section.design_sections``);
* ``figures``: the case figures (``theory.report.case_figures.draw_case``);
* ``pages``: the case pages, contents and search index (``theory.report.render.render_pages``);

and prints each with its ratio to ``checks``. Target: design + figures + pages at most
:data:`TARGET` of the checks' CPU time (the whole bundled report's extras were 13 s of CPU beside
about 100 s of checks when this was written). No assertion: the numbers are the result.
"""

from __future__ import annotations

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import argparse  # noqa: E402  (BLAS threads must be fixed before numpy loads)
import json  # noqa: E402
import resource  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from theory.kinds import load_case  # noqa: E402
from theory.registry import all_claims  # noqa: E402
from theory.report.case_figures import draw_case  # noqa: E402
from theory.report.design_section import design_sections  # noqa: E402
from theory.report.render import render_pages, write_report  # noqa: E402
from theory.report.runner import run_claims  # noqa: E402

CASES = ("fig43-case-d", "topology-distance-rule-21", "ch5-example-1-wg", "pursuit-table1-n3")
TARGET = 0.15
"""Largest acceptable (design + figures + pages) / checks CPU ratio."""


def _clock() -> float:
    """CPU seconds of this process and of the processes it waited for (the certificate
    checker runs as ``python -m proofs_check``)."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def _cpu(work) -> tuple[float, object]:
    start = _clock()
    value = work()
    return _clock() - start, value


def main() -> None:
    """Measure and print the four CPU times and the ratios."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", default=list(CASES))
    args = parser.parse_args()
    cases = [load_case(name) for name in args.cases]
    kinds = {case.kind for case in cases}
    claims = [c for c in all_claims() if set(c.kinds) & kinds]
    checks, run = _cpu(lambda: run_claims(cases, seed=0, claims=claims))
    design, _ = _cpu(lambda: design_sections(cases))
    with tempfile.TemporaryDirectory() as folder:
        figures, _ = _cpu(lambda: [draw_case(c, Path(folder) / c.name) for c in cases])
        document = write_report(run, Path(folder) / "report")
    pages, _ = _cpu(lambda: render_pages(document))
    extras = design + figures + pages
    result = {
        "cases": args.cases,
        "cpu_seconds": {"checks": checks, "design": design, "figures": figures, "pages": pages},
        "ratio_to_checks": {
            "design": design / checks,
            "figures": figures / checks,
            "pages": pages / checks,
            "extras": extras / checks,
        },
        "target_extras_ratio": TARGET,
        "meets_target": extras / checks <= TARGET,
    }
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
