"""Validation of plain data from case files, in one place (STYLE.md, *Adopt* 5).

Each function takes the raw value and its dotted ``field`` name and either returns clean data
(numpy arrays of ``float``, plain Python scalars) or raises :class:`~theory.core.errors.CaseError`
naming the field, the expected form and what was found.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping, Sequence

import numpy as np

from theory.core.errors import CaseError
from theory.core.limits import LIMITS, limit
from theory.core.tolerances import COINCIDENCE_TOL, WEIGHT_SUM_TOL

__all__ = [
    "bounded_coordinates",
    "check_keys",
    "distinct_points",
    "finite_array",
    "finite_matrix",
    "finite_number",
    "finite_vector",
    "one_of",
    "positive_definite",
    "positive_int",
    "positive_number",
    "require",
    "row_stochastic",
]


def require(block: Mapping, key: str, prefix: str) -> object:
    """Return ``block[key]`` or raise naming the missing field ``prefix.key``.

    Parameters
    ----------
    block : Mapping
        The parsed block that should hold ``key``.
    key : str
        The required field.
    prefix : str
        Dotted name of ``block`` (empty at the top level, when the field is named ``key``).

    Returns
    -------
    object
        ``block[key]``, unchecked.

    Raises
    ------
    CaseError
        If ``key`` is not in ``block``.
    """
    if key not in block:
        raise CaseError(_join(prefix, key), "a value (the field is required)", "nothing")
    return block[key]


def check_keys(block: object, allowed: Sequence[str], prefix: str) -> Mapping:
    """Ensure ``block`` is a mapping whose keys are all in ``allowed``.

    Parameters
    ----------
    block : object
        The raw value of the block.
    allowed : Sequence of str
        The known field names; any other key is refused rather than ignored.
    prefix : str
        Dotted name of ``block`` in error messages (empty at the top level).

    Returns
    -------
    Mapping
        ``block`` itself.

    Raises
    ------
    CaseError
        If ``block`` is not a mapping, or naming the first unknown field (sorted) otherwise.
    """
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
    """Return ``value`` if it is one of ``choices``.

    Parameters
    ----------
    value : object
        The raw value.
    choices : Sequence of str
        The accepted strings.
    field : str
        Dotted field name for messages.

    Returns
    -------
    str
        ``value``.

    Raises
    ------
    CaseError
        If ``value`` is not a string among ``choices``.
    """
    if not isinstance(value, str) or value not in choices:
        raise CaseError(field, f"one of {list(choices)}", value)
    return value


def finite_number(value: object, field: str) -> float:
    """``value`` as a finite float (an ``int`` or ``float``; ``bool`` is refused).

    Parameters
    ----------
    value : object
        The raw value.
    field : str
        Dotted field name for messages.

    Returns
    -------
    float

    Raises
    ------
    CaseError
        If ``value`` is not a number, is NaN or infinite, is an integer beyond the range of a
        float (no ``OverflowError``), or is neither 0 nor of a magnitude within the ``exponent``
        limit (:mod:`theory.core.limits`).
    """
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise CaseError(field, "a number", value)
    problem = _number_problem(value, limit("exponent"))
    if problem:
        raise CaseError(field, problem, _shown(value), hint=_hint(problem))
    return float(value)


def positive_number(value: object, field: str, *, allow_zero: bool = False) -> float:
    """``value`` as a finite real number > 0 (or ≥ 0 with ``allow_zero``).

    Parameters
    ----------
    value : object
        The raw value; an ``int`` or ``float`` (``bool`` is refused).
    field : str
        Dotted field name for messages.
    allow_zero : bool
        Accept 0 as well (the bound becomes ≥ 0).

    Returns
    -------
    float

    Raises
    ------
    CaseError
        If ``value`` is not a number, or is not finite, or is out of bounds.
    """
    number = finite_number(value, field)
    if number < 0 or (number == 0 and not allow_zero):
        bound = "≥ 0" if allow_zero else "> 0"
        raise CaseError(field, f"a finite number {bound}", value)
    return number


def positive_int(value: object, field: str, *, minimum: int = 1) -> int:
    """``value`` as an integer ≥ ``minimum``.

    Parameters
    ----------
    value : object
        The raw value; an ``int`` (``bool`` is refused).
    field : str
        Dotted field name for messages.
    minimum : int
        The least accepted value.

    Returns
    -------
    int
        ``value``.

    Raises
    ------
    CaseError
        If ``value`` is not an integer or is below ``minimum``.
    """
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
    """``value`` as a 2-D array of finite reals.

    Parameters
    ----------
    value : object
        The raw value: a list of equal-length rows of numbers.
    field : str
        Dotted field name for messages.
    rows : int, optional
        Required number of rows; any when not given.
    cols : int, optional
        Required number of columns; any when not given.
    allow_empty_rows : bool
        Accept ``[]`` as a ``0 × cols`` matrix (only when ``cols`` is given).

    Returns
    -------
    ndarray of float, shape (rows, cols)

    Raises
    ------
    CaseError
        If ``value`` is not a matrix of finite numbers, or has the wrong shape.
    """
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
    """``value`` as a rectangular array of finite reals with a number of axes in ``ndims``.

    Parameters
    ----------
    value : object
        The raw value: nested lists of numbers.
    field : str
        Dotted field name for messages.
    expected : str
        What a valid value looks like, as said in messages.
    ndims : tuple of int
        The accepted numbers of axes.

    Returns
    -------
    ndarray of float
        Non-empty, with ``ndim`` in ``ndims``.

    Raises
    ------
    CaseError
        If ``value`` is not a rectangular array of finite numbers, is empty, or has a number of
        axes not in ``ndims``.
    """
    array = _numeric_array(value, field, expected)
    if array.ndim not in ndims or array.size == 0:
        raise CaseError(field, expected, value)
    return array


def finite_vector(value: object, field: str, *, length: int | None = None) -> np.ndarray:
    """``value`` as a 1-D array of finite reals, of ``length`` if given.

    Parameters
    ----------
    value : object
        The raw value: a list of numbers.
    field : str
        Dotted field name for messages.
    length : int, optional
        Required number of entries; any when not given.

    Returns
    -------
    ndarray of float, shape (length,)

    Raises
    ------
    CaseError
        If ``value`` is not a list of finite numbers, or has the wrong length.
    """
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
    """Refuse a coordinate beyond the ``coordinate`` limit (:mod:`theory.core.limits`).

    Squared distances, Jacobians and Gram matrices of the geometry must stay finite and
    meaningful in floating point; a point at ``1e308`` would overflow them and make every other
    point look coincident. The first offending entry is named by its 1-based index (the agent).

    Parameters
    ----------
    points : ndarray
        Coordinates (any shape; indices in messages follow it).
    field : str
        Dotted field name for messages.

    Returns
    -------
    ndarray
        ``points`` itself.

    Raises
    ------
    CaseError
        Naming the entry, the limit and how to raise it.
    """
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
    """Refuse two of ``points`` that coincide (seed 000 eq. (4.3): TDOA needs distinct receivers).

    Two points are one when their distance is at most ``coincidence_tol`` times their own
    magnitude (at least 1 m): the resolution of those two coordinates, so a far-away point does
    not make the others look coincident. The later point of the first coincident pair is named.

    Parameters
    ----------
    points : ndarray, shape (N, dim)
        Positions.
    field : str
        Dotted field name of the list of positions.
    noun : str
        What a point is, in messages (``agent``, ``node``).
    where : str
        Appended to the message, e.g. ``" at step 3"``.
    why : str
        Appended to the message: why coincident points are refused.

    Returns
    -------
    ndarray
        ``points`` itself.

    Raises
    ------
    CaseError
        Naming the later point of the first coincident pair and the earlier one.
    """
    gaps = np.linalg.norm(points[:, None] - points[None], axis=-1)
    size = np.maximum(1.0, np.abs(points).max(axis=1))
    close = gaps <= COINCIDENCE_TOL * np.maximum(size[:, None], size[None])
    close &= np.triu(np.ones_like(close), k=1)
    if close.any():
        i, j = (int(k) for k in np.argwhere(close)[0])
        raise CaseError(
            f"{field}[{j + 1}]",
            f"a position distinct from {noun} {i + 1}'s{where}{why}",
            points[j].tolist(),
        )
    return points


def positive_definite(matrix: np.ndarray, field: str, *, rel_tol: float = 1e-12) -> np.ndarray:
    """Check that ``matrix`` is symmetric positive definite.

    Parameters
    ----------
    matrix : ndarray
        Candidate matrix ``M``.
    field : str
        Dotted field name for messages.
    rel_tol : float
        Relative tolerance, scale-aware: λ_min must exceed ``rel_tol · max|m_ij|`` (the scale
        ``max|m_ij|`` is taken as at least 1); symmetry is checked to ``10³`` times that.

    Returns
    -------
    ndarray
        ``matrix`` itself.

    Raises
    ------
    CaseError
        If ``matrix`` is not square, not symmetric or not positive definite.
    """
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
    """Refuse the first entry (depth first, named by its 1-based index) that is no finite number.

    Iterative, so it neither recurses nor converts anything before the whole value is known
    to be nested lists of finite numbers.
    """
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
