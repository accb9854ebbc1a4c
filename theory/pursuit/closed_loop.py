"""Seed 003: the distributed estimation and control (DEC) loop of §V, simulated in continuous time.

Trackers (2)–(5) with ``v = [v₁, 0(, 0)]``: ``ṗ = R[v₁, 0(, 0)]ᵀ``, ``Ṙ = R S(ω)``, inputs
``u = (v₁, r)`` in 2-D and ``(v₁, p, q, r)`` in 3-D. Each tracker runs the DEKF of Algorithm 2
(:func:`theory.pursuit.dekf.dekf_step`) on a range every ``T_s``, tracks its S-T curve with
(48), (51), coordinates its path parameter with (45)–(47) and uses Controller Type I (49) or
Type II (50), (52). Every formula comes from :mod:`theory.pursuit.model`, evaluated on all
trackers at once: the vectors the controller rotates to the body frame are affine in the state and
the estimate and come from two matrix products (:class:`_FrameMaps`), since on arrays of a few
numbers NumPy's cost is per call (fewer calls, contiguous operands), not per number.

The controllers are continuous-time laws and Theorem 2 is a continuous-time statement, so the loop
is integrated as an ODE with error control, not with inputs held over a fixed step: a held-input
(sampled-data) step of 0.02 s is unstable for Table II with k_γ = 5 and stalls Table I's tracker
at 0.1 s (docs/simulation.md, docs/theory/pursuit-iss.md §8). The state of tracker i is
(p, R, γ, e_γ) with ``e_γ = γ̇ − ω_d`` obeying ``ė_γ = −k_γ e_γ + ê_pᵀRᵀr′(γ)`` ((47), (50b), (52),
i.e. (62)); e_γ ≡ 0 for Type I. Each step (:func:`heun_step`) is a predictor–corrector pair whose
difference estimates the local error, and the step adapts (:class:`StepControl`). Between
sampling instants the controller uses ``q̂(t) = q̂_{k|k} + (t − t_k)v̂``. Outputs are recorded
every ``dt``; steps never cross a record or a sampling instant.

A run stops early in two ways (records after the stop are NaN, :class:`StopCause`):
``"runaway"`` when, at a sampling instant, a tracker's localization error exceeds
``runaway_factor`` (:data:`theory.core.tolerances.RUNAWAY_FACTOR`) times the S-T curves' size —
the DEKF has lost the target and the loop escapes exponentially with it, the turn rates growing
with the estimate's jumps (docs/theory/pursuit-iss.md §11) — and ``"step_floor"`` when a step
falls below ``min_step``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from theory.core.engines import resolve_engine
from theory.core.tolerances import RUNAWAY_FACTOR
from theory.pursuit import compiled_run, model
from theory.pursuit.dekf import dekf_step, transition_matrix

__all__ = [
    "RUNAWAY_ERRATUM",
    "DecLoop",
    "DecRun",
    "DecSettings",
    "LoopState",
    "StepControl",
    "StopCause",
    "build_loop",
    "heun_step",
    "integrate_until",
    "runaway_reason",
    "simulate_dec",
]


RUNAWAY_ERRATUM = (
    "what makes a loop run away, and the published configuration that does not: docs/errata.md, "
    '"What makes the Table cases run away"'
)
"""Where the runaway message sends the reader (the ablation of seed 003's published scripts)."""


class StopCause(StrEnum):
    """Why a run stopped before its last record."""

    RUNAWAY = "runaway"  # the DEKF lost the target (:func:`runaway_reason`)
    STEP_FLOOR = "step_floor"  # a step fell below ``min_step``


@dataclass(frozen=True)
class DecSettings:
    """Parameters of the DEC loop (defaults: seed 003 Table I, 2-D).

    ``radii`` (r_x, r_y) of (16) serve when no paths are given; ``epsilon`` ε of (19) (ε₁ ≠ 0);
    ``Kp`` and ``Q`` are matrices or their diagonals (W = Q⁻¹); ``V`` the DEKF's inverse range
    variance, ``fusion_weight`` π^[i,j] for the self and the in-neighbour, ``Ts`` the range
    sampling period and ``dt`` the recording interval (s; Ts/dt an integer), ``sigma`` the range
    noise (m); the DEKF predicts ``predictions`` times per ``Ts`` with F(Ts/predictions) and
    W = Q⁻¹ per prediction (1: the paper's Algorithm 2; Ts/0.1 s: the authors' scripts, where Q
    is the process noise of 0.1 s). ``rtol`` is the local error per step (positions relative
    to the largest path semi-axis, attitude and γ absolute); a step below ``min_step`` (s) stops
    the run, and so does a localization error above ``runaway_factor`` S-T curve sizes at a
    sampling instant (``math.inf``: never).
    """

    omega_bar: float = 0.05
    radii: tuple[float, float] = (30.0, 30.0)
    epsilon: tuple[float, float] = (-0.5, 0.0)
    Kp: tuple[float, ...] | np.ndarray = (0.4, 0.2)
    k_gamma: float = 500.0
    k_c: float = 0.2
    controller: str = "II"
    V: float = 10.0
    Q: tuple[float, ...] | np.ndarray = (1e-3, 1e-3, 1e-4, 1e-4)
    fusion_weight: float = 0.5
    Ts: float = 2.0
    predictions: int = 1
    dt: float = 0.1
    sigma: float = 0.5
    rtol: float = 3e-4
    min_step: float = 1e-5
    runaway_factor: float = RUNAWAY_FACTOR


@dataclass(frozen=True, eq=False)
class DecRun:
    """Arrays every ``dt``: ``times`` (M+1,), ``positions`` (M+1, N, d), ``headings`` (yaw),
    ``gammas``, ``gamma_rates``, ``gamma_errors`` ``e_γ = γ̇ − ω_d`` (M+1, N),
    ``pursuit_errors`` ``‖e_p‖`` with the true target (M+1, N), ``localization_errors``
    ``‖q̂ − q‖`` and ``estimation_errors`` ``‖x̂ − x‖`` (state used by the controller at that
    instant) (M+1, N), ``target`` (M+1, 2d); ``steps`` and ``rejected`` count the integration
    steps taken and refused; ``stopped_at`` is the time the integration stopped early (records
    after it are NaN) or NaN, with the reason in ``stop_reason`` and its :class:`StopCause`."""

    times: np.ndarray
    positions: np.ndarray
    headings: np.ndarray
    gammas: np.ndarray
    gamma_rates: np.ndarray
    gamma_errors: np.ndarray
    pursuit_errors: np.ndarray
    localization_errors: np.ndarray
    estimation_errors: np.ndarray
    target: np.ndarray
    steps: int = 0
    rejected: int = 0
    stopped_at: float = math.nan
    stop_reason: str = ""
    stop_cause: str = ""

    @property
    def completed(self) -> bool:
        """Whether the integration reached the last record."""
        return math.isnan(self.stopped_at)


class LoopState:
    """(p, R, γ, e_γ) of every tracker; p, γ and e_γ are views of one flat vector ``z``.

    ``z`` = [p (N × d, row-major), γ (N), e_γ (N)]; ``R`` (N, d, d) the attitudes.
    """

    __slots__ = ("R", "e_gamma", "gamma", "p", "z")

    def __init__(self, z: np.ndarray, R: np.ndarray, n: int, d: int) -> None:
        self.z, self.R = z, R
        self.p = z[: n * d].reshape(n, d)
        self.gamma = z[n * d : n * d + n]
        self.e_gamma = z[n * d + n :]

    @classmethod
    def of(cls, p: np.ndarray, R: np.ndarray, gamma: np.ndarray, e_gamma: np.ndarray):
        """From the separate arrays (copied)."""
        n, d = p.shape
        return cls(np.concatenate([p.ravel(), gamma, e_gamma]).astype(float), R.copy(), n, d)


Rates = tuple[np.ndarray, np.ndarray]
"""(ż, ω): ż = [ṗ, γ̇, ê_pᵀRᵀr′] (the path feedback in e_γ's slot) and the body rates ω."""


@dataclass(frozen=True, eq=False)
class DecLoop:
    """The closed loop's constants, precomputed once (seed 003 eqs. (45)–(52)).

    ``input_gain``, ``input_offset``: G and g of :func:`theory.pursuit.model.input_gains`
    (u = [Rᵀc, Rᵀb] G + g, eq. (51)); ``k_gamma`` is 0 for Type I (e_γ ≡ 0); ``scale`` is the
    largest path semi-axis (m), against which positions are error-controlled.
    """

    dim: int
    n: int
    epsilon: np.ndarray
    K_p: np.ndarray
    delta_bar: np.ndarray
    laplacian: np.ndarray
    input_gain: np.ndarray
    input_offset: np.ndarray
    omega_bar: float
    k_c: float
    k_gamma: float
    paths: model.PathHarmonics
    scale: float

    def rates(self, t: float, state: LoopState, x_hat: np.ndarray, t_hat: float) -> Rates:
        """(ż, ω) of every tracker under controller (49)/(50), seed 003 eqs. (2)–(5), (45)–(51).

        ``x_hat`` are the filtered estimates of the last sampling instant ``t_hat``
        (q̂(t) = q̂_{k|k} + (t − t_hat) v̂); ż = [ṗ, γ̇, ê_pᵀRᵀr′] is flat, as ``state.z``.
        """
        n, d = self.n, self.dim
        a, b = n * d, n * (d + 1)  # z = [p (:a), γ (a:b), e_γ (b:)]
        frames, omega_d = self._frames(t, state, x_hat, t_hat)
        body = np.matmul(frames, state.R)  # the rows in the body frame, (vᵀR)ᵀ = Rᵀv
        u = body[:, :2].reshape(n, 2 * d) @ self.input_gain  # eq. (51), model.input_gains
        u += self.input_offset
        z_dot = np.empty(b + n)
        np.multiply(state.R[:, :, 0], u[:, :1], out=z_dot[:a].reshape(n, d))  # model.tracker_rates
        np.add(omega_d, state.e_gamma, out=z_dot[a:b])
        if self.k_gamma:  # ê_pᵀ(Rᵀr′) of (50b) with ê_p = Rᵀ(p − r − q̂) − ε of (48)
            np.einsum("ij,ij->i", body[:, 1] - self.epsilon, body[:, 2], out=z_dot[b:])
        else:
            z_dot[b:] = 0.0
        return z_dot, u[:, 1:]

    def _frames(
        self, t: float, state: LoopState, x_hat: np.ndarray, t_hat: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """The rows r′(γ)ω_d + v̂, p − r(γ) − q̂(t) and r′(γ) of every tracker (N, 3, d), which
        eqs. (48) and (51) need in the body frame, and ω_d of (46) (N,).

        Each row is A cos(fγ + φ) + B + C + (t − t_hat)D, with A and B affine in z = [p, γ, e_γ]
        and C, D linear in x̂ (:class:`_FrameMaps`): two matrix products and a few operations on
        whole arrays give every row of every tracker.
        """
        maps, size = self._frame_maps, 3 * self.n * self.dim
        affine = state.z @ maps.state_map  # [fγ + φ | A | B | ω_d]
        affine += maps.state_offset
        frames, amplitudes = affine[:size], affine[size : 2 * size]
        np.cos(frames, out=frames)
        frames *= amplitudes
        frames += affine[2 * size : 3 * size]
        estimates = x_hat.ravel() @ maps.estimate_map  # [C | D]
        frames += estimates[:size]
        drift = estimates[size:]
        drift *= t - t_hat
        frames += drift
        return frames.reshape(self.n, 3, self.dim), affine[3 * size :]

    @functools.cached_property
    def _frame_maps(self) -> _FrameMaps:
        """The affine maps of :meth:`_frames` (:func:`_frame_maps_of`)."""
        return _frame_maps_of(self)

    @functools.cached_property
    def _generators(self) -> np.ndarray:
        """G (k × d²) with vec(S(ω)) = ωG (:func:`model.skew` of the unit vectors)."""
        k = 1 if self.dim == 2 else 3
        return model.skew(np.eye(k)).reshape(k, self.dim**2)


@dataclass(frozen=True, eq=False)
class _FrameMaps:
    """The frame rows of :meth:`DecLoop.rates` as affine functions of z and x̂.

    Row k ∈ {0, 1, 2} (r′ω_d + v̂, p − r − q̂(t), r′) of tracker i, coordinate j, is entry
    ``3d·i + d·k + j`` of A cos(fγ + φ) + B + C + (t − t_k)D, each of length ``size = 3Nd``, where
    ``z @ state_map + state_offset`` = [fγ + φ | A | B | ω_d (N)] and ``x̂.ravel() @
    estimate_map`` = [C | D].

    Attributes
    ----------
    state_map : ndarray, shape (N·d + 2N, 3·size + N)
    state_offset : ndarray, shape (3·size + N,)
    estimate_map : ndarray, shape (2Nd, 2·size)
    """

    state_map: np.ndarray
    state_offset: np.ndarray
    estimate_map: np.ndarray


def _frame_maps_of(loop: DecLoop) -> _FrameMaps:
    """The :class:`_FrameMaps` of ``loop`` (seed 003, eqs. (15)/(16), (45)–(51)).

    With the path's harmonics r_j = a_j cos(f_jγ + φ_j) (:class:`model.PathHarmonics`), whose
    derivative is r′_j = a_j f_j cos(f_jγ + φ_j + π/2): the rows r′, −r, r′ have amplitudes af,
    −a, af and phases φ + π/2, φ, φ + π/2; the first row's amplitude is multiplied by
    ω_d = ω̄ − k_c(Lγ)_i (:func:`model.desired_speed`), affine in γ. B is p in the second row;
    C is v̂ in the first row and −q̂_{k|k} in the second, D is −v̂ in the second.
    """
    n, d, paths = loop.n, loop.dim, loop.paths
    a, m, rows = n * d, n * (d + 2), (n, 3, d)  # z = [p (:a), γ (a:a+n), e_γ]
    amplitude = np.stack([paths.slope, -paths.amplitude, paths.slope], axis=1)
    phase = np.stack([paths.phase + np.pi / 2, paths.phase, paths.phase + np.pi / 2], axis=1)
    frequency = np.broadcast_to(paths.frequency, (n, d))
    coupling = -loop.k_c * loop.laplacian  # ω_d = ω̄ + coupling·γ
    angles, amplitudes, positions = (np.zeros((m, *rows)) for _ in range(3))
    for i in range(n):
        angles[a + i, i] = frequency[i]
        amplitudes[a : a + n, i, 0] = np.outer(coupling[i], amplitude[i, 0])
        positions[i * d : (i + 1) * d, i, 1] = np.eye(d)
    speed = np.zeros((m, n))
    speed[a : a + n] = coupling.T
    first = np.ones(rows)
    first[:, 0] = loop.omega_bar
    state_map = np.concatenate(
        [block.reshape(m, -1) for block in (angles, amplitudes, positions, speed)], axis=1
    )
    state_offset = np.concatenate(
        [phase.ravel(), (amplitude * first).ravel(), np.zeros(a * 3), np.full(n, loop.omega_bar)]
    )
    estimate = np.zeros((n, 2, d, 2, *rows))  # x̂_i = [q̂, v̂] → [C | D]
    for i in range(n):
        estimate[i, 1, :, 0, i, 0] = np.eye(d)  # v̂ in the first row of C
        estimate[i, 0, :, 0, i, 1] = -np.eye(d)  # −q̂_{k|k} in the second row of C
        estimate[i, 1, :, 1, i, 1] = -np.eye(d)  # −v̂ in the second row of D
    return _FrameMaps(state_map, state_offset, estimate.reshape(2 * a, 6 * a))


Field = Callable[[float, LoopState, np.ndarray, float], Rates]
"""``field(t, state, x_hat, t_hat)``: :meth:`DecLoop.rates` or a per-tracker equivalent."""


def _etd_weights(k: float, h: float) -> tuple[float, ...]:
    """Exact weights for γ̇ = ω_d + e, ė = −ke + f over a step h with ω_d, f linear in time.

    Returns (E, w₁, w₂, g₁, g₂): E = e^{−kh}; w₁ = ∫₀ʰ e^{−ks}ds = (1 − E)/k;
    w₂ = ∫₀ʰ e^{−k(h−s)} s/h ds = (E − 1 + kh)/(k²h); g₁ = ∫₀ʰ w₁(s)ds = (h − w₁)/k;
    g₂ = h/(2k) − (h − w₁)/(k²h) (the γ-weight of the slope of f). Series in z = kh below 1e-3
    (k → 0: 1, h, h/2, h²/2, h²/6).
    """
    z = k * h
    if z < 1e-3:
        return (
            math.exp(-z),
            h * (1 - z / 2 + z * z / 6 - z**3 / 24),
            h * (0.5 - z / 6 + z * z / 24 - z**3 / 120),
            h * h * (0.5 - z / 6 + z * z / 24 - z**3 / 120),
            h * h * (1 / 6 - z / 24 + z * z / 120 - z**3 / 720),
        )
    decay = math.exp(-z)
    w1 = -math.expm1(-z) / k
    return decay, w1, (decay - 1.0 + z) / (k * z), (h - w1) / k, h / (2 * k) - (h - w1) / (k * z)


def heun_step(
    loop: DecLoop,
    field: Field,
    t: float,
    h: float,
    state: LoopState,
    rates: Rates,
    estimate: tuple[np.ndarray, float],
) -> tuple[LoopState, float]:
    """One predictor–corrector step of length ``h``: the corrected state and its local error.

    (γ, e_γ) obey γ̇ = ω_d + e_γ, ė_γ = −k_γe_γ + f (f = ê_pᵀRᵀr′) and are advanced exactly for
    ω_d, f constant (predictor, order 1: ETD1) or linear in time (corrector, order 2: ETD2RK),
    with the weights of :func:`_etd_weights`, so the stiff decay −k_γ costs nothing whatever k_γh.
    Positions: p + hṗ₀, then p + ½h(ṗ₀ + ṗ₁); attitude: R(I + hS(ω₀)) (only feeds the rates at
    the predicted state, need not be a rotation), then R exp(½hS(ω₀ + ω₁)) (exact on SO(3)).
    The error is the largest corrector − predictor difference in p (relative to
    :attr:`DecLoop.scale` or the largest coordinate), γ and R. ``rates`` is ``field`` at (t,
    state), ``estimate`` (x̂_{k|k}, t_k). Cox & Matthews, J. Comput. Phys. 176 (2002) (ETD2RK);
    Munthe-Kaas, BIT 38 (1998) (RKMK).
    """
    start = _start(loop, state.z, rates[0], _etd_weights(loop.k_gamma, h))
    z1, R1 = _predict(loop, h, state, rates, start)
    rates1 = field(t + h, LoopState(z1, R1, loop.n, loop.dim), *estimate)
    z2, R2 = _correct(loop, h, state, rates, (z1, R1), rates1, start)
    return LoopState(z2, R2, loop.n, loop.dim), _local_error(loop, state.z, (z1, R1), (z2, R2))


Start = tuple[tuple[float, ...], np.ndarray, np.ndarray]
"""What both γ-updates of a step share (:func:`_start`): the ETD weights (:func:`_etd_weights`),
γ + w₁e_γ + g₁f₀ and ω_d at the start."""


def _start(loop: DecLoop, z: np.ndarray, z_dot: np.ndarray, weights: tuple[float, ...]) -> Start:
    """The weights, the part γ + w₁e_γ + g₁f₀ of both γ-updates that does not depend on ω_d, and
    ω_d at the start of the step (γ̇ − e_γ)."""
    _, w1, _, g1, _ = weights
    a, b = loop.n * loop.dim, loop.n * (loop.dim + 1)  # z = [p (:a), γ (a:b), e_γ (b:)]
    e = z[b:]
    free = e * w1
    free += z[a:b]
    free += z_dot[b:] * g1
    return weights, free, z_dot[a:b] - e


def _predict(
    loop: DecLoop, h: float, state: LoopState, rates: Rates, start: Start
) -> tuple[np.ndarray, np.ndarray]:
    """The order-1 step: Euler in p, ETD1 in (γ, e_γ), R(I + hS(ω₀)) (:func:`heun_step`)."""
    (z_dot, omega), z, ((decay, w1, *_), free, speed) = rates, state.z, start
    a, b = loop.n * loop.dim, loop.n * (loop.dim + 1)
    z1 = np.empty_like(z)
    position, gamma, e = z1[:a], z1[a:b], z1[b:]
    np.multiply(z_dot[:a], h, out=position)
    position += z[:a]  # p + hṗ₀
    np.multiply(speed, h, out=gamma)
    gamma += free  # γ + w₁e_γ + g₁f₀ + hω_d
    np.multiply(z[b:], decay, out=e)
    e += z_dot[b:] * w1  # e^{−k_γh}e_γ + w₁f₀
    turn = (omega @ loop._generators).reshape(state.R.shape)  # S(ω₀), model.skew
    turn *= h
    return z1, state.R + state.R @ turn


def _correct(
    loop: DecLoop,
    h: float,
    state: LoopState,
    rates: Rates,
    predicted: tuple[np.ndarray, np.ndarray],
    rates1: Rates,
    start: Start,
) -> tuple[np.ndarray, np.ndarray]:
    """The order-2 step from the rates at both ends: Heun in p, ETD2RK in (γ, e_γ),
    R exp(½hS(ω₀ + ω₁)) (:func:`heun_step`)."""
    (z_dot, omega), (z_dot1, omega1), (z1, _) = rates, rates1, predicted
    ((_, _, w2, _, g2), free, speed), z, half = start, state.z, 0.5 * h
    a, b = loop.n * loop.dim, loop.n * (loop.dim + 1)
    slope = z_dot1[b:] - z_dot[b:]  # f₁ − f₀
    z2 = np.empty_like(z)
    position, gamma, e = z2[:a], z2[a:b], z2[b:]
    np.add(z_dot[:a], z_dot1[:a], out=position)
    position *= half
    position += z[:a]  # p + ½h(ṗ₀ + ṗ₁)
    np.subtract(z_dot1[a:b], z1[b:], out=gamma)  # ω_d at the predicted state
    gamma += speed
    gamma *= half
    gamma += free
    gamma += slope * g2  # γ + w₁e_γ + g₁f₀ + ½h(ω_d₀ + ω_d₁) + g₂(f₁ − f₀)
    np.multiply(slope, w2, out=e)
    e += z1[b:]  # ETD1's e_γ + w₂(f₁ − f₀)
    rotation = omega + omega1
    rotation *= half
    return z2, state.R @ model.exp_skew(rotation)


def _local_error(
    loop: DecLoop,
    z: np.ndarray,
    predicted: tuple[np.ndarray, np.ndarray],
    corrected: tuple[np.ndarray, np.ndarray],
) -> float:
    """Largest corrector − predictor difference: p relative to the larger of
    :attr:`DecLoop.scale` and the largest coordinate, γ and R absolute (e_γ not controlled).
    NaN when any difference is NaN."""
    (z1, R1), (z2, R2) = predicted, corrected
    a, b = loop.n * loop.dim, loop.n * (loop.dim + 1)
    difference = np.empty(b + R1.size)
    np.subtract(z2[:b], z1[:b], out=difference[:b])
    np.subtract(R2.ravel(), R1.ravel(), out=difference[b:])
    np.abs(difference, out=difference)
    positions = difference[:a]
    positions /= max(loop.scale, _largest(np.abs(z[:a])))
    return _largest(difference)


def _largest(values: np.ndarray) -> float:
    """``values.max()`` (NaN if any is NaN) by ``argmax``, which costs a third on a few numbers."""
    return float(values[values.argmax()])


@dataclass
class StepControl:
    """The adaptive step's state: the proposed step ``h`` (s).

    After a step of scaled error ``err`` (≤ 1: accepted) the step is multiplied by
    0.9·err^{−1/2} (at most 1 after a rejection), within [0.2, 2], and kept at most ``cap``. (A
    proportional–integral controller halved the rejections but took 20–90 % more steps here.)
    ``cap`` is the largest step (s), the recording interval.
    """

    h: float
    cap: float

    def update(self, step: float, error: float, accepted: bool, reached_end: bool) -> None:
        """Propose the next step after a step of length ``step`` with scaled error ``error``,
        ``accepted`` or not, that ``reached_end`` of its interval (then it may have been
        shortened to land there, and the proposal is kept)."""
        if not math.isfinite(error):
            self.h = 0.2 * step
            return
        factor = 2.0 if error == 0 else 0.9 / math.sqrt(error)
        proposal = step * min(2.0 if accepted else 1.0, max(0.2, factor))
        if accepted and reached_end:  # a step shortened to land on a record says nothing of h
            proposal = max(proposal, self.h)
        self.h = min(proposal, self.cap)


def integrate_until(
    loop: DecLoop,
    field: Field,
    t: float,
    t_end: float,
    state: LoopState,
    estimate: tuple[np.ndarray, float],
    control: StepControl,
    settings: DecSettings,
    rates: Rates | None = None,
) -> tuple[LoopState, Rates, int, int]:
    """Adaptive steps from ``t`` to ``t_end``: the state and rates there, accepted and rejected.

    ``control`` (the step size) is updated in place; ``rates`` is ``field`` at (t, state) if
    known. FloatingPointError if a step falls below ``settings.min_step``.
    """
    accepted = rejected = 0
    rates = field(t, state, *estimate) if rates is None else rates
    while t_end - t > 1e-12 * max(1.0, abs(t_end)):
        last = control.h >= t_end - t
        step = t_end - t if last else control.h
        candidate, error = heun_step(loop, field, t, step, state, rates, estimate)
        error /= settings.rtol
        ok = error <= 1.0
        if ok:
            t, state = (t_end if last else t + step), candidate
            accepted += 1
            rates = field(t, state, *estimate)
        else:
            rejected += 1
        control.update(step, error, ok, last)
        if control.h < settings.min_step:
            raise FloatingPointError(f"integration step below {settings.min_step} s at t = {t:g} s")
    return state, rates, accepted, rejected


def _matrix(values: tuple[float, ...] | np.ndarray) -> np.ndarray:
    """A matrix given as itself or by its diagonal."""
    values = np.asarray(values, dtype=float)
    return np.diag(values) if values.ndim == 1 else values


def _laplacian(in_neighbours: list[list[int]] | np.ndarray, n: int) -> np.ndarray:
    """L = D_in − A (seed 003 §II-B) of the in-neighbour lists (a_ij = 1) or of the weighted
    adjacency ``[a_ij]`` (an N × N array)."""
    if isinstance(in_neighbours, np.ndarray):
        adjacency = in_neighbours.astype(float)
    else:
        adjacency = np.zeros((n, n))
        for i, neighbours in enumerate(in_neighbours):
            adjacency[i, neighbours] = 1.0
    return np.diag(adjacency.sum(axis=1)) - adjacency


def _path_harmonics(paths: np.ndarray) -> model.PathHarmonics:
    """Rows (r_x, r_y, γ0) or (r_x, r_y, r_z, c, γ0) as :class:`model.PathHarmonics`."""
    if paths.shape[1] == 5:
        r_x, r_y, r_z, c, gamma0 = paths.T
        return model.PathHarmonics.of(r_x, r_y, gamma0, r_z, c)
    return model.PathHarmonics.of(paths[:, 0], paths[:, 1], paths[:, 2])


def build_loop(
    settings: DecSettings,
    paths: np.ndarray,
    in_neighbours: list[list[int]] | np.ndarray,
    dim: int,
) -> DecLoop:
    """The :class:`DecLoop` of ``settings`` for trackers on ``paths`` (rows: :func:`simulate_dec`).

    ValueError if Δ of (22) is not of full row rank (ε₁ = 0, Remark 6) or the controller unknown.
    """
    if settings.controller not in ("I", "II"):
        raise ValueError(f"controller must be 'I' or 'II', got {settings.controller!r}")
    epsilon, K_p = np.asarray(settings.epsilon, dtype=float), _matrix(settings.Kp)
    n, scale = paths.shape[0], float(np.max(paths[:, : 3 if dim == 3 else 2]))
    delta_bar = model.delta_bar(epsilon)
    input_gain, input_offset = model.input_gains(delta_bar, K_p, epsilon)
    return DecLoop(
        dim=dim,
        n=n,
        epsilon=epsilon,
        K_p=K_p,
        delta_bar=delta_bar,
        laplacian=_laplacian(in_neighbours, n),
        input_gain=input_gain,
        input_offset=input_offset,
        omega_bar=settings.omega_bar,
        k_c=settings.k_c,
        k_gamma=float(settings.k_gamma) if settings.controller == "II" else 0.0,
        paths=_path_harmonics(paths),
        scale=scale,
    )


def _initial_state(
    positions: np.ndarray, headings: np.ndarray, gammas: np.ndarray, e_gamma: np.ndarray | None
) -> LoopState:
    n, d = positions.shape
    headings = np.asarray(headings, dtype=float).reshape(n, -1)
    rotation = model.exp_skew(headings) if d == 2 else model.euler_rotation(headings)
    start = np.zeros(n) if e_gamma is None else np.asarray(e_gamma, dtype=float)
    return LoopState.of(positions.astype(float), rotation, gammas.astype(float), start)


def _outputs(loop: DecLoop, times, z, R, estimates, target) -> dict[str, np.ndarray]:
    """The arrays of :class:`DecRun` from the recorded states, all records at once.

    ``z`` (M+1, N·d + 2N) and ``R`` (M+1, N, d, d) are the states, ``estimates`` (M+1, N, 2d) the
    filtered x̂_{k|k} in force and their ages t − t_k on the last axis' extra column.
    """
    n, d = loop.n, loop.dim
    p = z[:, : n * d].reshape(-1, n, d)
    gamma, e_gamma = z[:, n * d : n * d + n], z[:, n * d + n :]
    x_hat, age = estimates[..., :-1], estimates[..., -1:]
    q_hat = x_hat[..., :d] + age * x_hat[..., d:]
    truth = target[: len(times), None, :]
    e_true = model.body_error(R, p, loop.paths.derivative(gamma), truth[..., :d], loop.epsilon)
    omega_d = loop.omega_bar + model.correction_speed(loop.laplacian, gamma.T, loop.k_c).T
    return {
        "positions": p,
        "headings": np.arctan2(R[..., 1, 0], R[..., 0, 0]),
        "gammas": gamma,
        "gamma_rates": omega_d + e_gamma,
        "gamma_errors": e_gamma,
        "pursuit_errors": np.linalg.norm(e_true, axis=-1),
        "localization_errors": np.linalg.norm(q_hat - truth[..., :d], axis=-1),
        "estimation_errors": np.linalg.norm(
            np.concatenate([q_hat, x_hat[..., d:]], axis=-1) - truth, axis=-1
        ),
    }


def _sample(loop, state, truth, filter_state, dekf, rng, settings):
    """Ranges (9)–(10) at the tracker positions and one DEKF step; returns (x̂, Ω, x̂_pred)."""
    x_pred, Omega = filter_state
    ranges = np.linalg.norm(state.p - truth[: loop.dim], axis=1)
    ranges = ranges + settings.sigma * rng.standard_normal(loop.n)
    x_hat, _, Omega, x_pred = dekf_step(
        x_pred, Omega, state.p, ranges, fusion=dekf["fusion"], F=dekf["F"], W=dekf["W"],
        V=settings.V, predictions=settings.predictions,
    )  # fmt: skip
    return x_hat, (x_pred, Omega)


def runaway_reason(
    loop: DecLoop,
    positions: np.ndarray,
    x_hat: np.ndarray,
    truth: np.ndarray,
    information: np.ndarray,
    factor: float,
) -> str:
    """Why the run is a runaway at a sampling instant, or ``""`` when it is not.

    A run has run away when a tracker's localization error ‖q̂ − q‖ exceeds ``factor`` times
    :attr:`DecLoop.scale`, the S-T curves' size: the tracker then circles a point that is not
    near the target, and the one-range DEKF, whose bearing error has passed 90°, pushes its
    estimate further out along the wrong ray at every correction (docs/theory/pursuit-iss.md §11).
    The reason states the evidence that nothing is singular: the estimated range ‖q̂ − p‖ (the
    divisor of the range Jacobian C_k of (41)) and λ_min of the information Ω_{k+1|k} (44),
    ``information`` (seed 003 eqs. (9)–(10), (41), (44); x̃ is Theorem 2's input).
    """
    d = loop.dim
    errors = np.linalg.norm(x_hat[:, :d] - truth[:d], axis=1)
    worst = int(np.argmax(errors))
    if not errors[worst] > factor * loop.scale:
        return ""
    to_estimate, to_target = x_hat[worst, :d] - positions[worst], truth[:d] - positions[worst]
    smallest = float(np.linalg.eigvalsh(information[worst])[0])
    return (
        f"runaway: tracker {worst + 1}'s localization error {errors[worst]:.4g} m exceeds "
        f"runaway_factor {factor:g} × {loop.scale:g} m (the DEKF lost the target: "
        f"{_bearing_error(to_estimate, to_target)}, estimated range "
        f"{np.linalg.norm(to_estimate):.4g} m, λ_min(Ω) = {smallest:.3g}); {RUNAWAY_ERRATUM}"
    )


def _bearing_error(to_estimate: np.ndarray, to_target: np.ndarray) -> str:
    """The angle between the tracker's rays to its estimate and to the target, as text (it has
    none when the tracker sits on either point)."""
    lengths = float(np.linalg.norm(to_estimate) * np.linalg.norm(to_target))
    if lengths == 0.0:
        return "bearing error undefined (the tracker is at the target or at its estimate)"
    cosine = float(to_estimate @ to_target) / lengths
    return f"bearing error {math.degrees(math.acos(min(1.0, max(-1.0, cosine)))):.0f}°"


def _run(
    loop: DecLoop, field: Field, target: np.ndarray, state: LoopState, dekf: dict, steps: int,
    rng: np.random.Generator, settings: DecSettings,
) -> DecRun:  # fmt: skip
    """Sample, record and integrate record by record; stop early (NaN records) on a runaway
    (:func:`runaway_reason`, checked at each sampling instant) or a step failure."""
    every, dt = round(settings.Ts / settings.dt), settings.dt
    z = np.full((steps + 1, state.z.size), np.nan)
    R = np.full((steps + 1, *state.R.shape), np.nan)
    estimates = np.full((steps + 1, loop.n, 2 * loop.dim + 1), np.nan)
    counts, control, stop = [0, 0], StepControl(dt, dt), {}
    filter_state = (dekf["x_pred"], dekf["Omega"])
    for m in range(steps + 1):
        if m % every == 0:
            x_hat, filter_state = _sample(loop, state, target[m], filter_state, dekf, rng, settings)
            t_hat, rates = m * dt, None
            reason = runaway_reason(
                loop, state.p, x_hat, target[m], filter_state[1], settings.runaway_factor
            )
        z[m], R[m] = state.z, state.R
        estimates[m, :, :-1], estimates[m, :, -1] = x_hat, m * dt - t_hat
        if m == steps:
            break
        if reason:
            stop = _stop(m * dt, reason, StopCause.RUNAWAY)
            break
        try:
            state, rates, accepted, refused = integrate_until(
                loop, field, m * dt, (m + 1) * dt, state, (x_hat, t_hat), control, settings, rates
            )
        except FloatingPointError as error:
            stop = _stop(m * dt, str(error), StopCause.STEP_FLOOR)
            break
        counts[0] += accepted
        counts[1] += refused
    return _dec_run(loop, target, steps, dt, (z, R, estimates), counts, stop)


def _dec_run(loop, target, steps, dt, records, counts, stop) -> DecRun:
    """The :class:`DecRun` of the recorded (z, R, estimates), step counts and stop fields."""
    times = dt * np.arange(steps + 1)
    return DecRun(
        times, **_outputs(loop, times, *records, target), target=target[: steps + 1],
        steps=counts[0], rejected=counts[1], **stop,
    )  # fmt: skip


def _stop(time: float, reason: str, cause: StopCause) -> dict[str, object]:
    """The :class:`DecRun` fields of a run stopped early at ``time``."""
    return {"stopped_at": time, "stop_reason": reason, "stop_cause": cause}


def _filter_setup(
    loop: DecLoop, settings: DecSettings, x0: np.ndarray, P0: np.ndarray, fusion: np.ndarray | None
) -> dict[str, np.ndarray]:
    """The DEKF's constants and first priors (Algorithm 2): F, W = Q⁻¹, π^[i,j] (default
    ``settings.fusion_weight`` on each in-edge, the rest on the tracker), Ω_{1|0} and x̂_{1|0}."""
    n, d = loop.n, loop.dim
    if fusion is None:
        adjacency = (np.diag(np.diag(loop.laplacian)) - loop.laplacian != 0).astype(float)
        weight = settings.fusion_weight
        fusion = np.diag(1 - weight * adjacency.sum(axis=1)) + weight * adjacency
    return {
        "F": transition_matrix(d, settings.Ts / settings.predictions),
        "W": np.linalg.inv(_matrix(settings.Q)),
        "fusion": fusion,
        "Omega": np.linalg.inv(np.broadcast_to(P0, (n, 2 * d, 2 * d))),
        "x_pred": np.broadcast_to(x0, (n, 2 * d)).astype(float),
    }


def simulate_dec(
    target: np.ndarray,
    initial_positions: np.ndarray,
    initial_headings: np.ndarray,
    initial_gammas: np.ndarray,
    in_neighbours: list[list[int]] | np.ndarray,
    x0: np.ndarray,
    P0: np.ndarray,
    steps: int,
    rng: np.random.Generator,
    settings: DecSettings = DecSettings(),
    *,
    paths: np.ndarray | None = None,
    fusion: np.ndarray | None = None,
    initial_gamma_errors: np.ndarray | None = None,
    field: Field | None = None,
    engine: str | None = None,
) -> DecRun:
    """Simulate the DEC system of seed 003 §V (2-D or 3-D), recording every ``settings.dt``.

    ``target`` holds the true states ``[q; v]`` at ``t = k·dt`` for ``steps + 1`` records;
    ``initial_headings`` are yaws (2-D) or roll–pitch–yaw (3-D); ``in_neighbours`` the 0-based
    N_in^[i] (a_ij = 1), or the N × N weighted adjacency [a_ij] of a weighted digraph; ``x0``,
    ``P0`` the priors x̂_{1|0}, P_{1|0} (one for all trackers or one each);
    ``rng`` draws the range noise. ``paths`` rows are ``(r_x, r_y, γ0)`` (16) or
    ``(r_x, r_y, r_z, c, γ0)`` (15) (default: ``settings.radii``, γ0^[i] = 2π(i−1)/N); ``fusion``
    the weights π^[i,j] (default ``settings.fusion_weight`` on each in-edge);
    ``initial_gamma_errors`` e_γ(0) (Type II, default 0); ``field`` replaces
    :meth:`DecLoop.rates` (a reference implementation, for tests and benchmarks; it runs on the
    NumPy engine). ``engine`` ``"numba"`` (compiled kernels, :mod:`theory.pursuit.kernels`) or
    ``"numpy"`` (this module, the reference), default ``$TRACKCERT_ENGINE`` else ``"numba"``
    (:func:`theory.core.engines.resolve_engine`; CaseError if unknown). ValueError if
    Δ of (22) is singular (ε₁ = 0), T_s/dt is not an integer or the controller is unknown.
    """
    n, d = initial_positions.shape
    every = round(settings.Ts / settings.dt)
    if every < 1 or abs(every * settings.dt - settings.Ts) > 1e-9 * settings.Ts:
        raise ValueError("Ts must be an integer multiple of dt")
    if paths is None:
        phases = 2 * np.pi * np.arange(n) / n if n > 1 else np.zeros(1)
        paths = np.column_stack([np.tile(settings.radii, (n, 1)), phases])
    loop = build_loop(settings, np.asarray(paths, dtype=float), in_neighbours, d)
    dekf = _filter_setup(loop, settings, x0, P0, fusion)
    state = _initial_state(
        initial_positions, initial_headings, initial_gammas, initial_gamma_errors
    )
    if field is None and resolve_engine(engine) == "numba":
        *records, counts, stop = compiled_run.record(
            loop, target, state, dekf, steps, rng, settings, runaway_reason
        )
        if stop:
            stop = _stop(*stop[:2], StopCause.RUNAWAY if stop[2] else StopCause.STEP_FLOOR)
        return _dec_run(loop, target, steps, settings.dt, records, counts, stop or {})
    return _run(loop, field or loop.rates, target, state, dekf, steps, rng, settings)
