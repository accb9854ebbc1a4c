"""Falsifiable wordings of seed 000's TDOA geometry claims (for ``trackcert falsify``).

Each example is a :class:`~theory.strategies.TdoaScene` whose agents form one connected path.
A connected component localizes the target iff its stacked position Jacobian (rows
``u_i − u_j`` with ``u_i = (p − p_i)/‖p − p_i‖``, seed 000 eqs. (4.8)–(4.10)) has rank ``d``.
Examples whose rank decision is inside tolerance are not counted as counterexamples.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from hypothesis import strategies as st

from theory.core.observability import numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR, MIRROR_TOL, RANK_TOL
from theory.falsify import Property, register_property
from theory.strategies import TdoaScene, tdoa_scenes
from theory.tdoa.model import tdoa_jacobian, tdoa_measurement, unit_directions

__all__ = ["component_rank", "mirror_target", "scene_case"]


def component_rank(scene: TdoaScene) -> tuple[int, bool]:
    """Rank of the stacked position Jacobian of all agents of ``scene``, and whether the
    decision is conclusive (every singular value clears the threshold by 10³)."""
    n, dim = scene.agents.shape
    jacobian = tdoa_jacobian(scene.target, scene.agents, 0, range(1, n))[:, :dim]
    result = numeric_rank(jacobian, rank_tol=RANK_TOL)
    return result.rank, result.conclusive(INCONCLUSIVE_FACTOR)


def _coplanar(points: np.ndarray) -> bool:
    centred = points - points.mean(axis=0)
    return numeric_rank(centred, rank_tol=RANK_TOL).rank < points.shape[1]


def _concyclic_directions(scene: TdoaScene) -> bool:
    """Whether some (a, c) ≠ 0 has u_i·a = c for all i: rank [U 1] < d + 1."""
    units = unit_directions(scene.target, scene.agents)
    augmented = np.hstack([units, np.ones((len(units), 1))])
    return numeric_rank(augmented, rank_tol=RANK_TOL).rank < units.shape[1] + 1


def mirror_target(scene: TdoaScene) -> np.ndarray:
    """``scene``'s target reflected through the plane that best fits its agents (least squares)."""
    centre = scene.agents.mean(axis=0)
    normal = np.linalg.svd(scene.agents - centre)[2][-1]
    return scene.target - 2 * np.dot(scene.target - centre, normal) * normal


def scene_case(scene: TdoaScene) -> dict[str, Any]:
    """A ready-to-run ``kind: tdoa`` case file reproducing ``scene`` (agents on a path)."""
    n, dim = scene.agents.shape
    rank, _ = component_rank(scene)
    return {
        "name": f"falsify-{scene.family}-{n}-agents",
        "source": "trackcert falsify (shrunk counterexample)",
        "kind": "tdoa",
        "tdoa": {
            "T": 1.0,
            "target": [float(v) for v in scene.target],
            "agents": [[float(v) for v in row] for row in scene.agents],
            "edges": [[i, i + 1] for i in range(1, n)],
            "weights": "metropolis",
        },
        "expect": {"observable": [rank == dim] * n},
    }


def _heuristic_paper(scene: TdoaScene) -> bool:
    rank, conclusive = component_rank(scene)
    enough = len(scene.agents) >= scene.agents.shape[1] + 1 and not _coplanar(scene.agents)
    return not conclusive or not enough or rank == scene.agents.shape[1]


def _heuristic_corrected(scene: TdoaScene) -> bool:
    rank, conclusive = component_rank(scene)
    return not conclusive or (rank == scene.agents.shape[1]) == (not _concyclic_directions(scene))


def _coplanar_paper(scene: TdoaScene) -> bool:
    rank, conclusive = component_rank(scene)
    return not conclusive or not _coplanar(scene.agents) or rank < scene.agents.shape[1]


def _coplanar_corrected(scene: TdoaScene) -> bool:
    if not _coplanar(scene.agents):
        return True
    n = len(scene.agents)
    here = tdoa_measurement(scene.target, scene.agents, 0, range(1, n))
    there = tdoa_measurement(mirror_target(scene), scene.agents, 0, range(1, n))
    scale = float(np.max(np.abs(scene.agents - scene.target)))
    return bool(np.max(np.abs(here - there)) <= MIRROR_TOL * scale)


SCENES_3D = st.one_of(
    tdoa_scenes(dim=3, family="general"),
    tdoa_scenes(dim=3, family="cone"),
    tdoa_scenes(dim=3, family="coplanar"),
    tdoa_scenes(dim=3, family="target-in-plane"),
)


def _scene_property(
    property_id: str,
    statement: str,
    holds: Callable[[TdoaScene], bool],
    *,
    expected_to_hold: bool = True,
) -> None:
    """Register ``property_id = "<claim>/<wording>"`` over :data:`SCENES_3D`."""
    claim, wording = property_id.split("/")
    register_property(
        Property(
            id=property_id,
            claim=claim,
            wording=wording,
            statement=statement,
            examples=SCENES_3D,
            holds=holds,
            to_case=scene_case,
            expected_to_hold=expected_to_hold,
        )
    )


_scene_property(
    "seed000.thm4.2.3/paper",
    "A connected component of ≥ 4 non-coplanar agents can localize the target.",
    _heuristic_paper,
    expected_to_hold=False,
)
_scene_property(
    "seed000.thm4.2.3/corrected",
    "A connected component can localize the target iff the unit directions from the agents to "
    "the target do not lie on one circle of the unit sphere (equivalently, the agents do not lie "
    "on one circular cone, or plane, through the target).",
    _heuristic_corrected,
)
_scene_property(
    "seed000.sec4.2.1.coplanar/paper",
    "det Λ = 0 when the 4 agents are coplanar: coplanar agents cannot localize.",
    _coplanar_paper,
    expected_to_hold=False,
)
_scene_property(
    "seed000.sec4.2.1.coplanar/corrected",
    "Coplanar receivers hear the target and its mirror image through their plane with identical "
    "TDOAs (a global ambiguity), whatever the local rank.",
    _coplanar_corrected,
)
