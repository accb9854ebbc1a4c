"""Canonical JSON: one byte-for-byte form for the same data (the report's reproducibility).

Evidence returned by claims mixes numpy arrays, sympy expressions, rationals and plain Python.
:func:`canonical` turns it into plain JSON types with one rule per type, and :func:`dumps` writes
it with sorted keys, fixed indentation and floats rounded to :data:`FLOAT_DIGITS` significant
digits, so the same inputs give the same bytes. Values with no faithful plain form are refused
(:class:`TypeError` naming where in the data they sit) instead of being written as a
``repr`` that could carry a memory address.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping
from fractions import Fraction
from pathlib import PurePath
from typing import Any

import numpy as np
import sympy as sp

__all__ = ["FLOAT_DIGITS", "canonical", "dumps", "layout"]

FLOAT_DIGITS = 12
"""Significant digits kept for floats in the report (exact values travel as rational strings)."""


def canonical(value: Any, where: str = "$") -> Any:
    """Plain JSON data (dict, list, str, int, float, bool, None) equal in content to ``value``.

    Parameters
    ----------
    value : object
        Numbers (Python, numpy, ``Fraction``, python-flint, sympy), arrays, sympy matrices and
        expressions, mappings, sequences, sets, dataclasses, paths.
    where : str
        Location of ``value`` in the enclosing data, used in error messages.

    Returns
    -------
    object
        Floats rounded to :data:`FLOAT_DIGITS` significant digits; non-finite floats as the
        strings ``"nan"``, ``"inf"``, ``"-inf"``; rationals as ``"p/q"`` strings; complex numbers
        as ``{"re", "im"}``; sympy objects as their ``str``; sets sorted.

    Raises
    ------
    TypeError
        If some part of ``value`` has no faithful JSON form (the message names where).
    """
    if value is None or isinstance(value, bool | str):
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        return _float(float(value))
    if isinstance(value, complex | np.complexfloating):
        return {"im": _float(float(value.imag)), "re": _float(float(value.real))}
    if isinstance(value, Fraction):
        return str(value)
    if isinstance(value, PurePath):
        return value.as_posix()
    if isinstance(value, sp.MatrixBase):
        return [[str(entry) for entry in row] for row in value.tolist()]
    if isinstance(value, sp.Basic):
        return str(value)
    if type(value).__module__.startswith("flint"):
        return _flint(value, where)
    if isinstance(value, np.ndarray):
        return canonical(value.tolist(), where)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return canonical(dataclasses.asdict(value), where)
    if isinstance(value, Mapping):
        return {str(k): canonical(v, f"{where}.{k}") for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [canonical(v, f"{where}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, set | frozenset):
        items = [canonical(v, f"{where}{{}}") for v in value]
        return sorted(items, key=lambda item: json.dumps(item, sort_keys=True))
    raise TypeError(
        f"{where}: a {type(value).__name__} has no JSON form in the report; "
        "return plain numbers, strings, lists, dicts, numpy arrays or sympy objects"
    )


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


def _float(number: float) -> float | str:
    if not math.isfinite(number):
        return str(number)
    if number == 0:
        return 0.0
    return float(f"{number:.{FLOAT_DIGITS}g}")


def _flint(value: Any, where: str) -> Any:
    if hasattr(value, "tolist"):
        return canonical(value.tolist(), where)
    if hasattr(value, "entries") and hasattr(value, "nrows"):
        rows, cols = value.nrows(), value.ncols()
        return [[str(value[i, j]) for j in range(cols)] for i in range(rows)]
    return str(value)
