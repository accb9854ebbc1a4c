"""Parameter specs of ``trackcert sweep --param PATH=SPEC`` and the grid they span.

A spec is one of (``docs/sweep.md``):

* ``a:b`` — the integers ``a, a+1, …, b−1`` (half-open, like Python's ``range``; ``seed=0:50``
  is the 50 seeds 0…49);
* ``a:b:linN`` — ``N ≥ 2`` evenly spaced numbers from ``a`` to ``b``, both included
  (``numpy.linspace``);
* ``a:b:logN`` — ``N ≥ 2`` log-spaced numbers from ``a`` to ``b``, both included, ``0 < a, b``
  (``numpy.geomspace``; ``k_gamma=1:400:log20``);
* ``v1,v2,…`` — an explicit list (``w=0.2,0.24,0.25``), kept in the order written;
* ``v`` — one value.

A number written as an integer (``5``, ``-3``) stays an integer; anything else is a float.
Several specs make the cartesian product, the first ``--param`` varying slowest (nested loops
in the order written), so the grid's order is deterministic. A linked parameter
(``--link PATH=EXPR``, :mod:`theory.sweep.links`) adds no dimension: at each point its value is
an affine function of one swept parameter's.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from theory.core.errors import CaseError

__all__ = [
    "MAX_POINTS",
    "SCALES",
    "Param",
    "check_size",
    "grid_points",
    "grid_size",
    "parse_param",
    "parse_spec",
]

MAX_POINTS = 100_000
"""Points a sweep refuses to exceed unless ``--max-points`` raises it."""

SCALES = ("range", "lin", "log", "list", "value", "link")
"""How a spec spaces its values (``log`` sweeps are drawn on a log axis)."""

FIELD = "--param"
EXPECTED = (
    "PATH=SPEC with SPEC one of FROM:TO (integers FROM…TO−1), FROM:TO:linN, FROM:TO:logN "
    "(N ≥ 2 points, ends included), v1,v2,… or a single number"
)
"""(Written FROM:TO rather than a:b: rich renders ``:b:`` in a message as an emoji.)"""

_SPACED = re.compile(r"^(?P<kind>lin|log)(?P<count>\d+)$")
_INTEGER = re.compile(r"^[+-]?\d+$")

Number = int | float


@dataclass(frozen=True)
class Param:
    """One swept parameter.

    Attributes
    ----------
    path : str
        The dotted path of the case field (``k_gamma``, ``W.0.1``) or ``seed``.
    spec : str
        The spec as written.
    scale : str
        One of :data:`SCALES`.
    values : tuple of int or float
        The values, in sweep order (of a link: its value at each value of its source).
    source : str or None
        A link's source: the path of the swept parameter it follows (``None``: swept itself).
    offset, factor : int or float
        A link's value is ``offset + factor · source``.
    """

    path: str
    spec: str
    scale: str
    values: tuple[Number, ...]
    source: str | None = None
    offset: Number = 0
    factor: Number = 1

    def linked(self, value: Number) -> Number:
        """A link's value where its source is ``value``."""
        return self.offset + self.factor * value

    def to_json(self) -> dict[str, object]:
        """``path``, ``spec``, ``scale`` and ``values`` (and a link's ``source``)."""
        out: dict[str, object] = {
            "path": self.path,
            "spec": self.spec,
            "scale": self.scale,
            "values": list(self.values),
        }
        if self.source is not None:
            out["source"] = self.source
        return out


def _bad(given: str, why: str = "") -> CaseError:
    return CaseError(FIELD, EXPECTED, given, file="<command line>", hint=why)


