"""What ``trackcert topology`` decides along a scene's time steps (seed 000 §4.2.2, Cor. 4.2.4),
the kind's observer, and the claims comparing the paper's wording with the exact verdicts.

A case with trajectories (``agents``: steps × N × d and/or ``target``: steps × d) and a distance
rule (``comm_range``) has a different graph, weights and geometry at each step; each step is
checked as a frozen network by :func:`~theory.tdoa.observability.topology.analyze_topology`.
Frozen-time verdicts are what Cor. 4.2.4 argues with; they are neither necessary nor sufficient
for uniform observability of the time-varying pair in general (``docs/topology.md``).

The property decided: every agent can localize the target at every step. Verdict True/False when
every deciding singular value clears ``inconclusive_factor`` times its threshold, ``None``
(inconclusive) otherwise. The kind's observer runs the same analysis as the command, so the
report's ``case.expect.tdoa`` claim and the command agree on every expectation. The claims
compare the paper's "≥ 4 connected non-coplanar agents" (Thm 4.2.3, Cor. 4.2.4) with the exact
per-agent verdicts, the networked pair's rank and detectability, step by step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, Status
from theory.core.errors import CaseError, SolverError
from theory.core.expectations import Expectation, Observed, judge
from theory.tdoa.case import TdoaSpec, rank_tolerances
from theory.tdoa.observability.topology import (
    TopologyResult,
    analyze_topology,
    check_topology_cost,
    observed_values,
)

__all__ = [
    "TopologyReport",
    "TrajectoryResult",
    "analyze_trajectory",
    "claims",
    "cor_4_2_4_claim",
    "heuristic_claim",
    "network_claim",
    "observe_topology",
    "run_topology",
    "topology_observed",
    "topology_report",
]

claims = ClaimSet()


@dataclass(frozen=True)
class TrajectoryResult:
    """Verdicts along a trajectory: one :class:`TopologyResult` per step (1-based ``step``
    inside), the first step at which some agent cannot localize (``None`` if none), each agent's
    number of steps with ``O_i`` rank deficient, and the steps where some agent fails the
    heuristic."""

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
    """The topology check at every time step of ``spec`` (``options`` of
    :func:`~theory.tdoa.observability.topology.analyze_topology`); seed 000 Cor. 4.2.4, §4.4."""
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


SOURCE = "trackcert topology"
"""The observations' source in the command's verdict records."""


def run_topology(case: Case, *, network_rank: bool = True, **tolerances: float) -> TrajectoryResult:
    """Analyze a ``kind: tdoa`` case at every step with its tolerances (``rank_tol`` /
    ``inconclusive_factor`` overridden unless ``None``).

    ``CaseError`` for another kind, a tolerance out of range or an analysis beyond the limits
    (:func:`~theory.tdoa.observability.topology.check_topology_cost`); ``SolverError`` when a
    linear-algebra routine fails (reported as inconclusive)."""
    if case.kind != "tdoa":
        raise CaseError("kind", "tdoa (trackcert topology checks TDOA cases)", case.kind)
    chosen = rank_tolerances(case)
    chosen.update({k: v for k, v in tolerances.items() if v is not None})
    if not 0 < chosen["rank_tol"] < 1:
        raise CaseError("--rank-tol", "a relative tolerance in (0, 1)", chosen["rank_tol"])
    if chosen["inconclusive_factor"] < 1:
        raise CaseError("--inconclusive-factor", "a factor ≥ 1", chosen["inconclusive_factor"])
    try:
        check_topology_cost(case.spec, network_rank=network_rank)
    except CaseError as error:
        raise error.in_file(case.file) from None
    try:
        return analyze_trajectory(case.spec, network_rank=network_rank, **chosen)
    except np.linalg.LinAlgError as error:
        raise SolverError(f"linear algebra failed: {error}") from None


def topology_observed(result: TrajectoryResult) -> Observed:
    """The value of every tdoa expect key in ``result``, and which ones are undecided: the static
    keys from the first step (undecided when it is inconclusive or a value was not computed), the
    trajectory keys from every step (undecided when a step is inconclusive)."""
    first = result.steps[0]
    static = observed_values(first)
    trajectory = {
        "first_failure_step": result.first_failure_step,
        "unobservable_steps": list(result.unobservable_steps),
    }
    undecided = {k for k, v in static.items() if v is None or not first.conclusive}
    undecided |= set(trajectory) if not result.conclusive else set()
    return Observed({**static, **trajectory}, frozenset(undecided))


def observe_topology(case: Case, ctx: Context) -> Observed:
    """The observer of ``kind: tdoa``: :func:`topology_observed` of :func:`run_topology`."""
    return topology_observed(run_topology(case))


@dataclass(frozen=True)
class TopologyReport:
    """The record ``trackcert topology`` prints: the verdicts per step and the case's ``expect``
    block judged against :func:`topology_observed`."""

    case: Case
    result: TrajectoryResult
    expectations: tuple[Expectation, ...]

    @property
    def verdict(self) -> bool | None:
        """Every agent localizes at every step (True/False), or None when inconclusive."""
        return self.result.first_failure_step is None if self.result.conclusive else None

    def sentence(self) -> str:
        """The verdict as one line (``HOLDS: …``, ``FAILS: …`` or ``INCONCLUSIVE: …``)."""
        result = self.result
        if self.verdict is None:
            return "INCONCLUSIVE: " + next(r for s in result.steps for r in s.inconclusive)
        if self.verdict:
            return _holds_sentence(result)
        return _fails_sentence(result)

    def to_json(self) -> dict[str, Any]:
        """The ``--json`` record: step 0's verdicts, ``time_varying`` when the scene moves,
        ``expectations`` (``met``, ``mismatches``, ``verdicts``) and ``verdict``."""
        data: dict[str, Any] = {"case": self.case.name, "source": self.case.source}
        data.update(self.result.steps[0].to_json())
        if len(self.result.steps) > 1:
            data["time_varying"] = self.result.to_json()
        data["expectations"] = {
            "met": all(e.met for e in self.expectations),
            "mismatches": [e.describe() for e in self.expectations if e.verdict == "unmet"],
            "verdicts": [e.to_json() for e in self.expectations],
        }
        data["verdict"] = self.sentence()
        return data


def topology_report(
    case: Case,
    *,
    network_rank: bool = True,
    rank_tol: float | None = None,
    inconclusive_factor: float | None = None,
) -> TopologyReport:
    """Analyze ``case`` and judge its expectations (what ``trackcert topology`` runs; errors as
    :func:`run_topology`)."""
    result = run_topology(
        case,
        network_rank=network_rank,
        rank_tol=rank_tol,
        inconclusive_factor=inconclusive_factor,
    )
    expectations = judge(case, topology_observed(result), source=SOURCE)
    return TopologyReport(case, result, tuple(expectations))


def _holds_sentence(result: TrajectoryResult) -> str:
    steps = f" at all {len(result.steps)} steps" if len(result.steps) > 1 else ""
    ambiguous = [a.id for a in result.steps[0].agents if a.uniqueness.unique is False]
    caveat = (
        f" (locally; for agents {ambiguous} another position has the same TDOAs)"
        if ambiguous
        else ""
    )
    return f"HOLDS: every agent can localize the target{steps}{caveat}"


def _fails_sentence(result: TrajectoryResult) -> str:
    step = result.steps[result.first_failure_step - 1]
    failing = [a.id for a in step.agents if not a.localizes]
    where = f" (first at step {step.step})" if len(result.steps) > 1 else ""
    why = (
        "; the networked pair is detectable, but a closed class upstream of them (agents that "
        "hear only each other) cannot localize on its own"
        if step.network.detectable
        else ""
    )
    return f"FAILS: agents {failing} cannot localize the target{where}{why}"


_SOURCE = "seed 000 §4.2.2, Thm 4.2.3; seed 001 Theorem 1"


def _first_step(case: Case) -> TopologyResult:
    return analyze_topology(case.spec, 0, **rank_tolerances(case))


def _inconclusive(result: TopologyResult) -> ClaimResult:
    return ClaimResult(
        Status.INCONCLUSIVE,
        Method.NUMERIC,
        {"reasons": list(result.inconclusive)},
        tolerance=dict(result.tolerances),
        message="a deciding singular value lies within tolerance: " + result.inconclusive[0],
    )


@claims.register(
    "seed000.thm4.2.3.heuristic",
    source=_SOURCE,
    statement="an agent can localize the target iff it belongs to a connected (sub)network of "
    "at least 4 non-coplanar agents (3 non-collinear in 2-D)",
    kinds=("tdoa",),
)
def heuristic_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """The paper's heuristic against the exact per-agent verdict at the first step."""
    result = _first_step(case)
    if not result.conclusive:
        return [_inconclusive(result)]
    disagree = [
        {"agent": a.id, "heuristic": a.heuristic_4_noncoplanar, "exact": a.localizes}
        | ({"reason": a.reason} if a.reason else {})
        for a in result.agents
        if a.heuristic_4_noncoplanar != a.localizes
    ]
    evidence: dict[str, Any] = {
        "disagreements": disagree,
        "agents": [
            {"agent": a.id, "rank_O_i": a.rank, "sigma_min": a.sigma_min, "margin": a.margin}
            for a in result.agents
        ],
        "corrected_statement": "agent i localizes iff the stacked TDOA Jacobian of the agents "
        "it exchanges information with has rank d (the unit directions from the target to them "
        "are affinely full-dimensional); coplanar receivers add a mirror-image ambiguity",
    }
    message = (
        f"heuristic and exact verdict disagree for agents {[d['agent'] for d in disagree]}"
        if disagree
        else "heuristic and exact verdict agree for every agent"
    )
    return [
        ClaimResult(
            Status.CORRECTED if disagree else Status.VERIFIED,
            Method.NUMERIC,
            evidence,
            min(a.margin for a in result.agents),
            dict(result.tolerances),
            message,
        )
    ]


