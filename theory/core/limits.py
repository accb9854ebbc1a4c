"""Every limit on the work one input may ask for: its default, what it bounds, how to raise it.

A case file or a command-line option that asks for more than a limit is refused *before*
anything is allocated (:class:`~theory.core.errors.CaseError`, exit 2) with a message naming the
field, the limit and how to raise it. Each limit ``name`` is read from the environment variable
``TRACKCERT_MAX_<NAME>`` when it is set (a positive integer), otherwise it is the default below.
:data:`LIMITS` is the table (``docs/cli.md``, *Limits*), :func:`table` its plain-data form.

The defaults are far above every bundled case (the largest bundled case uses at most a few
percent of each) and far below what exhausts a workstation: the point is to refuse a runaway
request in well under a second, not to police honest ones.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

from theory.core.errors import CaseError

__all__ = [
    "LIMITS",
    "Limit",
    "check_count",
    "check_estimate",
    "check_length",
    "limit",
    "table",
]


@dataclass(frozen=True)
class Limit:
    """One named limit.

    Attributes
    ----------
    name : str
        Its name, e.g. ``agents``; the environment variable is ``TRACKCERT_MAX_AGENTS``.
    default : int
        The value used when the environment does not set it.
    unit : str
        What it counts (``agents``, ``bytes``, …).
    bounds : str
        What it bounds, in one sentence.
    """

    name: str
    default: int
    unit: str
    bounds: str

    @property
    def env(self) -> str:
        """The environment variable overriding the default, ``TRACKCERT_MAX_<NAME>``."""
        return f"TRACKCERT_MAX_{self.name.upper()}"

    def value(self) -> int:
        """The limit in force: the environment's value if set, else :attr:`default`.

        Raises
        ------
        CaseError
            If the environment variable is set to something other than a positive integer.
        """
        raw = os.environ.get(self.env)
        if raw is None or not raw.strip():
            return self.default
        text = raw.strip().replace("_", "")
        if not text.isdigit() or len(text) > 30 or int(text) < 1:
            raise CaseError(self.env, "a positive integer", raw, file="<environment>")
        return int(text)

    def hint(self) -> str:
        """How to raise the limit, for error messages."""
        return f"Raise the limit with the environment variable {self.env}=N (docs/cli.md, Limits)."


LIMITS: dict[str, Limit] = {}
"""Name → :class:`Limit`, in the order defined below."""


def _limit(name: str, default: int, unit: str, bounds: str) -> None:
    LIMITS[name] = Limit(name, default, unit, bounds)


_limit("case_bytes", 1 << 20, "bytes", "the size of a case file (read no further)")
_limit("yaml_depth", 32, "levels", "the nesting depth of a case file's YAML (no RecursionError)")
_limit(
    "yaml_nodes",
    1_000_000,
    "nodes",
    "the YAML nodes of a case file, counted with every alias expanded (alias bombs)",
)
_limit("agents", 1_000, "agents", "agents or nodes of a tdoa, tdoa-sim, dkf or pf case")
_limit("trackers", 1_000, "trackers", "trackers of a pursuit case")
_limit("particles", 1_000_000, "particles", "particles of each particle filter (pf.particles)")
_limit("runs", 100_000, "runs", "Monte Carlo runs (pf.runs, --runs)")
_limit(
    "steps",
    1_000_000,
    "steps",
    "time steps: pings, target moves, 0.1 s steps, trajectory samples (steps, --steps)",
)
_limit("examples", 1_000_000, "examples", "the search budget of trackcert falsify (--examples)")
_limit(
    "dkf_dimension",
    256,
    "rows",
    "N·n, the size of a dkf case's stacked error system (the LMIs' and operators' matrices)",
)
_limit(
    "exponent",
    100,
    "decades",
    "the range of every number in a case: 0 or a magnitude between 10^-e and 10^e, so that the "
    "square or product of any two stays a normal float (no overflow to inf, no underflow to 0)",
)
_limit(
    "coordinate",
    10**9,
    "m",
    "the magnitude of a position coordinate (agents, nodes, target), so that squared distances "
    "and Jacobians stay finite and meaningful in floating point",
)
_limit(
    "memory_bytes",
    2 << 30,
    "bytes",
    "the estimated memory of the largest arrays a case asks for (each kind states its estimate)",
)
_limit(
    "work",
    10**11,
    "elementary updates",
    "the estimated work of a run: runs × steps × (particles or agents) per filter",
)


def limit(name: str) -> int:
    """The value in force of the limit ``name`` (environment or default).

    Parameters
    ----------
    name : str
        A key of :data:`LIMITS`.

    Returns
    -------
    int
    """
    return LIMITS[name].value()


def check_count(name: str, value: int, field: str, *, file: str | None = None) -> int:
    """Refuse ``value`` if it exceeds the limit ``name``.

    Parameters
    ----------
    name : str
        A key of :data:`LIMITS`.
    value : int
        The requested count (already checked to be an integer).
    field : str
        The case field or command-line option that asked for it (``pf.particles``, ``--runs``).
    file : str, optional
        Where the request came from, when it is not a case file (``<command line>``).

    Returns
    -------
    int
        ``value``.

    Raises
    ------
    CaseError
        Naming ``field``, the limit and how to raise it.
    """
    entry = LIMITS[name]
    bound = entry.value()
    if value > bound:
        where = {} if file is None else {"file": file}
        raise CaseError(
            field,
            f"at most {bound:,} {entry.unit} (limit '{name}': {entry.bounds})",
            value,
            hint=entry.hint(),
            **where,
        )
    return value


def check_length(raw: Any, name: str, field: str) -> None:
    """Refuse a list whose length exceeds the limit ``name`` (before its entries are read).

    Parameters
    ----------
    raw : object
        The raw value; anything but a sized list or tuple is left to the field's own validation.
    name : str
        A key of :data:`LIMITS`.
    field : str
        The case field holding the list.

    Raises
    ------
    CaseError
        Naming ``field``, its length, the limit and how to raise it.
    """
    if isinstance(raw, list | tuple):
        check_count(name, len(raw), field)


def check_estimate(name: str, estimate: float, field: str, what: str) -> None:
    """Refuse a request whose estimated memory or work exceeds the limit ``name``.

    Parameters
    ----------
    name : str
        ``memory_bytes`` or ``work``.
    estimate : float
        The estimate (bytes or elementary updates).
    field : str
        The field that asked for the most (named in the message).
    what : str
        How the estimate was computed, e.g. ``"filters × particles × 48 B"``.

    Raises
    ------
    CaseError
        Naming ``field``, the estimate, its formula, the limit and how to raise it.
    """
    entry = LIMITS[name]
    bound = entry.value()
    if estimate > bound:
        raise CaseError(
            field,
            f"a case within the limit '{name}' of {bound:.3g} {entry.unit}",
            f"an estimated {estimate:.3g} {entry.unit} ({what})",
            hint=entry.hint(),
        )


def table() -> list[dict[str, Any]]:
    """The limits as plain data (name, default, value in force, unit, bounds, env).

    Returns
    -------
    list of dict
    """
    return [
        {
            "name": entry.name,
            "default": entry.default,
            "value": entry.value(),
            "unit": entry.unit,
            "bounds": entry.bounds,
            "env": entry.env,
        }
        for entry in LIMITS.values()
    ]
