"""A result's evidence as labelled tables with units, for reading (``report.json`` keeps the
evidence whole; this only shapes what the pages show).

A mapping becomes rows ``label | value | unit``; a list of mappings a table with a column per
key; a list of numbers or a matrix one line per row; rationals written as ``p/q`` are shown with
their decimal value beside them; anything deeper than :data:`DEPTH` levels, or longer than
:data:`ROWS` rows, is cut with a note saying how much is left in ``report.json``.
"""

from __future__ import annotations

import json
import re
from fractions import Fraction
from typing import Any

from theory.report.glossary import unit_of

__all__ = ["DEPTH", "ROWS", "evidence_rows", "shown_value"]

DEPTH = 3
"""Nesting levels shown as tables (deeper values are shown as compact JSON)."""
ROWS = 40
"""Rows (or list items) shown per table."""

_RATIONAL = re.compile(r"^-?\d+/\d+$")


def evidence_rows(evidence: Any, depth: int = 0) -> list[dict[str, Any]]:
    """Rows of a mapping's table: each ``{"label", "unit"}`` and either ``"value"`` (text),
    ``"rows"`` (a nested table) or ``"columns"``/``"records"`` (a list of mappings)."""
    if not isinstance(evidence, dict):
        return [{"label": "value", "unit": "", "value": shown_value(evidence)}]
    rows = [_row(str(key), value, depth) for key, value in list(evidence.items())[:ROWS]]
    if len(evidence) > ROWS:
        rows.append(_more(len(evidence) - ROWS, "keys"))
    return rows


def _row(key: str, value: Any, depth: int) -> dict[str, Any]:
    row: dict[str, Any] = {"label": key, "unit": unit_of(key)}
    if depth < DEPTH and isinstance(value, dict) and value:
        row["rows"] = evidence_rows(value, depth + 1)
    elif depth < DEPTH and _records(value):
        columns = list(dict.fromkeys(k for item in value for k in item))
        row["columns"] = [{"label": c, "unit": unit_of(c)} for c in columns]
        row["records"] = [[shown_value(item.get(c, "")) for c in columns] for item in value[:ROWS]]
        row["value"] = "" if len(value) <= ROWS else f"{len(value) - ROWS} more in report.json"
    else:
        row["value"] = shown_value(value)
    return row


def _records(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _more(count: int, what: str) -> dict[str, Any]:
    return {"label": "…", "unit": "", "value": f"{count} more {what} in report.json"}


def shown_value(value: Any) -> str:
    """One value as text: numbers to 6 significant digits, ``p/q`` with its decimal, lists of
    scalars on one line (a matrix one row per line), the rest as compact JSON."""
    if isinstance(value, bool) or value is None:
        return json.dumps(value)
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return _rational(value)
    if isinstance(value, list) and all(_scalar(v) for v in value):
        return _line(value)
    if isinstance(value, list) and value and all(isinstance(v, list) for v in value):
        if all(all(_scalar(x) for x in v) for v in value):
            lines = [_line(v) for v in value[:ROWS]]
            if len(value) > ROWS:
                lines.append(f"… {len(value) - ROWS} more rows in report.json")
            return "\n".join(lines)
    text = json.dumps(value, ensure_ascii=False, separators=(", ", ": "))
    return text if len(text) <= 2000 else text[:2000] + f" … ({len(text) - 2000} more characters)"


def _scalar(value: Any) -> bool:
    return value is None or isinstance(value, bool | int | float | str)


def _line(values: list[Any]) -> str:
    shown = ", ".join(shown_value(v) for v in values[:ROWS])
    more = f", … {len(values) - ROWS} more" if len(values) > ROWS else ""
    return f"[{shown}{more}]"


def _rational(text: str) -> str:
    """``"661745/524288"`` → ``"≈ 1.26218 (661745/524288)"``; other text unchanged."""
    if not _RATIONAL.match(text) or int(text.split("/")[1]) == 0:
        return text
    return f"≈ {float(Fraction(text)):.6g} ({text})"
