"""Case-file validation: every invalid input is refused with file, field, expected and got."""

from __future__ import annotations

import copy

import numpy as np
import pytest
import yaml

from theory.core.case_file import bundled_cases
from theory.core.errors import CaseError
from theory.kinds import load_case, parse_case

BASE = {
    "name": "t",
    "source": "test",
    "kind": "tdoa",
    "tdoa": {
        "T": 1.0,
        "target": [17, -5, -15],
        "agents": [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]],
        "edges": [[1, 2], [2, 3], [3, 4]],
        "weights": "metropolis",
    },
}


def with_change(path: str, value: object) -> dict:
    data = copy.deepcopy(BASE)
    *parents, last = path.split(".")
    node = data
    for key in parents:
        node = node[key]
    if value is DELETE:
        del node[last]
    else:
        node[last] = value
    return data


DELETE = object()

BAD = [
    ("kind", "nope", "kind"),
    ("name", DELETE, "name"),
    ("extra", 1, "extra"),
    ("tdoa.agents", DELETE, "tdoa.agents"),
    ("tdoa.speed", 3, "tdoa.speed"),
    ("tdoa.agents", [[0, 0, 0], [1, 1]], "tdoa.agents"),
    ("tdoa.agents", [[0, 0, float("nan")], [1, 1, 1]], "tdoa.agents[1][3]"),
    ("tdoa.agents", [[0, 0, 0], [1, 1, float("inf")]], "tdoa.agents[2][3]"),
    ("tdoa.agents", [[0, 0, 0, 0], [1, 1, 1, 1]], "tdoa.agents"),
    ("tdoa.agents", [[0, 0, 0], [0, 0, 0], [1, 2, 3], [3, 2, 1]], "tdoa.agents[2]"),
    ("tdoa.target", [-7, 3, 5], "tdoa.target"),
    ("tdoa.target", [1, 2], "tdoa.target"),
    ("tdoa.T", -1, "tdoa.T"),
    ("tdoa.T", "fast", "tdoa.T"),
    ("tdoa.dim", 2, "tdoa.dim"),
    ("tdoa.edges", [[1, 5]], "tdoa.edges[1]"),
    ("tdoa.edges", [[2, 2]], "tdoa.edges[1]"),
    ("tdoa.edges", [[0, 1]], "tdoa.edges[1]"),
    ("tdoa.edges", "all", "tdoa.edges"),
    ("tdoa.comm_range", 21, "tdoa.edges"),
    ("tdoa.weights", "equal", "tdoa.weights"),
    (
        "tdoa.weights",
        [[0.5, 0.5, 0, 0], [0.5, 0.5, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
        "tdoa.weights[2][3]",
    ),
    (
        "tdoa.weights",
        [[1.5, -0.5, 0, 0], [0.5, 0, 0.5, 0], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5]],
        "tdoa.weights[1][2]",
    ),
    (
        "tdoa.weights",
        [[0.5, 0.4, 0, 0], [0.5, 0, 0.5, 0], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5]],
        "tdoa.weights[1]",
    ),
    (
        "tdoa.weights",
        [[0.5, 0.5, 0, 0], [0.5, 0, 0.5, 0], [0, 0.5, 0.25, 0.25], [0, 0, 0.5, 0.5]],
        "tdoa.weights[2][2]",
    ),
    (
        "tdoa.weights",
        [[0.5, 0.5, 0, 0], [0.25, 0.25, 0.5, 0], [0, 0.5, 0.25, 0.25], [0.1, 0, 0.4, 0.5]],
        "tdoa.weights[4][1]",
    ),
    ("expect", {"observable": [True], "colour": "red"}, "expect.colour"),
    ("tolerances", {"rank_tol": -1}, "tolerances.rank_tol"),
    ("expect", {"observable": [True, True]}, "expect.observable"),
    ("expect", {"observable": [1, 1, 1, 1]}, "expect.observable"),
    ("expect", {"network_detectable": "yes"}, "expect.network_detectable"),
    ("expect", {"network_rank": -3}, "expect.network_rank"),
    ("expect", {"unobservable_steps": [0, 0, 0, 2]}, "expect.unobservable_steps"),
]


@pytest.mark.parametrize(
    ("path", "value", "field"), BAD, ids=[f"{p}={v!r}"[:40] for p, v, _ in BAD]
)
def test_invalid_case_names_field(path: str, value: object, field: str) -> None:
    with pytest.raises(CaseError) as info:
        parse_case(with_change(path, value), file="bad.yaml")
    assert info.value.field == field
    message = str(info.value)
    assert message.startswith("bad.yaml: field ")
    assert "expected" in message and "got" in message


def test_valid_base_case_parses() -> None:
    case = parse_case(BASE)
    assert case.spec.n_agents == 4 and case.spec.dim == 3 and case.spec.steps == 1
    np.testing.assert_allclose(case.spec.weights[0].sum(axis=1), 1.0)


def test_explicit_weights_define_edges() -> None:
    weights = [[0.5, 0.5, 0, 0], [0.25, 0.5, 0.25, 0], [0, 0.25, 0.5, 0.25], [0, 0, 0.5, 0.5]]
    data = with_change("tdoa.edges", DELETE)
    data["tdoa"]["weights"] = weights
    case = parse_case(data)
    assert case.spec.hears[0].sum() == 6


def test_comm_range_and_trajectory() -> None:
    data = with_change("tdoa.edges", DELETE)
    data["tdoa"]["comm_range"] = 21
    data["tdoa"]["target"] = [[17, -5, -15], [16, -4, -14], [15, -3, -13]]
    case = parse_case(data)
    assert case.spec.steps == 3 and case.spec.hears.shape == (3, 4, 4)
    assert case.spec.comm_range == 21


def test_directed_edges_mean_sender_to_receiver() -> None:
    data = with_change("tdoa.directed", True)
    data["tdoa"]["weights"] = "uniform"
    case = parse_case(data)
    hears = case.spec.hears[0]
    assert hears[1, 0] and not hears[0, 1]


def test_file_errors(tmp_path) -> None:
    missing = tmp_path / "none.yaml"
    with pytest.raises(CaseError, match=r"none\.yaml"):
        load_case(missing)
    broken = tmp_path / "broken.yaml"
    broken.write_text("name: [unclosed\n")
    with pytest.raises(CaseError, match="valid YAML"):
        load_case(broken)
    wrong = tmp_path / "wrong.yaml"
    wrong.write_text(yaml.safe_dump(with_change("tdoa.T", 0)))
    with pytest.raises(CaseError, match=r"wrong\.yaml: field 'tdoa\.T'"):
        load_case(wrong)


def test_every_bundled_case_loads() -> None:
    cases = bundled_cases()
    assert cases, "no bundled cases found"
    for name, path in cases.items():
        case = load_case(path)
        assert case.name == name, f"{path}: name {case.name!r} differs from the file stem"
        assert case.source, f"{path}: a bundled case must cite its source"
