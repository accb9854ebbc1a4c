"""Reading a certificate file safely: size limits, canonical exact rationals, typed fields.

Everything here raises :class:`MalformedError` (exit code 2) on input that is not a well-formed
certificate: unreadable or oversized files, invalid JSON, nesting too deep, JSON floats (numbers
must be exact rational strings, spelled canonically: ``"2/2"``, ``"-0"`` are refused), numbers
longer than :data:`MAX_NUMBER_CHARS`, a key repeated in one object (JSON parsers silently keep
the last), wrong types or shapes, unknown fields, a number outside its range (:func:`bounded`).
Nothing here decides whether a claim holds.
"""

from __future__ import annotations

import json
import re
from fractions import Fraction
from typing import Any

__all__ = [
    "FORMAT",
    "MAX_DIM",
    "MAX_FILE_BYTES",
    "MAX_INT_DIGITS",
    "MAX_ITEMS",
    "MAX_NUMBER_CHARS",
    "SPANS",
    "MalformedError",
    "Matrix",
    "bounded",
    "fields",
    "index",
    "load",
    "loads",
    "matrix",
    "matrix_list",
    "rational",
    "text",
]

FORMAT = "trackcert-certificate/1"
MAX_FILE_BYTES = 4_000_000
"""Larger files are refused unread."""
MAX_NUMBER_CHARS = 2000
"""Longest accepted rational string (sign, numerator, '/', denominator)."""
MAX_INT_DIGITS = 9
"""Longest accepted JSON integer (indices and counts only)."""
MAX_DIM = 64
"""Largest accepted matrix dimension."""
MAX_ITEMS = 256
"""Longest accepted list of matrices (agents, modes, certificates in a bundle)."""

Matrix = list[list[Fraction]]
_RATIONAL = re.compile(r"-?(0|[1-9][0-9]*)(/[1-9][0-9]*)?")


class MalformedError(ValueError):
    """The file is not a well-formed certificate (exit code 2); the message says where."""


def load(path: str) -> dict[str, Any]:
    """Read ``path`` (at most :data:`MAX_FILE_BYTES`) and parse it with :func:`loads`."""
    try:
        with open(path, "rb") as handle:
            raw = handle.read(MAX_FILE_BYTES + 1)
    except OSError as error:
        raise MalformedError(f"cannot read: {error.strerror}") from None
    if len(raw) > MAX_FILE_BYTES:
        raise MalformedError(f"larger than {MAX_FILE_BYTES} bytes; refused unread")
    try:
        return loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise MalformedError("not UTF-8 text") from None


def loads(content: str) -> dict[str, Any]:
    """Parse certificate JSON: floats, NaN, long integers, repeated keys refused while parsing."""
    try:
        data = json.loads(
            content,
            parse_float=_refuse_float,
            parse_int=_small_int,
            parse_constant=_refuse_float,
            object_pairs_hook=_unique_keys,
        )
    except RecursionError:
        raise MalformedError("JSON nested too deeply") from None
    except json.JSONDecodeError as error:
        why = f"not valid JSON: {error.msg} (line {error.lineno}, column {error.colno})"
        raise MalformedError(why) from None
    if not isinstance(data, dict):
        raise MalformedError("top level: expected a JSON object")
    return data


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """An object from its ``(key, value)`` pairs, refusing a key given twice."""
    data: dict[str, Any] = {}
    for key, value in pairs:
        if key in data:
            why = f"the key {key[:60]!r} appears twice in one object (the certificate is ambiguous)"
            raise MalformedError(why)
        data[key] = value
    return data


def _refuse_float(token: str) -> Any:
    why = f'JSON number {token[:40]!r}: numbers must be exact rational strings such as "-3/7"'
    raise MalformedError(why)


def _small_int(token: str) -> int:
    digits = token.lstrip("-")
    if len(digits) > MAX_INT_DIGITS:
        why = f"JSON integer of {len(digits)} digits: only small indices are integers"
        raise MalformedError(why)
    if token == "-0":
        raise MalformedError("JSON integer -0: write 0 (numbers are canonical)")
    return int(token)


def fields(value: Any, where: str, required: tuple[str, ...], optional: tuple[str, ...] = ()):
    """``value`` as an object with exactly the ``required`` keys plus some ``optional`` ones."""
    if not isinstance(value, dict):
        raise MalformedError(f"{where}: expected an object, got {type(value).__name__}")
    missing = [key for key in required if key not in value]
    if missing:
        raise MalformedError(f"{where}: missing field {missing[0]!r}")
    unknown = sorted(set(value) - set(required) - set(optional))
    if unknown:
        raise MalformedError(f"{where}: unknown field {unknown[0]!r}")
    return value


