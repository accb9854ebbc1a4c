"""``PATH=EXPR`` links: a field set to an affine function of one named source, as ``trackcert
sweep --link`` and ``trackcert design self-weight --link`` write them (docs/sweep.md).

``EXPR`` is ``SOURCE``, ``-SOURCE``, ``B*SOURCE``, ``A+SOURCE``, ``A-SOURCE``, ``A+B*SOURCE`` or
``A-B*SOURCE`` (``A``, ``B`` numbers; spaces ignored); nothing else is evaluated.
"""

from __future__ import annotations

import re
from collections.abc import Collection
from dataclasses import dataclass
from fractions import Fraction

from theory.core.errors import COMMAND_LINE, CaseError

__all__ = ["LINK_EXPECTED", "SWEPT", "Link", "parse_link_expr"]

SWEPT = "the path of a --param"
"""What ``SOURCE`` is for ``trackcert sweep --link``."""

LINK_EXPECTED = (
    "PATH=EXPR with EXPR one of SOURCE, -SOURCE, B*SOURCE, A+SOURCE, A-SOURCE, A+B*SOURCE, "
    "A-B*SOURCE (A, B numbers; SOURCE {source})"
)

_NUMBER = r"(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
_EXPR = re.compile(
    rf"(?:(?P<offset>-?{_NUMBER})(?P<sign>[+-])|(?P<negate>-))?"
    rf"(?:(?P<factor>{_NUMBER})\*)?(?P<source>[A-Za-z_][\w.]*)"
)


@dataclass(frozen=True)
class Link:
    """``path = offset + sign · factor · source``, the numbers as written (None: absent)."""

    path: str
    expr: str
    source: str
    offset: str | None
    factor: str | None
    sign: int

    def exact(self) -> tuple[Fraction, Fraction]:
        """``(offset, signed factor)`` as the exact decimals written."""
        offset = Fraction(self.offset) if self.offset is not None else Fraction(0)
        factor = Fraction(self.factor) if self.factor is not None else Fraction(1)
        return offset, self.sign * factor


def _bad(given: str, why: str, field: str, source: str) -> CaseError:
    """The command-line error of one link text."""
    expected = LINK_EXPECTED.format(source=source)
    return CaseError(field, expected, given, file=COMMAND_LINE, hint=why)


def parse_link_expr(
    text: str, sources: Collection[str], *, field: str = "--link", source: str = SWEPT
) -> Link:
    """One ``PATH=EXPR`` argument whose ``EXPR`` is affine in one of ``sources`` (else a
    :class:`CaseError` of ``field`` on the command line; ``source`` says what a source is)."""
    path, sep, expr = text.partition("=")
    path, expr = path.strip(), "".join(expr.split())
    if not sep or not path or not expr or any(not part for part in path.split(".")):
        raise _bad(text, "write PATH=EXPR, e.g. W.0.1=1-W.0.0", field, source)
    match = _EXPR.fullmatch(expr)
    if match is None:
        raise _bad(text, f"{expr!r} is not an affine expression of one source", field, source)
    if match["source"] not in sources:
        why = f"{match['source']!r} is not a source; sources: {', '.join(sources)}"
        raise _bad(text, why, field, source)
    sign = -1 if match["sign"] == "-" or match["negate"] else 1
    return Link(path, expr, match["source"], match["offset"], match["factor"], sign)
