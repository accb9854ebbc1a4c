"""Plain JSON data from what the library returns (numpy, sympy, rationals, dataclasses), and its
canonical text.

One conversion, :func:`plain`, for the commands' ``--json`` output, the files they write and the
report: one rule per type, and a value with no faithful plain form refused (a :class:`TypeError`
naming where it sits) rather than written as a ``repr`` that could carry a memory address. sympy
is never imported here: a value can only be a sympy object if sympy is already loaded.
:func:`canonical` rounds floats to :data:`FLOAT_DIGITS` and :func:`dumps` writes sorted keys with a
fixed layout, so the same data gives the same bytes (the report's reproducibility).
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys
from collections.abc import Mapping
from fractions import Fraction
from pathlib import PurePath
from typing import Any

import numpy as np

__all__ = ["FLOAT_DIGITS", "canonical", "dumps", "layout", "plain"]

FLOAT_DIGITS = 12
"""Significant digits of the report's floats (exact values travel as rational strings)."""


def plain(value: Any, *, digits: int | None = None, where: str = "$") -> Any:
    """Plain JSON data (dict, list, str, int, float, bool, None) equal in content to ``value``.

    Parameters
    ----------
    value : object
        Numbers (Python, numpy, ``Fraction``, python-flint, sympy), arrays, sympy matrices and
        expressions, mappings, sequences, sets, dataclasses, paths.
    digits : int, optional
        Significant digits kept for floats (``None``: floats unchanged).
    where : str
        Location of ``value`` in the enclosing data, used in error messages.

    Returns
    -------
    object
        Non-finite floats as the strings ``"nan"``, ``"inf"``, ``"-inf"``; rationals as ``"p/q"``
        strings; complex numbers as ``{"re", "im"}``; sympy objects as their ``str``; sets
        sorted.

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
        return _float(float(value), digits)
    if isinstance(value, complex | np.complexfloating):
        return {"im": _float(float(value.imag), digits), "re": _float(float(value.real), digits)}
    if isinstance(value, Fraction):
        return str(value)
    if isinstance(value, PurePath):
        return value.as_posix()
    symbolic = _sympy(value)
    if symbolic is not None:
        return symbolic
    if type(value).__module__.startswith("flint"):
        return _flint(value, digits, where)
    if isinstance(value, np.ndarray):
        return plain(value.tolist(), digits=digits, where=where)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return plain(dataclasses.asdict(value), digits=digits, where=where)
    return _container(value, digits, where)


def canonical(value: Any, where: str = "$") -> Any:
    """:func:`plain` with floats rounded to :data:`FLOAT_DIGITS` significant digits."""
    return plain(value, digits=FLOAT_DIGITS, where=where)


def dumps(value: Any, *, width: int = 100) -> str:
    """The canonical text of ``value``: :func:`layout` of :func:`canonical`, newline at the end."""
    return layout(canonical(value), width=width) + "\n"


def layout(data: Any, *, width: int = 100, indent: int = 0) -> str:
    """Deterministic JSON text of plain ``data``, sorted keys: a container whose one-line form
    fits in ``width`` (from ``indent``) stays on one line (a matrix prints a row a line), larger
    ones are expanded with a 2-space indent."""
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


def _container(value: Any, digits: int | None, where: str) -> Any:
    if isinstance(value, Mapping):
        return {str(k): plain(v, digits=digits, where=f"{where}.{k}") for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain(v, digits=digits, where=f"{where}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, set | frozenset):
        items = [plain(v, digits=digits, where=f"{where}{{}}") for v in value]
        return sorted(items, key=lambda item: json.dumps(item, sort_keys=True))
    raise TypeError(
        f"{where}: a {type(value).__name__} has no JSON form; "
        "return plain numbers, strings, lists, dicts, numpy arrays or sympy objects"
    )


def _sympy(value: Any) -> Any:
    """A sympy matrix as rows of strings, a sympy expression as its string, else ``None``."""
    sp = sys.modules.get("sympy")
    if sp is None:
        return None
    if isinstance(value, sp.MatrixBase):
        return [[str(entry) for entry in row] for row in value.tolist()]
    if isinstance(value, sp.Basic):
        return str(value)
    return None


def _float(number: float, digits: int | None) -> float | str:
    if not math.isfinite(number):
        return str(number)
    if digits is None:
        return number
    if number == 0:
        return 0.0
    return float(f"{number:.{digits}g}")


def _flint(value: Any, digits: int | None, where: str) -> Any:
    if hasattr(value, "tolist"):
        return plain(value.tolist(), digits=digits, where=where)
    if hasattr(value, "entries") and hasattr(value, "nrows"):
        rows, cols = value.nrows(), value.ncols()
        return [[str(value[i, j]) for j in range(cols)] for i in range(rows)]
    return str(value)
