"""What ``trackcert iss`` reports on a ``kind: pursuit`` case, as a library call (seed 003).

:func:`iss_report` runs the ISS analysis (:mod:`theory.pursuit.iss`: the conditions of Lemmas 1–4
and Theorems 1–2, the decay rates and gains, the derivative identity (70)), the case-level seed 003
claims, and judges the case's ``expect`` block with :mod:`theory.core.expectations`; the command
only prints it. :func:`observe_iss` is the kind's observer, so the report's ``case.expect.pursuit``
claim and the command agree on every key. ``simulation_bounded`` is not observed here: the
simulation observes it (:func:`theory.pursuit.simulation.simulation_observed`, claim
``seed003.thm2.sim-trajectories``).

The property decided: every condition holds (True), one fails (False), or a margin lies inside
``margin_tol`` (None, inconclusive).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import get_claim
from theory.core.errors import CaseError
from theory.core.expectations import Expectation, Observed, judge
from theory.core.tolerances import INEQUALITY_RTOL, MARGIN_TOL
from theory.core.verdicts import Verdict

__all__ = ["SCOPE", "IssReport", "iss_observed", "iss_report", "observe_iss"]

SOURCE = "trackcert iss"
"""The observations' source in the command's verdict records."""

SCOPE = (
    "the pursuit and coordination errors μ = (ξ, e) are ISS with respect to the DEKF's "
    "estimation error x̃ (Theorem 2, corrected); x̃ is the input: whether the DEKF keeps it "
    "bounded in closed loop is not part of the certificate"
)
"""What a ``holds`` verdict of ``trackcert iss`` covers (and what it does not)."""


@dataclass(frozen=True)
class IssReport:
    """The record ``trackcert iss`` prints.

    Attributes
    ----------
    record : dict
        Plain data: ``case``, ``controller``, ``lyapunov``, ``decay_rate``, ``iss_gain``,
        ``constants``, ``conditions``, ``claims``, ``tolerances``, ``scope`` (DESIGN.md).
    expectations : tuple of Expectation
        The case's ``expect`` block judged against :func:`iss_observed`.
    """

    record: dict[str, Any]
    expectations: tuple[Expectation, ...]

    @property
    def verdict(self) -> Verdict:
        """False if a condition fails, None if one is inconclusive, else True."""
        statuses = {c["status"] for c in self.record["conditions"]}
        return False if "fails" in statuses else None if "inconclusive" in statuses else True

    def to_json(self) -> dict[str, Any]:
        """The ``--json`` record with ``expectations`` (each ``key``, ``expected``, ``got``,
        ``met``, ``verdict``, ``observations``)."""
        return {**self.record, "expectations": [e.to_json() for e in self.expectations]}


def iss_report(case: Case, *, margin_tol: float | None = None) -> IssReport:
    """Analyze ``case``, run its seed 003 claims and judge its expectations (``trackcert iss``).

    Parameters
    ----------
    case : Case
        A loaded ``kind: pursuit`` case.
    margin_tol : float, optional
        Overrides the case's ``tolerances.margin_tol`` (table default ``margin_tol``).

    Returns
    -------
    IssReport

    Raises
    ------
    CaseError
        If the case is not of kind ``pursuit`` or ``margin_tol`` is not positive.

    References
    ----------
    seed 003, Lemmas 1–4, Theorems 1–2, eq. (70).
    """
    from theory.pursuit.iss_claims import run_case_claims  # sympy: imported on use

    record = iss_record(case, margin_tol=margin_tol)
    record["claims"] = [r.to_json(get_claim(r.claim).source) for r in run_case_claims(case)]
    expectations = judge(case, iss_observed(record), source=SOURCE)
    return IssReport(record, tuple(expectations))


def iss_record(case: Case, *, margin_tol: float | None = None) -> dict[str, Any]:
    """The analysis part of :func:`iss_report` (no claims, no expectations).

    Parameters
    ----------
    case : Case
        A loaded ``kind: pursuit`` case.
    margin_tol : float, optional
        As in :func:`iss_report`.

    Returns
    -------
    dict
    """
    from theory.pursuit.iss import coordination_iss, iss_bound, iss_conditions, pursuit_iss
    from theory.pursuit.iss_symbolic import lyapunov_derivative_check

    if case.kind != "pursuit":
        raise CaseError(
            "kind", "pursuit (trackcert iss analyses seed 003 cases)", case.kind, file=case.file
        )
    tol = _margin_tol(case, margin_tol)
    spec = case.spec
    conditions = iss_conditions(spec, margin_tol=tol)
    pursuit, coordination = pursuit_iss(spec), coordination_iss(spec)
    statuses = {c.status for c in conditions}
    gains: dict[str, Any] = {"pursuit": pursuit.gain, "pursuit_paper": pursuit.paper_gain}
    gains["coordination"] = coordination.gain
    gains["cascade"] = iss_bound(spec).gain if "fails" not in statuses else None
    r = [float(x) for x in coordination.r] if coordination.r else None
    identity = lyapunov_derivative_check(spec.dim, spec.controller, True)
    return {
        "case": case.name,
        "source": case.source,
        "controller": spec.controller,
        "dim": spec.dim,
        "n_trackers": spec.n_trackers,
        "holds": "fails" not in statuses and "inconclusive" not in statuses,
        "scope": SCOPE,
        "lyapunov": _lyapunov(spec, len(pursuit.K), r, identity.holds),
        "decay_rate": {
            "pursuit": pursuit.decay_rate,
            "pursuit_lyapunov": 2 * pursuit.decay_rate,
            "coordination": coordination.decay_rate,
            "coordination_spectral": coordination.spectral_rate,
            "coordination_printed_eq75": coordination.printed_decay_coefficient,
        },
        "iss_gain": gains,
        "constants": _constants(pursuit, coordination, r),
        "conditions": [c.to_json(tol) for c in conditions],
        "tolerances": {"margin_tol": tol, "inequality_rtol": INEQUALITY_RTOL},
    }


def iss_observed(record: dict[str, Any]) -> Observed:
    """The ``iss``, ``delta_full_rank`` and ``strongly_connected`` keys of an ISS record.

    Parameters
    ----------
    record : dict
        From :func:`iss_record`.

    Returns
    -------
    Observed
        An inconclusive condition leaves its key (and ``iss``) undecided.
    """
    status = {c["name"]: c["status"] for c in record["conditions"]}
    values = {
        "iss": record["holds"],
        "delta_full_rank": _holds(status.get("delta_full_rank")),
        "strongly_connected": _holds(status.get("graph_strongly_connected", "holds")),
    }
    if "inconclusive" in status.values():
        values["iss"] = None
    return Observed(values, frozenset(k for k, v in values.items() if v is None))


def observe_iss(case: Case) -> Observed:
    """The observer of ``kind: pursuit`` (:func:`theory.core.case_file.register_kind`).

    Parameters
    ----------
    case : Case
        A loaded pursuit case (its own ``margin_tol`` applies).

    Returns
    -------
    Observed
        :func:`iss_observed` of :func:`iss_record`.
    """
    return iss_observed(iss_record(case))


def _holds(status: str | None) -> bool | None:
    return None if status in (None, "inconclusive") else status == "holds"


def _margin_tol(case: Case, margin_tol: float | None) -> float:
    if margin_tol is not None and not margin_tol > 0:
        raise CaseError("--margin-tol", "a number > 0", margin_tol, file=case.file)
    tol = margin_tol if margin_tol is not None else case.tolerances.get("margin_tol")
    return float(MARGIN_TOL) if tol is None else float(tol)


def _lyapunov(spec: Any, size: int, r: list[float] | None, identity: bool) -> dict[str, Any]:
    return {
        "pursuit": {
            "function": "V_e = ½‖e‖² = eᵀ P_e e, e = col(e_p^[i], e_γ^[i])",
            "P_e": 0.5 * np.eye(size * spec.n_trackers),
            "derivative_identity_eq70": identity,
        },
        "coordination": {
            "function": "V_c = ½ ξᵀ R ξ, ξ = (I − 1rᵀ)γ, R = diag(r)",
            "R": np.diag(r) if r else None,
        },
    }


def _constants(pursuit: Any, coordination: Any, r: list[float] | None) -> dict[str, Any]:
    return pursuit.constants() | {
        "printed_region_eq72_argument_sound": pursuit.printed_region_sound,
        "printed_region_eq72_holds_by_sharp_bound": pursuit.printed_region_holds,
        "a_L": coordination.a_L,
        "r": r,
        "kappa": coordination.kappa,
        "b": coordination.b,
    }
