"""Exact TDOA geometry on rational coordinates: affine ranks, direction ranks, mirror images.

A case's coordinates are the decimals the user wrote
(:func:`theory.core.exact.exact_decimal`),
so every geometric predicate the topology verdicts rest on can be decided exactly:

* **coplanarity / collinearity** of agents — the rank of their rational differences
  (:func:`exact_affine_rank`, the orientation determinants of seed 000 Thm 4.2.3's "4
  non-coplanar agents");
* **the rank of a connected set's stacked TDOA Jacobian** ``dim aff{u_i}`` with
  ``u_i = (p_i − p)/‖p_i − p‖`` (seed 000 eqs. (4.8)–(4.10); :mod:`theory.tdoa.geometry`) —
  irrational entries, decided by :func:`exact_direction_rank` through sums of square roots of
  rationals (:func:`sqrt_sum_vanishes`);
* **the mirror image** of the target through the receivers' affine hull, a rational point
  (:func:`exact_mirror`).

Nothing here has a tolerance: the answers are exact for the rational points given.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from math import isqrt

import flint

from theory.core.exact import exact_decimal

__all__ = [
    "exact_affine_rank",
    "exact_direction_rank",
    "exact_mirror",
    "rational_points",
    "rational_square_root",
    "same_ray_pair",
    "sqrt_sum_vanishes",
]

Number = float | int | Fraction
Point = Sequence[Number]


def rational_points(points: Sequence[Point]) -> list[list[Fraction]]:
    """Points read as the rationals written (``0.1 → 1/10``, :func:`exact_decimal`).

    Parameters
    ----------
    points : sequence of sequences of float, int or Fraction
        Coordinates, one point per row.

    Returns
    -------
    list of list of Fraction
    """
    return [[exact_decimal(x) for x in point] for point in points]


def _fmpq_mat(rows: Sequence[Sequence[Fraction]], n_cols: int) -> flint.fmpq_mat:
    entries = [flint.fmpq(x.numerator, x.denominator) for row in rows for x in row]
    return flint.fmpq_mat(len(rows), n_cols, entries)


def _fraction(x: flint.fmpq) -> Fraction:
    return Fraction(int(x.p), int(x.q))


def _rref_columns(rows: Sequence[Sequence[Fraction]], n_cols: int) -> tuple[list[int], list]:
    """Pivot columns of the reduced row echelon form of ``rows`` and that form (flint)."""
    if not rows or n_cols == 0:
        return [], []
    reduced, rank = _fmpq_mat(rows, n_cols).rref()
    pivots, col = [], 0
    for r in range(int(rank)):
        while reduced[r, col] == 0:
            col += 1
        pivots.append(col)
    return pivots, reduced


def exact_affine_rank(points: Sequence[Point]) -> int:
    """Exact dimension of the affine hull of ``points`` (read as rationals).

    ``d + 1`` points in ``ℝ^d`` are affinely dependent (coplanar in 3-D, collinear in 2-D) iff
    their orientation determinant ``det[p_1 − p_0, …, p_d − p_0]`` vanishes; this is the rank of
    all differences ``p_i − p_0``, computed in exact rational arithmetic (python-flint).

    Parameters
    ----------
    points : sequence of sequences of float, int or Fraction
        The points.

    Returns
    -------
    int
        ``-1`` for no points, ``0`` for one.
    """
    pts = rational_points(points)
    if not pts:
        return -1
    differences = [[x - y for x, y in zip(p, pts[0], strict=True)] for p in pts[1:]]
    return len(_rref_columns(differences, len(pts[0]))[0])


def rational_square_root(x: Fraction) -> Fraction | None:
    """``√x`` when it is rational (``x ≥ 0`` a square of a rational), else ``None``."""
    if x < 0:
        return None
    num, den = isqrt(x.numerator), isqrt(x.denominator)
    return Fraction(num, den) if num * num == x.numerator and den * den == x.denominator else None


def sqrt_sum_vanishes(terms: Sequence[tuple[Fraction, Fraction]]) -> bool:
    """Whether ``Σ_k c_k √q_k = 0`` exactly, for rationals ``c_k`` and ``q_k > 0``.

    Two roots ``√q`` and ``√q'`` are rationally proportional iff ``q/q'`` is the square of a
    rational; group the terms into these classes (an equivalence) and sum each class on a
    representative. Square roots from different classes are linearly independent over ℚ
    (Besicovitch 1940), so the sum vanishes iff every class's coefficient does. No integer is
    factored: each test is an integer square root.

    Parameters
    ----------
    terms : sequence of (Fraction, Fraction)
        Pairs ``(c_k, q_k)`` with ``q_k > 0``.

    Returns
    -------
    bool
    """
    classes: list[list[Fraction]] = []  # [representative q, accumulated coefficient]
    for c, q in terms:
        if c == 0:
            continue
        for entry in classes:
            ratio = rational_square_root(q / entry[0])
            if ratio is not None:
                entry[1] += c * ratio
                break
        else:
            classes.append([q, c])
    return all(coefficient == 0 for _, coefficient in classes)


def exact_direction_rank(target: Point, agents: Sequence[Point]) -> int:
    """Exact ``dim aff{u_i}``: the rank of a connected set's stacked TDOA Jacobian.

    With ``v_i = p_i − p`` (rational) and ``r_i = ‖v_i‖``, scaling row ``i`` of ``[u_i, 1]`` by
    ``r_i > 0`` gives ``rank [u_i, 1] = rank [V, r]`` and ``dim aff{u_i} = rank [V, r] − 1``.
    ``rank [V, r] = rank V + 1`` unless ``r`` lies in the column space of the rational ``V``,
    i.e. unless ``n·r = 0`` for every vector ``n`` of the left kernel of ``V``. The reduced
    echelon form of ``Vᵀ`` gives a kernel basis with ``rank V + 1`` non-zeros per vector
    (``n_j = e_j − Σ_b λ_jb e_b`` over the pivot rows ``b``), so each test is a sum of at most
    ``d + 1`` square roots (:func:`sqrt_sum_vanishes`): ``O(N d²)`` rational operations.

    Parameters
    ----------
    target : sequence of float, int or Fraction
        Target position ``p`` (read as the decimal written).
    agents : sequence of sequences
        Agent positions, none on the target.

    Returns
    -------
    int
        ``dim aff{u_i}`` (``0`` for one agent, ``-1`` for none).

    Raises
    ------
    ValueError
        If an agent sits on the target.

    References
    ----------
    seed 000, eqs. (4.8)–(4.10); ``docs/theory/tdoa-observability.md``.
    """
    p = rational_points([target])[0]
    V = [[a - x for a, x in zip(agent, p, strict=True)] for agent in rational_points(agents)]
    if not V:
        return -1
    squared = [sum(x * x for x in v) for v in V]
    if 0 in squared:
        raise ValueError(f"agent {squared.index(0) + 1} is on the target")
    transposed = [[v[c] for v in V] for c in range(len(p))]
    pivots, reduced = _rref_columns(transposed, len(V))
    basis = set(pivots)
    outside = any(
        not sqrt_sum_vanishes(
            [(Fraction(-1), squared[j])]
            + [(_fraction(reduced[row, j]), squared[b]) for row, b in enumerate(pivots)]
        )
        for j in range(len(V))
        if j not in basis
    )
    return len(pivots) + int(outside) - 1


def exact_mirror(points: Sequence[Point], target: Point) -> tuple[int, tuple[Fraction, ...] | None]:
    """Affine dimension of ``points`` and the target's exact reflection through their hull.

    The reflection ``p' = p − 2 n`` negates the target's offset ``n`` orthogonal to the hull
    (``n = (p − c) − Π(p − c)`` with ``Π`` the orthogonal projection on the hull's directions,
    rational for rational data), so every receiver is as far from ``p'`` as from ``p``: same
    ranges, same TDOAs (seed 000 §4.2.1, DESIGN.md's mirror ambiguity).

    Parameters
    ----------
    points : sequence of sequences
        Receiver positions (read as rationals).
    target : sequence
        Target position.

    Returns
    -------
    (int, tuple of Fraction or None)
        The hull's dimension (``-1`` for no points) and the mirror point, ``None`` when the hull
        is full-dimensional or contains the target.
    """
    pts, p = rational_points(points), rational_points([target])[0]
    dim = len(p)
    if not pts:
        return -1, None
    centre = pts[0]
    differences = [[x - y for x, y in zip(q, centre, strict=True)] for q in pts[1:]]
    pivots, reduced = _rref_columns(differences, dim)
    if len(pivots) == dim:
        return dim, None
    offset = [x - c for x, c in zip(p, centre, strict=True)]
    hull = [[_fraction(reduced[r, c]) for c in range(dim)] for r in range(len(pivots))]
    normal = _orthogonal_part(offset, hull)
    if not any(normal):
        return len(pivots), None
    return len(pivots), tuple(x - 2 * n for x, n in zip(p, normal, strict=True))


def _orthogonal_part(vector: list[Fraction], basis: list[list[Fraction]]) -> list[Fraction]:
    """``vector`` minus its orthogonal projection on the row space of ``basis`` (exact)."""
    if not basis:
        return list(vector)
    dim = len(vector)
    B = _fmpq_mat(basis, dim)
    gram_inverse = (B * B.transpose()).inv()
    v = _fmpq_mat([[x] for x in vector], 1)
    projection = B.transpose() * (gram_inverse * (B * v))
    return [vector[i] - _fraction(projection[i, 0]) for i in range(dim)]


def same_ray_pair(target: Point, agents: Sequence[Point]) -> tuple[int, int] | None:
    """Two agents on one ray from the target (equal unit directions), exactly, or ``None``.

    ``u_a = u_b`` iff ``v_a / ‖v_a‖_∞ = v_b / ‖v_b‖_∞`` for ``v = p_i − p``: a rational key.

    Parameters
    ----------
    target : sequence
        Target position.
    agents : sequence of sequences
        Agent positions, none on the target.

    Returns
    -------
    (int, int) or None
        0-based indices ``a < b`` of the first such pair.
    """
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
