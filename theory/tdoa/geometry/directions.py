"""When TDOA Jacobians lose rank: the geometry seen from the target (corrects seed 000 §4.2.1).

For a connected set of agents ``1…m`` and a target at ``p``, the rows of the stacked TDOA Jacobian
are ``u_i − u_j`` over the edges, ``u_i = (p − p_i)/‖p − p_i‖`` (eqs. (4.8)–(4.10)). The edges
connect the set, so their span equals ``span{u_i − u_1}`` and

    rank (stacked Jacobian) = dim aff{u_1, …, u_m}.

The ``u_i`` lie on the unit sphere, and an affine hyperplane meets the sphere in a circle, so the
Jacobian has rank ``< d`` **iff every agent lies on one circular cone with apex at the target**
(``n·u_i = c``: the agents see the target under the same angle from the axis ``n``; ``c = 0`` is
the plane through the target). In the plane: the agents lie on at most two rays from the target.

The paper's "det Λ = 0 ⇔ the 4 agents are coplanar" is therefore wrong both ways: coplanar agents
with the target off their plane are generically fine (though the target's mirror image gives the
same measurements), and non-coplanar agents on such a cone are not (claim
``seed000.sec4.2.1.coplanar``; proof in ``docs/theory/tdoa-observability.md``). The exact test is
:func:`~theory.tdoa.geometry.exact.exact_direction_rank`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, Status
from theory.core.network import components
from theory.core.observability import RANK_TOL, numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR
from theory.tdoa.case import TDOA, rank_tolerances
from theory.tdoa.geometry.exact import exact_affine_rank, exact_direction_rank
from theory.tdoa.model import unit_directions

__all__ = [
    "DirectionGeometry",
    "analyze_geometry",
    "claims",
    "coplanar_claim",
    "direction_differences",
]

claims = ClaimSet()


@dataclass(frozen=True)
class DirectionGeometry:
    """Rank of a connected set's stacked TDOA Jacobian and the paper's heuristic beside it.

    ``rank`` is the float rank of ``[u_i − u_1]`` at ``rank_tol`` (``sigma_min`` its ``d``-th
    singular value, ``margin`` how far the decision clears the threshold), ``exact_rank`` the
    exact one; ``conclusive`` unless the exact rank is full but the floats are within
    ``inconclusive_factor`` of losing it. ``agents_coplanar`` (exact), ``target_on_agents_plane``,
    ``heuristic_4_noncoplanar`` (≥ d + 1 agents, not coplanar) and ``mirror_ambiguous`` (coplanar,
    target off their plane) are beside it; when rank-deficient, ``cone_axis`` is a unit ``n``
    with ``n·u_i = cone_cos`` for all ``i``.
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
    """``[u_i − u_1]_{i ≥ 2}``: a stand-in for the stacked Jacobian of a connected set."""
    units = unit_directions(target, agents)
    return units[1:] - units[0]


def analyze_geometry(
    target: np.ndarray,
    agents: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    inconclusive_factor: float = INCONCLUSIVE_FACTOR,
) -> DirectionGeometry:
    """Rank of a connected set's TDOA Jacobian at ``target``, with the paper's heuristic beside
    it (seed 000 §4.2.1 after eq. (4.20), Thm 4.2.3)."""
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


@claims.register(
    "seed000.sec4.2.1.coplanar",
    source="seed 000, §4.2.1 after eq. (4.20); seed 001 (same wording)",
    statement="det Λ = 0 iff the 4 agents are coplanar.",
    kinds=("tdoa",),
)
def coplanar_claim(case: Case | None, ctx: Context) -> list[ClaimResult]:
    """Exact rank loss against coplanarity, per component and step (model: two bundled cases)."""
    if case is None:
        return [_coplanar_model()]
    return [_coplanar_step(case, k, **rank_tolerances(case)) for k in range(case.spec.steps)]


def _coplanar_step(case: Case, k: int, rank_tol: float, inconclusive_factor: float) -> ClaimResult:
    spec = case.spec
    agents, target = spec.agents[k], spec.target[k]
    rows, status = [], Status.VERIFIED
    for part in components(spec.hears[k]):
        geometry = analyze_geometry(
            target, agents[part], rank_tol=rank_tol, inconclusive_factor=inconclusive_factor
        )
        exact = exact_direction_rank(target.tolist(), agents[part].tolist())
        if len(part) < geometry.dim + 1:
            continue
        rows.append(
            {
                "agents": [i + 1 for i in part],
                "coplanar": geometry.agents_coplanar,
                "exact_rank": exact,
                "numeric_rank": geometry.rank,
                "sigma_min": geometry.sigma_min,
                "cone_axis": geometry.cone_axis,
                "cone_cos": geometry.cone_cos,
                "mirror_ambiguous": geometry.mirror_ambiguous,
            }
        )
        if (exact < geometry.dim) != geometry.agents_coplanar:
            status = Status.CORRECTED
    return ClaimResult(
        status,
        Method.EXACT,
        {"step": k + 1, "components": rows},
        tolerance={"rank_tol": rank_tol, "inconclusive_factor": inconclusive_factor},
        message=f"step {k + 1}: rank loss is decided by the cone condition (exact rank), "
        "not by the agents' coplanarity.",
    )


def _coplanar_model() -> ClaimResult:
    evidence = {}
    disagreements = 0
    for name in ("coplanar-agents-observable", "cone-agents-unobservable"):
        spec = TDOA.load_case(name).spec
        target, agents = spec.target[0], spec.agents[0]
        geometry = analyze_geometry(target, agents)
        exact = exact_direction_rank(target.tolist(), agents.tolist())
        disagreements += (exact < 3) != geometry.agents_coplanar
        evidence[name] = {
            "coplanar": geometry.agents_coplanar,
            "exact_rank": exact,
            "cone_cos": geometry.cone_cos,
        }
    evidence["corrected_statement"] = (
        "det Λ = 0 iff all agents lie on one circular cone with apex at the target "
        "(docs/theory/tdoa-observability.md, Theorem 2)"
    )
    return ClaimResult(
        Status.CORRECTED if disagreements == 2 else Status.REFUTED,
        Method.EXACT,
        evidence,
        message="Coplanar agents can be observable and non-coplanar agents unobservable; the "
        "exact condition is the cone through the agents with apex at the target.",
    )
