"""Test oracles for the DEC simulator: a per-tracker vector field and a DOP853 integration.

``per_tracker_field`` evaluates every tracker separately through
:func:`theory.pursuit.model.closed_loop_rates` (the single-tracker model the properties use), in a
Python loop: the pre-vectorization form of :meth:`theory.pursuit.closed_loop.DecLoop.rates`.
``dop853_interval`` integrates the loop's ODE between two instants with scipy's DOP853 at a
tolerance far below the simulator's, with the estimate held as the simulator holds it.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from theory.pursuit import model
from theory.pursuit.closed_loop import DecLoop, LoopState

__all__ = ["dop853_interval", "per_tracker_field"]


def _path_params(row: np.ndarray) -> dict:
    if row.size == 5:
        return {"r_x": row[0], "r_y": row[1], "gamma0": row[4], "r_z": row[2], "c": row[3]}
    return {"r_x": row[0], "r_y": row[1], "gamma0": row[2]}


def per_tracker_field(loop: DecLoop, paths: np.ndarray, controller: str):
    """``field(t, state, x_hat, t_hat)`` of :func:`theory.pursuit.closed_loop.simulate_dec`,
    one tracker at a time."""
    d, n = loop.dim, loop.n

    def field(t, state, x_hat, t_hat):
        z_dot = np.zeros(n * d + 2 * n)
        omegas = []
        for i in range(n):
            omega_d = loop.omega_bar - loop.k_c * sum(
                loop.laplacian[i, j] * state.gamma[j] for j in range(n)
            )
            q_hat = x_hat[i, :d] + (t - t_hat) * x_hat[i, d:]
            rates = model.closed_loop_rates(
                position=state.p[i], rotation=state.R[i], gamma=state.gamma[i],
                gamma_dot=omega_d + state.e_gamma[i], target_position=q_hat,
                target_velocity=x_hat[i, d:], estimate_position=q_hat,
                estimate_velocity=x_hat[i, d:], epsilon=loop.epsilon, K_p=loop.K_p,
                k_gamma=loop.k_gamma, controller=controller, omega_d=omega_d, omega_d_dot=0.0,
                path_params=_path_params(paths[i]),
            )  # fmt: skip
            z_dot[i * d : (i + 1) * d] = rates.position_dot
            z_dot[n * d + i] = rates.gamma_dot
            z_dot[n * d + n + i] = rates.feedback
            omegas.append(rates.u[1:])
        return z_dot, np.array(omegas)

    return field


def dop853_interval(loop: DecLoop, state: LoopState, t0: float, t1: float, estimate, rtol=1e-11):
    """The state at ``t1`` from ``state`` at ``t0`` by DOP853 on (p, R, γ, e_γ) (R as 9 numbers)."""
    n, d = loop.n, loop.dim
    m = state.z.size

    def rhs(t, y):
        current = LoopState(y[:m].copy(), y[m:].reshape(n, d, d), n, d)
        z_dot, omega = loop.rates(t, current, *estimate)
        z_dot = z_dot.copy()
        z_dot[n * d + n :] -= loop.k_gamma * current.e_gamma
        return np.concatenate([z_dot, (current.R @ model.skew(omega)).ravel()])

    y0 = np.concatenate([state.z, state.R.ravel()])
    solution = solve_ivp(rhs, (t0, t1), y0, method="DOP853", rtol=rtol, atol=rtol)
    assert solution.success, solution.message
    y = solution.y[:, -1]
    return LoopState(y[:m].copy(), y[m:].reshape(n, d, d), n, d)
