"""Each case's ``expect`` block checked by the analysis of its own command, for the report.

One claim per case kind runs what ``trackcert topology`` / ``dkf`` / ``iss`` / ``simulate``
run and reports the observed value of every expected key under ``evidence["expectations"]``
(the mechanism of :mod:`theory.report.expectations`), so that ``trackcert report`` and the
commands agree on whether a case's expectations are met. Its status is ``verified`` when every
expected key matches, ``refuted`` when one does not, ``inconclusive`` when a value could not be
decided. ``kind: pf`` cases need no bridge: the claims of :mod:`theory.particle.claims`, which
``trackcert pf`` runs, report their observations themselves.
"""

from __future__ import annotations

from typing import Any

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, register

__all__ = ["dkf_observed", "pursuit_observed", "tdoa_observed", "tdoa_sim_observed"]


def tdoa_observed(case: Case) -> dict[str, Any]:
    """Observed values of ``case``'s tdoa keys, from :func:`theory.cli.topology.run_topology`.

    Static keys come from the first step, the trajectory keys from the whole trajectory.
    """
    from theory.cli.topology import run_topology
    from theory.tdoa.topology import observed_values

    result = run_topology(case)
    return {
        **observed_values(result.steps[0]),
        "first_failure_step": result.first_failure_step,
        "unobservable_steps": list(result.unobservable_steps),
    }


def dkf_observed(case: Case, analysis: Any = None) -> dict[str, Any]:
    """Observed values of ``case``'s dkf keys, from :func:`theory.consensus.claims.analyze_dkf`.

    Parameters
    ----------
    case : Case
        A ``dkf`` case.
    analysis : DkfAnalysis, optional
        Its analysis, when the caller has already computed it.
    """
    from theory.consensus.claims import analyze_dkf

    analysis = analysis or analyze_dkf(case, search_self_weight=False)
    return {e["key"]: e["got"] for e in analysis.expectations()}


def pursuit_observed(case: Case) -> dict[str, Any]:
    """Observed values of ``case``'s pursuit keys, from :func:`theory.cli.iss.iss_report`."""
    from theory.cli.iss import iss_report

    return {e["key"]: e["actual"] for e in iss_report(case)["expectations"]}


def tdoa_sim_observed(case: Case) -> dict[str, Any]:
    """Observed values of ``case``'s tdoa-sim keys: one run with seed 0, as ``trackcert simulate``
    runs it by default, judged by :func:`theory.tdoa.metrics.check_expectations`."""
    import math

    from theory.sim.runner import monte_carlo
    from theory.tdoa.metrics import check_expectations, summarize_runs

    results = monte_carlo(case.spec, runs=1, seed=0, workers=1)
    bound = case.tolerances.get("error_bound", 10.0 * math.sqrt(case.spec.r))
    checked = check_expectations(summarize_runs(case.spec, results), case.expect, error_bound=bound)
    return {key: entry["got"] for key, entry in checked.items()}


def _expectation_claim(kind: str, command: str, observe: Any) -> None:
    @register(
        f"case.expect.{kind}",
        source=f"the case file's expect block (checked as trackcert {command} checks it)",
        statement=f"Every expectation a {kind} case states is what trackcert {command} finds.",
        kinds=(kind,),
    )
    def run(case: Case, **computed: Any) -> list[ClaimResult]:
        from theory.report.expectations import matches

        observed = {k: v for k, v in observe(case, **computed).items() if k in case.expect}
        undecided = [k for k, v in observed.items() if v is None and case.expect[k] is not None]
        wrong = [
            k for k, v in observed.items() if k not in undecided and not matches(case.expect[k], v)
        ]
        status = "refuted" if wrong else "inconclusive" if undecided else "verified"
        detail = f"mismatch in {wrong}" if wrong else f"undecided: {undecided}" if undecided else ""
        return [
            ClaimResult(
                claim=f"case.expect.{kind}",
                case=case.name,
                method="numeric",
                status=status,
                evidence={"expectations": observed},
                message=detail or f"{len(observed)} expectation(s) checked",
            )
        ]


_expectation_claim("tdoa", "topology", tdoa_observed)
_expectation_claim("dkf", "dkf", dkf_observed)
_expectation_claim("pursuit", "iss", pursuit_observed)
_expectation_claim("tdoa-sim", "simulate", tdoa_sim_observed)