@claims.register(
    "seed000.thm4.2.3.network",
    source=_SOURCE,
    statement="the networked pair (W ⊗ A, D_H) is observable iff every agent is part of a "
    "(sub)network with at least 4 connected, non-coplanar agents",
    kinds=("tdoa",),
)
def network_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """The paper's condition against the rank and detectability of the networked pair."""
    result = _first_step(case)
    if not result.conclusive:
        return [_inconclusive(result)]
    net = result.network
    predicted = all(a.heuristic_4_noncoplanar for a in result.agents)
    evidence = {
        "paper_predicts_observable": predicted,
        "network_rank": net.rank,
        "n_states": net.n_states,
        "network_observable": net.observable,
        "network_detectable": net.detectable,
        "unobservable_eigenvalues": [
            {"re": z.real, "im": z.imag} for z in (net.unobservable_eigenvalues or ())
        ],
        "method": net.method,
    }
    if net.observable is None or net.margin < result.tolerances["inconclusive_factor"]:
        status = Status.INCONCLUSIVE
        message = f"network rank not decided: {net.note or net.margin}"
    elif predicted == net.observable:
        status, message = Status.VERIFIED, f"network rank {net.rank}/{net.n_states} as predicted"
    elif predicted and net.detectable:
        status = Status.CORRECTED
        message = (
            f"the pair is only detectable (rank {net.rank}/{net.n_states}; unobservable modes "
            "inside the unit circle), which is what the estimator needs"
        )
    else:
        status = Status.REFUTED
        message = (
            f"paper predicts observable={predicted}, the pair has rank {net.rank}/{net.n_states}"
        )
    return [
        ClaimResult(status, Method.NUMERIC, evidence, net.margin, dict(result.tolerances), message)
    ]


