"""Validation of case data, in one place: the limits on the work an input may ask for, and the
field checks that turn raw values into clean data or a :class:`~theory.core.errors.CaseError`.

A request above a limit is refused *before* anything is allocated (exit 2), naming the field, the
limit and how to raise it. A limit ``name`` is read from ``TRACKCERT_MAX_<NAME>`` when set (a
positive integer), else its default (:data:`LIMITS`, documented in ``docs/cli.md``, *Limits*).
The defaults are far above every bundled case and far below what exhausts a workstation: they
refuse a runaway request in well under a second, not honest ones.

Each check takes the raw value and its dotted ``field`` name and returns clean data (numpy arrays
of ``float``, plain Python scalars) or raises a :class:`~theory.core.errors.CaseError` naming the
field, the expected form and what was found.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.errors import ENVIRONMENT, CaseError
from theory.core.network import near_pairs
from theory.core.tolerances import COINCIDENCE_TOL, WEIGHT_SUM_TOL

__all__ = [
    "LIMITS",
    "Limit",
    "bounded_coordinates",
    "check_count",
    "check_estimate",
    "check_keys",
    "check_length",
    "distinct_points",
    "finite_array",
    "finite_matrix",
    "finite_number",
    "finite_vector",
    "limit",
    "one_of",
    "positive_definite",
    "positive_int",
    "positive_number",
    "require",
    "row_stochastic",
]


@dataclass(frozen=True)
class Limit:
    """One named limit: its default, the ``unit`` it counts and what it ``bounds``."""

    name: str
    default: int
    unit: str
    bounds: str

    @property
    def env(self) -> str:
        """The environment variable overriding the default, ``TRACKCERT_MAX_<NAME>``."""
        return f"TRACKCERT_MAX_{self.name.upper()}"

    def value(self) -> int:
        """The limit in force: the environment's positive integer if set, else the default."""
        raw = os.environ.get(self.env)
        if raw is None or not raw.strip():
            return self.default
        text = raw.strip().replace("_", "")
        if not text.isdigit() or len(text) > 30 or int(text) < 1:
            raise CaseError(self.env, "a positive integer", raw, file=ENVIRONMENT)
        return int(text)

    def hint(self) -> str:
        """How to raise the limit, for error messages."""
        return f"Raise the limit with the environment variable {self.env}=N (docs/cli.md, Limits)."


LIMITS: dict[str, Limit] = {
    entry.name: entry
    for entry in (
        Limit("case_bytes", 1 << 20, "bytes", "the size of a case file (read no further)"),
        Limit(
            "yaml_depth",
            32,
            "levels",
            "the nesting depth of a case file's YAML (no RecursionError)",
        ),
        Limit(
            "yaml_nodes",
            1_000_000,
            "nodes",
            "the YAML nodes of a case file, counted with every alias expanded (alias bombs)",
        ),
        Limit("agents", 10_000, "agents", "agents or nodes of a tdoa, tdoa-sim, dkf or pf case"),
        Limit("trackers", 1_000, "trackers", "trackers of a pursuit case"),
        Limit(
            "particles", 1_000_000, "particles", "particles of each particle filter (pf.particles)"
        ),
        Limit("runs", 100_000, "runs", "Monte Carlo runs (pf.runs, --runs)"),
        Limit(
            "steps",
            1_000_000,
            "steps",
            "time steps: pings, target moves, 0.1 s steps, trajectory samples (steps, --steps)",
        ),
        Limit(
            "examples", 1_000_000, "examples", "the search budget of trackcert falsify (--examples)"
        ),
        Limit(
            "dkf_dimension",
            256,
            "rows",
            "N·n, the size of a dkf case's stacked error system (the LMIs' and operators' "
            "matrices)",
        ),
        Limit(
            "exponent",
            100,
            "decades",
            "the range of every number in a case: 0 or a magnitude between 10^-e and 10^e, so "
            "that the square or product of any two stays a normal float (no overflow to inf, no "
            "underflow to 0)",
        ),
        Limit(
            "coordinate",
            10**9,
            "m",
            "the magnitude of a position coordinate (agents, nodes, target), so that squared "
            "distances and Jacobians stay finite and meaningful in floating point",
        ),
        Limit(
            "memory_bytes",
            2 << 30,
            "bytes",
            "the estimated memory of the largest arrays a case asks for (each kind states its "
            "estimate)",
        ),
        Limit(
            "work",
            10**11,
            "elementary updates",
            "the estimated work of a run: runs × steps × (particles or agents) per filter",
        ),
    )
}
"""Name → :class:`Limit` (the table of ``docs/cli.md``, *Limits*)."""


