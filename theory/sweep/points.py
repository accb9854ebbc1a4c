"""One sweep point: its values set, the case re-validated, judged by the analysis behind its
kind's command, simulated once and compared.

:func:`evaluate_point` is pure in its arguments, so a point gives the same row in any process and
any order; :func:`evaluate_batch` runs a batch of points as one engine task. A point whose data
the case loader (:func:`theory.kinds.parse_case`) or its analysis rejects is a row of status
``invalid`` with the loader's message; a solver failure makes the verdict inconclusive. The
simulation is one run with root seed ``sim_seed`` (child 0 of ``SeedSequence(sim_seed)``, as
``trackcert simulate --seed sim_seed``), summarised by the kind's simulator without writing files.

Each kind's verdict is the property its command decides, computed by the same library function:

* ``pursuit`` — ``trackcert iss``: every condition of the corrected Theorem 2 (seed 003) holds
  (:func:`theory.pursuit.iss.iss_record`); margin: the smallest relative margin of a condition.
* ``dkf`` — ``trackcert dkf``: S-detectability (seed 000 Def. 5.2.4,
  :func:`theory.consensus.analysis.analyze_dkf` without the self-weight bisection); margin: the
  LMI witness's relative margin (``None`` when not S-detectable).
* ``tdoa`` — ``trackcert topology``: every agent localizes the target at every step
  (:func:`theory.tdoa.observability.trajectory.run_topology`); margin: the least factor by which a
  deciding singular value clears ``rank_tol · σ_max``.
* ``pf`` — ``trackcert pf``: the case's ``expect`` block judged by the pf claims (its Monte Carlo
  is the verdict); no margin.
* ``tdoa-sim`` (any kind not in :data:`ANALYSES`) — ``trackcert simulate``: the ``expect`` block
  judged against the point's own simulation.

A holding verdict may predict something of the simulation (:data:`PREDICTIONS`): for ``pursuit``,
Theorem 2 certifies that the errors μ stay within the ISS estimate β(‖μ(0)‖, t) + γ(sup‖x̃‖),
which the pursuit simulator checks on every run (its summary's ``iss_agreement``). The other
kinds predict nothing of their simulation (the dkf simulation runs the optimal-gain filter, whose
convergence S-detectability does not decide).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import Status, status_of
from theory.core.errors import CaseError, InconclusiveError, PropertyFails, SolverError
from theory.core.expectations import Observed, judge
from theory.core.verdicts import EXIT_BAD_INPUT, Verdict, exit_code, expectations_verdict
from theory.kinds import KINDS, SIMULATED, parse_case, simulator, simulator_for
from theory.sim.simulate import monte_carlo
from theory.sweep.grid import Target, apply_values

__all__ = [
    "ANALYSES",
    "ANALYSIS_MODULES",
    "PREDICTIONS",
    "Agreement",
    "Judgement",
    "PointStatus",
    "Row",
    "SweepSetup",
    "agreement",
    "analysis_for",
    "dkf_judgement",
    "evaluate_batch",
    "evaluate_point",
    "pf_judgement",
    "point_modules",
    "pursuit_judgement",
    "pursuit_prediction",
    "simulate_point",
    "tdoa_judgement",
]

SOURCE = "trackcert sweep"
"""The observations' source when a point is judged by its simulation."""


class PointStatus(StrEnum):
    """A point's status: its verdict's (:func:`theory.core.claims.status_of`), or ``invalid``
    when the case loader or the analysis rejects it."""

    VERIFIED = "verified"
    REFUTED = "refuted"
    INCONCLUSIVE = "inconclusive"
    INVALID = "invalid"


class Agreement(StrEnum):
    """Whether a point's simulation bears out what its verdict predicts (:func:`agreement`)."""

    AGREE = "agree"
    DISAGREE = "disagree"
    INCONCLUSIVE = "inconclusive"
    NA = "n/a"


_VERDICT_OF = {
    PointStatus.VERIFIED: True,
    PointStatus.REFUTED: False,
    PointStatus.INCONCLUSIVE: None,
}


@dataclass(frozen=True)
class Judgement:
    """The verdict of one point's analysis, the ``margin`` it was decided with (per kind: module
    docstring), every tolerance used and one line saying why."""

    verdict: Verdict
    margin: float | None
    tolerances: dict[str, float] = field(default_factory=dict)
    message: str = ""


@dataclass(frozen=True)
class SweepSetup:
    """What every point shares (sent with each task): the case file's parsed YAML ``data`` and
    ``file``, the ``targets`` of the swept paths, the simulation's ``steps`` (``None``: the
    kind's), whether to ``simulate`` and the root ``seed`` when ``seed`` is not swept."""

    data: dict[str, Any]
    file: str
    targets: tuple[Target, ...]
    steps: int | None = None
    simulate: bool = True
    seed: int = 0