@claims.register(
    "seed000.cor4.2.4",
    source="seed 000 Cor. 4.2.4; seed 001 Corollary 1",
    statement="for a time-varying undirected network, if every agent remains part of a "
    "network of at least 4 connected non-coplanar agents, the networked system is observable",
    kinds=("tdoa",),
)
def cor_4_2_4_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """At every step where the hypothesis holds, does every agent localize (and is the pair
    observable, as the paper words it)? Static cases give no result."""
    if case.spec.steps < 2:
        return []
    trajectory = analyze_trajectory(case.spec, **rank_tolerances(case))
    if not trajectory.conclusive:
        return [_inconclusive(next(s for s in trajectory.steps if not s.conclusive))]
    hypothesis = [s for s in trajectory.steps if all(a.heuristic_4_noncoplanar for a in s.agents)]
    fails = [s.step for s in hypothesis if not s.every_agent_localizes]
    unobservable = [s.step for s in hypothesis if s.network.observable is False]
    evidence = {
        "steps": len(trajectory.steps),
        "hypothesis_steps": [s.step for s in hypothesis],
        "hypothesis_steps_where_some_agent_fails": fails,
        "hypothesis_steps_where_pair_unobservable": unobservable,
        "first_failure_step": trajectory.first_failure_step,
        "unobservable_steps": list(trajectory.unobservable_steps),
    }
    if fails:
        status = Status.REFUTED
        message = f"hypothesis holds but some agent fails at steps {fails}"
    elif unobservable:
        status = Status.CORRECTED
        message = (
            f"every agent localizes at all {len(hypothesis)} hypothesis steps, but the pair is "
            f"only detectable (not observable) at steps {unobservable}"
        )
    else:
        status = Status.VERIFIED
        message = f"every agent localizes at all {len(hypothesis)} steps where the hypothesis holds"
    margin = min(min(a.margin for a in s.agents) for s in trajectory.steps)
    tolerance = dict(trajectory.steps[0].tolerances)
    return [ClaimResult(status, Method.NUMERIC, evidence, margin, tolerance, message)]