def limit(name: str) -> int:
    """The value in force of the limit ``name`` (environment or default)."""
    return LIMITS[name].value()


def check_count(name: str, value: int, field: str, *, file: str | None = None) -> int:
    """``value``, refused (naming ``field``, the limit and how to raise it) above limit ``name``;
    ``file`` names where a request that is not a case field came from (``<command line>``)."""
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
    """Refuse a list longer than the limit ``name`` before its entries are read."""
    if isinstance(raw, list | tuple):
        check_count(name, len(raw), field)


def check_estimate(
    name: str, estimate: float, field: str, what: str, *, alternative: str = ""
) -> None:
    """Refuse an estimated memory or work (``what``: its formula) above the limit ``name``;
    ``alternative`` (a sentence) says how to ask for less instead of raising the limit."""
    entry = LIMITS[name]
    bound = entry.value()
    if estimate > bound:
        raise CaseError(
            field,
            f"a case within the limit '{name}' of {bound:.3g} {entry.unit}",
            f"an estimated {estimate:.3g} {entry.unit} ({what})",
            hint=f"{alternative} {entry.hint()}".strip(),
        )


def require(block: Mapping, key: str, prefix: str) -> object:
    """``block[key]``, or a :class:`CaseError` naming the missing field ``prefix.key``."""
    if key not in block:
        raise CaseError(_join(prefix, key), "a value (the field is required)", "nothing")
    return block[key]


def check_keys(block: object, allowed: Sequence[str], prefix: str) -> Mapping:
    """``block`` if it is a mapping whose keys are all in ``allowed`` (unknown fields are refused,
    never ignored)."""
    if not isinstance(block, Mapping):
        raise CaseError(prefix or "<top level>", "a mapping of fields", block)
    unknown = sorted(str(k) for k in block if k not in allowed)
    if unknown:
        raise CaseError(
            _join(prefix, unknown[0]),
            f"one of the known fields {sorted(allowed)}",
            f"unknown field {unknown[0]!r}",
            hint="Check the spelling; unknown fields are refused rather than ignored.",
        )
    return block


def one_of(value: object, choices: Sequence[str], field: str) -> str:
    """``value`` if it is a string among ``choices``."""
    if not isinstance(value, str) or value not in choices:
        raise CaseError(field, f"one of {list(choices)}", value)
    return value