@dataclass(frozen=True)
class Row:
    """One point's result, a row of ``sweep.csv``.

    ``point`` is its 0-based index in grid order, ``values`` the swept values in ``--param``
    order; ``sim_seed`` is ``None`` when not simulated; ``simulated`` holds the worst agent's value
    of every ``*_error`` field of the simulation summary and every key the simulation observes,
    each prefixed ``sim_``; ``message`` says why (the loader's message for an invalid point).
    """

    point: int
    values: tuple[Any, ...]
    status: PointStatus
    margin: float | None = None
    tolerances: dict[str, float] = field(default_factory=dict)
    sim_seed: int | None = None
    simulated: dict[str, Any] = field(default_factory=dict)
    agreement: Agreement = Agreement.NA
    message: str = ""

    @property
    def exit_code(self) -> int:
        """0 verified, 1 refuted, 3 inconclusive, 2 invalid (:mod:`theory.core.verdicts`)."""
        if self.status == PointStatus.INVALID:
            return EXIT_BAD_INPUT
        return exit_code(_VERDICT_OF[PointStatus(self.status)])


# -------------------------------------------------------------------------- each kind's verdict
def pursuit_judgement(case: Case) -> Judgement:
    """``trackcert iss``'s verdict on a pursuit case (seed 003 Lemmas 1–4, Theorems 1–2)."""
    from theory.pursuit.iss import IssReport, iss_record

    record = iss_record(case)
    conditions = record["conditions"]
    margins = [c["margin"] for c in conditions if c["margin"] is not None]
    unmet = [
        f"{c['name']} {c['status']}" for c in conditions if c["status"] in ("fails", "inconclusive")
    ]
    return Judgement(
        IssReport(record, ()).verdict,
        min(margins) if margins else None,
        dict(record["tolerances"]),
        "; ".join(unmet) or f"all {len(conditions)} ISS conditions hold",
    )


def dkf_judgement(case: Case) -> Judgement:
    """``trackcert dkf``'s verdict: S-detectability (seed 000 Def. 5.2.4)."""
    from theory.consensus.analysis import analyze_dkf

    analysis = analyze_dkf(case, search_self_weight=False)
    decision = analysis.decision
    return Judgement(
        decision.verdict,
        decision.witness_margin if decision.verdict else None,
        dict(analysis.to_json()["tolerances"]),
        decision.reason,
    )


def tdoa_judgement(case: Case) -> Judgement:
    """``trackcert topology``'s verdict: every agent localizes at every step (seed 000 §4.2.2)."""
    from theory.tdoa.observability.trajectory import TopologyReport, run_topology

    result = run_topology(case)
    report = TopologyReport(case, result, ())
    margins = [a.margin for step in result.steps for a in step.agents]
    return Judgement(
        report.verdict,
        min(margins) if margins else None,
        dict(result.steps[0].tolerances),
        report.sentence(),
    )


def pf_judgement(case: Case) -> Judgement:
    """``trackcert pf``'s verdict: the case's expectations judged by the pf claims (seed 002)."""
    from theory.particle.report import pf_report

    report = pf_report(case)
    unmet = [e.describe() for e in report.expectations if not e.met]
    return Judgement(
        report.verdict,
        None,
        dict(case.tolerances),
        "; ".join(unmet) or f"{len(report.expectations)} expectation(s) met",
    )


ANALYSES: dict[str, Callable[[Case], Judgement]] = {
    "pursuit": pursuit_judgement,
    "dkf": dkf_judgement,
    "tdoa": tdoa_judgement,
    "pf": pf_judgement,
}
"""Kind → its analysis verdict; a kind not listed is judged by its simulation alone."""

ANALYSIS_MODULES: dict[str, str] = {
    "pursuit": "theory.pursuit.iss",
    "dkf": "theory.consensus.analysis",
    "tdoa": "theory.tdoa.observability.trajectory",
    "pf": "theory.particle.report",
}
"""Kind → the module its analysis imports (lazily, so that a sweep imports only its kind's)."""


def pursuit_prediction(summary: Mapping[str, Any]) -> tuple[Verdict, str]:
    """Whether a pursuit run stayed within the ISS estimate its verdict certifies (Theorem 2):
    the summary's ``iss_agreement`` as a verdict (``None`` when the integration stopped inside
    the estimate — x̃ ran away, nothing is contradicted — or nothing is certified) and message."""
    found = summary.get("iss_agreement")
    if not found:
        return None, ""
    status = {Status.VERIFIED: True, Status.REFUTED: False}.get(found["status"])
    return status, found["message"]


PREDICTIONS: dict[str, Callable[[Mapping[str, Any]], tuple[Verdict, str]]] = {
    "pursuit": pursuit_prediction,
}
"""Kind → what a holding verdict predicts of its simulation: ``check(summary) -> (verdict,
message)``, True when the simulation bears it out."""


def point_modules(kind: str) -> tuple[str, ...]:
    """The modules evaluating a point of ``kind`` imports — this one, the kind's, its simulator's
    and its analysis's — imported once by the workers' forkserver (the engine's ``preload``)."""
    simulated = (simulator(kind).__module__,) if kind in SIMULATED else ()
    analysis = (ANALYSIS_MODULES[kind],) if kind in ANALYSIS_MODULES else ()
    return (__name__, KINDS[kind].parse.__module__, *simulated, *analysis)


