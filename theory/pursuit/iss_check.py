"""The ISS estimate of seed 003 Theorem 2 checked along simulated DEC trajectories.

With ``μ = col(ξ, e)``, ``ξ = (I − 1rᵀ)γ`` (eq. (56), ``r`` the left eigenvector of ``L`` with
``rᵀ1 = 1``), ``e^[i] = [e_p^[i], e_γ^[i]]`` (true target) and ``x̃`` the stacked estimation
errors of the state each controller uses, :func:`theory.pursuit.iss.iss_bound` gives
``‖μ(t)‖ ≤ β(‖μ(0)‖, t) + γ(sup_{s≤t}‖x̃(s)‖)``. :func:`iss_margin_along` evaluates both sides at
every record of a run; :func:`simulation_agreement` turns that into the verdict shared by
``trackcert simulate`` and the claim ``seed003.thm2.sim-trajectories``: does the simulated loop
stay within what ``trackcert iss`` certifies? The estimate is conditional on x̃, which the DEKF
produces in closed loop; a run whose estimate runs away stays within it while diverging, so the
verdict also reports how x̃ grew.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from theory.core.tolerances import ISS_BOUND_RTOL
from theory.pursuit.case import PursuitSpec
from theory.pursuit.closed_loop import DecRun
from theory.pursuit.iss import coordination_iss, iss_bound

__all__ = ["STOPS", "iss_margin_along", "simulation_agreement"]



def iss_margin_along(spec: PursuitSpec, run: DecRun) -> dict[str, Any]:
    """Both sides of the Theorem 2 estimate along ``run`` (its completed records).

    Parameters
    ----------
    spec : PursuitSpec
        The case the run simulates (its gains and graph define β and γ).
    run : DecRun
        A run of :func:`theory.pursuit.simulation.run_pursuit_case`.

    Returns
    -------
    dict
        ``mu`` (‖μ(t)‖), ``bound`` (β + γ), ``margin`` (``min(bound − mu)``), ``relative_margin``
        (``min((bound − mu)/bound)``), ``holds`` (within the table's ``iss_bound_rtol``),
        ``worst_time``, ``gain`` and ``constants`` of the estimate, and ``x_tilde`` (‖x̃(t)‖).

    Raises
    ------
    ValueError
        If the analysis' conditions fail (from :func:`theory.pursuit.iss.iss_bound`).

    References
    ----------
    seed 003, Theorem 2, eqs. (55)–(78).
    """
    estimate = iss_bound(spec)
    done = np.isfinite(run.pursuit_errors).all(axis=1)
    done &= np.isfinite(run.estimation_errors).all(axis=1)
    times, gammas = run.times[done], run.gammas[done]
    if spec.n_trackers > 1:
        r = np.array([float(v) for v in coordination_iss(spec).r])
        xi_sq = ((gammas - (gammas @ r)[:, None]) ** 2).sum(axis=1)
    else:
        xi_sq = np.zeros(len(times))
    e_sq = (run.pursuit_errors[done] ** 2).sum(axis=1) + (run.gamma_errors[done] ** 2).sum(axis=1)
    mu = np.sqrt(xi_sq + e_sq)
    x_tilde = np.sqrt((run.estimation_errors[done] ** 2).sum(axis=1))
    sup_error = np.maximum.accumulate(x_tilde)
    bound = np.array([estimate.beta(mu[0], t) for t in times]) + np.array(
        [estimate.gamma(s) for s in sup_error]
    )
    slack = bound - mu
    worst = int(np.argmin(slack / bound))
    return {
        "mu": mu,
        "bound": bound,
        "margin": float(slack.min()),
        "relative_margin": float(slack[worst] / bound[worst]),
        "holds": bool(np.all(mu <= bound * (1 + ISS_BOUND_RTOL))),
        "worst_time": float(times[worst]),
        "gain": estimate.gain,
        "constants": estimate.constants,
        "x_tilde": x_tilde,
    }


STOPS = {
    "runaway": "a runaway: the DEKF lost the target",
    "step_floor": "the integrator's step fell below its floor",
}
"""How a stopped run's message names its cause (the full reason is in the run's warning)."""


def simulation_agreement(spec: PursuitSpec, run: DecRun) -> dict[str, Any]:
    """Whether a run of a certified case stays within the certified estimate (and finite).

    ``simulation_bounded`` is true when the integration reached the last record and ‖μ(t)‖ stays
    within β(‖μ(0)‖, t) + γ(sup‖x̃‖) at every record (slack: the table's ``iss_bound_rtol``).
    ``status`` is
    ``verified`` then, ``refuted`` when μ leaves the estimate, ``inconclusive`` when the
    run stopped early inside it (the loop ran away with its estimate, docs/theory/pursuit-iss.md
    §11: the certificate, which takes x̃ as its input, is not contradicted).

    Parameters
    ----------
    spec : PursuitSpec
        A case every condition of :func:`theory.pursuit.iss.iss_conditions` holds for.
    run : DecRun
        One simulated run of it.

    Returns
    -------
    dict
        ``simulation_bounded``, ``status``, ``message`` and the numbers: ``margin``,
        ``relative_margin``, ``worst_time``, ``gain``, ``final_mu``, ``final_bound``,
        ``x_tilde_initial``, ``x_tilde_max``, ``x_tilde_final``, ``completed``, ``stopped_at``,
        ``stop_cause`` (``"runaway"``, ``"step_floor"`` or ``None``).

    Raises
    ------
    ValueError
        If the analysis' conditions fail (there is no estimate to compare with).

    References
    ----------
    seed 003, Theorem 2; docs/theory/pursuit-iss.md §8.
    """
    along = iss_margin_along(spec, run)
    x_tilde = along["x_tilde"]
    numbers = {
        "margin": along["margin"],
        "relative_margin": along["relative_margin"],
        "iss_bound_rtol": ISS_BOUND_RTOL,
        "worst_time": along["worst_time"],
        "gain": along["gain"],
        "final_mu": float(along["mu"][-1]),
        "final_bound": float(along["bound"][-1]),
        "x_tilde_initial": float(x_tilde[0]),
        "x_tilde_max": float(x_tilde.max()),
        "x_tilde_final": float(x_tilde[-1]),
        "completed": run.completed,
        "stopped_at": None if run.completed else run.stopped_at,
        "stop_cause": None if run.completed else run.stop_cause,
    }
    if not along["holds"]:
        status = "refuted"
        message = (
            f"‖μ‖ leaves the certified estimate at t = {along['worst_time']:g} s (relative "
            f"margin {along['relative_margin']:.3g})"
        )
    elif not run.completed:
        status = "inconclusive"
        stop = STOPS.get(run.stop_cause, run.stop_reason)
        message = (
            f"within the estimate until the run stopped at t = {run.stopped_at:g} s ({stop}); "
            f"‖x̃‖ grew from {x_tilde[0]:.3g} to {x_tilde.max():.3g}"
        )
    else:
        status = "verified"
        message = (
            f"within the certified estimate at every record (relative margin "
            f"{along['relative_margin']:.3g}); ‖x̃‖ from {x_tilde[0]:.3g} to {x_tilde[-1]:.3g}"
        )
    bounded = status == "verified"
    return {"simulation_bounded": bounded, "status": status, "message": message, **numbers}
