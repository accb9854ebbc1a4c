"""``kind: dkf`` validation: every invalid block is refused naming the field."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from theory.consensus.case import Order
from theory.core.case_file import bundled_cases
from theory.core.errors import CaseError
from theory.kinds import load_case, parse_case

BASE = {
    "name": "t",
    "source": "test",
    "kind": "dkf",
    "dkf": {
        "A": [[2, 0], [0, 2]],
        "C": [[[1, 0]], [], [[1, 0], [0, 1]]],
        "W": [[0.5, 0.5, 0], [0.2, 0.3, 0.5], [0, 0, 1]],
        "Q": [[1, 0], [0, 1]],
        "R": [[[1]], [], [[1, 0], [0, 1]]],
    },
}
DELETE = object()


def changed(field: str, value: object) -> dict:
    data = copy.deepcopy(BASE)
    if value is DELETE:
        del data["dkf"][field]
    else:
        data["dkf"][field] = value
    return data


BAD = [
    ("A", DELETE, "dkf.A"),
    ("A", [[1, 2, 3], [4, 5, 6]], "dkf.A"),
    ("A", [[1, float("nan")], [0, 1]], "dkf.A[1][2]"),
    ("W", [[0.5, 0.6, 0], [0.2, 0.3, 0.5], [0, 0, 1]], "dkf.W[1]"),
    ("W", [[0.5, 0.5, 0], [0.2, 0.3, 0.5], [0.5, 0.5, 0]], "dkf.W[3][3]"),
    ("W", [[1.5, -0.5, 0], [0.2, 0.3, 0.5], [0, 0, 1]], "dkf.W[1][2]"),
    ("C", [[[1, 0]], [[0, 1]]], "dkf.C"),
    ("C", [[[1, 0, 0]], [], [[1, 0], [0, 1]]], "dkf.C[1]"),
    ("Q", [[1, 0], [0, -1]], "dkf.Q"),
    ("Q", [[1, 2], [0, 1]], "dkf.Q"),
    ("Q", [[1, 0]], "dkf.Q"),
    ("R", [[[0]], [], [[1, 0], [0, 1]]], "dkf.R[1]"),
    ("R", [[[1]], [[1]], [[1, 0], [0, 1]]], "dkf.R[2]"),
    ("R", [[[1]], [], [[1]]], "dkf.R[3]"),
    ("L", [[[1, 0]], [], [[1, 0], [0, 1]]], "dkf.L[1]"),
    ("L", [[[1], [0]], [[1], [0]], [[1, 0], [0, 1]]], "dkf.L[2]"),
    ("order", "filter-first", "dkf.order"),
    ("speed", 1, "dkf.speed"),
]


@pytest.mark.parametrize(("field", "value", "where"), BAD)
def test_bad_fields_are_named(field, value, where):
    with pytest.raises(CaseError) as info:
        parse_case(changed(field, value), file="x.yaml")
    assert info.value.field == where
    assert info.value.file == "x.yaml"


def test_unknown_order_lists_the_two_orders():
    with pytest.raises(CaseError) as info:
        parse_case(changed("order", "consensus-then-filtr"))
    assert info.value.expected == "one of ['consensus-then-filter', 'filter-then-consensus']"
    with pytest.raises(ValueError, match="consensus-then-filtr"):
        Order("consensus-then-filtr")


def test_valid_block_keeps_zero_row_agents_and_directed_weights():
    case = parse_case(
        changed("L", [[[1], [0]], [], [[1, 0], [0, 1]]]) | {"expect": {"s_detectable": True}}
    )
    spec = case.spec
    assert spec.C[1].shape == (0, 2) and spec.R[1].shape == (0, 0) and spec.L[1].shape == (2, 0)
    assert not np.array_equal(spec.W, spec.W.T)
    assert spec.order is Order.CONSENSUS_THEN_FILTER
    reverse = parse_case(changed("order", "filter-then-consensus"))
    assert reverse.spec.order is Order.FILTER_THEN_CONSENSUS


def test_bundled_ch5_cases_load_and_cite_their_source():
    names = [n for n in bundled_cases() if n.startswith("ch5-")]
    assert {"ch5-example-1-wg", "ch5-example-1-wc", "ch5-example-1-wb"} <= set(names)
    assert {"ch5-example-2-wg", "ch5-example-2-wb", "ch5-counterexample"} <= set(names)
    for name in names:
        case = load_case(name)
        assert case.kind == "dkf"
        assert "seed 000" in case.source or "trackcert" in case.source
    assert "[0 1]" in load_case("ch5-example-1-wg").source
