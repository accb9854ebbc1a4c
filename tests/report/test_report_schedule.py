"""The report's schedule: tasks longest first by estimated cost, estimates from the previous
run's timings.json over the bundled costs, and a report that does not depend on the order."""

from __future__ import annotations

import functools
import itertools
import json

from hypothesis import given
from hypothesis import strategies as st

from theory.kinds import load_case
from theory.registry import all_claims
from theory.report.runner import (
    BATCH_SECONDS,
    COSTS_FORMAT,
    SMALL_SECONDS,
    TIMINGS_FORMAT,
    UNKNOWN_SECONDS,
    Estimates,
    batches,
    bundled_costs_path,
    costs_document,
    load_estimates,
    longest_first,
    run_claims,
)
from theory.report.tasks import CheckTask, plan_tasks


@functools.cache
def _case(name: str):
    return load_case(name)


def _task(*claims: str, case: str = "-") -> CheckTask:
    return CheckTask(tuple(claims), None if case == "-" else _case(case), 0, None, False)


def test_a_task_costs_the_sum_of_its_checks_and_unknown_checks_are_estimated() -> None:
    estimates = Estimates.of({("a", "-"): 2.0, ("b", "-"): 0.5, ("b", "x"): 1.5})
    assert estimates.task(_task("a", "b")) == 2.5
    assert estimates.check("b", "elsewhere") == 1.0  # the claim's mean over its cases
    assert estimates.check("new", "-") == UNKNOWN_SECONDS


@given(st.lists(st.floats(0, 100, allow_nan=False), min_size=1, max_size=30))
def test_longest_first_is_a_stable_sort_by_decreasing_cost(costs: list[float]) -> None:
    tasks = [(_task(f"claim{i}"),) for i in range(len(costs))]
    estimates = Estimates.of({(f"claim{i}", "-"): c for i, c in enumerate(costs)})
    ordered = longest_first(tasks, estimates)
    assert sorted(ordered, key=lambda b: b[0].claims) == sorted(tasks, key=lambda b: b[0].claims)
    seen = [estimates.task(b[0]) for b in ordered]
    assert seen == sorted(seen, reverse=True)
    for earlier, later in itertools.pairwise(ordered):
        if estimates.task(earlier[0]) == estimates.task(later[0]):  # ties keep the report order
            assert tasks.index(earlier) < tasks.index(later)


CASES = ("fig43-case-a", "fig43-case-b", "fig43-case-c", "fig43-case-d")


@given(
    st.lists(
        st.tuples(st.sampled_from(("c1", "c2", "c3")), st.sampled_from(CASES), st.floats(0, 2)),
        max_size=12,
        unique_by=lambda row: row[:2],
    )
)
def test_batches_hold_every_task_once_and_only_short_tasks_of_one_claim_together(rows) -> None:
    tasks = [_task(claim, case=case) for claim, case, _ in rows]
    estimates = Estimates.of({(claim, case): cost for claim, case, cost in rows})
    scheduled = batches(tasks, estimates)
    position = {(t.claims, t.case_name): i for i, t in enumerate(tasks)}
    placed = [position[(t.claims, t.case_name)] for b in scheduled for t in b]
    assert sorted(placed) == list(range(len(tasks)))  # every task once
    for batch in scheduled:
        if len(batch) > 1:
            assert len({t.claims for t in batch}) == 1
            assert all(estimates.task(t) < SMALL_SECONDS for t in batch)
            assert sum(estimates.task(t) for t in batch) <= BATCH_SECONDS
            order = [position[(t.claims, t.case_name)] for t in batch]
            assert order == sorted(order)
    costs = [sum(estimates.task(t) for t in b) for b in scheduled]
    assert costs == sorted(costs, reverse=True)


def test_the_previous_runs_timings_override_the_bundled_costs(tmp_path) -> None:
    bundled = load_estimates()
    assert bundled.seconds, f"{bundled_costs_path()} holds no costs"
    claim, case = next(iter(bundled.seconds))
    checks = [{"id": claim, "case": case, "cpu_seconds": 123.0, "wall_seconds": 1.0}]
    timings = {"format": TIMINGS_FORMAT, "checks": checks}
    (tmp_path / "timings.json").write_text(json.dumps(timings))
    assert load_estimates(tmp_path).check(claim, case) == 123.0
    assert load_estimates(tmp_path).seconds.keys() == bundled.seconds.keys()