def analysis_for(kind: str) -> Callable[[Case], Judgement] | None:
    """The analysis verdict of ``kind`` (``None``: the kind is judged by its simulation)."""
    return ANALYSES.get(kind)


def agreement(kind: str, verdict: Verdict, summary: Mapping[str, Any] | None) -> tuple[str, str]:
    """Whether a point's simulation (``summary``, ``None``: not simulated) agrees with its
    verdict, and the comparison's message.

    ``agree`` / ``disagree`` when the verdict holds and the simulation bears its prediction out /
    contradicts it; ``inconclusive`` when the verdict or the comparison is undecided; ``n/a``
    when nothing is predicted: the kind predicts nothing, the point was not simulated, or the
    verdict fails (the conditions are sufficient, so a failing verdict predicts nothing).
    """
    check = PREDICTIONS.get(kind)
    if check is None or summary is None or verdict is False:
        return Agreement.NA, ""
    if verdict is None:
        return Agreement.INCONCLUSIVE, "the verdict is inconclusive"
    bears_out, message = check(summary)
    word = {True: Agreement.AGREE, False: Agreement.DISAGREE, None: Agreement.INCONCLUSIVE}
    return word[bears_out], message


# ------------------------------------------------------------------------------- the point
def _judge(case: Case) -> Judgement | None:
    analysis = analysis_for(case.kind)
    if analysis is None:
        return None
    try:
        return analysis(case)
    except (SolverError, InconclusiveError, np.linalg.LinAlgError) as error:
        return Judgement(None, None, {}, f"inconclusive: {error}")


def simulate_point(
    case: Case, steps: int | None, seed: int
) -> tuple[dict[str, Any], Observed | None]:
    """One run of ``case``'s simulator (``steps``: ``None`` for the kind's) with root ``seed``:
    its summary and what it observes. Raises :class:`CaseError` if the simulator refuses the case,
    :class:`PropertyFails` if the case's controller does not exist (ε₁ = 0)."""
    chosen = simulator_for(case, steps)
    runs = monte_carlo(chosen.spec, runs=1, seed=seed, workers=1, simulate=chosen.run)
    finished = chosen.finish(case, chosen.spec, runs, None, False)  # the summary, no files
    return finished.summary, finished.observed


def _simulated(summary: Mapping[str, Any], observed: Observed | None) -> dict[str, Any]:
    agents = summary.get("agents") or []
    keys = [k for k in (agents[0] if agents else {}) if k.endswith("_error")]
    out = {f"sim_{k}": float(np.max([a[k] for a in agents])) for k in keys}
    if observed is not None:
        out |= {f"sim_{k}": v for k, v in observed.values.items()}
    return out


def _by_simulation(case: Case, observed: Observed | None, summary: Mapping[str, Any]) -> Judgement:
    """``trackcert simulate``'s verdict: the case's expectations against the simulation."""
    if observed is None:
        return Judgement(None, None, {}, "no analysis verdict and no simulated observation")
    expectations = judge(case, observed, source=SOURCE)
    unmet = [e.describe() for e in expectations if not e.met]
    return Judgement(
        expectations_verdict(expectations),
        None,
        dict(summary.get("tolerances") or {}),
        "; ".join(unmet) or f"{len(expectations)} simulated expectation(s) met",
    )


def _seed(setup: SweepSetup, values: Sequence[Any]) -> int:
    chosen = [v for t, v in zip(setup.targets, values, strict=True) if t.is_seed]
    return int(chosen[0]) if chosen else setup.seed


def evaluate_point(setup: SweepSetup, point: int, values: Sequence[Any]) -> Row:
    """The row of the point of index ``point`` (grid order) and ``values`` (one per target)."""
    values = tuple(values)
    try:
        case = parse_case(apply_values(setup.data, setup.targets, values), file=setup.file)
        judgement = _judge(case)
    except CaseError as error:
        return Row(point, values, PointStatus.INVALID, message=str(error))
    simulate = setup.simulate and case.kind in SIMULATED
    seed = _seed(setup, values) if simulate else None
    summary: dict[str, Any] = {}
    observed: Observed | None = None
    notes = []
    if simulate:
        try:
            summary, observed = simulate_point(case, setup.steps, seed)
        except CaseError as error:
            seed, notes = None, [f"not simulated: {error.expected} at {error.field}"]
        except PropertyFails as error:  # e.g. ε₁ = 0: the controller does not exist
            seed, notes = None, [f"not simulated: {error}"]
        notes += list(summary.get("warnings") or [])
    if judgement is None:
        judgement = _by_simulation(case, observed, summary)
    agrees, why = agreement(case.kind, judgement.verdict, summary if seed is not None else None)
    return Row(
        point,
        values,
        PointStatus(status_of(judgement.verdict)),
        judgement.margin,
        judgement.tolerances,
        seed,
        _simulated(summary, observed),
        Agreement(agrees),
        "; ".join(m for m in [judgement.message, why, *notes] if m),
    )


def evaluate_batch(setup: SweepSetup, batch: Sequence[tuple[int, Sequence[Any]]]) -> list[Row]:
    """The rows of a batch of ``(index, values)`` points (one engine task), in batch order."""
    return [evaluate_point(setup, point, values) for point, values in batch]
