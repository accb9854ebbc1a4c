"""Seed 003: the DEC loop as the authors' published scripts run it (the ``published`` variant).

github.com/hungrepo/cooperative-distributed-range-based-SLAP, ``SLAP_2D_1Tracker.m``,
``SLAP_2D_3Trackers.m``, ``SLAP_3D_1Tracker.m``, ``SLAP_3D_3Trackers.m``: a discrete loop of
period :data:`STEP` = 0.1 s, in the scripts' order at every ``t = k·STEP``:

1. ω_d = ω̄ − k_c(Lγ) (``Coordination_CC.m``, eqs. (45)–(46));
2. the tracking law (51) on the DEKF's prior x̂_{t|t−δ} (``Tracking_Controller_2D/3D.m``);
   Type II: ``γ̈ = −k_γ(γ̇ − ω_d) + ê_pᵀRᵀr′(γ)`` (eq. (50b) without v̇_c), clamped to
   ``gamma_ddot``, and γ̇ ← γ̇ + δγ̈ (forward Euler); Type I: γ̇ = ω_d;
3. u clamped to [``inputs_min``, ``inputs_max``] (``Tracker.InputMin/Max``);
4. at a sampling instant (every ``T_s``) the ranges (10) and the DEKF's correction and fusion
   (:func:`theory.pursuit.dekf.dekf_step`); the prior mean is propagated by F(δ) every step and
   the information by (44) ``predictions`` times per ``T_s`` (the scripts: every δ, W per δ);
5. the vehicle (2)–(5) with u held over δ, four RK4 steps on (p, yaw) in 2-D and on
   (p, roll, pitch, yaw) with the Euler-angle kinematics in 3-D (``RK4_integrator.m``);
6. γ ← γ + δγ̇.

Records are every δ and hold what the step used: the prior estimate, the γ̇ just computed.
Deviations from the scripts, none of which changes a statistic beyond its noise: ranges are
drawn only at sampling instants, and the one-tracker 3-D script's Kalman-form EKF (predict, then
correct the prior of t + δ with the range of t) is replaced by Algorithm 1 (docs/errata.md,
"What makes the Table cases run away").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.pursuit import model
from theory.pursuit.closed_loop import (
    DecLoop,
    DecRun,
    DecSettings,
    StopCause,
    build_loop,
    runaway_reason,
)
from theory.pursuit.dekf import dekf_step, transition_matrix

__all__ = ["STEP", "PublishedControl", "simulate_published"]

STEP = 0.1
"""The scripts' period δ (s): controller, γ and vehicle updates, DEKF mean propagation."""

RK4_SUBSTEPS = 4
"""RK4 steps per δ of the vehicle (``update_vehicle`` in the scripts)."""


@dataclass(frozen=True, eq=False)
class PublishedControl:
    """The scripts' implementation limits: u = (v₁, ω) clamped to [``inputs_min``,
    ``inputs_max``] (length 2 in 2-D, 4 in 3-D; ``None``: not clamped) and γ̈ to ``gamma_ddot``
    = (min, max) (``None``: not clamped)."""

    inputs_min: np.ndarray | None
    inputs_max: np.ndarray | None
    gamma_ddot: tuple[float, float] | None


def _kinematics(state: np.ndarray, u: np.ndarray, d: int) -> np.ndarray:
    """Rates of (p, yaw) (2-D) or (p, roll, pitch, yaw) (3-D), ``vehicle`` of the scripts,
    seed 003 eqs. (2)–(5) with v = [v₁, 0(, 0)]."""
    speed, rates = u[:, 0], np.empty_like(state)
    if d == 2:
        yaw = state[:, 2]
        rates[:, 0], rates[:, 1], rates[:, 2] = speed * np.cos(yaw), speed * np.sin(yaw), u[:, 1]
        return rates
    roll, pitch, yaw = state[:, 3], state[:, 4], state[:, 5]
    p, q, r = u[:, 1], u[:, 2], u[:, 3]
    sr, cr, cp = np.sin(roll), np.cos(roll), np.cos(pitch)
    turn = q * sr + r * cr
    rates[:, 0] = speed * np.cos(yaw) * cp
    rates[:, 1] = speed * np.sin(yaw) * cp
    rates[:, 2] = -speed * np.sin(pitch)
    rates[:, 3] = p + turn * np.tan(pitch)
    rates[:, 4] = q * cr - r * sr
    rates[:, 5] = turn / cp
    return rates


