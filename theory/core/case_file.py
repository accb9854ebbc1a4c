"""Case files: the shared header, a kind's block parsed by its :class:`KindSpec`, bundled cases.

A case file is YAML with the header ``name``, ``source``, ``kind``, optional ``description``,
``expect`` and ``tolerances``, and one block named after the kind (``tdoa:``, ``dkf:``…). Each
domain defines its kind as a :class:`KindSpec` in its ``case`` module; :mod:`theory.kinds` lists
them. The YAML is read by :mod:`theory.core.safe_yaml` (sizes, depth, aliases and tags bounded
or refused); parsers raise :class:`~theory.core.errors.CaseError`, attributed here to the file.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from theory.core.errors import CaseError
from theory.core.safe_yaml import decode_text, load_yaml, read_case_bytes
from theory.core.validation import check_keys, one_of, positive_number, require

__all__ = [
    "Case",
    "KindSpec",
    "bundled_case_dir",
    "bundled_cases",
    "load_case",
    "parse_case",
    "read_case_data",
    "resolve_case_path",
]

HEADER_FIELDS = ("name", "source", "kind", "description", "expect", "tolerances")


@dataclass(frozen=True)
class KindSpec:
    """How one case kind is parsed and judged.

    ``parse(block)`` validates the kind's block and returns its spec; ``check_expect(spec,
    expect)`` validates expected values against the spec; ``expect_rules`` maps an expect key to
    its :class:`~theory.core.expectations.Rule` (default ``equal``).
    """

    name: str
    parse: Callable[[Mapping[str, Any]], Any]
    expect_keys: tuple[str, ...]
    tolerance_keys: tuple[str, ...] = ()
    check_expect: Callable[[Any, Mapping[str, Any]], None] | None = None
    expect_rules: Mapping[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        unknown = sorted(set(self.expect_rules) - set(self.expect_keys))
        if unknown:
            raise ValueError(f"kind {self.name!r}: expect_rules name unknown keys {unknown}")

    def parse_case(self, data: object, *, file: str = "<data>") -> Case:
        """A case of this kind from plain data (:func:`parse_case` with this kind only)."""
        return parse_case(data, {self.name: self}, file=file)

    def load_case(self, path: str | Path) -> Case:
        """A case of this kind from a file or a bundled name (:func:`load_case`)."""
        return load_case(path, {self.name: self})


@dataclass(frozen=True, eq=False)
class Case:
    """A validated case: the header fields, the kind's ``spec``, ``expect`` and ``tolerances``.

    ``expect_rules`` are the kind's comparison rules; ``file`` is where it was loaded from
    (``<data>`` for in-memory cases).
    """

    name: str
    source: str
    kind: str
    spec: Any
    expect: dict[str, Any] = field(default_factory=dict)
    tolerances: dict[str, float] = field(default_factory=dict)
    description: str = ""
    file: str = "<data>"
    expect_rules: Mapping[str, str] = field(default_factory=dict)


def parse_case(data: object, kinds: Mapping[str, KindSpec], *, file: str = "<data>") -> Case:
    """Validate a case given as plain data (the parsed YAML) against the known ``kinds``; a
    :class:`CaseError` names ``file``, the field, the expected form and what was found."""
    try:
        return _parse(data, kinds, file)
    except CaseError as error:
        raise error.in_file(file) from None


def read_case_data(path: Path) -> object:
    """The plain data of a case file, read within :mod:`theory.core.safe_yaml`'s bounds."""
    try:
        return load_yaml(decode_text(read_case_bytes(str(path))))
    except CaseError as error:
        raise error.in_file(str(path)) from None


def load_case(path: str | Path, kinds: Mapping[str, KindSpec]) -> Case:
    """Load and validate a case file (``path``) or a bundled case (by name)."""
    resolved = resolve_case_path(path)
    return parse_case(read_case_data(resolved), kinds, file=str(resolved))


def bundled_case_dir() -> Path:
    """The folder of bundled cases (inside the installed package, or ``cases/`` in a checkout)."""
    package = Path(__file__).resolve().parents[1]
    packaged = package / "bundled_cases"
    return packaged if packaged.is_dir() else package.parent / "cases"


def bundled_cases() -> dict[str, Path]:
    """Bundled cases by name (file stem), sorted."""
    folder = bundled_case_dir()
    paths = folder.glob("*.yaml") if folder.is_dir() else []
    return dict(sorted((p.stem, p) for p in paths))


def resolve_case_path(name_or_path: str | Path) -> Path:
    """``name_or_path`` as a path if that file exists, otherwise the bundled case of that name."""
    path = Path(name_or_path)
    if path.is_file():
        return path
    bundled = bundled_cases()
    if str(name_or_path) in bundled:
        return bundled[str(name_or_path)]
    raise CaseError(
        "<case>",
        "a path to a YAML case file or the name of a bundled case",
        str(name_or_path),
        file=str(name_or_path),
        hint="'trackcert cases' lists the bundled cases.",
    )


def _parse(data: object, kinds: Mapping[str, KindSpec], file: str) -> Case:
    if not isinstance(data, Mapping):
        raise CaseError("<top level>", "a mapping with name, kind and a kind block", data)
    kind = one_of(require(data, "kind", ""), sorted(kinds), "kind")
    check_keys(data, (*HEADER_FIELDS, kind), "")
    name = require(data, "name", "")
    if not isinstance(name, str) or not name.strip():
        raise CaseError("name", "a non-empty string", name)
    source = data.get("source", "")
    if not isinstance(source, str):
        raise CaseError("source", "a string citing where the case comes from", source)
    spec_info = kinds[kind]
    spec = spec_info.parse(require(data, kind, ""))
    expect = dict(check_keys(data.get("expect") or {}, spec_info.expect_keys, "expect"))
    if spec_info.check_expect is not None:
        spec_info.check_expect(spec, expect)
    tolerances = {
        key: positive_number(value, f"tolerances.{key}")
        for key, value in check_keys(
            data.get("tolerances") or {}, spec_info.tolerance_keys, "tolerances"
        ).items()
    }
    description = data.get("description", "")
    if not isinstance(description, str):
        raise CaseError("description", "a string", description)
    rules = dict(spec_info.expect_rules)
    return Case(name, source, kind, spec, expect, tolerances, description, file, rules)
