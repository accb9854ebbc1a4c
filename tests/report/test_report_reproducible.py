"""Reproducibility of the real report: the whole bundled report — every registered claim on every
bundled case — twice, byte-identical: once serially in this process with its BLAS allowed two
threads (the default of a two-core machine), once on two workers.

This is the test that catches a check drawing randomness without the seed the report passes,
writing a figure with a timestamp, or a result depending on the worker count (a BLAS summing in
another order on more threads: every task is pinned to one, theory.core.parallel). Slow: the two
reports take about 160 s and 200 s on a loaded two-core machine (100 s and 60 s of CPU);
``test_report_parallel.py`` makes the same comparison on a subset in the default run.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from threadpoolctl import threadpool_limits

from theory.core.case_file import bundled_cases
from theory.core.parallel import engine
from theory.kinds import load_case
from theory.report.render import write_report
from theory.report.runner import run_claims
from theory.report.tasks import worker_modules


@pytest.mark.slow
def test_the_whole_report_is_identical_for_the_same_seed_and_any_workers(tmp_path: Path) -> None:
    cases = [load_case(path) for path in bundled_cases().values()]
    texts = []
    for workers in (1, 2):
        out = tmp_path / f"workers-{workers}"
        with threadpool_limits(limits=2), engine(workers, preload=worker_modules()) as runner:
            run = run_claims(cases, seed=11, runner=runner)
        assert run.all_expectations_met
        write_report(run, out)
        texts.append([(out / name).read_bytes() for name in ("report.json", "report.md")])
        assert (out / "index.html").stat().st_size > 0
    assert texts[0] == texts[1]
    _tolerances_come_from_the_table(json.loads(texts[0][0]), cases)


def _tolerances_come_from_the_table(document: dict, cases: list) -> None:
    """Every tolerance a result echoes is named in the table, with the table's default unless a
    case overrides it (theory.core.tolerances)."""
    table = {row["name"]: row["default"] for row in document["environment"]["tolerance_table"]}
    overridden = {name for case in cases for name in case.tolerances}
    for name, values in document["environment"]["tolerances"].items():
        assert name in table, f"{name} is echoed but not in the tolerance table"
        if name not in overridden:
            assert values == [table[name]], (name, values)
