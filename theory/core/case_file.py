"""Case files: loading, the shared header, dispatch to a kind's parser, bundled cases (DESIGN.md).

A case file is YAML with the header ``name``, ``source``, ``kind``, optional ``description``,
``expect`` and ``tolerances``, and one block named after the kind (``tdoa:``, ``dkf:``,
``pursuit:``). Each kind registers a parser with :func:`register_kind` from a module named
``case.py`` or ``*_case.py`` of its domain package (found by :mod:`theory.core.discovery`; loading
a case imports the module of its kind only); parsers raise :class:`~theory.core.errors.CaseError`
and this module attributes the error to the file. The YAML is read by
:mod:`theory.core.safe_yaml` (size, UTF-8, depth, aliases, tags and repeated keys bounded or
refused), and the parsers check the limits of :mod:`theory.core.limits` before allocating.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from theory.core.discovery import kind_index
from theory.core.errors import CaseError
from theory.core.safe_yaml import decode_text, load_yaml, read_case_bytes
from theory.core.validation import check_keys, one_of, positive_number, require

__all__ = [
    "Case",
    "KindSpec",
    "bundled_case_dir",
    "bundled_cases",
    "kind_spec",
    "known_kinds",
    "load_case",
    "parse_case",
    "register_kind",
    "resolve_case_path",
]

HEADER_FIELDS = ("name", "source", "kind", "description", "expect", "tolerances")


@dataclass(frozen=True)
class KindSpec:
    """How one case kind is parsed and observed.

    Attributes
    ----------
    parse : callable
        Validates the kind's block and returns its spec.
    expect_keys, tolerance_keys : tuple of str
        Keys the ``expect`` and ``tolerances`` blocks may use.
    check_expect : callable or None
        ``check_expect(spec, expect)`` validates the expected values against the spec (types,
        one entry per agent, …), raising :class:`~theory.core.errors.CaseError`.
    observe : str or None
        ``"module:function"`` of the kind's observer, ``observe(case) ->``
        :class:`~theory.core.expectations.Observed` (imported on first use, so registering a kind
        stays cheap); ``None`` when the kind's claims observe its keys themselves.
    expect_rules : dict
        Expect key → comparison rule of :data:`theory.core.expectations.RULES` (default
        ``equal``), e.g. ``{"max_final_error": "at_most"}``.
    simulate : str or None
        ``"module:function"`` of the kind's simulator for ``trackcert simulate``,
        ``simulate(case, steps) ->`` :class:`theory.simulate.Simulator`; ``None`` when the kind
        is not simulated that way.
    """

    parse: Callable[[Mapping[str, Any]], Any]
    expect_keys: tuple[str, ...]
    tolerance_keys: tuple[str, ...] = ()
    check_expect: Callable[[Any, Mapping[str, Any]], None] | None = None
    observe: str | None = None
    expect_rules: dict[str, str] = field(default_factory=dict)
    simulate: str | None = None

    def observer(self) -> Callable[[Case], Any] | None:
        """The function :attr:`observe` names, imported (``None`` when there is none).

        Returns
        -------
        callable or None
        """
        return _resolve(self.observe)

    def simulator(self) -> Callable[[Case, int | None], Any] | None:
        """The function :attr:`simulate` names, imported (``None`` when there is none).

        Returns
        -------
        callable or None
        """
        return _resolve(self.simulate)


def _resolve(reference: str | None) -> Any:
    """The object ``"module:name"`` names (imported now), or ``None``."""
    if reference is None:
        return None
    module, _, name = reference.partition(":")
    return getattr(importlib.import_module(module), name)


_KINDS: dict[str, KindSpec] = {}


@dataclass(frozen=True, eq=False)
class Case:
    """A validated case.

    Attributes
    ----------
    name, source, kind, description : str
        Header fields.
    spec : object
        The kind-specific frozen dataclass returned by the kind's parser.
    expect : dict
        Expected verdicts (validated keys; values as written).
    tolerances : dict
        Named tolerances overriding the defaults (e.g. ``rank_tol``).
    file : str
        Where it was loaded from (``<data>`` for in-memory cases).
    """

    name: str
    source: str
    kind: str
    spec: Any
    expect: dict[str, Any] = field(default_factory=dict)
    tolerances: dict[str, float] = field(default_factory=dict)
    description: str = ""
    file: str = "<data>"


def register_kind(
    kind: str,
    parse: Callable[[Mapping[str, Any]], Any],
    *,
    expect_keys: tuple[str, ...],
    tolerance_keys: tuple[str, ...] = (),
    check_expect: Callable[[Any, Mapping[str, Any]], None] | None = None,
    observe: str | None = None,
    expect_rules: Mapping[str, str] | None = None,
    simulate: str | None = None,
) -> None:
    """Register the parser of ``kind`` (called by the kind's module at import time).

    The other arguments are stored, under ``kind``, as a :class:`KindSpec`.

    Parameters
    ----------
    kind : str
        The kind's name, also the name of its block in a case file (e.g. ``tdoa``).
    parse : callable
        ``parse(block)`` validates the kind's block and returns its spec.
    expect_keys : tuple of str
        Keys the case's ``expect`` block may use.
    tolerance_keys : tuple of str
        Keys the case's ``tolerances`` block may use.
    check_expect : callable, optional
        ``check_expect(spec, expect)``, when given, validates the expected values themselves.
    observe : str, optional
        ``"module:function"`` of the kind's observer (:class:`KindSpec`).
    expect_rules : mapping, optional
        Expect key → comparison rule (:data:`theory.core.expectations.RULES`).
    simulate : str, optional
        ``"module:function"`` of the kind's simulator (:class:`KindSpec`).

    Raises
    ------
    ValueError
        If ``observe`` or ``simulate`` is not of the form ``"module:function"``, or a rule names
        an unknown key.
    """
    for reference in (observe, simulate):
        if reference is not None and reference.count(":") != 1:
            raise ValueError(f"{reference!r} is not 'module:function'")
    rules = dict(expect_rules or {})
    if set(rules) - set(expect_keys):
        raise ValueError(f"expect_rules name unknown keys {sorted(set(rules) - set(expect_keys))}")
    _KINDS[kind] = KindSpec(
        parse, tuple(expect_keys), tuple(tolerance_keys), check_expect, observe, rules, simulate
    )


def known_kinds() -> dict[str, KindSpec]:
    """Every case kind, sorted (imports every kind module: :func:`kind_spec` imports one).

    Returns
    -------
    dict
        Kind name → :class:`KindSpec`.
    """
    for module in kind_index().values():
        importlib.import_module(module)
    return dict(sorted(_KINDS.items()))


def kind_spec(kind: str) -> KindSpec:
    """The :class:`KindSpec` of ``kind``, importing only the module that registers it.

    Parameters
    ----------
    kind : str
        A case kind, e.g. ``tdoa``.

    Returns
    -------
    KindSpec

    Raises
    ------
    CaseError
        If no module registers ``kind`` (the message lists the known kinds).
    """
    if kind not in _KINDS and kind in kind_index():
        importlib.import_module(kind_index()[kind])
    if kind not in _KINDS:
        raise CaseError("kind", f"one of {_kind_names()}", kind)
    return _KINDS[kind]


def _kind_names() -> list[str]:
    return sorted(set(kind_index()) | set(_KINDS))


def parse_case(data: object, *, file: str = "<data>") -> Case:
    """Validate a case given as plain data (the parsed YAML).

    Parameters
    ----------
    data : object
        The parsed YAML: a mapping with the header fields and the kind's block.
    file : str
        Where ``data`` came from, named in errors (``<data>`` for in-memory cases).

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        Naming ``file``, the field, the expected form and what was found.
    """
    try:
        return _parse(data, file)
    except CaseError as error:
        raise error.in_file(file) from None


def load_case(path: str | Path) -> Case:
    """Load and validate a case file (``path``) or a bundled case (by name).

    Raises
    ------
    CaseError
        If the file cannot be read, is too large, is not UTF-8 text, is not plain YAML (tags,
        repeated keys, nesting or aliases beyond :mod:`theory.core.limits`), or fails validation
        (:mod:`theory.core.safe_yaml`).
    """
    resolved = resolve_case_path(path)
    try:
        data = load_yaml(decode_text(read_case_bytes(str(resolved))))
    except CaseError as error:
        raise error.in_file(str(resolved)) from None
    return parse_case(data, file=str(resolved))


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


def _parse(data: object, file: str) -> Case:
    if not isinstance(data, Mapping):
        raise CaseError("<top level>", "a mapping with name, kind and a kind block", data)
    kind = one_of(require(data, "kind", ""), _kind_names(), "kind")
    check_keys(data, (*HEADER_FIELDS, kind), "")
    name = require(data, "name", "")
    if not isinstance(name, str) or not name.strip():
        raise CaseError("name", "a non-empty string", name)
    source = data.get("source", "")
    if not isinstance(source, str):
        raise CaseError("source", "a string citing where the case comes from", source)
    spec_info = kind_spec(kind)
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
    return Case(name, source, kind, spec, expect, tolerances, description, file)
