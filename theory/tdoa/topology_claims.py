"""Registered claims about TDOA network topology (seed 000 Thm 4.2.3, Cor. 4.2.4).

Each check runs :mod:`theory.tdoa.topology` / :mod:`theory.tdoa.time_varying` on a ``kind: tdoa``
case and
compares the paper's wording with the exact verdict:

* ``seed000.thm4.2.3.heuristic`` — "an agent can localize iff it is part of a connected
  (sub)network of ≥ 4 non-coplanar agents" (≥ 3 non-collinear in 2-D), per agent.
* ``seed000.thm4.2.3.network`` — the same condition for every agent ⇔ the networked pair
  ``(W ⊗ A, D_H)`` is observable.
* ``seed000.cor4.2.4`` — along a trajectory, every step satisfying the hypothesis has every
  agent localizing (and, in the paper's words, the networked system observable).
"""

from __future__ import annotations

from typing import Any

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, register
from theory.tdoa.time_varying import TrajectoryResult, analyze_trajectory
from theory.tdoa.topology import TopologyResult

__all__ = ["check_cor_4_2_4", "check_heuristic", "check_network_observability"]

_SOURCE = "seed 000 §4.2.2, Thm 4.2.3; seed 001 Theorem 1"


def _trajectory(case: Case) -> TrajectoryResult:
    chosen = {k: v for k, v in case.tolerances.items() if k in ("rank_tol", "inconclusive_factor")}
    return analyze_trajectory(case.spec, **chosen)


def _inconclusive(claim: str, case: Case, result: TopologyResult) -> ClaimResult:
    return ClaimResult(
        claim,
        case.name,
        "numeric",
        "inconclusive",
        {"reasons": list(result.inconclusive)},
        tolerance=dict(result.tolerances),
        message="a deciding singular value lies within tolerance: " + result.inconclusive[0],
    )


@register(
    "seed000.thm4.2.3.heuristic",
    source=_SOURCE,
    statement="an agent can localize the target iff it belongs to a connected (sub)network of "
    "at least 4 non-coplanar agents (3 non-collinear in 2-D)",
    kinds=("tdoa",),
)
def check_heuristic(case: Case) -> list[ClaimResult]:
    """Paper's heuristic vs the exact per-agent verdict at the first step of ``case``.

    Parameters
    ----------
    case : Case
        A ``kind: tdoa`` case.

    Returns
    -------
    list of ClaimResult
    """
    result = _trajectory(case).steps[0]
    if not result.conclusive:
        return [_inconclusive("seed000.thm4.2.3.heuristic", case, result)]
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
    status = "corrected" if disagree else "verified"
    message = (
        f"heuristic and exact verdict disagree for agents {[d['agent'] for d in disagree]}"
        if disagree
        else "heuristic and exact verdict agree for every agent"
    )
    margin = min(a.margin for a in result.agents)
    return [
        ClaimResult(
            "seed000.thm4.2.3.heuristic",
            case.name,
            "numeric",
            status,
            evidence,
            margin,
            dict(result.tolerances),
            message,
        )
    ]


@register(
    "seed000.thm4.2.3.network",
    source=_SOURCE,
    statement="the networked pair (W ⊗ A, D_H) is observable iff every agent is part of a "
    "(sub)network with at least 4 connected, non-coplanar agents",
    kinds=("tdoa",),
)
def check_network_observability(case: Case) -> list[ClaimResult]:
    """Paper's condition vs the rank and detectability of the networked pair.

    Parameters
    ----------
    case : Case
        A ``kind: tdoa`` case.

    Returns
    -------
    list of ClaimResult
    """
    result = _trajectory(case).steps[0]
    if not result.conclusive:
        return [_inconclusive("seed000.thm4.2.3.network", case, result)]
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
        status, message = "inconclusive", f"network rank not decided: {net.note or net.margin}"
    elif predicted == net.observable:
        status, message = "verified", f"network rank {net.rank}/{net.n_states} as predicted"
    elif predicted and net.detectable:
        status = "corrected"
        message = (
            f"the pair is only detectable (rank {net.rank}/{net.n_states}; unobservable modes "
            "inside the unit circle), which is what the estimator needs"
        )
    else:
        status = "refuted"
        message = (
            f"paper predicts observable={predicted}, the pair has rank {net.rank}/{net.n_states}"
        )
    return [
        ClaimResult(
            "seed000.thm4.2.3.network",
            case.name,
            "numeric",
            status,
            evidence,
            net.margin,
            dict(result.tolerances),
            message,
        )
    ]


@register(
    "seed000.cor4.2.4",
    source="seed 000 Cor. 4.2.4; seed 001 Corollary 1",
    statement="for a time-varying undirected network, if every agent remains part of a "
    "network of at least 4 connected non-coplanar agents, the networked system is observable",
    kinds=("tdoa",),
)
def check_cor_4_2_4(case: Case) -> list[ClaimResult]:
    """At every step where the hypothesis holds, does every agent localize (and is the pair
    observable, as the paper words it)?

    Parameters
    ----------
    case : Case
        A ``kind: tdoa`` case; static cases (one step) give no result.

    Returns
    -------
    list of ClaimResult
    """
    if case.spec.steps < 2:
        return []
    trajectory = _trajectory(case)
    if not trajectory.conclusive:
        first = next(s for s in trajectory.steps if not s.conclusive)
        return [_inconclusive("seed000.cor4.2.4", case, first)]
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
        status, message = "refuted", f"hypothesis holds but some agent fails at steps {fails}"
    elif unobservable:
        status = "corrected"
        message = (
            f"every agent localizes at all {len(hypothesis)} hypothesis steps, but the pair is "
            f"only detectable (not observable) at steps {unobservable}"
        )
    else:
        status = "verified"
        message = f"every agent localizes at all {len(hypothesis)} steps where the hypothesis holds"
    return [
        ClaimResult(
            "seed000.cor4.2.4",
            case.name,
            "numeric",
            status,
            evidence,
            min(min(a.margin for a in s.agents) for s in trajectory.steps),
            dict(trajectory.steps[0].tolerances),
            message,
        )
    ]
