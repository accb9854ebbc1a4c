"""What ``trackcert topology`` reports on a ``kind: tdoa`` case, and the kind's observer.

:func:`topology_report` runs :func:`run_topology` (the verdicts of
:mod:`theory.tdoa.topology` at every step, :mod:`theory.tdoa.time_varying`) and judges the case's
``expect`` block with :mod:`theory.core.expectations`; the command only prints it. The kind's
observer :func:`observe_topology` runs the same analysis, so the report's ``case.expect.tdoa``
claim and the command agree on every expectation.

The property decided (seed 000 §4.2.2, Cor. 4.2.4): every agent can localize the target at
every step. Verdict True/False when every deciding singular value clears ``inconclusive_factor``
times its threshold, ``None`` (inconclusive) otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.errors import CaseError, SolverError
from theory.core.expectations import Expectation, Observed, judge
from theory.tdoa.time_varying import TrajectoryResult, analyze_trajectory
from theory.tdoa.topology import observed_values

__all__ = [
    "TopologyReport",
    "observe_topology",
    "run_topology",
    "topology_observed",
    "topology_report",
]

SOURCE = "trackcert topology"
"""The observations' source in the command's verdict records."""


def run_topology(case: Case, *, network_rank: bool = True, **tolerances: float) -> TrajectoryResult:
    """Analyze a ``kind: tdoa`` case at every step with the case's tolerances (overridable).

    Parameters
    ----------
    case : Case
        A loaded case.
    network_rank : bool
        ``False`` skips the rank of the whole networked matrix (cubic in the largest component);
        per-agent verdicts and detectability are always computed.
    **tolerances : float
        ``rank_tol`` / ``inconclusive_factor`` overriding the case's (``None`` = keep).

    Returns
    -------
    TrajectoryResult

    Raises
    ------
    CaseError
        If the case is not ``kind: tdoa`` or a tolerance is out of range.
    SolverError
        If a linear-algebra routine fails (reported as inconclusive).
    """
    if case.kind != "tdoa":
        raise CaseError("kind", "tdoa (trackcert topology checks TDOA cases)", case.kind)
    chosen = {k: v for k, v in case.tolerances.items() if k in ("rank_tol", "inconclusive_factor")}
    chosen.update({k: v for k, v in tolerances.items() if v is not None})
    if not 0 < chosen.get("rank_tol", 0.5) < 1:
        raise CaseError("--rank-tol", "a relative tolerance in (0, 1)", chosen["rank_tol"])
    if chosen.get("inconclusive_factor", 1.0) < 1:
        raise CaseError("--inconclusive-factor", "a factor ≥ 1", chosen["inconclusive_factor"])
    try:
        return analyze_trajectory(case.spec, network_rank=network_rank, **chosen)
    except np.linalg.LinAlgError as error:
        raise SolverError(f"linear algebra failed: {error}") from None


def topology_observed(result: TrajectoryResult) -> Observed:
    """The value of every tdoa expect key in ``result``, and which ones are undecided.

    Static keys come from the first step (undecided when that step is inconclusive, or when a
    value was not computed, e.g. ``network_rank`` with ``--no-network-rank``); the trajectory keys
    ``first_failure_step`` and ``unobservable_steps`` from every step (undecided when a step is
    inconclusive).

    Parameters
    ----------
    result : TrajectoryResult
        The verdicts along the case's steps.

    Returns
    -------
    Observed
    """
    first = result.steps[0]
    static = observed_values(first)
    trajectory = {
        "first_failure_step": result.first_failure_step,
        "unobservable_steps": list(result.unobservable_steps),
    }
    undecided = {k for k, v in static.items() if v is None or not first.conclusive}
    undecided |= set(trajectory) if not result.conclusive else set()
    return Observed({**static, **trajectory}, frozenset(undecided))


def observe_topology(case: Case) -> Observed:
    """The observer of ``kind: tdoa`` (:func:`theory.core.case_file.register_kind`).

    Parameters
    ----------
    case : Case
        A loaded tdoa case (its own tolerances apply).

    Returns
    -------
    Observed
        :func:`topology_observed` of :func:`run_topology`.
    """
    return topology_observed(run_topology(case))


@dataclass(frozen=True)
class TopologyReport:
    """The record ``trackcert topology`` prints: verdicts, expectations, exit verdict.

    Attributes
    ----------
    case : Case
        The case analysed.
    result : TrajectoryResult
        Per-step verdicts.
    expectations : tuple of Expectation
        The case's ``expect`` block judged against :func:`topology_observed`.
    """

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
        """The DESIGN.md ``--json`` record: step 0's verdicts, ``time_varying`` when the scene
        moves, ``expectations`` (``met``, ``mismatches``, ``verdicts``) and ``verdict``."""
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
    """Analyze ``case`` and judge its expectations (the one function ``trackcert topology`` runs).

    Parameters
    ----------
    case : Case
        A loaded ``kind: tdoa`` case.
    network_rank : bool
        Whether to rank the whole networked pair (:func:`run_topology`).
    rank_tol, inconclusive_factor : float, optional
        Override the case's tolerances (``None`` keeps them).

    Returns
    -------
    TopologyReport

    Raises
    ------
    CaseError, SolverError
        As :func:`run_topology`.
    """
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
