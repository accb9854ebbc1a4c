"""The grid of ``trackcert sweep``: ``--param PATH=SPEC`` and ``--link PATH=EXPR`` parsed, the
points they span, and where each path lands in the case's data (docs/sweep.md).

A spec is ``a:b`` (the integers ``a … b−1``, half-open like ``range``: ``seed=0:50`` is 50
seeds), ``a:b:linN`` (``N ≥ 2`` evenly spaced numbers, both ends included, ``numpy.linspace``),
``a:b:logN`` (``N ≥ 2`` log-spaced, ``0 < a, b``, ``numpy.geomspace``), ``v1,v2,…`` (a list, in
the order written) or ``v`` (one value). A number written as an integer stays an integer. Several
specs make the cartesian product, the first ``--param`` varying slowest, so the grid's order is
deterministic.

A link sets a field that cannot be swept alone from one swept parameter, adding no dimension: a
row of an explicit consensus matrix ``W`` must stay row-stochastic (seed 000 eq. (5.3)), so
Example 1's self-weight sweep needs ``--param W.0.0=0.2:0.3:lin11 --link 'W.0.1=1-W.0.0'``.
``EXPR`` is affine in one ``--param`` path: ``SOURCE``, ``-SOURCE``, ``B*SOURCE``, ``A+SOURCE``,
``A-SOURCE``, ``A+B*SOURCE`` or ``A-B*SOURCE`` (``A``, ``B`` numbers; spaces ignored); nothing
else is evaluated.

A path names a numeric field by its keys and 0-based list indices, separated by dots
(``k_gamma``, ``trackers.0.r_x``, ``W.0.1``), looked up first inside the kind's block, then from
the top of the file. ``seed``, when the case has no such field, is the simulation's root seed (as
``trackcert simulate --seed``). A path that does not exist or holds no number is refused up front
(exit 2), listing the fields that exist where the lookup stopped.
"""

from __future__ import annotations

import copy
import itertools
import math
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np

from theory.core.errors import COMMAND_LINE, CaseError
from theory.core.links import LINK_EXPECTED, SWEPT, parse_link_expr

__all__ = [
    "MAX_POINTS",
    "SEED",
    "Param",
    "Scale",
    "Target",
    "apply_values",
    "check_size",
    "grid_points",
    "grid_size",
    "parse_link",
    "parse_param",
    "parse_spec",
    "resolve_target",
]

MAX_POINTS = 100_000
"""Points a sweep refuses to exceed unless ``--max-points`` raises it."""

SEED = "seed"
"""The path that, when the case has no such field, sets the simulation's root seed."""


class Scale(StrEnum):
    """How a parameter's values are spaced (``log`` sweeps are drawn on a log axis)."""

    RANGE = "range"
    LIN = "lin"
    LOG = "log"
    LIST = "list"
    VALUE = "value"
    LINK = "link"


# (Written FROM:TO rather than a:b: rich renders ``:b:`` in a message as an emoji.)
PARAM_EXPECTED = (
    "PATH=SPEC with SPEC one of FROM:TO (integers FROM…TO−1), FROM:TO:linN, FROM:TO:logN "
    "(N ≥ 2 points, ends included), v1,v2,… or a single number"
)

_SPACED = re.compile(r"^(?P<kind>lin|log)(?P<count>\d+)$")
_INTEGER = re.compile(r"^[+-]?\d+$")

Number = int | float
Key = str | int


@dataclass(frozen=True)
class Param:
    """One swept parameter: its dotted ``path`` (or ``seed``), the ``spec`` as written, its
    ``scale`` and ``values`` in sweep order. A link also has its ``source`` (the swept path it
    follows) and takes ``offset + factor · source`` (its ``values``: at each source value)."""

    path: str
    spec: str
    scale: Scale
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


def _bad(given: str, why: str = "", *, field: str = "--param") -> CaseError:
    expected = LINK_EXPECTED.format(source=SWEPT) if field == "--link" else PARAM_EXPECTED
    return CaseError(field, expected, given, file=COMMAND_LINE, hint=why)


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


def parse_spec(spec: str, given: str | None = None) -> tuple[Scale, tuple[Number, ...]]:
    """The scale and the values of one spec (``given``: the whole ``--param`` text, for errors)."""
    given = spec if given is None else given
    parts = spec.split(":")
    if len(parts) == 1:
        items = spec.split(",")
        values = tuple(_number(item, given) for item in items)
        return (Scale.VALUE if len(items) == 1 else Scale.LIST), values
    if len(parts) == 2:
        return Scale.RANGE, _integer_range(parts, given)
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


def _spaced(parts: Sequence[str], given: str) -> tuple[Scale, tuple[float, ...]]:
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
    return Scale(kind), tuple(float(v) for v in values)


def parse_param(text: str) -> Param:
    """One ``--param PATH=SPEC`` argument (e.g. ``k_gamma=1:400:log20``)."""
    path, sep, spec = text.partition("=")
    path, spec = path.strip(), spec.strip()
    if not sep or not path or not spec:
        raise _bad(text, "write PATH=SPEC, e.g. k_gamma=1:400:log20")
    if any(not part for part in path.split(".")):
        raise _bad(text, f"{path!r} has an empty part between dots")
    scale, values = parse_spec(spec, text)
    return Param(path, spec, scale, values)


