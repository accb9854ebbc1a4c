"""What ``trackcert dkf`` and ``trackcert simulate`` report on a ``kind: dkf`` case.

:func:`dkf_report` runs :func:`theory.consensus.claims.analyze_dkf` and every registered claim
of kind ``dkf`` and judges the case's ``expect`` block with :mod:`theory.core.expectations`; the
command only prints it. The kind's observer :func:`observe_dkf` reads the same analysis, so the
report's ``case.expect.dkf`` claim and the command agree on every expectation.
:func:`dkf_simulator` is the kind's simulator (:mod:`theory.sim.simulate`,
:mod:`theory.consensus.simulation`).

The property decided (seed 000 Def. 5.2.4): S-detectability, True/False, or None when the LMI
decision is inconclusive.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from theory.consensus.case import EXPECT_KEYS
from theory.core.case_file import Case
from theory.core.claims import ClaimResult, get_claim
from theory.core.errors import CaseError
from theory.core.expectations import Expectation, Observed, judge
from theory.sim.simulate import Finished, Simulator

__all__ = [
    "DkfReport",
    "dkf_observed",
    "dkf_report",
    "dkf_simulator",
    "observe_dkf",
    "riccati_converges",
]

SOURCE = "trackcert dkf"
"""The observations' source in the command's verdict records."""

SOLVERS = ("CLARABEL", "SCS")


def dkf_observed(analysis: Any) -> Observed:
    """The value of every dkf expect key in ``analysis`` (``None`` values are undecided).

    Parameters
    ----------
    analysis : DkfAnalysis
        From :func:`theory.consensus.claims.analyze_dkf`.

    Returns
    -------
    Observed
        ``s_detectable`` (Def. 5.2.4), ``spectral_radius_B`` / ``_L`` (with the case's gains or
        the witness's), ``self_weight_ok``, ``paper_conditions_ok`` and
        ``blind_set_condition_ok`` (Thm 5.2.10), read off the ``--json`` record, and
        ``riccati_converges`` (eqs. (5.7)–(5.9)).
    """
    data = analysis.to_json()
    values = {key: data.get(key) for key in EXPECT_KEYS}
    values["riccati_converges"] = riccati_converges(data["riccati"]["status"], data["s_detectable"])
    return Observed(values, frozenset(k for k, v in values.items() if v is None))


def riccati_converges(status: str, s_detectable: bool | None) -> bool | None:
    """Whether the coupled Riccati iteration converges, never read off a float budget alone.

    Footnote 5 holds both ways for boundedness (``docs/theory/s-detectability.md`` §7): not
    S-detectable ⇒ unbounded from every ``P0 ⪰ 0``, so an exact negative verdict answers False
    whatever the iteration did within ``max_iter`` (e.g. Example 1's ``W_c``, ``r_σ = 1``, whose
    iterates grow only linearly); S-detectable ⇒ bounded, and the answer is True when the
    iteration met ``conv_tol``. Anything else — the budget ran out, a float "diverged" against a
    positive certificate, or an inconclusive decision — is None.

    Parameters
    ----------
    status : str
        :attr:`theory.consensus.riccati.RiccatiRun.status`.
    s_detectable : bool or None
        The exact S-detectability verdict.

    Returns
    -------
    bool or None
    """
    if s_detectable is False:
        return False
    if s_detectable is True and status == "converged":
        return True
    return None


def observe_dkf(case: Case, analysis: Any = None) -> Observed:
    """The observer of ``kind: dkf`` (:func:`theory.core.case_file.register_kind`).

    Parameters
    ----------
    case : Case
        A loaded dkf case (its own tolerances apply).
    analysis : DkfAnalysis, optional
        Its analysis, when the caller has already computed it.

    Returns
    -------
    Observed
        :func:`dkf_observed` of the analysis the dkf claims share (no self-weight search: no
        expect key depends on it).
    """
    from theory.consensus.claims import analyze_dkf

    return dkf_observed(analysis or analyze_dkf(case, search_self_weight=False))


@dataclass(frozen=True)
class DkfReport:
    """The record ``trackcert dkf`` prints.

    Attributes
    ----------
    analysis : DkfAnalysis
        LMI decision, necessary conditions, radii, self-weight searches, Riccati run.
    claims : tuple of ClaimResult
        Every registered ``dkf`` claim's results on the case.
    expectations : tuple of Expectation
        The case's ``expect`` block judged against :func:`dkf_observed`.
    """

    analysis: Any
    claims: tuple[ClaimResult, ...]
    expectations: tuple[Expectation, ...]

    @property
    def verdict(self) -> bool | None:
        """S-detectable (True/False), or None when the LMI decision is inconclusive."""
        return self.analysis.decision.verdict

    def to_json(self) -> dict[str, Any]:
        """The DESIGN.md ``--json`` record, with ``expectations`` (each ``key``, ``expected``,
        ``got``, ``met``, ``verdict``, ``observations``) and ``claims``."""
        return {
            **self.analysis.to_json(),
            "expectations": [e.to_json() for e in self.expectations],
            "claims": [r.to_json(get_claim(r.claim).source) for r in self.claims],
        }


def dkf_report(
    case: Case, *, search_self_weight: bool = True, solver: str = "CLARABEL"
) -> DkfReport:
    """Analyze ``case``, run its claims and judge its expectations (``trackcert dkf``).

    Parameters
    ----------
    case : Case
        A loaded ``kind: dkf`` case.
    search_self_weight : bool
        Whether to bisect each agent's largest self-weight.
    solver : str
        ``CLARABEL`` or ``SCS``.

    Returns
    -------
    DkfReport

    Raises
    ------
    CaseError
        If the case is not ``kind: dkf`` or the solver is unknown.
    """
    if case.kind != "dkf":
        raise CaseError("kind", "dkf", case.kind, file=case.file)
    if solver not in SOLVERS:
        raise CaseError("--solver", " or ".join(SOLVERS), solver, file=case.file)
    from theory.consensus.claims import analyze_dkf, dkf_claim_results  # cvxpy: on use

    analysis = analyze_dkf(case, search_self_weight=search_self_weight, solver=solver)
    claims = [result for _, result in dkf_claim_results(analysis)]
    expectations = judge(case, dkf_observed(analysis), source=SOURCE)
    return DkfReport(analysis, tuple(claims), tuple(expectations))


def dkf_simulator(case: Case, steps: int | None = None) -> Simulator:
    """The simulator of ``case`` for :func:`theory.sim.simulate.simulate_case`.

    Parameters
    ----------
    case : Case
        A ``kind: dkf`` case.
    steps : int, optional
        Horizon ``K`` (default :data:`theory.consensus.simulation.DEFAULT_STEPS`).

    Returns
    -------
    Simulator
        The dkf keys are about S-detectability, so the runs observe no expectation.
    """
    from theory.consensus.simulation import DEFAULT_STEPS, run_dkf_case

    steps = steps or DEFAULT_STEPS
    fields = {"order": case.spec.order, "steps": steps}
    return Simulator(case.spec, functools.partial(run_dkf_case, steps=steps), fields, _finish)


def _finish(case: Case, spec: Any, results: list, folder: Path, figures: bool) -> Finished:
    from theory.consensus.simulation import summarize_dkf, write_dkf_data

    del case, figures
    summary = summarize_dkf(spec, results)
    return Finished(summary, write_dkf_data(results, summary, folder))
