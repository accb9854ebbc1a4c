"""The safe YAML reader agrees with ``yaml.safe_load`` on plain data and refuses the rest."""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Iterator

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from theory.core.errors import CaseError
from theory.core.safe_yaml import decode_text, load_yaml

SCALARS = (
    st.none()
    | st.booleans()
    | st.integers(-(10**30), 10**30)
    | st.floats(allow_nan=False)
    | st.text(st.characters(codec="utf-8", exclude_categories=("Cs", "Cc")), max_size=8)
)
KEYS = st.text("abcdefgh_", min_size=1, max_size=6) | st.integers(0, 99)
DATA = st.recursive(
    SCALARS,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(KEYS, inner, max_size=4),
    max_leaves=25,
)


@given(DATA, st.sampled_from([None, True, False]))
def test_agrees_with_safe_load_on_plain_data(data, flow) -> None:
    text = yaml.safe_dump({"root": data}, default_flow_style=flow, allow_unicode=True)
    assert load_yaml(decode_text(text.encode())) == yaml.safe_load(text)


def test_aliases_are_shared_as_safe_load_shares_them() -> None:
    text = "a: &m [[1, 0], [0, 1]]\nb: *m\n"
    data = load_yaml(text)
    assert data == yaml.safe_load(text) and data["a"] is data["b"]


@pytest.mark.parametrize(
    ("text", "field", "says"),
    [
        ("a: 1\nb:\n  c: 2\n  c: 3\n", "b.c", "'c' twice, on lines 3 and 4"),
        ("a: 1\na: 1\n", "a", "on lines 1 and 2"),
        ("x: [{k: 1, k: 2}]\n", "x[1].k", "'k' twice"),
        ("x: !!python/name:os.system ''\n", "x", "tags are not allowed"),
        ("x: !!str 3\n", "x", "tags are not allowed"),
        ("x: !!map {}\n", "x", "tags are not allowed"),
        ("x: &a [*a]\n", "x[1]", "no recursive aliases"),
        ("x: *nope\n", "x", "an alias to an earlier anchor"),
        ("<<: {a: 1}\n", "<top level>", "no merge keys"),
        ("? [1, 2]\n: 3\n", "<top level>", "plain keys"),
        ("a: 1\n---\nb: 2\n", "<yaml>", "a single YAML document"),
        ("a: [1, 2\n", "<yaml>", "line 2"),
    ],
)
def test_refused_naming_the_node(text: str, field: str, says: str) -> None:
    with pytest.raises(CaseError) as info:
        load_yaml(text)
    assert info.value.field == field
    assert says in str(info.value)


@pytest.mark.parametrize(
    ("raw", "says"),
    [
        (b"\xff\xfea\x00:\x00", "UTF-16 byte-order mark"),
        ("a: é".encode("latin-1"), "byte 0xe9 at offset 3"),
        (b"a: 1\nb: \x00\n", "U+0000 on line 2"),
        (b"a: \x1b[31m\n", "U+001B"),
    ],
)
def test_not_utf8_text(raw: bytes, says: str) -> None:
    with pytest.raises(CaseError, match="not UTF-8 text") as info:
        decode_text(raw)
    assert says in str(info.value) and info.value.field == "<file>"


def test_a_utf8_byte_order_mark_is_accepted() -> None:
    assert load_yaml(decode_text(b"\xef\xbb\xbfa: 1\n")) == {"a": 1}


@contextlib.contextmanager
def environment(name: str, value: int) -> Iterator[None]:
    """Set ``name`` (a limit's variable) to ``value`` for the block (hypothesis-safe)."""
    old = os.environ.get(name)
    os.environ[name] = str(value)
    try:
        yield
    finally:
        if old is None:
            del os.environ[name]
        else:
            os.environ[name] = old


@given(st.integers(1, 12), st.integers(1, 12))
def test_depth_limit_is_exact(bound, depth) -> None:
    text = "[" * depth + "]" * depth  # depth levels of sequences
    with environment("TRACKCERT_MAX_YAML_DEPTH", bound):
        if depth <= bound:
            assert load_yaml(text) == yaml.safe_load(text)
        else:
            with pytest.raises(CaseError, match="limit 'yaml_depth'"):
                load_yaml(text)


@given(st.integers(1, 6), st.integers(1, 6))
def test_alias_expansion_is_counted_exactly(fan_out, levels) -> None:
    """``levels`` anchors each aliasing the last ``fan_out`` times: the nodes of the expansion."""
    parts = ["&l0 [1]"] + [
        f"&l{k} [" + ", ".join([f"*l{k - 1}"] * fan_out) + "]" for k in range(1, levels)
    ]
    text = "[" + ", ".join(parts) + "]"
    sizes = [2]  # [1]: one sequence node and one scalar
    for _ in range(1, levels):
        sizes.append(1 + fan_out * sizes[-1])
    expanded = 1 + sum(sizes)
    with environment("TRACKCERT_MAX_YAML_NODES", expanded):
        assert load_yaml(text) == yaml.safe_load(text)
    with environment("TRACKCERT_MAX_YAML_NODES", expanded - 1):
        with pytest.raises(CaseError, match="limit 'yaml_nodes'"):
            load_yaml(text)


def test_special_floats_read_as_yaml_says() -> None:
    data = load_yaml("a: [.inf, -.inf, .nan, 1.0e+400, 1e400]\n")
    assert data["a"][:2] == [math.inf, -math.inf] and math.isnan(data["a"][2])
    assert data["a"][3] == math.inf and data["a"][4] == "1e400"  # YAML 1.1: no dot, a string
