"""Time-varying topologies (seed 000 Cor. 4.2.4): the topology verdict at every time step.

A case with trajectories (``agents``: steps × N × d and/or ``target``: steps × d) and a distance
rule (``comm_range``) has a different graph, weights and geometry at each step. Each step is
checked as a frozen network with :func:`theory.tdoa.topology.analyze_topology`; this module collects
the per-step verdicts, the first step where some agent cannot localize, and how many steps each
agent spends unobservable.

Frozen-time verdicts are what Cor. 4.2.4 argues with; they are neither necessary nor sufficient
for uniform observability of the time-varying pair in general (see ``docs/topology.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from theory.tdoa.case import TdoaSpec
from theory.tdoa.topology import TopologyResult, analyze_topology

__all__ = ["TrajectoryResult", "analyze_trajectory"]


@dataclass(frozen=True)
class TrajectoryResult:
    """Verdicts along a trajectory.

    Attributes
    ----------
    steps : tuple of TopologyResult
        One per time step (``step`` is 1-based inside each).
    first_failure_step : int or None
        First 1-based step at which some agent cannot localize (undirected: the networked pair
        is not detectable), or ``None``.
    unobservable_steps : tuple of int
        For each agent, the number of steps at which its ``O_i`` is rank deficient.
    heuristic_failure_steps : tuple of int
        1-based steps at which some agent fails the paper's heuristic.
    """

    steps: tuple[TopologyResult, ...]
    first_failure_step: int | None
    unobservable_steps: tuple[int, ...]
    heuristic_failure_steps: tuple[int, ...]

    @property
    def conclusive(self) -> bool:
        """Whether every step's verdict is conclusive."""
        return all(step.conclusive for step in self.steps)

    def to_json(self) -> dict[str, Any]:
        """Per-step summary: ranks, detectability and which agents fail."""
        return {
            "first_failure_step": self.first_failure_step,
            "unobservable_steps": list(self.unobservable_steps),
            "heuristic_failure_steps": list(self.heuristic_failure_steps),
            "steps": [_step_json(step) for step in self.steps],
        }


def analyze_trajectory(spec: TdoaSpec, **options: Any) -> TrajectoryResult:
    """Run the topology check at every time step of ``spec``.

    Parameters
    ----------
    spec : TdoaSpec
        A scene with ``spec.steps ≥ 1`` time steps.
    **options
        Keyword arguments of :func:`theory.tdoa.topology.analyze_topology` (``rank_tol``,
        ``inconclusive_factor``, ``uniqueness_tol``, ``cluster_tol``, ``network_rank``).

    Returns
    -------
    TrajectoryResult

    References
    ----------
    seed 000 Cor. 4.2.4 and §4.4 (the distance rule with range 21).
    """
    steps = tuple(analyze_topology(spec, k, **options) for k in range(spec.steps))
    failing = [s.step for s in steps if not s.every_agent_localizes]
    counts = [sum(not step.agents[i].observable for step in steps) for i in range(spec.n_agents)]
    heuristic = [s.step for s in steps if not all(a.heuristic_4_noncoplanar for a in s.agents)]
    return TrajectoryResult(steps, failing[0] if failing else None, tuple(counts), tuple(heuristic))


def _step_json(step: TopologyResult) -> dict[str, Any]:
    return {
        "step": step.step,
        "network_rank": step.network.rank,
        "network_detectable": step.network.detectable,
        "every_agent_localizes": step.every_agent_localizes,
        "unobservable_agents": [a.id for a in step.agents if not a.observable],
        "heuristic_fails": [a.id for a in step.agents if not a.heuristic_4_noncoplanar],
        "components": len({a.component for a in step.agents}),
        "conclusive": step.conclusive,
    }
