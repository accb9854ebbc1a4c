"""Dotted paths into a case's data: which field a ``--param`` sweeps, and setting it.

A path names a numeric field of the case file by its keys and list indices, separated by dots:
``k_gamma``, ``trackers.0.r_x``, ``W.0.1``, ``target.velocity.1``. It is looked up first inside
the kind's block (so ``k_gamma`` means ``pursuit.k_gamma`` in a pursuit case) and then from the
top of the file (``pursuit.k_gamma`` works too). Indices are 0-based, as in the YAML lists.

``seed`` is special: when the case has no field of that name (a pursuit or dkf case), it is the
simulation's root seed, as ``trackcert simulate --seed``; when it has one (``pf.seed``), the
field is swept.

Only fields that exist and hold a number (an integer or a float, not a boolean) can be swept:
anything else is refused up front (exit 2) with the fields that do exist at that level.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from theory.core.errors import CaseError

__all__ = ["SEED", "Target", "apply_values", "resolve_target"]

SEED = "seed"
"""The path that, when the case has no such field, sets the simulation's root seed."""

Key = str | int


@dataclass(frozen=True)
class Target:
    """Where one swept path lands.

    Attributes
    ----------
    path : str
        The path as written.
    keys : tuple of str or int, or None
        The keys from the top of the case data; ``None`` for the simulation seed.
    """

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


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def resolve_target(data: Mapping[str, Any], kind: str, path: str, *, file: str) -> Target:
    """Where ``path`` lands in a case's data (module docstring).

    Parameters
    ----------
    data : mapping
        The case file's parsed YAML.
    kind : str
        The case's kind (its block is searched first).
    path : str
        A dotted path.
    file : str
        The case file, named in errors.

    Returns
    -------
    Target

    Raises
    ------
    CaseError
        Field ``--param PATH`` when the path does not exist (listing the fields that exist
        where the lookup stopped) or does not hold a number.
    """
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
    if _is_number(value):
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
    """A copy of ``data`` with each target's field set to its value (the seed target skipped).

    Parameters
    ----------
    data : mapping
        The case file's parsed YAML (not modified).
    targets : sequence of Target
        From :func:`resolve_target`.
    values : sequence
        One value per target.

    Returns
    -------
    dict
    """
    out = copy.deepcopy(dict(data))
    for target, value in zip(targets, values, strict=True):
        if target.keys is None:
            continue
        node: Any = out
        for key in target.keys[:-1]:
            node = node[key]
        node[target.keys[-1]] = value
    return out