def _number(text: str, given: str) -> Number:
    text = text.strip()
    if _INTEGER.match(text):
        return int(text)
    try:
        value = float(text)
    except ValueError:
        raise _bad(given, f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise _bad(given, f"{text!r} is not a finite number")
    return value


def parse_spec(spec: str, given: str | None = None) -> tuple[str, tuple[Number, ...]]:
    """The scale and the values of one spec (module docstring).

    Parameters
    ----------
    spec : str
        E.g. ``1:400:log20``, ``0:50``, ``0.2,0.24``, ``5``.
    given : str, optional
        The whole ``--param`` text, named in errors (default ``spec``).

    Returns
    -------
    (str, tuple)
        The scale (:data:`SCALES`) and the values.

    Raises
    ------
    CaseError
        Field ``--param``: the expected forms and what was given.
    """
    given = spec if given is None else given
    parts = spec.split(":")
    if len(parts) == 1:
        items = spec.split(",")
        values = tuple(_number(item, given) for item in items)
        return ("value" if len(items) == 1 else "list"), values
    if len(parts) == 2:
        return "range", _integer_range(parts, given)
    if len(parts) == 3:
        return _spaced(parts, given)
    raise _bad(given, "at most two ':'")


def _integer_range(parts: Sequence[str], given: str) -> tuple[int, ...]:
    start, stop = (_number(p, given) for p in parts)
    if not (isinstance(start, int) and isinstance(stop, int)):
        raise _bad(given, "FROM:TO takes integers (FROM:TO:linN takes any numbers)")
    if stop <= start:
        raise _bad(given, f"FROM:TO is half-open and needs FROM < TO ({start}:{stop} is empty)")
    return tuple(range(start, stop))


def _spaced(parts: Sequence[str], given: str) -> tuple[str, tuple[float, ...]]:
    match = _SPACED.match(parts[2].strip())
    if match is None:
        raise _bad(given, f"the third part {parts[2]!r} is not linN or logN")
    kind, count = match["kind"], int(match["count"])
    if count < 2:
        raise _bad(given, f"{kind}N needs N ≥ 2 (a single value is written alone)")
    start, stop = (float(_number(p, given)) for p in parts[:2])
    if start == stop:
        raise _bad(given, "FROM and TO are equal")
    if kind == "log":
        if start <= 0 or stop <= 0:
            raise _bad(given, "logN needs FROM > 0 and TO > 0")
        values = np.geomspace(start, stop, count)
    else:
        values = np.linspace(start, stop, count)
    values[0], values[-1] = start, stop  # the ends exactly as written
    return kind, tuple(float(v) for v in values)


def parse_param(text: str) -> Param:
    """One ``--param PATH=SPEC`` argument.

    Parameters
    ----------
    text : str
        E.g. ``k_gamma=1:400:log20``.

    Returns
    -------
    Param

    Raises
    ------
    CaseError
        Field ``--param`` when there is no ``=``, the path is empty or the spec is malformed.
    """
    path, sep, spec = text.partition("=")
    path, spec = path.strip(), spec.strip()
    if not sep or not path or not spec:
        raise _bad(text, "write PATH=SPEC, e.g. k_gamma=1:400:log20")
    if any(not part for part in path.split(".")):
        raise _bad(text, f"{path!r} has an empty part between dots")
    scale, values = parse_spec(spec, text)
    return Param(path, spec, scale, values)


def grid_size(params: Sequence[Param]) -> int:
    """The number of points of the product of ``params`` (1 for none; links add none).

    Parameters
    ----------
    params : sequence of Param

    Returns
    -------
    int
    """
    return math.prod(len(p.values) for p in params if p.source is None)


def check_size(params: Sequence[Param], max_points: int = MAX_POINTS) -> int:
    """The grid's size, refused above ``max_points`` (before anything is expanded).

    Parameters
    ----------
    params : sequence of Param
        At least one, with distinct paths.
    max_points : int
        The limit (``--max-points``).

    Returns
    -------
    int

    Raises
    ------
    CaseError
        No parameter, a path given twice, a limit below 1, or more points than the limit.
    """
    if not params:
        raise _bad("nothing", "give at least one --param")
    paths = [p.path for p in params]
    repeated = sorted({p for p in paths if paths.count(p) > 1})
    if repeated:
        raise _bad(", ".join(repeated), "each path may be set by one --param or --link only")
    if max_points < 1:
        raise CaseError("--max-points", "an integer ≥ 1", max_points, file="<command line>")
    size = grid_size(params)
    if size > max_points:
        raise CaseError(
            "--param",
            f"at most {max_points} points (--max-points raises the limit)",
            f"{size} points ({' × '.join(str(len(p.values)) for p in params if not p.source)})",
            file="<command line>",
        )
    return size


def grid_points(params: Sequence[Param]) -> Iterator[tuple[Number, ...]]:
    """The points of the grid: one value per parameter, the first parameter varying slowest.

    Parameters
    ----------
    params : sequence of Param
        Swept parameters, and links whose sources are among them.

    Yields
    ------
    tuple
        The values, in ``params`` order (a link's from its source's value at the point).
    """
    swept = [p for p in params if p.source is None]
    for point in itertools.product(*(p.values for p in swept)):
        at = dict(zip((p.path for p in swept), point, strict=True))
        yield tuple(at[p.path] if p.source is None else p.linked(at[p.source]) for p in params)
