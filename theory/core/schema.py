"""The case-file schema as data: each kind's fields (meaning, unit, default), published as a
Markdown reference page and as JSON Schema.

A kind's :class:`KindSchema` is built on the loader's own key tuples (``FIELDS``,
``EXPECT_KEYS``, ``TOLERANCE_KEYS`` of the kind's ``case`` module, :data:`HEADER_FIELDS`):
:func:`block` refuses, at import, documentation that names a key the loader does not accept or
leaves one out, so the published schema and the loader cannot drift apart. Tolerances take their
meaning, unit and default from :data:`theory.core.tolerances.TOLERANCES`. The JSON Schema checks
shapes and types (what an editor can check while a case is written); the loader checks the rest
(sizes that must agree, positive definiteness, row sums) and remains the judge.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from theory.core.case_file import HEADER_FIELDS
from theory.core.tolerances import TOLERANCES

__all__ = [
    "BOOL",
    "DRAFT",
    "INT",
    "MATRIX",
    "NUMBER",
    "POSITIVE",
    "VECTOR",
    "Field",
    "KindSchema",
    "block",
    "choice",
    "json_schema",
    "json_text",
    "list_of",
    "mapping_of",
    "markdown",
    "nullable",
    "one_of",
    "reference_files",
    "tolerance_fields",
]

DRAFT = "https://json-schema.org/draft/2020-12/schema"
NUMBER: dict[str, Any] = {"type": "number"}
POSITIVE: dict[str, Any] = {"type": "number", "exclusiveMinimum": 0}
INT: dict[str, Any] = {"type": "integer"}
BOOL: dict[str, Any] = {"type": "boolean"}
VECTOR: dict[str, Any] = {"type": "array", "items": NUMBER}
MATRIX: dict[str, Any] = {"type": "array", "items": VECTOR}


def list_of(item: Mapping[str, Any]) -> dict[str, Any]:
    """A JSON Schema list of ``item``."""
    return {"type": "array", "items": dict(item)}


def one_of(*alternatives: Mapping[str, Any]) -> dict[str, Any]:
    """A JSON Schema value matching any of ``alternatives``."""
    return {"anyOf": [dict(a) for a in alternatives]}


def choice(values: Sequence[str]) -> dict[str, Any]:
    """A JSON Schema string among ``values`` (a StrEnum's values, in its order)."""
    return {"type": "string", "enum": [str(v) for v in values]}


def nullable(value: Mapping[str, Any]) -> dict[str, Any]:
    """``value`` or ``null``."""
    return one_of(value, {"type": "null"})


@dataclass(frozen=True)
class Field:
    """One key of a case file: its JSON Schema ``value``, ``meaning``, ``unit``, ``default``
    (the text shown; ``None`` when the key is ``required``) and, for a nested block, its
    ``fields`` (``many``: a list of such mappings)."""

    name: str
    value: Mapping[str, Any]
    meaning: str
    unit: str = ""
    default: str | None = None
    required: bool = False
    fields: tuple[Field, ...] = ()
    many: bool = False

    def schema(self) -> dict[str, Any]:
        """The JSON Schema of this key's value (a mapping of ``fields``, or with ``many`` a list
        of them, ``value`` adding constraints), with its meaning as ``description``."""
        if not self.fields:
            return {**self.value, "description": self.meaning}
        if self.many:
            items = _object(self.fields)
            return {"type": "array", "items": items, **self.value, "description": self.meaning}
        return {**_object(self.fields), **self.value, "description": self.meaning}


@dataclass(frozen=True)
class KindSchema:
    """A case kind's schema: its block's ``fields``, its ``expect`` keys, its ``tolerances``,
    the paper it follows (``source``) and a one-paragraph ``summary``."""

    kind: str
    summary: str
    source: str
    fields: tuple[Field, ...]
    expect: tuple[Field, ...]
    tolerances: tuple[Field, ...] = field(default=())


def block(loader_keys: Sequence[str], *fields: Field, where: str) -> tuple[Field, ...]:
    """``fields`` in the loader's order, refused (ValueError) unless they name exactly the
    ``loader_keys`` that the loader's ``check_keys`` accepts at ``where``."""
    names = [f.name for f in fields]
    missing = [k for k in loader_keys if k not in names]
    extra = [n for n in names if n not in loader_keys]
    if missing or extra or len(set(names)) != len(names):
        raise ValueError(f"schema of {where}: undocumented {missing}, unknown {extra}")
    by_name = {f.name: f for f in fields}
    return tuple(by_name[k] for k in loader_keys)


def tolerance_fields(
    loader_keys: Sequence[str], *local: Field, where: str = "tolerances"
) -> tuple[Field, ...]:
    """The ``tolerances`` keys a kind accepts, documented from the tolerance table (``local``:
    keys that are not named tolerances, such as tdoa-sim's ``error_bound``)."""
    named = [
        Field(
            k,
            {"type": "number", "exclusiveMinimum": 0},
            TOLERANCES[k].meaning,
            TOLERANCES[k].unit,
            _number(TOLERANCES[k].default),
        )
        for k in loader_keys
        if k in TOLERANCES
    ]
    return block(loader_keys, *named, *local, where=where)


def mapping_of(*fields: Field) -> dict[str, Any]:
    """The closed JSON Schema object of ``fields``, for a value that may also take another form
    (e.g. a name or a mapping)."""
    return _object(fields)


def _number(value: float) -> str:
    return f"{value:g}"


def _object(fields: Sequence[Field]) -> dict[str, Any]:
    """A closed JSON Schema object of ``fields`` (unknown keys refused, as the loader does)."""
    schema: dict[str, Any] = {
        "type": "object",
        "properties": {f.name: f.schema() for f in fields},
        "additionalProperties": False,
    }
    required = [f.name for f in fields if f.required]
    if required:
        schema["required"] = required
    return schema


def header(kind: KindSchema) -> tuple[Field, ...]:
    """The shared header of a case file (:data:`theory.core.case_file.HEADER_FIELDS`) and the
    kind's block."""
    text = {"type": "string"}
    return (
        *block(
            HEADER_FIELDS,
            Field("name", {"type": "string", "minLength": 1}, "the case's name", required=True),
            Field(
                "source", text, "where the case comes from (paper, section, figure)", default='""'
            ),
            Field("kind", {"const": kind.kind}, f"the case kind: `{kind.kind}`", required=True),
            Field("description", text, "free text shown with the case", default='""'),
            Field("expect", {}, "expected verdicts (below)", default="{}", fields=kind.expect),
            Field(
                "tolerances",
                {},
                "tolerance overrides (below)",
                default="{}",
                fields=kind.tolerances,
            ),
            where="the case header",
        ),
        Field(kind.kind, {}, f"the `{kind.kind}` block (below)", required=True, fields=kind.fields),
    )


def json_schema(kind: KindSchema) -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of a case file of ``kind``."""
    return {
        "$schema": DRAFT,
        "$id": f"https://trackcert.invalid/schema/{kind.kind}.json",
        "title": f"trackcert case file, kind {kind.kind}",
        "description": kind.summary,
        **_object(header(kind)),
    }


def json_text(kind: KindSchema) -> str:
    """:func:`json_schema` as the text written to ``docs/schema/<kind>.json``."""
    return json.dumps(json_schema(kind), indent=2, ensure_ascii=False) + "\n"


# ---------------------------------------------------------------------------------- Markdown
def markdown(kind: KindSchema) -> str:
    """The reference page ``docs/cases/<kind>.md`` (generated; do not edit by hand)."""
    lines = [
        f"# Case files of kind `{kind.kind}`",
        "",
        "<!-- generated by `trackcert schema "
        f"{kind.kind} --write-docs docs`; edit theory/case_schemas.py instead -->",
        "",
        kind.summary,
        "",
        f"Paper: {kind.source}. JSON Schema: `docs/schema/{kind.kind}.json` "
        f"(`trackcert schema {kind.kind}` prints it), for editors that check YAML against a "
        "schema. The loader checks more than the schema can say (sizes that must agree, "
        "positive definiteness, row sums) and names the field of any refusal.",
        "",
        "## Header",
        "",
        *_table(header(kind)[:-1], "", nested=False),
        f"## The `{kind.kind}` block",
        "",
        *_table(kind.fields, kind.kind),
        "## `expect`",
        "",
        *_table(kind.expect, "expect", absent="not checked"),
        "## `tolerances`",
        "",
        *(_table(kind.tolerances, "tolerances") if kind.tolerances else ["None.", ""]),
    ]
    return "\n".join(lines).rstrip("\n") + "\n"


def _table(
    fields: Sequence[Field], prefix: str, *, nested: bool = True, absent: str = "—"
) -> list[str]:
    """A reference table; ``absent`` is shown for an optional key without a default."""
    rows = ["| field | type | meaning | unit | default |", "|---|---|---|---|---|"]
    rows += [_row(f, absent) for f in _flatten(fields, prefix, nested)]
    return [*rows, ""]


def _flatten(fields: Sequence[Field], prefix: str, nested: bool) -> list[tuple[str, Field]]:
    out: list[tuple[str, Field]] = []
    for f in fields:
        path = f"{prefix}.{f.name}" if prefix else f.name
        out.append((path, f))
        if nested and f.fields:
            out += _flatten(f.fields, path + "[]" if f.many else path, nested)
    return out


def _row(entry: tuple[str, Field], absent: str) -> str:
    path, f = entry
    default = "required" if f.required else (f.default if f.default is not None else absent)
    cells = (f"`{path}`", _type(f), f.meaning, f.unit or "—", default)
    return "| " + " | ".join(_cell(c) for c in cells) + " |"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _type(f: Field) -> str:
    """A short reading of a field's JSON Schema: ``number > 0``, ``list of list of number``…"""
    if f.fields:
        return "list of mappings" if f.many else "mapping"
    return _reading(f.value)


def _reading(value: Mapping[str, Any]) -> str:
    if "anyOf" in value:
        return " or ".join(_reading(v) for v in value["anyOf"])
    if "enum" in value:
        return " or ".join(f"`{v}`" for v in value["enum"])
    if "const" in value:
        return f"`{value['const']}`"
    kind = value.get("type")
    if kind == "array" and "prefixItems" in value:
        return "[" + ", ".join(_reading(v) for v in value["prefixItems"]) + "]"
    if kind == "array":
        return "list of " + _reading(value.get("items", {}))
    if kind == "object":
        return "mapping"
    if kind == "number" and "exclusiveMinimum" in value:
        return f"number > {value['exclusiveMinimum']}"
    if kind == "integer" and "minimum" in value:
        return f"integer ≥ {value['minimum']}"
    return str(kind or "any")


def reference_files(kind: KindSchema) -> dict[str, str]:
    """The generated documentation of ``kind``: relative path → text (``cases/<kind>.md``,
    ``schema/<kind>.json``), as ``trackcert schema --write-docs`` writes it under ``docs/``."""
    return {f"cases/{kind.kind}.md": markdown(kind), f"schema/{kind.kind}.json": json_text(kind)}