def text(value: Any, where: str, choices: tuple[str, ...] | None = None) -> str:
    """A string (one of ``choices`` when given), at most 2,000 characters."""
    if not isinstance(value, str) or len(value) > 2000:
        raise MalformedError(f"{where}: expected a string (at most 2000 characters)")
    if choices is not None and value not in choices:
        raise MalformedError(f"{where}: expected one of {list(choices)}, got {value[:60]!r}")
    return value


def index(value: Any, where: str, low: int, high: int) -> int:
    """An integer ``low ≤ value ≤ high`` (JSON booleans are not integers)."""
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise MalformedError(f"{where}: expected an integer from {low} to {high}, got {value!r}")
    return value


def rational(value: Any, where: str) -> Fraction:
    """An exact rational from its canonical string ``"p"`` or ``"p/q"`` (``str`` of a Fraction)."""
    if not isinstance(value, str):
        why = f'{where}: expected a rational string like "-3/7", got {value!r}'[:200]
        raise MalformedError(why)
    if len(value) > MAX_NUMBER_CHARS:
        why = f"{where}: number of {len(value)} characters (limit {MAX_NUMBER_CHARS})"
        raise MalformedError(why)
    if not _RATIONAL.fullmatch(value):
        raise MalformedError(f'{where}: {value[:60]!r} is not a rational string like "-3/7"')
    number = Fraction(value)
    if str(number) != value:
        why = "lowest terms, no denominator 1, no -0"
        raise MalformedError(
            f"{where}: {value[:60]!r} is not canonical ({why}); write {number!s:.60}"
        )
    return number


SPANS = {"(0, 1]": lambda x: 0 < x <= 1, "[1, ∞)": lambda x: x >= 1, "(0, ∞)": lambda x: x > 0}
"""The ranges a claimed number may be restricted to (see :func:`bounded`)."""


def bounded(value: Any, where: str, span: str, why: str) -> Fraction:
    """A rational in ``span`` (a key of :data:`SPANS`); ``why`` ends the message when it is not."""
    number = rational(value, where)
    if not SPANS[span](number):
        raise MalformedError(f"{where}: expected a rational in {span}, got {number}: {why}")
    return number


def matrix(
    value: Any, where: str, rows: int | None = None, cols: int | None = None, *,
    max_rows: int = MAX_DIM, max_cols: int = MAX_DIM,
) -> Matrix:  # fmt: skip
    """A rectangular matrix of rationals (a list of rows), optionally of a required shape, at
    most ``max_rows`` × ``max_cols`` (lists of points may be longer than a matrix to multiply)."""
    if not isinstance(value, list) or not value or len(value) > max_rows:
        raise MalformedError(f"{where}: expected a non-empty list of at most {max_rows} rows")
    width = len(value[0]) if isinstance(value[0], list) else -1
    if not 1 <= width <= max_cols or any(
        not isinstance(row, list) or len(row) != width for row in value
    ):
        raise MalformedError(f"{where}: expected rows of equal length between 1 and {max_cols}")
    if (rows is not None and len(value) != rows) or (cols is not None and width != cols):
        expected = f"{rows if rows is not None else '*'} × {cols if cols is not None else '*'}"
        raise MalformedError(f"{where}: expected shape {expected}, got {len(value)} × {width}")
    return [
        [rational(entry, f"{where}[{r + 1}][{c + 1}]") for c, entry in enumerate(row)]
        for r, row in enumerate(value)
    ]


def matrix_list(
    value: Any,
    where: str,
    count: int | None = None,
    rows: int | None = None,
    cols: int | None = None,
) -> list[Matrix]:
    """A list of matrices (one per agent), optionally ``count`` long and of a fixed shape."""
    if not isinstance(value, list) or not value or len(value) > MAX_ITEMS:
        raise MalformedError(f"{where}: expected a non-empty list of at most {MAX_ITEMS} matrices")
    if count is not None and len(value) != count:
        why = f"{where}: expected {count} matrices (one per agent), got {len(value)}"
        raise MalformedError(why)
    return [matrix(item, f"{where}[{k + 1}]", rows, cols) for k, item in enumerate(value)]