def finite_number(value: object, field: str) -> float:
    """``value`` (an ``int`` or ``float``, not ``bool``) as a finite float, 0 or of a magnitude
    within the ``exponent`` limit."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise CaseError(field, "a number", value)
    problem = _number_problem(value, limit("exponent"))
    if problem:
        raise CaseError(field, problem, _shown(value), hint=_hint(problem))
    return float(value)


def positive_number(value: object, field: str, *, allow_zero: bool = False) -> float:
    """``value`` as a finite float > 0 (≥ 0 with ``allow_zero``)."""
    number = finite_number(value, field)
    if number < 0 or (number == 0 and not allow_zero):
        bound = "≥ 0" if allow_zero else "> 0"
        raise CaseError(field, f"a finite number {bound}", value)
    return number


def positive_int(value: object, field: str, *, minimum: int = 1) -> int:
    """``value`` as an integer ≥ ``minimum`` (``bool`` refused)."""
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise CaseError(field, f"an integer ≥ {minimum}", value)
    return value


def finite_matrix(
    value: object,
    field: str,
    *,
    rows: int | None = None,
    cols: int | None = None,
    allow_empty_rows: bool = False,
) -> np.ndarray:
    """``value`` (equal-length rows of numbers) as a 2-D float array, of ``rows`` × ``cols`` when
    given; ``allow_empty_rows`` reads ``[]`` as a 0 × ``cols`` matrix."""
    array = _numeric_array(value, field, "a matrix (list of equal-length rows of numbers)")
    if array.ndim == 1 and array.size == 0 and allow_empty_rows and cols is not None:
        array = array.reshape(0, cols)
    if array.ndim != 2:
        raise CaseError(field, "a matrix (list of equal-length rows of numbers)", value)
    expected_shape = (
        f"shape ({rows if rows is not None else 'n'}, {cols if cols is not None else 'm'})"
    )
    if (rows is not None and array.shape[0] != rows) or (
        cols is not None and array.shape[1] != cols
    ):
        raise CaseError(field, f"a matrix of {expected_shape}", f"shape {array.shape}")
    return array


def finite_array(value: object, field: str, expected: str, *, ndims: tuple[int, ...]) -> np.ndarray:
    """``value`` as a non-empty rectangular float array with ``ndim`` in ``ndims`` (``expected``
    says what a valid value looks like)."""
    array = _numeric_array(value, field, expected)
    if array.ndim not in ndims or array.size == 0:
        raise CaseError(field, expected, value)
    return array


def finite_vector(value: object, field: str, *, length: int | None = None) -> np.ndarray:
    """``value`` as a 1-D float array, of ``length`` entries when given."""
    array = _numeric_array(value, field, "a list of numbers")
    if array.ndim != 1:
        raise CaseError(field, "a list of numbers", value)
    if length is not None and array.shape[0] != length:
        raise CaseError(field, f"a list of {length} numbers", f"{array.shape[0]} numbers")
    return array


def row_stochastic(
    matrix: np.ndarray,
    field: str,
    *,
    tol: float = WEIGHT_SUM_TOL,
    support: np.ndarray | None = None,
) -> np.ndarray:
    """Check a square, non-negative, row-stochastic matrix with positive diagonal.

    Parameters
    ----------
    matrix : ndarray
        Candidate weight matrix ``W``.
    field : str
        Field name for messages.
    tol : float
        Absolute tolerance on each row sum (rows of ``W`` sum to 1 up to ``tol``).
    support : ndarray of bool, optional
        If given, the off-diagonal sparsity that ``W`` must have exactly (``w_ij > 0`` iff
        ``support[i, j]``), e.g. the adjacency of the case's ``edges``.
    """
    n = matrix.shape[0]
    if matrix.shape != (n, n):
        raise CaseError(field, "a square matrix", f"shape {matrix.shape}")
    negative = np.argwhere(matrix < 0)
    if negative.size:
        i, j = negative[0]
        raise CaseError(f"{field}[{i + 1}][{j + 1}]", "a non-negative weight", matrix[i, j])
    sums = matrix.sum(axis=1)
    bad = np.flatnonzero(np.abs(sums - 1.0) > tol)
    if bad.size:
        i = bad[0]
        expected = f"a row summing to 1 (tolerance {tol:g})"
        raise CaseError(f"{field}[{i + 1}]", expected, f"sum {float(sums[i])!r}")
    zero_diag = np.flatnonzero(np.diag(matrix) <= 0)
    if zero_diag.size:
        i = zero_diag[0]
        raise CaseError(f"{field}[{i + 1}][{i + 1}]", "a positive self-weight w_ii > 0", 0.0)
    if support is not None:
        off = ~np.eye(n, dtype=bool)
        mismatch = np.argwhere(off & ((matrix > 0) != support))
        if mismatch.size:
            i, j = mismatch[0]
            want = "w_ij > 0 (i and j are neighbours)" if support[i, j] else "w_ij = 0 (no edge)"
            raise CaseError(
                f"{field}[{i + 1}][{j + 1}]",
                want,
                matrix[i, j],
                hint="The weights' sparsity must match the communication edges.",
            )
    return matrix


def bounded_coordinates(points: np.ndarray, field: str) -> np.ndarray:
    """``points``, refused at the first coordinate (named by 1-based index) beyond the
    ``coordinate`` limit: squared distances and Jacobians must stay finite in floating point."""
    bound = limit("coordinate")
    beyond = np.argwhere(np.abs(points) > bound)
    if beyond.size:
        index = tuple(int(k) for k in beyond[0])
        where = field + "".join(f"[{k + 1}]" for k in index)
        raise CaseError(
            where,
            f"a coordinate of magnitude at most {bound:.3g} m (limit 'coordinate')",
            float(points[index]),
            hint=LIMITS["coordinate"].hint(),
        )
    return points


def distinct_points(
    points: np.ndarray, field: str, *, noun: str = "agent", where: str = "", why: str = ""
) -> np.ndarray:
    """``points``, refused when two coincide (seed 000 eq. (4.3): TDOA needs distinct receivers).

    Two points are one when their distance is at most ``coincidence_tol`` times their own
    magnitude (at least 1 m), so a far-away point does not make the others look coincident. The
    message names the later point of the first pair (a ``noun``), ``where`` and ``why``. Only
    pairs in neighbouring cells of a grid are compared (:func:`theory.core.network.near_pairs`).
    """
    size = np.maximum(1.0, np.abs(points).max(axis=1, initial=0.0))
    reach = COINCIDENCE_TOL * float(size.max(initial=1.0))
    first: tuple[int, int] | None = None
    for i, j in near_pairs(points, reach):
        gaps = np.linalg.norm(points[i] - points[j], axis=-1)
        close = np.flatnonzero(gaps <= COINCIDENCE_TOL * np.maximum(size[i], size[j]))
        pairs = sorted(zip(i[close].tolist(), j[close].tolist(), strict=True))[:1]
        first = min([*pairs, *([first] if first else [])], default=None)
    if first is not None:
        i, j = first
        raise CaseError(
            f"{field}[{j + 1}]",
            f"a position distinct from {noun} {i + 1}'s{where}{why}",
            points[j].tolist(),
        )
    return points


def positive_definite(matrix: np.ndarray, field: str, *, rel_tol: float = 1e-12) -> np.ndarray:
    """``matrix`` if symmetric positive definite: λ_min > ``rel_tol`` · max|m_ij| (scale at
    least 1), symmetry to 10³ times that."""
    n = matrix.shape[0]
    if matrix.shape != (n, n):
        raise CaseError(field, "a square matrix", f"shape {matrix.shape}")
    scale = max(float(np.max(np.abs(matrix))), 1.0) if matrix.size else 1.0
    if not np.allclose(matrix, matrix.T, rtol=0, atol=rel_tol * scale * 1e3):
        raise CaseError(field, "a symmetric matrix", matrix.tolist())
    if n and float(np.linalg.eigvalsh(matrix).min()) <= rel_tol * scale:
        raise CaseError(field, "a positive-definite matrix", matrix.tolist())
    return matrix


def _numeric_array(value: object, field: str, expected: str) -> np.ndarray:
    if isinstance(value, str | bytes | Mapping) or not isinstance(
        value, list | tuple | int | float
    ):
        raise CaseError(field, expected, value)
    _check_leaves(value, field, expected)
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise CaseError(field, expected, value) from None
    return array


def _check_leaves(value: object, field: str, expected: str) -> None:
    """Refuse the first entry (depth first, by 1-based index) that is no usable number; iterative,
    so it neither recurses nor converts anything before the whole value is checked."""
    stack: list[tuple[object, str]] = [(value, field)]
    decades = limit("exponent")
    while stack:
        item, where = stack.pop()
        if isinstance(item, list | tuple):
            stack.extend(
                (entry, f"{where}[{k + 1}]") for k, entry in reversed(list(enumerate(item)))
            )
        elif isinstance(item, bool) or not isinstance(item, int | float):
            raise CaseError(where, f"a number (the field is {expected})", item)
        else:
            problem = _number_problem(item, decades)
            if problem:
                raise CaseError(where, problem, _shown(item), hint=_hint(problem))


def _number_problem(value: int | float, decades: int) -> str:
    """Why the number ``value`` is unusable, or ``""`` (finite, 0 or within ``10^±decades``)."""
    if isinstance(value, int) and abs(value) > _FLOAT_MAX:
        return f"a finite number (|x| ≤ {_FLOAT_MAX:.3g})"
    if isinstance(value, float) and not math.isfinite(value):
        return "a finite number (no NaN or inf)"
    low, high = 10.0 ** -min(decades, 323), 10.0 ** min(decades, 308)
    if value != 0 and not low <= abs(value) <= high:
        return (
            f"0 or a number of magnitude between 1e-{decades} and 1e+{decades} (limit 'exponent')"
        )
    return ""


def _hint(problem: str) -> str:
    return LIMITS["exponent"].hint() if "limit 'exponent'" in problem else ""


def _shown(value: int | float) -> object:
    """``value``, or a description when it is an integer too long to print."""
    if isinstance(value, int) and abs(value) > _FLOAT_MAX:
        return f"an integer of about 10^{int(value.bit_length() * math.log10(2))}"
    return value


_FLOAT_MAX = sys.float_info.max


def _join(prefix: str, key: str) -> str:
    return f"{prefix}.{key}" if prefix else key
