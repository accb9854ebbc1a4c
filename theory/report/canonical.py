"""Canonical JSON: one byte-for-byte form for the same data (the report's reproducibility).

Evidence returned by claims mixes numpy arrays, sympy expressions, rationals and plain Python.
:func:`canonical` turns it into plain JSON types (:func:`theory.core.jsonable.plain`, the one
conversion the commands use too) with floats rounded to :data:`FLOAT_DIGITS` significant digits,
and :func:`dumps` writes it with sorted keys and fixed indentation, so the same inputs give the
same bytes.
"""

from __future__ import annotations

import json
from typing import Any

from theory.core.jsonable import plain

__all__ = ["FLOAT_DIGITS", "canonical", "dumps", "layout"]

FLOAT_DIGITS = 12
"""Significant digits kept for floats in the report (exact values travel as rational strings)."""


def canonical(value: Any, where: str = "$") -> Any:
    """Plain JSON data equal in content to ``value``, floats rounded to :data:`FLOAT_DIGITS`.

    Parameters
    ----------
    value : object
        Anything :func:`theory.core.jsonable.plain` accepts.
    where : str
        Location of ``value`` in the enclosing data, used in error messages.

    Returns
    -------
    object
        :func:`theory.core.jsonable.plain` with ``digits=FLOAT_DIGITS``.

    Raises
    ------
    TypeError
        If some part of ``value`` has no faithful JSON form (the message names where).
    """
    return plain(value, digits=FLOAT_DIGITS, where=where)


def dumps(value: Any, *, width: int = 100) -> str:
    """The canonical text of ``value``: JSON with sorted keys, UTF-8, newline at the end.

    Parameters
    ----------
    value : object
        Anything :func:`canonical` accepts.
    width : int
        A list or mapping whose one-line form fits in ``width`` characters stays on one line (so
        a matrix prints one row a line); larger ones are expanded with a 2-space indent.

    Returns
    -------
    str

    Raises
    ------
    TypeError
        As :func:`canonical`.
    """
    return layout(canonical(value), width=width) + "\n"


def layout(data: Any, *, width: int = 100, indent: int = 0) -> str:
    """Deterministic JSON text of plain ``data``.

    Parameters
    ----------
    data : object
        Plain JSON data (as returned by :func:`canonical`).
    width : int
        Line width under which a container stays on one line.
    indent : int
        Indentation of the line ``data`` starts on.

    Returns
    -------
    str
    """
    flat = json.dumps(data, sort_keys=True, ensure_ascii=False)
    if not isinstance(data, dict | list) or not data or indent + len(flat) <= width:
        return flat
    pad = " " * (indent + 2)
    if isinstance(data, dict):
        items = [
            f"{pad}{json.dumps(k, ensure_ascii=False)}: "
            + layout(data[k], width=width, indent=indent + 2).lstrip()
            for k in sorted(data)
        ]
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    items = [pad + layout(v, width=width, indent=indent + 2).lstrip() for v in data]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"
