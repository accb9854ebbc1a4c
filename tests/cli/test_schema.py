"""``trackcert schema``: the case-file schema published as JSON Schema and reference pages, which
must match the loader (every bundled case accepted, every required field really required, every
unknown key refused by both) and the committed docs."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from theory.case_schemas import SCHEMAS, kind_schema
from theory.cli import app
from theory.core.case_file import bundled_cases, read_case_data
from theory.core.errors import CaseError
from theory.core.schema import Field, block, json_schema, reference_files
from theory.kinds import KINDS, parse_case

DOCS = Path(__file__).resolve().parents[2] / "docs"
runner = CliRunner()
CASES = {name: read_case_data(path) for name, path in bundled_cases().items()}


@pytest.fixture(scope="module")
def validator():
    """A JSON Schema validator of the published schema of a kind (needs ``jsonschema``)."""
    jsonschema = pytest.importorskip("jsonschema", reason="jsonschema validates the schema")

    def make(kind: str):
        schema = json.loads((DOCS / "schema" / f"{kind}.json").read_text(encoding="utf-8"))
        jsonschema.Draft202012Validator.check_schema(schema)
        return jsonschema.Draft202012Validator(schema)

    return make


def test_every_kind_has_a_schema() -> None:
    assert set(SCHEMAS) == set(KINDS)


@pytest.mark.parametrize("kind", sorted(SCHEMAS))
def test_committed_docs_are_the_generated_ones(kind: str) -> None:
    for relative, text in reference_files(kind_schema(kind)).items():
        committed = (DOCS / relative).read_text(encoding="utf-8")
        assert committed == text, (
            f"docs/{relative} is stale: trackcert schema all --write-docs docs"
        )


@pytest.mark.parametrize("name", sorted(CASES))
def test_every_bundled_case_validates(name: str, validator) -> None:
    data = CASES[name]
    errors = [e.message for e in validator(data["kind"]).iter_errors(data)]
    assert errors == []


def _blocks(fields: tuple[Field, ...], path: tuple[str, ...] = ()):
    """Every documented mapping (as a path of keys) with its fields; list items as ``0``."""
    yield path, fields
    for f in fields:
        if f.fields:
            yield from _blocks(f.fields, (*path, f.name, *((0,) if f.many else ())))


def _at(data, path):
    for key in path:
        if isinstance(key, int):
            if not isinstance(data, list) or not data:
                return None
            data = data[key]
        elif not isinstance(data, dict) or key not in data:
            return None
        else:
            data = data[key]
    return data


def _mutations(name: str):
    data = CASES[name]
    schema = kind_schema(data["kind"])
    block_fields = (Field(schema.kind, {}, "", fields=schema.fields),)
    for path, fields in _blocks(block_fields):
        target = _at(data, path)
        if not isinstance(target, dict):
            continue
        yield "unknown", path, "not_a_field"
        yield from (("drop", path, f.name) for f in fields if f.required and f.name in target)


MUTATIONS = [(name, *m) for name in sorted(CASES) for m in _mutations(name)]


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(MUTATIONS))
def test_loader_and_schema_refuse_the_same_mutations(validator, mutation) -> None:
    """An unknown key in any documented block, or a field documented as required dropped: the
    loader refuses the case (exit 2) and so does the published JSON Schema."""
    name, action, path, key = mutation
    data = copy.deepcopy(CASES[name])
    target = _at(data, path)
    if action == "unknown":
        target[key] = 1
    else:
        del target[key]
    with pytest.raises(CaseError):
        parse_case(data, file=name)
    assert not validator(data["kind"]).is_valid(data)


def test_mutations_cover_every_kind() -> None:
    kinds = {CASES[name]["kind"] for name, action, *_ in MUTATIONS if action == "drop"}
    assert kinds == set(KINDS)


def test_documentation_that_drifts_from_the_loader_is_refused() -> None:
    keys = ("A", "B")
    with pytest.raises(ValueError, match="undocumented"):
        block(keys, Field("A", {}, "a"), where="test")
    with pytest.raises(ValueError, match="unknown"):
        block(keys, Field("A", {}, "a"), Field("B", {}, "b"), Field("C", {}, "c"), where="test")


def test_schema_prints_the_json_schema() -> None:
    result = runner.invoke(app, ["schema", "dkf"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout) == json_schema(kind_schema("dkf"))


def test_write_docs_writes_page_and_schema(tmp_path: Path) -> None:
    result = runner.invoke(app, ["schema", "all", "--write-docs", str(tmp_path)])
    assert result.exit_code == 0, result.output
    for kind in SCHEMAS:
        for relative, text in reference_files(kind_schema(kind)).items():
            assert (tmp_path / relative).read_text(encoding="utf-8") == text


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["schema", "tdoa-simulation"], "KIND"),
        (["schema", "all"], "KIND"),
        (["schema", "dkf", "--write-docs", "missing-folder"], "--write-docs"),
    ],
)
def test_bad_requests_exit_2_without_traceback(args, field, tmp_path: Path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, args)
    assert result.exit_code == 2
    assert f"'{field}'" in result.output and "Traceback" not in result.output
    assert not list(tmp_path.iterdir())
