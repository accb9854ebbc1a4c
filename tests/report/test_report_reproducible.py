"""Reproducibility of the real report: every registered claim, twice, byte-identical JSON — once
serially in this process with its BLAS allowed two threads (the default of a two-core machine),
once on two workers.

This is the test that catches a check drawing randomness without the seed the report passes,
writing a figure with a timestamp, or a result depending on the worker count (a BLAS summing in
another order on more threads: every task is pinned to one, theory.core.parallel). To bound its
time it runs the model claims and every claim on the first bundled case of each kind (all
registered claims run at least once when each kind has a bundled case); the whole bundled report
is compared in ``test_report_whole.py``.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from threadpoolctl import threadpool_limits

from theory.core.case_file import bundled_cases, load_case
from theory.core.parallel import engine
from theory.report.render import write_report
from theory.report.runner import run_claims


def _one_case_per_kind():
    cases = {}
    for path in bundled_cases().values():
        case = load_case(path)
        cases.setdefault(case.kind, case)
    return list(cases.values())


@pytest.mark.slow
def test_real_report_json_is_identical_for_the_same_seed_and_any_workers(tmp_path: Path) -> None:
    cases = _one_case_per_kind()
    texts = []
    for workers in (1, 2):
        out = tmp_path / f"workers-{workers}"
        with threadpool_limits(limits=2), engine(workers) as runner:
            write_report(run_claims(cases, seed=11, runner=runner), out)
        texts.append((out / "report.json").read_bytes())
        assert (out / "index.html").stat().st_size > 0
    assert texts[0] == texts[1]
    _tolerances_come_from_the_table(json.loads(texts[0]), cases)


def _tolerances_come_from_the_table(document: dict, cases: list) -> None:
    """Every tolerance a result echoes is named in the table, with the table's default unless a
    case overrides it (theory.core.tolerances)."""
    table = {row["name"]: row["default"] for row in document["environment"]["tolerance_table"]}
    overridden = {name for case in cases for name in case.tolerances}
    for name, values in document["environment"]["tolerances"].items():
        assert name in table, f"{name} is echoed but not in the tolerance table"
        if name not in overridden:
            assert values == [table[name]], (name, values)
