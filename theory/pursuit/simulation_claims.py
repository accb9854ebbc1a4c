"""The claim ``seed003.thm2.sim-trajectories``: ``trackcert iss`` and ``trackcert simulate`` agree.

On every ``kind: pursuit`` case for which the ISS analysis issues a verdict (every condition of
:func:`theory.pursuit.iss.iss_conditions` holds) and which can be simulated, one run — seed 0,
the default duration, exactly the run ``trackcert simulate CASE`` makes by default — is checked
against the certified estimate of Theorem 2 (:func:`theory.pursuit.iss_check.simulation_agreement`).
The observed ``simulation_bounded`` goes under ``evidence["expectations"]``, so cases can state
``expect: {simulation_bounded: true}``. One run serves both questions the claim answers (does
the trajectory satisfy the estimate; does the simulator contradict the certificate).

References
----------
seed 003, Theorem 2; docs/theory/pursuit-iss.md §8.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, NotApplicable, register
from theory.core.errors import CaseError

__all__ = ["SIMULATION_SEED", "check_simulation_agrees", "default_run"]

SIMULATION_SEED = 0
"""Root seed of the run (``trackcert simulate``'s default)."""


def default_run(case: Case):
    """The run ``trackcert simulate CASE`` makes by default (one run, root seed 0, 450 s).

    Parameters
    ----------
    case : Case
        A ``kind: pursuit`` case with ``target`` and ``dekf`` blocks.

    Returns
    -------
    theory.pursuit.closed_loop.DecRun
    """
    from theory.pursuit.simulation import run_pursuit_case, runaway_factor_of
    from theory.sim.runner import run_seeds

    (sequence,) = run_seeds(SIMULATION_SEED, 1)
    rng = np.random.default_rng(sequence)
    return run_pursuit_case(case.spec, rng, runaway_factor=runaway_factor_of(case))


def _certified(case: Case) -> None:
    """Raise :class:`NotApplicable` unless ``trackcert iss`` certifies the case and it simulates."""
    from theory.pursuit.iss import iss_conditions
    from theory.pursuit.simulation import check_pursuit_case

    tol = case.tolerances.get("margin_tol")
    options = {} if tol is None else {"margin_tol": float(tol)}
    undecided = [c.name for c in iss_conditions(case.spec, **options) if c.status != "holds"]
    if case.spec.n_trackers == 1:  # graph conditions are not applicable to one tracker
        undecided = [name for name in undecided if name != "graph_strongly_connected"]
    if undecided:
        raise NotApplicable(f"trackcert iss certifies nothing here (conditions {undecided})")
    try:
        check_pursuit_case(case.spec)
    except CaseError as error:
        raise NotApplicable(f"nothing to simulate: {error.field} is not {error.expected}") from None


@register(
    "seed003.thm2.sim-trajectories",
    source="seed 003, Theorem 2 (corrected constants of theory.pursuit.iss) against the simulator",
    statement="When trackcert iss certifies a case, its simulated trajectory (trackcert simulate, "
    "seed 0) stays finite and within the certified estimate ‖μ(t)‖ ≤ β(‖μ(0)‖, t) + "
    "γ(sup‖x̃‖) at every record.",
    kinds=("pursuit",),
)
def check_simulation_agrees(case: Case, *, figure_dir: Path | None = None) -> list[ClaimResult]:
    """Simulate a certified case once and compare the run with the certified estimate.

    Parameters
    ----------
    case : Case
        A ``kind: pursuit`` case.
    figure_dir : Path, optional
        Where to draw ‖μ(t)‖ against the estimate (``mu_bound.png``).

    Returns
    -------
    list of ClaimResult
        ``verified`` (agreement), ``refuted`` (μ leaves the estimate) or ``inconclusive`` (the
        integration stopped early inside it), method ``simulation``.

    Raises
    ------
    NotApplicable
        If a condition does not hold (no verdict to compare with) or the case cannot be simulated.
    """
    from theory.pursuit.iss_check import iss_margin_along, simulation_agreement

    _certified(case)
    run = default_run(case)
    verdict = simulation_agreement(case.spec, run)
    figures = ()
    if figure_dir is not None:
        figures = (_figure(run.times, iss_margin_along(case.spec, run), Path(figure_dir)),)
    evidence = {k: v for k, v in verdict.items() if k not in ("status", "message")}
    evidence |= {"seed": SIMULATION_SEED, "records": len(run.times), "steps": run.steps}
    evidence["expectations"] = {"simulation_bounded": verdict["simulation_bounded"]}
    return [
        ClaimResult(
            claim="seed003.thm2.sim-trajectories", case=case.name, method="simulation",
            status=verdict["status"], evidence=evidence, margin=verdict["relative_margin"],
            tolerance={"iss_bound_rtol": verdict["iss_bound_rtol"]}, message=verdict["message"],
            figures=figures,
        )
    ]  # fmt: skip


def _figure(times: np.ndarray, along: dict[str, Any], folder: Path) -> str:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from theory.sim.figures import save_figure

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.semilogy(times[: len(along["mu"])], along["mu"], lw=1, label="‖μ(t)‖ (simulated)")
    ax.semilogy(times[: len(along["bound"])], along["bound"], lw=1, label="β + γ (certified)")
    ax.set_xlabel("time (s)")
    ax.legend(fontsize=7)
    return str(save_figure(fig, folder / "mu_bound.png"))