def test_unreadable_or_foreign_timings_are_ignored(tmp_path) -> None:
    bundled = load_estimates()
    for content in (
        "not json",
        json.dumps({"format": "something/1", "checks": []}),
        json.dumps({"format": TIMINGS_FORMAT, "checks": [{"id": 3}, {"cpu_seconds": "x"}]}),
        json.dumps({"format": TIMINGS_FORMAT, "checks": [{"id": "a", "case": "b",
                                                          "cpu_seconds": -1}]}),
    ):  # fmt: skip
        (tmp_path / "timings.json").write_text(content)
        assert load_estimates(tmp_path) == bundled
    (tmp_path / "timings.json").write_bytes(b"\xff\xfe")
    assert load_estimates(tmp_path) == bundled


def test_costs_document_round_trips_through_the_bundled_format(tmp_path, monkeypatch) -> None:
    checks = [
        {"id": "seed000.eq4.20", "case": "-", "cpu_seconds": 0.61},
        {"id": "case.expect.tdoa", "case": "fig43-case-d", "cpu_seconds": 0.02},
    ]
    document = costs_document({"format": TIMINGS_FORMAT, "checks": checks}, "a test")
    assert document["format"] == COSTS_FORMAT and document["source"] == "a test"
    path = tmp_path / "check_costs.json"
    path.write_text(json.dumps(document))
    monkeypatch.setattr("theory.report.runner.bundled_costs_path", lambda: path)
    estimates = load_estimates()
    assert estimates.check("seed000.eq4.20", "-") == 0.61
    assert estimates.check("case.expect.tdoa", "fig43-case-d") == 0.02


def test_the_report_is_the_same_whatever_the_order_of_its_tasks() -> None:
    """Report order, longest first and its reverse give identical records and expectations."""
    claims = [
        c
        for c in all_claims()
        if c.id in ("seed000.thm4.2.3", "seed000.def5.2.4", "seed000.lem5.2.2", "case.expect.tdoa")
    ]
    cases = [load_case("fig43-case-d"), load_case("ch5-example-1-wb")]
    checks = [(c.id, case.name) for case in cases for c in claims if case.kind in c.kinds]
    forward = Estimates.of({(c, case): 1.0 + (case == "fig43-case-d") for c, case in checks})
    backward = Estimates.of({(c, case): 1.0 + (case != "fig43-case-d") for c, case in checks})
    planned = plan_tasks(
        [(c, case) for case in cases for c in claims if case.kind in c.kinds],
        seed=3,
        seconds=None,
        figures=False,
    )
    orders = [batches(planned, e) for e in (forward, backward)]
    assert orders[0][0][0].case_name == orders[1][-1][-1].case_name == "fig43-case-d"
    assert orders[1][0][0].case_name == orders[0][-1][-1].case_name == "ch5-example-1-wb"
    runs = [
        run_claims(cases, seed=3, claims=claims, estimates=e) for e in (None, forward, backward)
    ]
    texts = {json.dumps([r.to_json() for r in run.records], sort_keys=True) for run in runs}
    assert len(texts) == 1
    assert runs[0].expectations == runs[1].expectations == runs[2].expectations


def test_short_tasks_of_one_claim_share_a_batch_up_to_its_limit() -> None:
    tasks = [_task("c1", case=c) for c in CASES] + [_task("c2", case="fig43-case-a")]
    costs = {("c1", c): 0.2 for c in CASES} | {("c2", "fig43-case-a"): 0.2}
    scheduled = batches(tasks, Estimates.of(costs))
    sizes = sorted((len(b), b[0].claims[0]) for b in scheduled)
    # 0.2 s each: the four c1 checks fit in one batch (0.8 s ≤ 1 s); c2 is another claim
    assert sizes == [(1, "c2"), (4, "c1")]
    heavy = batches(tasks, Estimates.of(dict.fromkeys(costs, SMALL_SECONDS)))
    assert all(len(b) == 1 for b in heavy)
