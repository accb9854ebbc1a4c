"""Linked parameters of ``trackcert sweep --link PATH=EXPR``: a field set from a swept one.

Some fields cannot be swept alone: a row of an explicit consensus matrix ``W`` must stay
row-stochastic (seed 000 eq. (5.3)), so Example 1's self-weight sweep w₁₁ = 0.2 … 0.3 needs
w₁₂ = 1 − w₁₁ at every point. A link sets such a field from one swept parameter, adding no
dimension to the grid::

    --param W.0.0=0.2:0.3:lin11 --link 'W.0.1=1-W.0.0'

``EXPR`` is affine in one ``--param`` path (``SOURCE``), in one of the forms ``SOURCE``,
``-SOURCE``, ``B*SOURCE``, ``A+SOURCE``, ``A-SOURCE``, ``A+B*SOURCE`` or ``A-B*SOURCE``, with
``A`` and ``B`` numbers (``A`` may be negative, ``B`` is not); spaces are ignored. Nothing else
is evaluated. Integers stay integers (``1-seed`` of an integer seed is an integer).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from theory.core.errors import CaseError
from theory.sweep.grid import Number, Param

__all__ = ["parse_link"]

FIELD = "--link"
EXPECTED = (
    "PATH=EXPR with EXPR one of SOURCE, -SOURCE, B*SOURCE, A+SOURCE, A-SOURCE, A+B*SOURCE, "
    "A-B*SOURCE (A, B numbers; SOURCE the path of a --param)"
)

_NUMBER = r"(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
_EXPR = re.compile(
    rf"(?:(?P<offset>-?{_NUMBER})(?P<sign>[+-])|(?P<negate>-))?"
    rf"(?:(?P<factor>{_NUMBER})\*)?(?P<source>[A-Za-z_][\w.]*)"
)


def _bad(given: str, why: str) -> CaseError:
    return CaseError(FIELD, EXPECTED, given, file="<command line>", hint=why)


def _number(text: str | None, default: Number) -> Number:
    if text is None:
        return default
    value = float(text)
    return int(value) if re.fullmatch(r"-?\d+", text) else value


def parse_link(text: str, params: Sequence[Param]) -> Param:
    """One ``--link PATH=EXPR`` argument, following one of ``params``.

    Parameters
    ----------
    text : str
        E.g. ``W.0.1=1-W.0.0``.
    params : sequence of Param
        The swept parameters (``--param``); ``SOURCE`` must be one of their paths.

    Returns
    -------
    Param
        Scale ``link``, its ``source``, ``offset`` and ``factor``, and its value at each value
        of the source.

    Raises
    ------
    CaseError
        Field ``--link``: no ``=``, an expression of another form, or a source that no
        ``--param`` sweeps (the hint names the swept paths).
    """
    path, sep, expr = text.partition("=")
    path, expr = path.strip(), "".join(expr.split())
    if not sep or not path or not expr or any(not part for part in path.split(".")):
        raise _bad(text, "write PATH=EXPR, e.g. W.0.1=1-W.0.0")
    match = _EXPR.fullmatch(expr)
    if match is None:
        raise _bad(text, f"{expr!r} is not an affine expression of one --param path")
    swept = {p.path: p for p in params if p.source is None}
    source = swept.get(match["source"])
    if source is None:
        raise _bad(text, f"{match['source']!r} is not swept; --param paths: {', '.join(swept)}")
    sign = -1 if match["sign"] == "-" or match["negate"] else 1
    offset, factor = _number(match["offset"], 0), sign * _number(match["factor"], 1)
    values = tuple(offset + factor * v for v in source.values)
    return Param(path, expr, "link", values, source.path, offset, factor)
