"""Global uniqueness of a TDOA fix: every position with the same range differences (exact algebra).

A set of receivers ``q_1, …, q_n`` measures the range differences ``δ_j = r_j − r_1`` with
``r_j = ‖p − q_j‖``. Local observability (a full-rank Jacobian) says the target is an isolated
solution; it does not say it is the only one. This module finds all of them.

Method (spherical intersection, exact reformulation): with ``q_1`` moved to the origin, every
solution ``(x, r)`` with ``r = ‖x‖`` satisfies the linear equations

.. math:: 2 q_j^\\top x + 2 δ_j r = ‖q_j‖^2 − δ_j^2, \\qquad j = 2, …, n,

and conversely any ``(x, r)`` on that affine set with ``‖x‖^2 = r^2``, ``r ≥ 0`` and
``r + δ_j ≥ 0`` reproduces every measured difference (subtract the squared range equations). So
the solution set is an affine space intersected with a quadric cone. With ``f`` free directions
in the affine space: ``f = 0`` gives one point (unique); ``f = 1`` a quadratic with at most two
roots (e.g. four non-coplanar receivers in 3-D, three in 2-D, or a mirror pair for coplanar
receivers); ``f ≥ 2`` is not decided here (reported as ``None``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.core.observability import RANK_TOL, numeric_rank
from theory.core.tolerances import UNIQUENESS_TOL
from theory.tdoa.model import ranges

__all__ = ["METHOD", "Uniqueness", "tdoa_solutions"]

METHOD = "spherical intersection: linear system in (p, r_1) + quadric r_1 = ‖p − q_1‖"


@dataclass(frozen=True)
class Uniqueness:
    """All positions consistent with the TDOAs a receiver set measures.

    ``unique`` is True (only the target), False (another solution, or infinitely many) or None
    (``free_dims ≥ 2``: not decided); ``solutions`` lists the others found; ``note`` explains."""

    unique: bool | None
    solutions: tuple[tuple[float, ...], ...]
    free_dims: int
    note: str
    method: str = METHOD
    tol: float = UNIQUENESS_TOL


def tdoa_solutions(
    receivers: np.ndarray,
    target: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    tol: float = UNIQUENESS_TOL,
) -> Uniqueness:
    """Every position giving the same noise-free TDOAs as ``target`` to ``receivers`` (one
    component); ``tol`` is relative to the scene's size (seed 000 eq. (4.4); seed 002 §4.3.3)."""
    receivers, target = np.asarray(receivers, float), np.asarray(target, float)
    n, d = receivers.shape
    if n < 2:
        return Uniqueness(False, (), d, "no TDOA measurement: every position is consistent")
    origin = receivers[0]
    scale = float(max(np.abs(receivers - origin).max(), np.abs(target - origin).max()))
    q, t = (receivers - origin) / scale, (target - origin) / scale
    delta, L, b = _linear_system(q, t)
    rank = numeric_rank(L, rank_tol=rank_tol).rank
    _, _, vt = np.linalg.svd(L, full_matrices=L.shape[0] < L.shape[1])
    u0 = np.linalg.lstsq(L, b, rcond=None)[0]
    free = vt[rank:]
    if free.shape[0] == 0:
        return Uniqueness(True, (), 0, "the linear equations fix the position: unique")
    if free.shape[0] >= 2:
        note = f"{free.shape[0]} free directions: a conic/quadric family, not decided here"
        return Uniqueness(None, (), free.shape[0], note)
    candidates = _line_roots(u0, free[0], tol)
    if candidates is None:
        return Uniqueness(False, (), 1, "a whole line of solutions: infinitely many positions")
    others = [
        x
        for x in candidates
        if _consistent(x, q, delta, tol) and np.linalg.norm(x[:-1] - t) > tol * 10
    ]
    points = tuple(tuple(float(v) for v in origin + scale * x) for x in _distinct(others, tol))
    if not points:
        return Uniqueness(True, (), 1, "the second root of the quadratic is not a valid position")
    return Uniqueness(False, points, 1, f"{len(points)} other position(s) give the same TDOAs")


def _linear_system(q: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Range differences ``δ_j = ‖t − q_j‖ − ‖t − q_0‖`` and the linear system ``L [x; r₀] = b``
    they impose on a position ``x`` with range ``r₀`` to receiver 0 (at the origin)."""
    distances = ranges(t, q)
    delta = distances[1:] - distances[0]
    L = 2.0 * np.hstack([q[1:], delta[:, None]])
    b = (q[1:] ** 2).sum(axis=1) - delta**2
    return delta, L, b


def _line_roots(u0: np.ndarray, direction: np.ndarray, tol: float) -> list[np.ndarray] | None:
    """Points ``u0 + τ·direction`` on the cone ``‖x‖² = r²``; ``None`` if the whole line is."""
    xp, xr, np_, nr = u0[:-1], u0[-1], direction[:-1], direction[-1]
    a = float(np_ @ np_ - nr**2)
    b = float(2 * (xp @ np_ - xr * nr))
    c = float(xp @ xp - xr**2)
    if max(abs(a), abs(b)) <= tol:
        return None if abs(c) <= tol else []
    if abs(a) <= tol:
        roots = [-c / b]
    else:
        disc = b * b - 4 * a * c
        if disc < -tol:
            return []
        root = np.sqrt(max(disc, 0.0))
        roots = [(-b - root) / (2 * a), (-b + root) / (2 * a)]
    return [u0 + tau * direction for tau in roots]


def _consistent(u: np.ndarray, q: np.ndarray, delta: np.ndarray, tol: float) -> bool:
    """Whether ``u = (x, r)`` reproduces every range difference (re-checked from scratch)."""
    distances = ranges(u[:-1], q)
    return bool(np.max(np.abs((distances[1:] - distances[0]) - delta), initial=0.0) <= tol)


def _distinct(points: list[np.ndarray], tol: float) -> list[np.ndarray]:
    out: list[np.ndarray] = []
    for point in points:
        if all(np.linalg.norm(point[:-1] - seen[:-1]) > tol * 10 for seen in out):
            out.append(point)
    return [p[:-1] for p in out]
