"""The verdict of one sweep point: the analysis behind the kind's command, and what the
simulation is compared with.

Each kind's verdict is the property its command decides, computed by the same library
function (nothing is re-derived here):

* ``pursuit`` — ``trackcert iss``: every condition of the corrected Theorem 2 holds
  (:func:`theory.pursuit.iss.iss_record`, the analysis part of
  :func:`~theory.pursuit.iss.iss_report`, read by
  :attr:`~theory.pursuit.iss.IssReport.verdict`; the case-level claims the command also
  lists do not enter its verdict and are not run per point). Margin: the smallest relative margin
  of a condition; tolerance ``margin_tol``.
* ``dkf`` — ``trackcert dkf``: S-detectability (seed 000 Def. 5.2.4) by
  :func:`theory.consensus.analysis.analyze_dkf` without the self-weight bisection (no verdict
  depends on it). Margin: the LMI witness's relative margin (``None`` when not S-detectable);
  tolerances ``lmi_margin``, ``cert_tol``, ``rank_tol``, ``value_tol``.
* ``tdoa`` — ``trackcert topology``: every agent localizes the target at every step
  (:func:`theory.tdoa.observability.trajectory.run_topology`). Margin: the least factor by which a
  deciding singular value clears ``rank_tol · σ_max`` (inconclusive below
  ``inconclusive_factor``).
* ``pf`` — ``trackcert pf``: the case's ``expect`` block judged by the pf claims
  (:func:`theory.particle.report.pf_report`; its Monte Carlo is the verdict). No margin.
* ``tdoa-sim`` (and any kind not listed in :data:`ANALYSES`) — ``trackcert simulate``: the case's
  ``expect`` block judged against the point's own simulation.

:data:`PREDICTIONS` says what a holding verdict predicts of the simulation: for ``pursuit``,
Theorem 2 (seed 003) certifies that the pursuit and coordination errors μ stay within the ISS
estimate β(‖μ(0)‖, t) + γ(sup‖x̃‖), which the pursuit simulator checks on every run
(:func:`theory.pursuit.simulation.simulation_agreement`, its summary's ``iss_agreement``).
:func:`agreement` compares them; the other kinds predict nothing of their simulation (the dkf
simulation runs the optimal-gain filter, whose convergence S-detectability does not decide).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from theory.core.case_file import Case
from theory.core.verdicts import Verdict

__all__ = [
    "AGREEMENTS",
    "ANALYSES",
    "ANALYSIS_MODULES",
    "PREDICTIONS",
    "Judgement",
    "agreement",
    "analysis_for",
    "dkf_judgement",
    "pf_judgement",
    "point_modules",
    "pursuit_judgement",
    "pursuit_prediction",
    "tdoa_judgement",
]

AGREEMENTS = ("agree", "disagree", "inconclusive", "n/a")
"""Values of a point's ``agreement`` (:func:`agreement`)."""


@dataclass(frozen=True)
class Judgement:
    """The verdict of one point's analysis.

    Attributes
    ----------
    verdict : bool or None
        True holds, False fails, None inconclusive (:mod:`theory.core.verdicts`).
    margin : float or None
        The margin the verdict was decided with (per kind: module docstring).
    tolerances : dict
        Name → value of every tolerance used.
    message : str
        One line saying why.
    """

    verdict: Verdict
    margin: float | None
    tolerances: dict[str, float] = field(default_factory=dict)
    message: str = ""


def pursuit_judgement(case: Case) -> Judgement:
    """``trackcert iss``'s verdict on a pursuit case (seed 003 Lemmas 1–4, Theorems 1–2).

    Parameters
    ----------
    case : Case
        A loaded ``kind: pursuit`` case.

    Returns
    -------
    Judgement
    """
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
    """``trackcert dkf``'s verdict: S-detectability (seed 000 Def. 5.2.4).

    Parameters
    ----------
    case : Case
        A loaded ``kind: dkf`` case.

    Returns
    -------
    Judgement
    """
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
    """``trackcert topology``'s verdict: every agent localizes at every step (seed 000 §4.2.2).

    Parameters
    ----------
    case : Case
        A loaded ``kind: tdoa`` case.

    Returns
    -------
    Judgement
    """
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
    """``trackcert pf``'s verdict: the case's expectations judged by the pf claims (seed 002).

    Parameters
    ----------
    case : Case
        A loaded ``kind: pf`` case.

    Returns
    -------
    Judgement
    """
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
"""Kind → the module its analysis imports (each imports lazily, so that a sweep imports only its
kind's): the sweep's workers are forked with it already imported (:func:`point_modules`)."""


