"""The distributed TDOA particle filter of seed 002 §3.2 (2D), vectorised over nodes/particles.

Every filtering node ``i`` keeps ``P`` particles (positions, headings) and at each time step ``k``:

1. computes each particle's TDOA vector ``d_i^n`` against its neighbours (eq. 3.9);
2. weights it by ``exp(−‖y_i − d_i^n‖² / (2σ²))`` (eqs. 3.10–3.11) and normalises (eq. 3.12);
3. *consensus*: broadcasts its ``m`` highest-weighted particles to its filtering neighbours and
   replaces its own ``|N_i| m`` lowest-weighted particles with those received, then renormalises;
4. estimates ``χ_i`` from the top 20 % of particles (eq. 3.13, weights renormalised over them);
5. resamples ``P`` particles multinomially;
6. propagates them with a motion model (eqs. 3.14–3.16).

Choices the thesis leaves open (documented in ``docs/particle-filter.md``) are fields of
:class:`~theory.particle.case.PfConfig`: the weight a received particle keeps (its sender's,
renormalised with the receiver's set, or the receiver's own likelihood), the heading it carries
(the sender's, or a fresh uniform one), and the rounds of exchange per step (with two or more,
particles received in round 1 are forwarded in round 2; with one, information travels one hop per
step through resampling).

The TDOA model ``d_i^n`` (eq. 3.9) and the measurements (eqs. 3.6–3.8) are those of seed 000
eqs. (4.3)–(4.4), evaluated by the one implementation in :mod:`theory.tdoa.model` (broadcast over
filtering nodes × particles). Weights are computed in the log domain (the maximum subtracted
before exponentiating), which equals eqs. (3.11)–(3.12) after normalisation but never underflows.

Motion models (step 6) draw a turning angle and a step length per particle, ``(nodes,
particles)`` arrays, and ``observe(estimates)`` returns the model for the next step:
:class:`DcrwMotion` (the true DCRW), :class:`GaussianMotion` (the thesis's mis-specified baseline
of §3.3.2), :class:`UniformMotion` (the learner's prior "uniform distribution at k = 0"; the
maximum step is ours, the thesis gives no range) and :class:`OnlineLearner` (§3.2.2): each node
forms turning angles and step lengths from its own successive estimates (eqs. 3.17–3.19), refits
``(μ, γ, κ, λ)`` by maximum likelihood and propagates with the fitted DCRW, with the prior before
its first accepted fit. Guards against degenerate early fits (the thesis fits from ``k > 3``,
where the likelihood of (3.1) is maximised at ``γ → 1``): no fit before ``min_samples`` turning
angles (10); ``γ`` clamped to ``gamma_max`` (0.95) and ``κ`` to ``kappa_bounds`` (0.5, 10), so one
straight or evenly-stepped stretch cannot freeze the particles onto a line or a step length; the
first ``burn_in`` (5) estimates unused, since before convergence the estimate jumps across the
workspace.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Protocol, Self

import numpy as np
from scipy import special
from scipy.stats._continuous_distns import _log_gauss_mass

from theory.core.engines import resolve_engine
from theory.particle.case import (
    DcrwParams,
    ExchangeWeights,
    Model,
    PfConfig,
    PfNetwork,
    PfSpec,
    ReceivedHeading,
)
from theory.particle.dcrw import fit_dcrw, movement_samples, sample_weibull, sample_wrapped_cauchy
from theory.tdoa.model import range_differences, ranges

__all__ = [
    "DcrwMotion",
    "GaussianMotion",
    "Motion",
    "OnlineLearner",
    "PfRun",
    "PfState",
    "UniformMotion",
    "build_motion",
    "cloud_moments",
    "consensus_exchange",
    "estimate",
    "initial_state",
    "log_likelihood",
    "measure",
    "multinomial_resample",
    "normalise_log_weights",
    "particle_tdoa",
    "pf_step",
    "pf_update",
    "predicted_measurements",
    "propagate",
    "run_filter",
    "simulate_measurements",
    "truncated_normal",
]


class Motion(Protocol):
    """A propagation model (module docstring)."""

    def sample(self, rng: np.random.Generator, shape: tuple[int, int]) -> tuple:
        """Turning angles and step lengths, each of ``shape`` ``(F, P)``, drawn from ``rng``."""

    def observe(self, estimates: np.ndarray) -> Self:
        """The model to use after the estimates ``χ(k)``, ``(F, 2)``."""


@dataclass(frozen=True, eq=False)
class PfState:
    """Particles of every node: ``positions (F, P, 2)``, ``headings`` and ``weights (F, P)``."""

    positions: np.ndarray
    headings: np.ndarray
    weights: np.ndarray


@dataclass(frozen=True, eq=False)
class PfRun:
    """One filter run: ``estimates (K+1, F, 2)``, errors ``E_i(k)`` ``(K+1, F)`` (eq. 3.20), the
    weighted particles ``(F, P, 3)`` (x, y, w̄) at the snapshot steps, the final motion model;
    the weighted cloud's mean ``(K+1, F, 2)`` and covariance ``(K+1, F, 2, 2)`` after the
    consensus step, and the innovations ``y − ŷ`` ``(K+1, F, N)`` with covariances
    ``(K+1, F, N, N)`` of :func:`predicted_measurements` (zero/identity off the mask)."""

    estimates: np.ndarray
    errors: np.ndarray
    snapshots: dict[int, np.ndarray]
    motion: Motion
    cloud_means: np.ndarray
    cloud_covariances: np.ndarray
    innovations: np.ndarray
    innovation_covariances: np.ndarray


def initial_state(
    n_filters: int, particles: int, bounds: np.ndarray, rng: np.random.Generator
) -> PfState:
    """Particles uniform on the workspace ``bounds``, headings uniform, weights ``1/P`` (§3.2.1,
    *Initialization*)."""
    low, high = np.asarray(bounds, float)[:, 0], np.asarray(bounds, float)[:, 1]
    positions = low + (high - low) * rng.random((n_filters, particles, 2))
    headings = rng.uniform(-np.pi, np.pi, (n_filters, particles))
    return PfState(positions, headings, np.full((n_filters, particles), 1.0 / particles))


def measure(
    target: np.ndarray, network: PfNetwork, noise_sigma: float, rng: np.random.Generator
) -> np.ndarray:
    """TDOA measurements ``y_i = h_i(p) + w_i`` of every filtering node, ``(F, N)``, 0 outside
    the measurement mask (eqs. (3.6)–(3.8))."""
    clean = range_differences(target, network.nodes, np.asarray(network.filters, dtype=int))
    mask = network.measurement_mask
    noise = noise_sigma * rng.standard_normal(mask.shape)
    return np.where(mask, clean + noise, 0.0)


def simulate_measurements(
    path: np.ndarray, network: PfNetwork, noise_sigma: float, rng: np.random.Generator
) -> np.ndarray:
    """:func:`measure` at every point of ``path``: an ``(K + 1, F, N)`` array (the same numbers:
    one draw of all the noise is the successive draws of each step's)."""
    points = np.asarray(path, dtype=float)[:, None, :]
    clean = range_differences(points, network.nodes, network.filter_array[None, :])
    mask = network.measurement_mask
    noise = noise_sigma * rng.standard_normal((len(points), *mask.shape))
    return np.where(mask, clean + noise, 0.0)


def particle_tdoa(positions: np.ndarray, network: PfNetwork) -> np.ndarray:
    """``d_i^n`` ``(F, Q, N)`` of ``Q`` positions per filtering node ``(F, Q, 2)`` (eq. (3.9)):
    :func:`theory.tdoa.model.range_differences` with the node's own range picked by indexing
    (the same numbers, without its broadcasting of the agents per call)."""
    distances = ranges(positions, network.nodes)
    own = distances[np.arange(len(network.filters)), :, network.filter_array][..., None]
    return own - distances


def log_likelihood(
    positions: np.ndarray,
    y: np.ndarray,
    network: PfNetwork,
    sigma: float,
    *,
    predicted: np.ndarray | None = None,
) -> np.ndarray:
    """``−‖y_i − d_i^n‖² / (2σ²)`` ``(F, Q)`` of ``Q`` positions per node ``(F, Q, 2)``, up to a
    constant (eqs. (3.9)–(3.11)); ``predicted``: their :func:`particle_tdoa`, if already known."""
    if predicted is None:
        predicted = particle_tdoa(positions, network)
    mask = network.measurement_mask[:, None, :]
    residual = np.where(mask, y[:, None, :] - predicted, 0.0)
    return -0.5 * np.sum(residual**2, axis=-1) / sigma**2


def normalise_log_weights(log_weights: np.ndarray) -> np.ndarray:
    """Eq. (3.12) from ``log_weights`` ``(F, P)``, row by row (max subtracted first; never 0/0)."""
    w = np.exp(log_weights - log_weights.max(axis=1, keepdims=True))
    return w / w.sum(axis=1, keepdims=True)


def consensus_exchange(
    state: PfState,
    network: PfNetwork,
    config: PfConfig,
    rng: np.random.Generator,
    *,
    y: np.ndarray | None,
) -> PfState:
    """The consensus step of seed 002 §3.2.1 step 3 (``y``: the measurements, needed for local
    weights); ``ValueError`` if a node would replace ``P`` or more particles (``m < P/N``)."""
    neighbours = network.filter_neighbours
    m, P = config.share, config.particles
    if m == 0 or neighbours.shape[1] == 0:
        return state
    if neighbours.shape[1] * m >= P:
        raise ValueError(
            f"m·max_degree = {neighbours.shape[1] * m} must be < P = {P} (seed 002: m < P/N)"
        )
    for _ in range(config.exchange_rounds):
        state = _exchange_round(state, network, config, rng, neighbours, y)
    return state


def _exchange_round(
    state: PfState,
    network: PfNetwork,
    config: PfConfig,
    rng: np.random.Generator,
    neighbours: np.ndarray,
    y: np.ndarray | None,
) -> PfState:
    m = config.share
    n_filters, width = neighbours.shape
    top = np.argpartition(-state.weights, m - 1, axis=1)[:, :m]
    sender = np.repeat(neighbours, m, axis=1)
    valid = sender >= 0
    safe = np.where(valid, sender, 0)
    pick = top[safe, np.tile(np.arange(m), width)]
    positions = state.positions[safe, pick]
    headings = state.headings[safe, pick]
    if config.received_heading is ReceivedHeading.UNIFORM:
        headings = rng.uniform(-np.pi, np.pi, headings.shape)
    if config.exchange_weights is ExchangeWeights.SENDER:
        weights = state.weights[safe, pick]
    else:
        own = log_likelihood(state.positions, y, network, config.sigma)
        peak = own.max(axis=1, keepdims=True)
        scale = np.exp(own - peak).sum(axis=1, keepdims=True)
        weights = np.exp(log_likelihood(positions, y, network, config.sigma) - peak) / scale
    rows = np.arange(n_filters)[:, None]
    slots = np.argsort(state.weights, axis=1, kind="stable")[:, : width * m]
    new_positions, new_headings, new_weights = (
        state.positions.copy(),
        state.headings.copy(),
        state.weights.copy(),
    )
    new_positions[rows, slots] = np.where(valid[..., None], positions, new_positions[rows, slots])
    new_headings[rows, slots] = np.where(valid, headings, new_headings[rows, slots])
    new_weights[rows, slots] = np.where(valid, weights, new_weights[rows, slots])
    return PfState(new_positions, new_headings, new_weights / new_weights.sum(1, keepdims=True))


def estimate(state: PfState, fraction: float = 0.2) -> np.ndarray:
    """``χ_i`` ``(F, 2)``: weighted mean of the top ``fraction`` of particles (eq. (3.13)).

    The weights of the selected particles are renormalised to sum 1 (the thesis writes
    ``χ_i = W_i^T C_i`` with the unrenormalised weights, which shrinks the estimate towards the
    origin; see ``docs/errata.md``).
    """
    count = max(1, int(np.ceil(fraction * state.weights.shape[1])))
    top = np.argpartition(-state.weights, count - 1, axis=1)[:, :count]
    rows = np.arange(top.shape[0])[:, None]
    w, c = state.weights[rows, top], state.positions[rows, top]
    return np.einsum("fq,fqd->fd", w, c) / w.sum(axis=1, keepdims=True)


def cloud_moments(state: PfState) -> tuple[np.ndarray, np.ndarray]:
    """Weighted mean ``(F, 2)`` and covariance ``(F, 2, 2)`` of every node's particle cloud (the
    posterior the particles represent, seed 002 eq. (3.12))."""
    mean = np.einsum("fp,fpd->fd", state.weights, state.positions)
    spread = state.positions - mean[:, None]
    return mean, np.einsum("fp,fpd,fpe->fde", state.weights, spread, spread)


def predicted_measurements(
    state: PfState,
    y: np.ndarray,
    network: PfNetwork,
    sigma: float,
    *,
    predicted: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Innovations ``y − ŷ`` ``(F, N)`` and their covariances ``(F, N, N)`` from the prior
    particles: ``ŷ = Σ w h(x)``, ``S = Σ w (h − ŷ)(h − ŷ)ᵀ + σ²I`` on the measured rows (the
    others 0 and identity, :func:`theory.core.consistency.padded`); eqs. (3.6)–(3.9);
    ``predicted``: the particles' :func:`particle_tdoa`, if already known."""
    mask = network.measurement_mask
    h = particle_tdoa(state.positions, network) if predicted is None else predicted
    mean = np.einsum("fp,fpn->fn", state.weights, h)
    spread = (h - mean[:, None]) * mask[:, None]
    S = np.einsum("fp,fpn,fpm->fnm", state.weights, spread, spread)
    S += np.eye(mask.shape[1]) * np.where(mask, sigma**2, 1.0)[:, None, :]
    return np.where(mask, y - mean, 0.0), S


def multinomial_resample(state: PfState, rng: np.random.Generator) -> PfState:
    """Draw ``P`` particles per node with replacement with probabilities ``w̄`` (§3.2.1 step 5).

    All nodes are searched at once: row ``f``'s cumulative weights are shifted by ``f`` so that one
    ``searchsorted`` on the flattened, increasing array serves every node.
    """
    n_filters, P = state.weights.shape
    cumulative = np.cumsum(state.weights, axis=1)
    cumulative[:, -1] = 1.0
    offsets = np.arange(n_filters)[:, None]
    draws = rng.random((n_filters, P)) + offsets
    flat = np.searchsorted((cumulative + offsets).ravel(), draws.ravel(), side="right")
    index = np.minimum(flat.reshape(n_filters, P) - offsets * P, P - 1)
    rows = np.arange(n_filters)[:, None]
    return PfState(
        state.positions[rows, index],
        state.headings[rows, index],
        np.full((n_filters, P), 1.0 / P),
    )


def propagate(state: PfState, motion: Motion, rng: np.random.Generator) -> PfState:
    """Time update eqs. (3.14)–(3.16): turn, then step along the new heading."""
    turn, step = motion.sample(rng, state.weights.shape)
    headings = state.headings + turn
    move = step[..., None] * np.stack([np.cos(headings), np.sin(headings)], axis=-1)
    return PfState(state.positions + move, headings, state.weights)


def pf_step(
    state: PfState,
    y: np.ndarray,
    network: PfNetwork,
    config: PfConfig,
    motion: Motion,
    rng: np.random.Generator,
) -> tuple[PfState, np.ndarray, PfState]:
    """Steps 1–6 of seed 002 §3.2.1: the particles for ``k + 1``, ``χ_i(k)`` ``(F, 2)`` and the
    weighted set after consensus."""
    weighted, chi = pf_update(state, y, network, config, rng)
    return propagate(multinomial_resample(weighted, rng), motion, rng), chi, weighted


def pf_update(
    state: PfState,
    y: np.ndarray,
    network: PfNetwork,
    config: PfConfig,
    rng: np.random.Generator,
    *,
    predicted: np.ndarray | None = None,
) -> tuple[PfState, np.ndarray]:
    """Steps 1–4 of seed 002 §3.2.1: weights, consensus exchange, estimate ``χ_i(k)``
    (``predicted``: the particles' :func:`particle_tdoa`, if already known)."""
    log_weights = log_likelihood(state.positions, y, network, config.sigma, predicted=predicted)
    weights = normalise_log_weights(log_weights)
    weighted = consensus_exchange(replace(state, weights=weights), network, config, rng, y=y)
    return weighted, estimate(weighted, config.estimate_fraction)


def run_filter(
    path: np.ndarray,
    network: PfNetwork,
    config: PfConfig,
    motion: Motion,
    rng: np.random.Generator,
    *,
    bounds: np.ndarray,
    measurements: np.ndarray,
    snapshot_steps: tuple[int, ...] = (),
) -> PfRun:
    """Run the distributed PF on ``measurements`` ``(K + 1, F, N)`` of a target path ``p(0), …,
    p(K)``, from particles uniform on ``bounds``; after each estimate the filter continues with
    ``motion.observe(χ)``, and keeps the weighted particles at ``snapshot_steps``."""
    state = initial_state(len(network.filters), config.particles, bounds, rng)
    estimates, snapshots, moments, innovations = [], {}, [], []
    for k, y in enumerate(measurements):
        h = particle_tdoa(state.positions, network)
        innovations.append(predicted_measurements(state, y, network, config.sigma, predicted=h))
        weighted, chi = pf_update(state, y, network, config, rng, predicted=h)
        moments.append(cloud_moments(weighted))
        motion = motion.observe(chi)
        state = propagate(multinomial_resample(weighted, rng), motion, rng)
        estimates.append(chi)
        if k in snapshot_steps:
            snapshots[k] = np.concatenate([weighted.positions, weighted.weights[..., None]], -1)
    chis = np.asarray(estimates)
    errors = np.linalg.norm(chis - np.asarray(path)[:, None, :], axis=-1)
    means, covariances = (np.asarray(a) for a in zip(*moments, strict=True))
    nu, S = (np.asarray(a) for a in zip(*innovations, strict=True))
    return PfRun(chis, errors, snapshots, motion, means, covariances, nu, S)


@dataclass(frozen=True)
class DcrwMotion:
    """Propagate with a known DCRW ``params`` (seed 002 eqs. (3.1)–(3.2), (3.14)–(3.16))."""

    params: DcrwParams

    def sample(self, rng: np.random.Generator, shape: tuple[int, int]) -> tuple:
        """Turning angles and step lengths, each of ``shape``, drawn from ``rng``."""
        p = self.params
        return (
            sample_wrapped_cauchy(rng, p.mu, p.gamma, shape),
            sample_weibull(rng, p.kappa, p.lam, shape),
        )

    def observe(self, estimates: np.ndarray) -> DcrwMotion:
        """A fixed model ignores the estimates."""
        return self


@dataclass(frozen=True)
class GaussianMotion:
    """Truncated-normal turning angle ``N(0, turn_sigma²)`` on ``(−π, π]`` and step
    ``N(step_mean, step_sigma²)`` on ``δ ≥ 0`` (seed 002 §3.3.2, the Gaussian baseline)."""

    turn_sigma: float = np.pi / 4
    step_mean: float = 2.0
    step_sigma: float = 1.0

    def sample(self, rng: np.random.Generator, shape: tuple[int, int]) -> tuple:
        """Turning angles and steps, each of ``shape``, drawn from ``rng``."""
        bound = np.pi / self.turn_sigma
        turn = truncated_normal(rng, -bound, bound, 0.0, self.turn_sigma, shape)
        low = -self.step_mean / self.step_sigma
        step = truncated_normal(rng, low, np.inf, self.step_mean, self.step_sigma, shape)
        return turn, step

    def observe(self, estimates: np.ndarray) -> GaussianMotion:
        """A fixed model ignores the estimates."""
        return self


@dataclass(frozen=True)
class UniformMotion:
    """Uniform turning angle on ``(−π, π]`` and uniform step on ``[0, max_step]``."""

    max_step: float

    def sample(self, rng: np.random.Generator, shape: tuple[int, int]) -> tuple:
        """Turning angles and step lengths, each of ``shape``, drawn from ``rng``."""
        return rng.uniform(-np.pi, np.pi, shape), rng.uniform(0.0, self.max_step, shape)

    def observe(self, estimates: np.ndarray) -> UniformMotion:
        """A fixed model ignores the estimates."""
        return self


def truncated_normal(
    rng: np.random.Generator, a: float, b: float, loc: float, scale: float, shape: tuple
) -> np.ndarray:
    """``scipy.stats.truncnorm.rvs(a, b, loc, scale, size=shape, random_state=rng)`` for
    ``a < 0``, the same numbers without its per-call overhead.

    scipy draws ``q ~ U[0, 1)`` and inverts the CDF in log space,
    ``x = ndtri_exp(log(Φ(a) + q·(Φ(b) − Φ(a))))``, the sum formed as its ``logsumexp`` of the two
    logs does (the larger one taken out, ``log1p`` of the ratio); the interval's log-mass depends
    on ``(a, b)`` only and is computed once here instead of per draw.
    """
    if not a < 0:
        raise ValueError(f"truncated_normal needs a < 0, got a={a!r}")
    q = rng.uniform(size=shape)
    first = special.log_ndtr(a)
    second = np.log(q) + _log_gauss_mass(a, b)
    top, tie = np.maximum(first, second), first == second
    ratio = np.where(tie, 0.0, np.exp(np.minimum(first, second) - top))
    log_cdf = np.log1p(ratio) + np.log(np.where(tie, 2.0, 1.0)) + top
    return special.ndtri_exp(log_cdf) * scale + loc


@dataclass(frozen=True, eq=False)
class OnlineLearner:
    """A propagation model refitting a DCRW per node after every estimate (seed 002 §3.2.2).

    ``history`` holds the estimates seen, each ``(F, 2)``; ``params`` ``(F, 4)`` the fitted
    ``(μ, γ, κ, λ)``, ``nan`` rows for nodes not yet fitted (module docstring for the guards).
    ``engine``: the refits by the compiled kernel (``"numba"``, :mod:`theory.particle.kernels`)
    or by the NumPy reference (``"numpy"``), equal to rounding.
    """

    prior: UniformMotion
    min_samples: int = 10
    gamma_max: float = 0.95
    kappa_bounds: tuple[float, float] = (0.5, 10.0)
    burn_in: int = 5
    engine: str = "numba"
    history: tuple[np.ndarray, ...] = ()
    params: np.ndarray | None = None

    @property
    def fitted(self) -> np.ndarray:
        """``(F,)`` bool: which nodes have switched to their learned DCRW."""
        return np.zeros(0, bool) if self.params is None else ~np.isnan(self.params[:, 0])

    def observe(self, estimates: np.ndarray) -> OnlineLearner:
        """Append ``χ(k)`` ``(F, 2)`` of every node and refit where there are enough samples."""
        history = (*self.history, np.asarray(estimates, dtype=float))
        tracks = np.asarray(history[self.burn_in :])
        params = np.full((len(estimates), 4), np.nan)
        refit = self._fit_compiled if self.engine == "numba" else self._fit_reference
        for f in range(len(estimates)) if tracks.shape[0] >= 3 else ():
            fit = refit(np.ascontiguousarray(tracks[:, f]))
            if fit is not None:
                params[f] = fit
        return replace(self, history=history, params=params)

    def _fit_reference(self, track: np.ndarray) -> tuple[float, ...] | None:
        """``(μ, γ, κ, λ)`` of one node's track by eqs. (3.17)–(3.19) and the ML fits of
        :mod:`~theory.particle.dcrw`, ``κ`` clamped; ``None`` with too few samples."""
        turns, steps = movement_samples(track)
        if turns.size < self.min_samples or not steps.size:
            return None
        fit = fit_dcrw(turns, steps, gamma_max=self.gamma_max)
        kappa = float(np.clip(fit.kappa, *self.kappa_bounds))
        return fit.mu, fit.gamma, kappa, _scale_for(steps, kappa)

    def _fit_compiled(self, track: np.ndarray) -> tuple[float, ...] | None:
        """:meth:`_fit_reference` by the compiled kernel (:func:`kernels.fit_track`), the
        reference where the kernel hands the node back."""
        from theory.particle import kernels

        out = np.empty(4)
        status = kernels.fit_track(
            track, self.min_samples, self.gamma_max, *map(float, self.kappa_bounds), out
        )
        if status == kernels.FALLBACK:
            return self._fit_reference(track)
        return None if status == kernels.TOO_FEW else tuple(out.tolist())

    def sample(self, rng: np.random.Generator, shape: tuple[int, int]) -> tuple:
        """Turns and steps of ``shape`` ``(F, P)``, drawn from ``rng``: the learned DCRW where
        fitted, the prior elsewhere."""
        turn, step = self.prior.sample(rng, shape)
        if self.params is None or not self.fitted.any():
            return turn, step
        p = np.where(self.fitted[:, None], self.params, [[0.0, 0.0, 1.0, 1.0]])
        learned_turn = sample_wrapped_cauchy(rng, p[:, :1], p[:, 1:2], shape)
        learned_step = sample_weibull(rng, p[:, 2:3], p[:, 3:4], shape)
        use = self.fitted[:, None]
        return np.where(use, learned_turn, turn), np.where(use, learned_step, step)


def _scale_for(steps: np.ndarray, kappa: float) -> float:
    """ML Weibull scale for a fixed shape ``κ``: ``λ = (mean δ^κ)^{1/κ}``."""
    return float(np.mean(steps**kappa) ** (1.0 / kappa))


def build_motion(spec: PfSpec, model: Model, engine: str | None = None) -> Motion:
    """The propagation model ``model`` of ``spec``: its true DCRW, the Gaussian baseline, or an
    online learner over the uniform prior with the case's learning settings, refitting on
    ``engine`` (:func:`theory.core.engines.resolve_engine`: ``"numba"``, ``"numpy"``,
    ``None`` for ``$TRACKCERT_ENGINE`` or ``"numba"``)."""
    match Model(model):
        case Model.DCRW:
            return DcrwMotion(spec.target)
        case Model.GAUSSIAN:
            return GaussianMotion()
        case Model.LEARNED:
            prior = UniformMotion(spec.uniform_max_step)
            return OnlineLearner(prior, **spec.learning, engine=resolve_engine(engine))
