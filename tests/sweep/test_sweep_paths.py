"""Dotted paths: found in the kind's block or from the top, indices from 0, ``seed`` special."""

from __future__ import annotations

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from theory.core.case_file import resolve_case_path
from theory.core.errors import CaseError
from theory.sweep.grid import apply_values, resolve_target


def data(name: str) -> dict:
    return yaml.safe_load(resolve_case_path(name).read_text(encoding="utf-8"))


PURSUIT = data("pursuit-table1-n3")
DKF = data("ch5-example-1-wb")
PF = data("pf-path3")


def numeric_leaves(node, prefix=()):
    """Every (keys, value) of a number in ``node``."""
    if isinstance(node, dict):
        items = node.items()
    elif isinstance(node, list):
        items = enumerate(node)
    else:
        if isinstance(node, int | float) and not isinstance(node, bool):
            yield prefix, node
        return
    for key, child in items:
        yield from numeric_leaves(child, (*prefix, key))


@pytest.mark.parametrize(
    ("case", "path", "keys"),
    [
        (PURSUIT, "k_gamma", ("pursuit", "k_gamma")),
        (PURSUIT, "pursuit.k_gamma", ("pursuit", "k_gamma")),
        (PURSUIT, "trackers.2.r_x", ("pursuit", "trackers", 2, "r_x")),
        (PURSUIT, "target.velocity.1", ("pursuit", "target", "velocity", 1)),
        (DKF, "W.0.1", ("dkf", "W", 0, 1)),
        (DKF, "A.1.1", ("dkf", "A", 1, 1)),
    ],
)
def test_paths_land_on_the_field(case: dict, path: str, keys: tuple) -> None:
    target = resolve_target(case, case["kind"], path, file="f.yaml")
    assert target.keys == keys and not target.is_seed


def test_seed_is_the_simulation_seed_unless_the_case_has_one() -> None:
    assert resolve_target(PURSUIT, "pursuit", "seed", file="f").is_seed
    if "seed" in PF["pf"]:
        assert resolve_target(PF, "pf", "seed", file="f").keys == ("pf", "seed")


@pytest.mark.parametrize(
    ("path", "missing", "listed"),
    [
        ("k_gama", "k_gama", "k_gamma"),
        ("trackers.7.r_x", "7", "indices 0…2"),
        ("trackers.0.radius", "radius", "r_x"),
        ("nothing.here", "nothing", "k_gamma"),
    ],
)
def test_unknown_path_names_it_and_the_fields_that_exist(path, missing, listed) -> None:
    with pytest.raises(CaseError) as caught:
        resolve_target(PURSUIT, "pursuit", path, file="cases/p.yaml")
    error = caught.value
    assert error.field == f"--param {path}"
    assert missing in str(error.got)
    assert listed in error.hint
    assert error.file == "cases/p.yaml"


@pytest.mark.parametrize("path", ["controller", "trackers", "edges.0", "name"])
def test_non_numeric_fields_are_refused(path: str) -> None:
    with pytest.raises(CaseError, match="numeric"):
        resolve_target(PURSUIT, "pursuit", path, file="f")


@given(st.data())
def test_setting_any_numeric_leaf_changes_only_that_leaf(draw) -> None:
    leaves = list(numeric_leaves(PURSUIT["pursuit"], ("pursuit",)))
    keys, old = draw.draw(st.sampled_from(leaves))
    value = draw.draw(st.floats(-1e3, 1e3, allow_nan=False))
    path = ".".join(str(k) for k in keys)
    target = resolve_target(PURSUIT, "pursuit", path, file="f")
    assert target.keys == keys
    changed = apply_values(PURSUIT, [target], [value])
    node = changed
    for key in keys:
        node = node[key]
    assert node == value
    restored = apply_values(changed, [target], [old])
    assert restored == PURSUIT
    assert PURSUIT == data("pursuit-table1-n3")  # the original is never modified
