"""When TDOA Jacobians lose rank: the geometry seen from the target (corrects seed 000 §4.2.1).

For a connected set of agents ``1…m`` and a target at ``p``, the rows of the stacked TDOA Jacobian
are ``u_i − u_j`` over the edges, with ``u_i = (p − p_i)/‖p − p_i‖`` (eqs. 4.8–4.10). Because the
edges connect the set, their span equals ``span{u_i − u_1}``, so

    rank (stacked Jacobian) = dim aff{u_1, …, u_m}.

The ``u_i`` lie on the unit sphere, and an affine hyperplane meets the sphere in a circle, so the
Jacobian has rank ``< d`` **iff every agent lies on one circular cone with apex at the target**
(``n·u_i = c`` for a unit ``n``: the agents see the target under the same angle from the axis
``n``). The plane through the target (``c = 0``) is the degenerate cone. In the plane (``d = 2``)
the condition reads: the agents lie on at most two rays from the target.

The paper's wording "det Λ = 0 ⇔ the 4 agents are coplanar" is therefore wrong both ways:
coplanar agents with the target off their plane are generically fine (though the target's mirror
image in that plane gives the same measurements), and non-coplanar agents on such a cone are not.
Proof in ``docs/theory/tdoa-observability.md``; the exact test for rational coordinates is
:func:`exact_direction_rank` (:mod:`theory.tdoa.exact_geometry`, re-exported here).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from theory.core.exact import exact_decimal
from theory.core.observability import RANK_TOL, numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR
from theory.tdoa.exact_geometry import exact_affine_rank, exact_direction_rank
from theory.tdoa.model import unit_directions

__all__ = [
    "DirectionGeometry",
    "analyze_geometry",
    "direction_differences",
    "exact_affine_rank",
    "exact_direction_rank",
    "rational",
    "stacked_jacobian_position",
]


@dataclass(frozen=True)
class DirectionGeometry:
    """Rank of a connected set's stacked TDOA Jacobian and the paper's heuristic beside it.

    Attributes
    ----------
    n_agents, dim : int
        Size of the set and the space dimension.
    rank : int
        Float rank of ``[u_i − u_1]`` at ``rank_tol`` (evidence beside ``exact_rank``).
    exact_rank : int
        Exact rank of the stacked position Jacobian on the coordinates as written
        (:func:`exact_direction_rank`).
    full_rank : bool
        ``exact_rank == dim``: the target position is locally observable from this set.
    sigma_min : float
        The ``dim``-th singular value of ``[u_i − u_1]`` (0 if fewer rows).
    rank_tol, margin : float
        Relative rank tolerance and the factor by which the decision cleared it.
    conclusive : bool
        The exact rank is deficient (settled), or full with the float decision clearing its
        threshold by ``inconclusive_factor`` (full but ill-conditioned is inconclusive).
    agents_coplanar : bool
        The agents' own affine hull has dimension ``< dim`` (exact on the given coordinates).
    target_on_agents_plane : bool
        Agents coplanar and the target in their (affine) hull.
    heuristic_4_noncoplanar : bool
        The paper's condition: at least ``dim + 1`` agents, not coplanar.
    mirror_ambiguous : bool
        Agents coplanar, target off their plane: its mirror image gives the same TDOAs.
    cone_axis : tuple of float or None
        When rank-deficient (exactly or in floats): a unit ``n`` with ``n·u_i = c`` for all
        ``i`` (the axis).
    cone_cos : float or None
        That ``c`` (cosine of the half-angle; 0 for a plane through the target).
    """

    n_agents: int
    dim: int
    rank: int
    exact_rank: int
    full_rank: bool
    sigma_min: float
    rank_tol: float
    margin: float
    conclusive: bool
    agents_coplanar: bool
    target_on_agents_plane: bool
    heuristic_4_noncoplanar: bool
    mirror_ambiguous: bool
    cone_axis: tuple[float, ...] | None
    cone_cos: float | None


def direction_differences(target: np.ndarray, agents: np.ndarray) -> np.ndarray:
    """``[u_i − u_1]_{i ≥ 2}``: a basis-free stand-in for the stacked Jacobian of a connected set.

    Parameters
    ----------
    target : ndarray, shape (d,)
        Target position.
    agents : ndarray, shape (m, d)
        Agent positions (``m ≥ 1``).

    Returns
    -------
    ndarray, shape (m − 1, d)

    References
    ----------
    seed 000, eqs. (4.8)–(4.10), (4.41)–(4.42).
    """
    units = unit_directions(target, agents)
    return units[1:] - units[0]


def stacked_jacobian_position(
    target: np.ndarray, agents: np.ndarray, hears: np.ndarray
) -> np.ndarray:
    """Position block of all TDOA rows ``u_r − u_s`` for ``hears[r, s]`` (seed 000 eq. (4.7)).

    Parameters
    ----------
    target : ndarray, shape (d,)
        Target position.
    agents : ndarray, shape (m, d)
        Agent positions.
    hears : ndarray of bool, shape (m, m)
        ``hears[r, s]``: agent ``r`` measures the TDOA against agent ``s``.

    Returns
    -------
    ndarray, shape (number of pairs, d)
    """
    units = unit_directions(target, agents)
    pairs = np.argwhere(hears)
    return units[pairs[:, 0]] - units[pairs[:, 1]] if pairs.size else np.zeros((0, agents.shape[1]))


def rational(value: float | int | Fraction) -> Fraction:
    """The rational a user wrote (``0.1 → 1/10``): :func:`theory.core.exact.exact_decimal`.

    Parameters
    ----------
    value : float, int or Fraction
        A coordinate as parsed from a case file.

    Returns
    -------
    Fraction
    """
    return exact_decimal(value)


def analyze_geometry(
    target: np.ndarray,
    agents: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    inconclusive_factor: float = INCONCLUSIVE_FACTOR,
) -> DirectionGeometry:
    """Rank of a connected set's TDOA Jacobian at ``target``, with the paper's heuristic beside it.

    Parameters
    ----------
    target : ndarray, shape (d,)
        Target position.
    agents : ndarray, shape (m, d)
        Positions of a connected set of agents.
    rank_tol : float
        Relative rank tolerance (threshold ``rank_tol · σ_max``; ``σ_max ≤ 2`` here).
    inconclusive_factor : float
        A singular value within this factor of the threshold makes the verdict inconclusive.

    Returns
    -------
    DirectionGeometry

    References
    ----------
    seed 000, §4.2.1 (text after eq. 4.20) and Thm 4.2.3; ``docs/theory/tdoa-observability.md``.
    """
    target, agents = np.asarray(target, float), np.asarray(agents, float)
    m, dim = agents.shape
    D = direction_differences(target, agents)
    result = numeric_rank(D, rank_tol=rank_tol) if m > 1 else None
    rank = result.rank if result else 0
    exact = exact_direction_rank(target.tolist(), agents.tolist()) if m > 1 else 0
    sv = result.singular_values if result else ()
    coplanar = exact_affine_rank(agents.tolist()) < dim
    on_plane = coplanar and exact_affine_rank([*agents.tolist(), target.tolist()]) < dim
    axis, cos = _cone(target, agents) if min(rank, exact) < dim and m > 1 else (None, None)
    margin = result.margin if result else np.inf
    return DirectionGeometry(
        n_agents=m,
        dim=dim,
        rank=rank,
        exact_rank=exact,
        full_rank=exact == dim,
        sigma_min=float(sv[dim - 1]) if len(sv) >= dim else 0.0,
        rank_tol=rank_tol,
        margin=float(margin),
        conclusive=exact < dim or (rank == dim and bool(margin >= inconclusive_factor)),
        agents_coplanar=coplanar,
        target_on_agents_plane=on_plane,
        heuristic_4_noncoplanar=m >= dim + 1 and not coplanar,
        mirror_ambiguous=coplanar and not on_plane and m >= dim,
        cone_axis=axis,
        cone_cos=cos,
    )


def _cone(target: np.ndarray, agents: np.ndarray) -> tuple[tuple[float, ...], float]:
    """Unit ``n`` and ``c`` with ``n·u_i = c``: the null vector of ``[u_i, −1]``."""
    units = unit_directions(target, agents)
    _, _, vh = np.linalg.svd(np.hstack([units, -np.ones((len(units), 1))]))
    null = vh[-1]
    norm = np.linalg.norm(null[:-1])
    n, c = null[:-1] / norm, null[-1] / norm
    if c < 0:
        n, c = -n, -c
    return tuple(float(x) for x in n), float(c)
