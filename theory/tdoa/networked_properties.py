"""Falsifiable wordings of seed 000's rank-sum claim after eq. (4.36) (for ``trackcert falsify``).

Seed 000 §4.2.2 (and seed 001 after its eq. (36)) asserts ``rank O = Σ_i rank O_i`` for the
observability matrix ``O = [O_1 … O_N]`` of the networked pair ``(W ⊗ A, D_H)``. It is false in
general (singular ``W`` such as uniform weights on a complete graph, or the Fig. 4.3 stars). What
is true (``docs/theory/tdoa-observability.md``): ``rank O ≤ Σ rank O_i`` always (the rank of a
block row is at most the sum of its blocks' ranks), and the pair is *detectable* iff every
connected component's stacked position Jacobian has full rank ``d`` (Thm 4.2.3, corrected).

Each example is a :class:`~theory.strategies.TdoaScene` (2D or 3D) with weights from
:func:`~theory.strategies.weight_matrices` on an undirected network drawn by
:func:`~theory.strategies.networks` (connected or not), of every kind (Metropolis, uniform,
random, singular). Verdicts come from :func:`~theory.tdoa.networked_observability.analyze_network`;
an inconclusive rank or unit-circle decision is never a counterexample.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from hypothesis import strategies as st

from theory.core.network import components, weights_support
from theory.falsify import Property, register_property
from theory.strategies import WEIGHT_KINDS, TdoaScene, tdoa_scenes, weight_matrices
from theory.tdoa.geometry_properties import component_rank
from theory.tdoa.model import cv_discrete, tdoa_jacobian
from theory.tdoa.networked_observability import NetworkObservability, analyze_network

__all__ = [
    "WeightedScene",
    "analyze_weighted_scene",
    "component_ranks",
    "weighted_scene_case",
    "weighted_scenes",
]

PERIOD = 1.0
"""Ping period T of eq. (4.6) used for the target dynamics A (A is unipotent for every T)."""


@dataclass(frozen=True, eq=False)
class WeightedScene:
    """A TDOA scene with consensus weights on the network they define.

    Attributes
    ----------
    scene : TdoaScene
        Target and receivers.
    weights : ndarray, shape (N, N)
        Row-stochastic consensus weights with positive diagonal; their off-diagonal support is
        the (undirected) network: agent i hears agent j iff ``weights[i, j] > 0``.
    rule : str
        ``metropolis``, ``uniform`` (the weights follow that rule on the support; the case file
        names the rule) or ``explicit`` (the case file carries the matrix).
    """

    scene: TdoaScene
    weights: np.ndarray
    rule: str


@st.composite
def weighted_scenes(draw: st.DrawFn, *, max_agents: int = 5) -> WeightedScene:
    """General-position 2D or 3D scenes of 2 to ``max_agents`` receivers, with weights of a
    drawn kind on an undirected network (connected or not) of the same size."""
    dim = draw(st.sampled_from((2, 3)))
    scene = draw(tdoa_scenes(dim=dim, min_agents=2, max_agents=max_agents))
    n = len(scene.agents)
    kind = draw(st.sampled_from(WEIGHT_KINDS))
    W = draw(weight_matrices(min_agents=n, max_agents=n, kind=kind, connected=None))
    rule = kind if kind in ("metropolis", "uniform") else "explicit"
    return WeightedScene(scene, W, rule)


def _jacobians(example: WeightedScene) -> list[np.ndarray]:
    """Agent i's Jacobian H_i (eqs. (4.7)–(4.10)) over the agents it hears."""
    hears = weights_support(example.weights)
    target, agents = example.scene.target, example.scene.agents
    return [tdoa_jacobian(target, agents, i, np.flatnonzero(hears[i])) for i in range(len(agents))]


def analyze_weighted_scene(example: WeightedScene) -> NetworkObservability:
    """Rank of ``O``, ``rank O_i`` and detectability of ``(W ⊗ A, D_H)`` (seed 000 eq. (4.36))
    for ``example``."""
    dim = example.scene.agents.shape[1]
    A = cv_discrete(PERIOD, dim)[0]
    return analyze_network(A, example.weights, _jacobians(example))


def component_ranks(example: WeightedScene) -> list[tuple[int, bool]]:
    """(rank, conclusive) of each connected component's stacked position Jacobian in
    ``example``."""
    parts = components(weights_support(example.weights))
    target, agents = example.scene.target, example.scene.agents
    return [component_rank(TdoaScene(target, agents[part], "component")) for part in parts]


def weighted_scene_case(example: WeightedScene) -> dict[str, Any]:
    """A ready-to-run ``kind: tdoa`` case reproducing ``example`` (explicit weights unless they
    are Metropolis or uniform on the support), with the verdicts it should reproduce."""
    scene, W = example.scene, example.weights
    n, dim = scene.agents.shape
    block: dict[str, Any] = {
        "T": PERIOD,
        "target": [float(v) for v in scene.target],
        "agents": [[float(v) for v in row] for row in scene.agents],
    }
    if example.rule == "explicit":
        block["weights"] = [[float(v) for v in row] for row in W]
    else:
        hears = weights_support(W)
        block["edges"] = [[i + 1, j + 1] for i in range(n) for j in range(i + 1, n) if hears[i, j]]
        block["weights"] = example.rule
    net = analyze_weighted_scene(example)
    return {
        "name": f"falsify-rank-sum-{dim}d-{n}-agents-{example.rule}",
        "source": "trackcert falsify (shrunk counterexample to seed 000 after eq. (4.36))",
        "description": f"rank O = {net.network_rank}, Σ rank O_i = {net.rank_sum} "
        f"(rank O_i = {net.agent_ranks}).",
        "kind": "tdoa",
        "tdoa": block,
        "expect": {
            "network_rank": net.network_rank,
            "network_observable": net.observable,
            "network_detectable": net.detectable,
        },
    }


def _rank_sum_paper(example: WeightedScene) -> bool:
    net = analyze_weighted_scene(example)
    return not net.conclusive or net.rank_sum_claim_holds


def _rank_sum_corrected(example: WeightedScene) -> bool:
    net = analyze_weighted_scene(example)
    ranks = component_ranks(example)
    if not net.conclusive or not all(conclusive for _, conclusive in ranks):
        return True
    dim = example.scene.agents.shape[1]
    full = all(rank == dim for rank, _ in ranks)
    return net.network_rank <= net.rank_sum and net.detectable == full


register_property(
    Property(
        id="seed000.eq4.36.rank-sum/paper",
        claim="seed000.eq4.36.rank-sum",
        wording="paper",
        statement="From the structure of D_H, rank O = Σ_i rank O_i (seed 000 after eq. (4.36)).",
        examples=weighted_scenes(),
        holds=_rank_sum_paper,
        to_case=weighted_scene_case,
        expected_to_hold=False,
    )
)
register_property(
    Property(
        id="seed000.eq4.36.rank-sum/corrected",
        claim="seed000.eq4.36.rank-sum",
        wording="corrected",
        statement=(
            "rank O ≤ Σ_i rank O_i, and (W ⊗ A, D_H) is detectable iff every connected "
            "component's stacked position Jacobian has full rank d."
        ),
        examples=weighted_scenes(),
        holds=_rank_sum_corrected,
        to_case=weighted_scene_case,
    )
)
