"""The ISS estimate of seed 003 Theorem 2 checked along simulated DEC trajectories.

With ``μ = col(ξ, e)``, ``ξ = (I − 1rᵀ)γ`` (eq. (56), ``r`` the left eigenvector of ``L`` with
``rᵀ1 = 1``), ``e^[i] = [e_p^[i], e_γ^[i]]`` (true target) and ``x̃`` the stacked estimation
errors of the state each controller uses, :func:`theory.pursuit.iss.iss_bound` gives
``‖μ(t)‖ ≤ β(‖μ(0)‖, t) + γ(sup_{s≤t}‖x̃(s)‖)``. :func:`iss_margin_along` evaluates both sides at
every step of a run (forward-Euler trajectories of step ``dt``, so a violation of the order of
``dt`` would be a discretization effect; the report gives the margin).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from theory.pursuit.case import PursuitSpec
from theory.pursuit.closed_loop import DecRun
from theory.pursuit.iss import coordination_iss, iss_bound

__all__ = ["iss_margin_along"]


def iss_margin_along(spec: PursuitSpec, run: DecRun) -> dict[str, Any]:
    """Both sides of the Theorem 2 estimate along ``run``.

    Parameters
    ----------
    spec : PursuitSpec
        The case the run simulates (its gains and graph define β and γ).
    run : DecRun
        A run of :func:`theory.pursuit.simulation.run_pursuit_case`.

    Returns
    -------
    dict
        ``mu`` (‖μ(t)‖), ``bound`` (β + γ), ``margin`` (``min(bound − mu)``), ``holds``,
        ``worst_time``, ``gain`` and ``constants`` of the estimate.

    Raises
    ------
    ValueError
        If the analysis' conditions fail (from :func:`theory.pursuit.iss.iss_bound`).

    References
    ----------
    seed 003, Theorem 2, eqs. (55)–(78).
    """
    estimate = iss_bound(spec)
    n = spec.n_trackers
    if n > 1:
        r = np.array([float(v) for v in coordination_iss(spec).r])
        xi = run.gammas - (run.gammas @ r)[:, None]
        xi_sq = (xi**2).sum(axis=1)
    else:
        xi_sq = np.zeros(len(run.times))
    e_sq = (run.pursuit_errors**2).sum(axis=1) + (run.gamma_errors**2).sum(axis=1)
    mu = np.sqrt(xi_sq + e_sq)
    sup_error = np.maximum.accumulate(np.sqrt((run.estimation_errors**2).sum(axis=1)))
    bound = np.array([estimate.beta(mu[0], t) for t in run.times]) + np.array(
        [estimate.gamma(s) for s in sup_error]
    )
    slack = bound - mu
    worst = int(np.argmin(slack))
    return {
        "mu": mu,
        "bound": bound,
        "margin": float(slack[worst]),
        "holds": bool(slack.min() >= 0),
        "worst_time": float(run.times[worst]),
        "gain": estimate.gain,
        "constants": estimate.constants,
    }
