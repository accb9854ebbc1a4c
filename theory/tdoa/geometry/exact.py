"""Exact TDOA geometry on the rational coordinates a case states: affine ranks, direction ranks,
mirror images. Nothing here has a tolerance.

* **coplanarity / collinearity** of agents: the rank of their rational differences
  (:func:`exact_affine_rank`, seed 000 Thm 4.2.3's "4 non-coplanar agents");
* **the rank of a connected set's stacked TDOA Jacobian** ``dim aff{u_i}``,
  ``u_i = (p_i − p)/‖p_i − p‖`` (seed 000 eqs. (4.8)–(4.10)): irrational entries, decided by
  :func:`exact_direction_rank` through sums of square roots of rationals
  (:func:`sqrt_sum_vanishes`);
* **the mirror image** of the target through the receivers' affine hull, a rational point
  (:func:`exact_mirror`).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from math import isqrt

from theory.core.exact import exact_decimal, fractions_of, to_fmpq

__all__ = [
    "exact_affine_rank",
    "exact_direction_rank",
    "exact_mirror",
    "rational_points",
    "same_ray_pair",
    "sqrt_sum_vanishes",
]

Number = float | int | Fraction
Point = Sequence[Number]


def rational_points(points: Sequence[Point]) -> list[list[Fraction]]:
    """Points read as the rationals written (``0.1 → 1/10``, :func:`exact_decimal`)."""
    return [[exact_decimal(x) for x in point] for point in points]


def _rref(rows: list[list[Fraction]], n_cols: int) -> tuple[list[int], list[list[Fraction]]]:
    """Pivot columns and rows of the reduced row echelon form of ``rows`` (python-flint)."""
    if not rows or n_cols == 0:
        return [], []
    reduced, rank = to_fmpq(rows).rref()
    echelon = fractions_of(reduced)[: int(rank)]
    return [next(c for c, x in enumerate(row) if x != 0) for row in echelon], echelon


def exact_affine_rank(points: Sequence[Point]) -> int:
    """Exact dimension of the affine hull of ``points`` (``-1`` for none, ``0`` for one): the
    rank of the differences ``p_i − p_0``, zero iff the orientation determinants vanish."""
    pts = rational_points(points)
    if not pts:
        return -1
    differences = [[x - y for x, y in zip(p, pts[0], strict=True)] for p in pts[1:]]
    return len(_rref(differences, len(pts[0]))[0])


def _rational_square_root(x: Fraction) -> Fraction | None:
    """``√x`` when it is rational (``x ≥ 0`` a square of a rational), else ``None``."""
    if x < 0:
        return None
    num, den = isqrt(x.numerator), isqrt(x.denominator)
    return Fraction(num, den) if num * num == x.numerator and den * den == x.denominator else None


def sqrt_sum_vanishes(terms: Sequence[tuple[Fraction, Fraction]]) -> bool:
    """Whether ``Σ_k c_k √q_k = 0`` exactly, for pairs ``(c_k, q_k)`` with ``q_k > 0``.

    Two roots ``√q``, ``√q'`` are rationally proportional iff ``q/q'`` is a rational square;
    group the terms into these classes and sum each on a representative. Roots of different
    classes are linearly independent over ℚ (Besicovitch 1940), so the sum vanishes iff every
    class's coefficient does. No integer is factored: each test is an integer square root.
    """
    classes: list[list[Fraction]] = []  # [representative q, accumulated coefficient]
    for c, q in terms:
        if c == 0:
            continue
        for entry in classes:
            ratio = _rational_square_root(q / entry[0])
            if ratio is not None:
                entry[1] += c * ratio
                break
        else:
            classes.append([q, c])
    return all(coefficient == 0 for _, coefficient in classes)


def exact_direction_rank(target: Point, agents: Sequence[Point]) -> int:
    """Exact ``dim aff{u_i}``, the rank of a connected set's stacked TDOA Jacobian (``0`` for one
    agent, ``-1`` for none; ``ValueError`` if an agent sits on the target).

    With ``v_i = p_i − p`` (rational) and ``r_i = ‖v_i‖``, scaling row ``i`` of ``[u_i, 1]`` by
    ``r_i > 0`` gives ``dim aff{u_i} = rank [V, r] − 1``, and ``rank [V, r] = rank V + 1`` unless
    ``n·r = 0`` for every ``n`` of the left kernel of ``V``. The echelon form of ``Vᵀ`` gives a
    kernel basis with ``rank V + 1`` non-zeros per vector, so each test is a sum of at most
    ``d + 1`` square roots (:func:`sqrt_sum_vanishes`). Seed 000 eqs. (4.8)–(4.10).
    """
    p = rational_points([target])[0]
    V = [[a - x for a, x in zip(agent, p, strict=True)] for agent in rational_points(agents)]
    if not V:
        return -1
    squared = [sum(x * x for x in v) for v in V]
    if 0 in squared:
        raise ValueError(f"agent {squared.index(0) + 1} is on the target")
    transposed = [[v[c] for v in V] for c in range(len(p))]
    pivots, reduced = _rref(transposed, len(V))
    basis = set(pivots)
    outside = any(
        not sqrt_sum_vanishes(
            [(Fraction(-1), squared[j])]
            + [(reduced[row][j], squared[b]) for row, b in enumerate(pivots)]
        )
        for j in range(len(V))
        if j not in basis
    )
    return len(pivots) + int(outside) - 1


def exact_mirror(points: Sequence[Point], target: Point) -> tuple[int, tuple[Fraction, ...] | None]:
    """The affine dimension of ``points`` (``-1`` for none) and the target's exact reflection
    through their hull (``None`` when the hull is full-dimensional or contains the target).

    The reflection ``p' = p − 2 n`` negates the target's offset ``n`` orthogonal to the hull, so
    every receiver is as far from ``p'`` as from ``p``: same ranges, same TDOAs (seed 000 §4.2.1).
    """
    pts, p = rational_points(points), rational_points([target])[0]
    dim = len(p)
    if not pts:
        return -1, None
    centre = pts[0]
    differences = [[x - y for x, y in zip(q, centre, strict=True)] for q in pts[1:]]
    pivots, hull = _rref(differences, dim)
    if len(pivots) == dim:
        return dim, None
    offset = [x - c for x, c in zip(p, centre, strict=True)]
    normal = _orthogonal_part(offset, hull)
    if not any(normal):
        return len(pivots), None
    return len(pivots), tuple(x - 2 * n for x, n in zip(p, normal, strict=True))


def _orthogonal_part(vector: list[Fraction], basis: list[list[Fraction]]) -> list[Fraction]:
    """``vector`` minus its orthogonal projection on the row space of ``basis`` (exact)."""
    if not basis:
        return list(vector)
    B = to_fmpq(basis)
    gram_inverse = (B * B.transpose()).inv()
    projection = fractions_of(B.transpose() * (gram_inverse * (B * to_fmpq([[x] for x in vector]))))
    return [vector[i] - projection[i][0] for i in range(len(vector))]


def same_ray_pair(target: Point, agents: Sequence[Point]) -> tuple[int, int] | None:
    """0-based ``a < b`` of the first two agents on one ray from the target, or ``None``:
    ``u_a = u_b`` iff ``v_a/‖v_a‖_∞ = v_b/‖v_b‖_∞`` for ``v = p_i − p`` (a rational key)."""
    p = rational_points([target])[0]
    seen: dict[tuple[Fraction, ...], int] = {}
    for index, agent in enumerate(rational_points(agents)):
        v = [a - x for a, x in zip(agent, p, strict=True)]
        top = max(abs(x) for x in v)
        key = tuple(x / top for x in v)
        if key in seen:
            return seen[key], index
        seen[key] = index
    return None