def parse_link(text: str, params: Sequence[Param]) -> Param:
    """One ``--link PATH=EXPR`` argument (e.g. ``W.0.1=1-W.0.0``) following one of the swept
    ``params``: a :class:`Param` of scale ``link`` (:func:`theory.core.links.parse_link_expr`)."""
    swept = {p.path: p for p in params if p.source is None}
    link = parse_link_expr(text, swept)
    source = swept[link.source]
    offset = _link_number(link.offset, 0)
    factor = link.sign * _link_number(link.factor, 1)
    values = tuple(offset + factor * v for v in source.values)
    return Param(link.path, link.expr, Scale.LINK, values, source.path, offset, factor)


def _link_number(text: str | None, default: Number) -> Number:
    if text is None:
        return default
    value = float(text)
    return int(value) if re.fullmatch(r"-?\d+", text) else value


def grid_size(params: Sequence[Param]) -> int:
    """The number of points of the product of ``params`` (1 for none; links add none)."""
    return math.prod(len(p.values) for p in params if p.source is None)


def check_size(params: Sequence[Param], max_points: int = MAX_POINTS) -> int:
    """The grid's size, refused (before anything is expanded) with no parameter, a path given
    twice, a limit below 1 or more points than ``max_points``."""
    if not params:
        raise _bad("nothing", "give at least one --param")
    paths = [p.path for p in params]
    repeated = sorted({p for p in paths if paths.count(p) > 1})
    if repeated:
        raise _bad(", ".join(repeated), "each path may be set by one --param or --link only")
    if max_points < 1:
        raise CaseError("--max-points", "an integer ≥ 1", max_points, file=COMMAND_LINE)
    size = grid_size(params)
    if size > max_points:
        raise CaseError(
            "--param",
            f"at most {max_points} points (--max-points raises the limit)",
            f"{size} points ({' × '.join(str(len(p.values)) for p in params if not p.source)})",
            file=COMMAND_LINE,
        )
    return size


def grid_points(params: Sequence[Param]) -> Iterator[tuple[Number, ...]]:
    """The grid's points, one value per parameter in ``params`` order (a link's from its source),
    the first swept parameter varying slowest."""
    swept = [p for p in params if p.source is None]
    for point in itertools.product(*(p.values for p in swept)):
        at = dict(zip((p.path for p in swept), point, strict=True))
        yield tuple(at[p.path] if p.source is None else p.linked(at[p.source]) for p in params)


# --------------------------------------------------------------------------------- the paths
@dataclass(frozen=True)
class Target:
    """Where one swept ``path`` lands: its ``keys`` from the top of the case data (``None``: the
    simulation seed)."""

    path: str
    keys: tuple[Key, ...] | None

    @property
    def is_seed(self) -> bool:
        """Whether this path sets the simulation's root seed rather than a case field."""
        return self.keys is None


def _step(node: Any, part: str) -> tuple[bool, Any, Key]:
    if isinstance(node, Mapping):
        return part in node, node.get(part), part
    if isinstance(node, list) and part.isdigit() and int(part) < len(node):
        return True, node[int(part)], int(part)
    return False, None, part


def _walk(data: Any, parts: Sequence[str]) -> tuple[tuple[Key, ...], Any, int]:
    """Follow ``parts``: (keys followed, the node reached, how many parts matched)."""
    node, keys = data, []
    for depth, part in enumerate(parts):
        found, child, key = _step(node, part)
        if not found:
            return tuple(keys), node, depth
        node = child
        keys.append(key)
    return tuple(keys), node, len(parts)


def _fields(node: Any) -> str:
    if isinstance(node, Mapping):
        return ", ".join(str(k) for k in node) or "none"
    if isinstance(node, list):
        return f"indices 0…{len(node) - 1}" if node else "none (an empty list)"
    return f"none ({type(node).__name__} {node!r} has no fields)"


def resolve_target(data: Mapping[str, Any], kind: str, path: str, *, file: str) -> Target:
    """Where ``path`` lands in a case's data of ``kind`` (its block searched first); a path that
    does not exist or holds no number is a :class:`CaseError` of field ``--param PATH`` in
    ``file``."""
    parts = path.split(".")
    block = data.get(kind)
    tries = [((kind,), block)] if isinstance(block, Mapping) else []
    tries.append(((), data))
    best: tuple[tuple[Key, ...], Any, int] | None = None
    for prefix, root in tries:
        keys, node, matched = _walk(root, parts)
        if matched == len(parts):
            return _numeric(Target(path, prefix + keys), node, file)
        if best is None or matched > best[2]:
            best = (prefix + keys, node, matched)
    if path == SEED:
        return Target(path, None)
    keys, node, matched = best  # type: ignore[misc]
    where = ".".join(str(k) for k in keys) or "the top of the case"
    raise CaseError(
        f"--param {path}",
        "a dotted path to a numeric field of the case (list indices from 0)",
        f"no '{parts[matched]}' in {where}",
        file=file,
        hint=f"fields there: {_fields(node)}",
    )


def _numeric(target: Target, value: Any, file: str) -> Target:
    if isinstance(value, int | float) and not isinstance(value, bool):
        return target
    raise CaseError(
        f"--param {target.path}",
        "a numeric field (an integer or a float)",
        value,
        file=file,
        hint=f"{'.'.join(str(k) for k in target.keys or ())} holds no number; fields there: "
        f"{_fields(value)}",
    )


def apply_values(
    data: Mapping[str, Any], targets: Sequence[Target], values: Sequence[Any]
) -> dict[str, Any]:
    """A copy of ``data`` with each target's field set to its value (the seed target skipped)."""
    out = copy.deepcopy(dict(data))
    for target, value in zip(targets, values, strict=True):
        if target.keys is None:
            continue
        node: Any = out
        for key in target.keys[:-1]:
            node = node[key]
        node[target.keys[-1]] = value
    return out