def _vehicle_step(state: np.ndarray, u: np.ndarray, d: int) -> np.ndarray:
    """The state after δ with u held: :data:`RK4_SUBSTEPS` classical RK4 steps."""
    h = STEP / RK4_SUBSTEPS
    for _ in range(RK4_SUBSTEPS):
        k1 = _kinematics(state, u, d)
        k2 = _kinematics(state + h / 2 * k1, u, d)
        k3 = _kinematics(state + h / 2 * k2, u, d)
        k4 = _kinematics(state + h * k3, u, d)
        state = state + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return state


def _rotation(state: np.ndarray, d: int) -> np.ndarray:
    """R of the yaw (2-D) or of (roll, pitch, yaw) (3-D, Z-Y-X), seed 003 eq. (2)."""
    return model.euler_rotation(state[:, d:])


def _control(
    loop: DecLoop,
    control: PublishedControl,
    state: np.ndarray,
    gamma: np.ndarray,
    gamma_rate: np.ndarray,
    x_prior: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(clamped u, new γ̇, e_γ) of steps 1–3 (module docstring; seed 003 eqs. (45)–(51))."""
    d = loop.dim
    R = _rotation(state, d)
    omega_d = model.desired_speed(loop.omega_bar, loop.laplacian, gamma, loop.k_c)
    point, slope = loop.paths.derivative(gamma), loop.paths.derivative(gamma, 1)
    e_hat = model.body_error(R, state[:, :d], point, x_prior[:, :d], loop.epsilon)
    u = model.tracking_input(R, slope, omega_d, x_prior[:, d:], e_hat, loop.delta_bar, loop.K_p)
    if loop.k_gamma:
        e_gamma = gamma_rate - omega_d
        acceleration = -loop.k_gamma * e_gamma + model.path_feedback(e_hat, R, slope)
        if control.gamma_ddot is not None:
            acceleration = np.clip(acceleration, *control.gamma_ddot)
        new_rate = gamma_rate + STEP * acceleration
    else:
        e_gamma, new_rate = np.zeros_like(gamma), omega_d
    if control.inputs_min is not None:
        u = np.maximum(u, control.inputs_min)
    if control.inputs_max is not None:
        u = np.minimum(u, control.inputs_max)
    return u, new_rate, e_gamma


def simulate_published(
    target: np.ndarray,
    initial_positions: np.ndarray,
    initial_headings: np.ndarray,
    initial_gammas: np.ndarray,
    initial_gamma_rates: np.ndarray,
    in_neighbours: list[list[int]] | np.ndarray,
    x0: np.ndarray,
    P0: np.ndarray,
    steps: int,
    rng: np.random.Generator,
    settings: DecSettings,
    *,
    paths: np.ndarray,
    fusion: np.ndarray,
    control: PublishedControl,
) -> DecRun:
    """Simulate seed 003's DEC loop as the published scripts do (module docstring).

    Parameters
    ----------
    target : ndarray, shape (steps + 1, 2d)
        True target states [q; v] at t = k·STEP.
    initial_positions, initial_headings, initial_gammas, initial_gamma_rates : ndarray
        p(0) (N, d); yaw (N,) in 2-D or (roll, pitch, yaw) (N, 3) in 3-D; γ(0) and γ̇(0) (N,).
    in_neighbours : list of list of int, or ndarray of shape (N, N)
        N_in^[i] (0-based) of the coordination law (45), or the weighted adjacency [a_ij].
    x0, P0 : ndarray
        Priors x̂_{1|0} (2d,) or (N, 2d) and P_{1|0} (2d, 2d) or (N, 2d, 2d).
    steps : int
        Records after the first, one every STEP.
    rng : numpy.random.Generator
        Draws the range noise (σ = ``settings.sigma``).
    settings : DecSettings
        Gains, controller type, V, Q, T_s, predictions per T_s, runaway factor.
    paths : ndarray
        Rows (r_x, r_y, γ0) (16) or (r_x, r_y, r_z, c, γ0) (15).
    fusion : ndarray, shape (N, N)
        Fusion weights π^[i,j] of the DEKF (43).
    control : PublishedControl
        Input and γ̈ clamps.

    Returns
    -------
    DecRun
        Records every STEP; stopped early (NaN records) on a runaway at a sampling instant.
    """
    n, d = initial_positions.shape
    every = round(settings.Ts / STEP)
    if every < 1 or abs(every * STEP - settings.Ts) > 1e-9 * settings.Ts:
        raise ValueError(f"Ts must be an integer multiple of {STEP} s, got {settings.Ts}")
    loop = build_loop(settings, np.asarray(paths, dtype=float), in_neighbours, d)
    headings = np.asarray(initial_headings, dtype=float).reshape(n, -1)
    state = np.hstack([np.asarray(initial_positions, dtype=float), headings])
    gamma = np.asarray(initial_gammas, dtype=float).copy()
    gamma_rate = np.asarray(initial_gamma_rates, dtype=float).copy()
    x_prior = np.broadcast_to(x0, (n, 2 * d)).astype(float)
    Omega = np.linalg.inv(np.broadcast_to(P0, (n, 2 * d, 2 * d)))
    W = np.linalg.inv(np.asarray(settings.Q, dtype=float))
    F_step = transition_matrix(d, STEP)
    F_prediction = transition_matrix(d, settings.Ts / settings.predictions)
    records = _Records(steps, n, d)
    stop: dict[str, object] = {}
    for m in range(steps + 1):
        u, new_rate, e_gamma = _control(loop, control, state, gamma, gamma_rate, x_prior)
        records.store(m, state, gamma, new_rate, e_gamma, x_prior)
        if m % every == 0:
            truth = target[m]
            ranges = np.linalg.norm(state[:, :d] - truth[:d], axis=1)
            ranges += settings.sigma * rng.standard_normal(n)
            x_hat, _, Omega, _ = dekf_step(
                x_prior, Omega, state[:, :d], ranges, fusion=fusion, F=F_prediction, W=W,
                V=settings.V, predictions=settings.predictions,
            )  # fmt: skip
            reason = runaway_reason(loop, state[:, :d], x_hat, truth, Omega,
                                    settings.runaway_factor)  # fmt: skip
            if reason:
                stop = {"stopped_at": m * STEP, "stop_reason": reason,
                        "stop_cause": StopCause.RUNAWAY}  # fmt: skip
                break
            x_prior = x_hat
        if m == steps:
            break
        x_prior = x_prior @ F_step.T
        state = _vehicle_step(state, u, d)
        gamma, gamma_rate = gamma + STEP * new_rate, new_rate
    return records.run(loop, target[: steps + 1], **stop)


class _Records:
    """The states of every record (NaN after a stop), turned into a :class:`DecRun` at the end."""

    def __init__(self, steps: int, n: int, d: int) -> None:
        self.states = np.full((steps + 1, n, 3 if d == 2 else 6), np.nan)  # p, Euler angles
        self.gammas, self.rates, self.e_gamma = (np.full((steps + 1, n), np.nan) for _ in range(3))
        self.estimates = np.full((steps + 1, n, 2 * d), np.nan)

    def store(self, m, state, gamma, gamma_rate, e_gamma, x_prior) -> None:
        """Record m: the state, γ, the γ̇ just computed, e_γ and the prior estimate in use."""
        self.states[m], self.gammas[m], self.rates[m] = state, gamma, gamma_rate
        self.e_gamma[m], self.estimates[m] = e_gamma, x_prior

    def run(self, loop: DecLoop, target: np.ndarray, **stop: object) -> DecRun:
        """The :class:`DecRun`: errors with the true target, e_p of seed 003 (19) (``steps``
        counts the δ-steps taken, none rejected)."""
        d = loop.dim
        p, truth = self.states[..., :d], target[:, None, :]
        rotation = model.euler_rotation(self.states[..., d:])
        e_true = model.body_error(
            rotation, p, loop.paths.derivative(self.gammas), truth[..., :d], loop.epsilon
        )
        return DecRun(
            STEP * np.arange(len(target)),
            p,
            headings=self.states[..., -1],
            gammas=self.gammas,
            gamma_rates=self.rates,
            gamma_errors=self.e_gamma,
            pursuit_errors=np.linalg.norm(e_true, axis=-1),
            localization_errors=np.linalg.norm(self.estimates[..., :d] - truth[..., :d], axis=-1),
            estimation_errors=np.linalg.norm(self.estimates - truth, axis=-1),
            target=target,
            steps=int(np.isfinite(self.gammas[:, 0]).sum()) - 1,
            **stop,
        )
