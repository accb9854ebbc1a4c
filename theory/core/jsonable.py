"""Plain JSON data from what the library returns (numpy, sympy, rationals, dataclasses).

One conversion for the commands' ``--json`` output, the files they write and the report
(:mod:`theory.report.canonical` rounds floats for reproducible bytes): one rule per type, and
values with no faithful plain form refused (:class:`TypeError` naming where in the data they sit)
instead of being written as a ``repr`` that could carry a memory address. sympy is never
imported here: a value can only be a sympy object if sympy is already loaded.
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

__all__ = ["plain"]


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
