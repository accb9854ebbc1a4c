"""Pursuit claims that still live outside :mod:`theory.pursuit` (interim, until its merge).

* ``seed003.thm2.sim-trajectories`` — the ISS estimate along simulated DEC trajectories;
* ``case.expect.pursuit`` — each pursuit case's expect block, observed by
  :func:`observe_pursuit` from ``trackcert iss``'s record (:func:`theory.cli.iss.iss_report`,
  imported lazily: the one place the library still reaches into the CLI).

The pursuit engineer moves both into :mod:`theory.pursuit` (the observer registered with the
kind, ``register_kind(..., observe=...)``). The tdoa and consensus simulation claims live in
:mod:`theory.tdoa.simulation_claims`, :mod:`theory.tdoa.formation_claims` and
:mod:`theory.consensus.simulation_claims`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from theory.core.claims import ClaimResult, NotApplicable, register
from theory.core.expectations import Observed, expectation_claim

__all__ = ["check_iss_along_runs", "observe_pursuit"]


def observe_pursuit(case: Any) -> Observed:
    """The expect keys of a ``kind: pursuit`` case, as ``trackcert iss`` finds them (interim).

    Parameters
    ----------
    case : Case
        A loaded pursuit case.

    Returns
    -------
    Observed
        ``iss``, ``delta_full_rank``, ``strongly_connected``; ``None`` values undecided.
    """
    from theory.cli.iss import iss_report  # interim: moves with the pursuit merge

    values = {e["key"]: e["actual"] for e in iss_report(case)["expectations"]}
    return Observed(values, frozenset(k for k, v in values.items() if v is None))


expectation_claim("pursuit", command="iss", observe=observe_pursuit)

ISS_STEPS = 1500
ISS_SEEDS = (0, 1)


@register(
    "seed003.thm2.sim-trajectories",
    source="seed 003, Theorem 2 (with the corrected constants of theory.pursuit.iss)",
    statement="Along every trajectory of the DEC, ‖μ(t)‖ ≤ β(‖μ(0)‖, t) + γ(sup‖x̃‖).",
    kinds=("pursuit",),
)
def check_iss_along_runs(case: Any) -> list[ClaimResult]:
    """Simulate the 2-D DEC loop (seeds :data:`ISS_SEEDS`) and evaluate both sides of the ISS
    estimate at every step.

    Parameters
    ----------
    case : Case
        A ``kind: pursuit`` case.
    """
    from theory.core.errors import CaseError
    from theory.pursuit.iss_check import iss_margin_along
    from theory.pursuit.simulation import check_pursuit_case, run_pursuit_case

    def result(status: str, message: str, **evidence: Any) -> list[ClaimResult]:
        return [
            ClaimResult(
                claim="seed003.thm2.sim-trajectories",
                case=case.name,
                method="simulation",
                status=status,
                evidence=evidence,
                margin=evidence.get("margin"),
                message=message,
            )
        ]

    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise NotApplicable(f"nothing to simulate: {error.field} is not {error.expected}") from None
    checks = []
    for seed in ISS_SEEDS:
        run = run_pursuit_case(case.spec, np.random.default_rng(seed), steps=ISS_STEPS)
        try:
            checks.append(iss_margin_along(case.spec, run))
        except ValueError as error:
            return result("inconclusive", f"no ISS estimate: {error}")
    margin = min(c["margin"] for c in checks)
    return result(
        "verified" if margin >= 0 else "refuted",
        "bound evaluated at every 0.1 s step of forward-Euler runs",
        margin=margin,
        gain=checks[0]["gain"],
        seeds=list(ISS_SEEDS),
        steps=ISS_STEPS,
        worst_time=[c["worst_time"] for c in checks],
        final_mu=[float(c["mu"][-1]) for c in checks],
        final_bound=[float(c["bound"][-1]) for c in checks],
    )