def pursuit_prediction(summary: Mapping[str, Any]) -> tuple[Verdict, str]:
    """Whether a pursuit run stayed within the ISS estimate its verdict certifies (Theorem 2).

    Parameters
    ----------
    summary : mapping
        The pursuit simulator's summary (:func:`theory.pursuit.simulation.summarize_pursuit`),
        whose ``iss_agreement`` is :func:`theory.pursuit.simulation.simulation_agreement` of the
        run (``None`` when the analysis certifies nothing).

    Returns
    -------
    (bool or None, str)
        True within the estimate at every record, False when ‖μ‖ leaves it, None when the
        integration stopped inside it (the DEKF's x̃, the estimate's input, ran away: the
        certificate is not contradicted) or nothing is certified; and the checker's message.
    """
    found = summary.get("iss_agreement")
    if not found:
        return None, ""
    status = {"verified": True, "refuted": False}.get(found["status"])
    return status, found["message"]


PREDICTIONS: dict[str, Callable[[Mapping[str, Any]], tuple[Verdict, str]]] = {
    "pursuit": pursuit_prediction,
}
"""Kind → what a holding verdict predicts of the simulation: ``check(summary) -> (verdict,
message)``, True when the simulation bears the prediction out."""


def point_modules(kind: str) -> tuple[str, ...]:
    """The modules evaluating a sweep point of ``kind`` imports: the sweep's own, the kind's,
    its simulator's and its analysis's (the engine's ``preload``,
    :func:`theory.core.parallel.engine`: imported once by the workers' forkserver instead of in
    each worker's first task).

    Parameters
    ----------
    kind : str
        A case kind.

    Returns
    -------
    tuple of str
    """
    from theory.kinds import KINDS, SIMULATED, simulator

    simulated = (simulator(kind).__module__,) if kind in SIMULATED else ()
    analysis = (ANALYSIS_MODULES[kind],) if kind in ANALYSIS_MODULES else ()
    return ("theory.sweep.points", KINDS[kind].parse.__module__, *simulated, *analysis)


def analysis_for(kind: str) -> Callable[[Case], Judgement] | None:
    """The analysis verdict of ``kind`` (``None``: the kind is judged by its simulation).

    Parameters
    ----------
    kind : str
        A case kind.

    Returns
    -------
    callable or None
    """
    return ANALYSES.get(kind)


def agreement(kind: str, verdict: Verdict, summary: Mapping[str, Any] | None) -> tuple[str, str]:
    """Whether a point's simulation agrees with its verdict (one of :data:`AGREEMENTS`).

    Parameters
    ----------
    kind : str
        The case kind.
    verdict : bool or None
        The analysis verdict.
    summary : mapping or None
        The point's simulation summary (``None``: not simulated).

    Returns
    -------
    (str, str)
        ``agree`` / ``disagree`` when the verdict holds and the simulation bears its prediction
        (:data:`PREDICTIONS`) out / contradicts it; ``inconclusive`` when the verdict or the
        comparison is undecided; ``n/a`` when nothing is predicted: the kind predicts nothing of
        its simulation, the point was not simulated, or the verdict fails (the conditions are
        sufficient, so a failing verdict predicts nothing). And the comparison's message.
    """
    check = PREDICTIONS.get(kind)
    if check is None or summary is None or verdict is False:
        return "n/a", ""
    if verdict is None:
        return "inconclusive", "the verdict is inconclusive"
    bears_out, message = check(summary)
    word = {True: "agree", False: "disagree", None: "inconclusive"}[bears_out]
    return word, message
