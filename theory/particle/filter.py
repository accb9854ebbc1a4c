"""The distributed TDOA particle filter of seed 002 §3.2.1 (2D), vectorised over nodes/particles.

Every filtering node ``i`` keeps ``P`` particles (positions, headings) and at each time step ``k``:

1. computes each particle's TDOA vector ``d_i^n`` against its neighbours (eq. 3.9);
2. weights it by ``exp(−‖y_i − d_i^n‖² / (2σ²))`` (eqs. 3.10–3.11) and normalises (eq. 3.12);
3. *consensus*: broadcasts its ``m`` highest-weighted particles to its filtering neighbours and
   replaces its own ``|N_i| m`` lowest-weighted particles with those received, then renormalises;
4. estimates ``χ_i`` from the top 20 % of particles (eq. 3.13, weights renormalised over them);
5. resamples ``P`` particles multinomially;
6. propagates them with a motion model (eqs. 3.14–3.16, :mod:`theory.particle.motion`).

Choices the thesis leaves open (documented in ``docs/particle-filter.md``), as parameters of
:class:`PfConfig`:

``exchange_weights``
    ``"sender"`` (default, the thesis's message ``[w̄, x, y]``): a received particle keeps the
    normalised weight its sender gave it, and node ``i``'s whole set is renormalised to sum 1.
    ``"local"``: node ``i`` re-weights received particles with its own likelihood (same
    normalising constant as its own particles) before renormalising.
``exchange_rounds``
    Rounds of exchange per time step (default 1). In each round every node sends the top ``m`` of
    its *current* set, so with 2 or more rounds particles received in round 1 can be forwarded
    in round 2. With one round, information travels one hop per time step (through resampling).
``received_heading``
    ``"sender"`` (default): the heading travels with the particle (one extra number per message).
    ``"uniform"``: the thesis's message carries no heading; a fresh uniform heading is drawn.

The TDOA model ``d_i^n`` (eq. 3.9) and the measurements (eqs. 3.6–3.8) are those of seed 000
eqs. (4.3)–(4.4), evaluated by the one implementation in :mod:`theory.tdoa.model` (broadcast over
filtering nodes × particles).

Weights are computed in the log domain (subtracting the maximum before exponentiating), which
equals eqs. (3.11)–(3.12) after normalisation but never underflows to ``0/0``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from theory.tdoa.model import range_differences

__all__ = [
    "PfConfig",
    "PfNetwork",
    "PfRun",
    "PfState",
    "consensus_exchange",
    "estimate",
    "initial_state",
    "log_likelihood",
    "measure",
    "multinomial_resample",
    "normalise_log_weights",
    "pf_step",
    "pf_update",
    "propagate",
    "run_filter",
    "simulate_measurements",
]

EXCHANGE_WEIGHTS = ("sender", "local")
RECEIVED_HEADINGS = ("sender", "uniform")


@dataclass(frozen=True)
class PfConfig:
    """Parameters of the distributed PF (seed 002 §3.2.1, §3.3.1 defaults P = 100, m = 10).

    Attributes
    ----------
    particles : int
        ``P`` per node.
    share : int
        ``m``, the particles each node broadcasts (0 disables the consensus step).
    sigma : float
        Standard deviation of the TDOA noise assumed by the filter (eq. 3.11), in metres.
    estimate_fraction : float
        Fraction of highest-weighted particles averaged in the estimate (eq. 3.13; 0.2).
    exchange_weights : str
        ``"sender"`` or ``"local"`` (module docstring).
    exchange_rounds : int
        Exchange rounds per step (module docstring).
    received_heading : str
        ``"sender"`` or ``"uniform"`` (module docstring).
    """

    particles: int = 100
    share: int = 10
    sigma: float = 1.0
    estimate_fraction: float = 0.2
    exchange_weights: str = "sender"
    exchange_rounds: int = 1
    received_heading: str = "sender"

    def __post_init__(self) -> None:
        if self.exchange_weights not in EXCHANGE_WEIGHTS:
            raise ValueError(f"exchange_weights must be one of {EXCHANGE_WEIGHTS}")
        if self.received_heading not in RECEIVED_HEADINGS:
            raise ValueError(f"received_heading must be one of {RECEIVED_HEADINGS}")
        if not (0 < self.estimate_fraction <= 1 and self.sigma > 0 and self.particles >= 1):
            raise ValueError("need P ≥ 1, σ > 0 and 0 < estimate_fraction ≤ 1")
        if self.share < 0 or self.exchange_rounds < 1:
            raise ValueError("need m ≥ 0 and exchange_rounds ≥ 1")


@dataclass(frozen=True, eq=False)
class PfNetwork:
    """Stationary nodes, who hears whom, and which nodes run a filter (all 0-based).

    Attributes
    ----------
    nodes : ndarray, shape (N, 2)
        Node positions ``ρ_i``.
    hears : ndarray of bool, shape (N, N)
        ``hears[i, j]``: node ``i`` receives node ``j``'s TOA (``j ∈ N_i``).
    filters : tuple of int
        Nodes running the PF (seed 002 §3.3.1: nodes 1, 4 and 5).
    """

    nodes: np.ndarray
    hears: np.ndarray
    filters: tuple[int, ...]

    @property
    def measurement_mask(self) -> np.ndarray:
        """``(F, N)`` mask of the TDOA components each filtering node measures."""
        return self.hears[list(self.filters)]

    @property
    def filter_neighbours(self) -> np.ndarray:
        """``(F, D)`` filter-indices of each filter's filtering neighbours, padded with −1 last."""
        index = {node: f for f, node in enumerate(self.filters)}
        rows = [
            [index[j] for j in np.flatnonzero(self.hears[i]) if j in index] for i in self.filters
        ]
        width = max((len(r) for r in rows), default=0)
        return np.array([r + [-1] * (width - len(r)) for r in rows], dtype=int).reshape(
            len(rows), width
        )


@dataclass(frozen=True, eq=False)
class PfState:
    """Particles of every node: ``positions (F, P, 2)``, ``headings`` and ``weights (F, P)``."""

    positions: np.ndarray
    headings: np.ndarray
    weights: np.ndarray


@dataclass(frozen=True, eq=False)
class PfRun:
    """One filter run.

    Attributes
    ----------
    estimates : ndarray, shape (K+1, F, 2)
        ``χ_i(k)`` of every filtering node.
    errors : ndarray, shape (K+1, F)
        ``E_i(k)`` (eq. 3.20).
    snapshots : dict
        Step → weighted particles ``(F, P, 3)`` (x, y, w̄) after consensus.
    motion : object
        The motion model at the end of the run (the learner holds its fits).
    """

    estimates: np.ndarray
    errors: np.ndarray
    snapshots: dict[int, np.ndarray]
    motion: Any


def initial_state(
    n_filters: int, particles: int, bounds: np.ndarray, rng: np.random.Generator
) -> PfState:
    """Particles uniform on the workspace (§3.2.1, *Initialization*).

    Parameters
    ----------
    n_filters : int
        Number of filtering nodes ``F``.
    particles : int
        ``P`` per node.
    bounds : ndarray, shape (2, 2)
        ``[[xmin, xmax], [ymin, ymax]]``.
    rng : numpy.random.Generator
        Source of randomness. Headings are uniform on ``(−π, π]``, weights ``1/P``.
    """
    low, high = np.asarray(bounds, float)[:, 0], np.asarray(bounds, float)[:, 1]
    positions = low + (high - low) * rng.random((n_filters, particles, 2))
    headings = rng.uniform(-np.pi, np.pi, (n_filters, particles))
    return PfState(positions, headings, np.full((n_filters, particles), 1.0 / particles))


def measure(
    target: np.ndarray, network: PfNetwork, noise_sigma: float, rng: np.random.Generator
) -> np.ndarray:
    """TDOA measurements ``y_i = h_i(p) + w_i`` of every filtering node (eqs. (3.6)–(3.8)).

    Parameters
    ----------
    target : ndarray, shape (2,)
        True position ``p(k)``.
    network : PfNetwork
        Nodes and links.
    noise_sigma : float
        Standard deviation of ``w_i`` (m).
    rng : numpy.random.Generator
        Source of the noise.

    Returns
    -------
    ndarray, shape (F, N)
        Entries outside :attr:`PfNetwork.measurement_mask` are 0.
    """
    clean = range_differences(target, network.nodes, np.asarray(network.filters, dtype=int))
    mask = network.measurement_mask
    noise = noise_sigma * rng.standard_normal(mask.shape)
    return np.where(mask, clean + noise, 0.0)


def simulate_measurements(
    path: np.ndarray, network: PfNetwork, noise_sigma: float, rng: np.random.Generator
) -> np.ndarray:
    """:func:`measure` at every point of ``path``: an ``(K + 1, F, N)`` array.

    Parameters
    ----------
    path : ndarray, shape (K + 1, 2)
        True positions.
    network, noise_sigma, rng :
        As for :func:`measure`.
    """
    return np.asarray([measure(p, network, noise_sigma, rng) for p in path])


def log_likelihood(
    positions: np.ndarray, y: np.ndarray, network: PfNetwork, sigma: float
) -> np.ndarray:
    """``−‖y_i − d_i^n‖² / (2σ²)`` of each particle (eqs. (3.9)–(3.11)), up to a constant.

    Parameters
    ----------
    positions : ndarray, shape (F, Q, 2)
        ``Q`` candidate positions per filtering node.
    y : ndarray, shape (F, N)
        Measurements (:func:`measure`).
    network : PfNetwork
        Nodes and links.
    sigma : float
        Noise standard deviation assumed by the filter.

    Returns
    -------
    ndarray, shape (F, Q)
    """
    filters = np.asarray(network.filters, dtype=int)[:, None]
    predicted = range_differences(positions, network.nodes, filters)
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
    """The consensus step of seed 002 §3.2.1 step 3 (see the module docstring for the choices).

    Parameters
    ----------
    state : PfState
        Weighted particles after the measurement update.
    network : PfNetwork
        Nodes and links (exchange only between filtering neighbours).
    config : PfConfig
        ``share`` (m), ``exchange_weights``, ``exchange_rounds``, ``received_heading``.
    rng : numpy.random.Generator
        For uniform headings of received particles.
    y : ndarray or None
        Measurements, needed by ``exchange_weights="local"``.

    Returns
    -------
    PfState

    Raises
    ------
    ValueError
        If a node would replace ``P`` or more particles (the thesis asks ``m < P/N``).
    """
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
    if config.received_heading == "uniform":
        headings = rng.uniform(-np.pi, np.pi, headings.shape)
    if config.exchange_weights == "sender":
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
    """``χ_i``: weighted mean of the top ``fraction`` of particles (eq. (3.13)).

    The weights of the selected particles are renormalised to sum 1 (the thesis writes
    ``χ_i = W_i^T C_i`` with the unrenormalised weights, which shrinks the estimate towards the
    origin; see ``docs/errata.md``).

    Parameters
    ----------
    state : PfState
        Weighted particles.
    fraction : float
        Share of the highest-weighted particles used (0.2 in the thesis).

    Returns
    -------
    ndarray, shape (F, 2)
    """
    count = max(1, int(np.ceil(fraction * state.weights.shape[1])))
    top = np.argpartition(-state.weights, count - 1, axis=1)[:, :count]
    w = np.take_along_axis(state.weights, top, axis=1)
    c = np.take_along_axis(state.positions, top[..., None], axis=1)
    return np.einsum("fq,fqd->fd", w, c) / w.sum(axis=1, keepdims=True)


def multinomial_resample(state: PfState, rng: np.random.Generator) -> PfState:
    """Draw ``P`` particles with replacement with probabilities ``w̄`` (§3.2.1 step 5), per node.

    All nodes are searched at once: row ``f``'s cumulative weights are shifted by ``f`` so that one
    ``searchsorted`` on the flattened, increasing array serves every node.

    Parameters
    ----------
    state : PfState
        Weighted particles.
    rng : numpy.random.Generator
        Source of randomness.

    Returns
    -------
    PfState
        Equal weights ``1/P``; headings travel with their particles.
    """
    n_filters, P = state.weights.shape
    cumulative = np.cumsum(state.weights, axis=1)
    cumulative[:, -1] = 1.0
    offsets = np.arange(n_filters)[:, None]
    draws = rng.random((n_filters, P)) + offsets
    flat = np.searchsorted((cumulative + offsets).ravel(), draws.ravel(), side="right")
    index = np.minimum(flat.reshape(n_filters, P) - offsets * P, P - 1)
    return PfState(
        np.take_along_axis(state.positions, index[..., None], axis=1),
        np.take_along_axis(state.headings, index, axis=1),
        np.full((n_filters, P), 1.0 / P),
    )


def propagate(state: PfState, motion: Any, rng: np.random.Generator) -> PfState:
    """Time update eqs. (3.14)–(3.16): turn, then step along the new heading.

    Parameters
    ----------
    state : PfState
        Particles to move.
    motion : object
        A model with ``sample(rng, shape) -> (turns, steps)`` (:mod:`theory.particle.motion`).
    rng : numpy.random.Generator
        Source of randomness.
    """
    turn, step = motion.sample(rng, state.weights.shape)
    headings = state.headings + turn
    move = step[..., None] * np.stack([np.cos(headings), np.sin(headings)], axis=-1)
    return PfState(state.positions + move, headings, state.weights)


def pf_step(
    state: PfState,
    y: np.ndarray,
    network: PfNetwork,
    config: PfConfig,
    motion: Any,
    rng: np.random.Generator,
) -> tuple[PfState, np.ndarray, PfState]:
    """One iteration (steps 1–6 of seed 002 §3.2.1).

    Parameters
    ----------
    state : PfState
        Particles for time ``k``.
    y : ndarray, shape (F, N)
        Measurements at ``k``.
    network, config :
        Nodes and filter parameters.
    motion : object
        Propagation model.
    rng : numpy.random.Generator
        Source of randomness.

    Returns
    -------
    (next_state, estimates, weighted) :
        particles for ``k + 1``; ``χ_i(k)`` of shape ``(F, 2)``; the weighted set after consensus
        (for figures).
    """
    weighted, chi = pf_update(state, y, network, config, rng)
    return propagate(multinomial_resample(weighted, rng), motion, rng), chi, weighted


def pf_update(
    state: PfState, y: np.ndarray, network: PfNetwork, config: PfConfig, rng: np.random.Generator
) -> tuple[PfState, np.ndarray]:
    """Steps 1–4 of seed 002 §3.2.1: weights, consensus exchange, estimate ``χ_i(k)``.

    Parameters
    ----------
    state, y, network, config, rng :
        As for :func:`pf_step`.

    Returns
    -------
    (weighted, estimates) : PfState and ndarray of shape (F, 2)
    """
    weights = normalise_log_weights(log_likelihood(state.positions, y, network, config.sigma))
    weighted = consensus_exchange(replace(state, weights=weights), network, config, rng, y=y)
    return weighted, estimate(weighted, config.estimate_fraction)


def run_filter(
    path: np.ndarray,
    network: PfNetwork,
    config: PfConfig,
    motion: Any,
    rng: np.random.Generator,
    *,
    bounds: np.ndarray,
    measurements: np.ndarray,
    snapshot_steps: tuple[int, ...] = (),
) -> PfRun:
    """Run the distributed PF along a target path ``p(0), …, p(K)``.

    Parameters
    ----------
    path : ndarray, shape (K + 1, 2)
        True target positions.
    network, config : PfNetwork, PfConfig
        The nodes and the filter's parameters.
    motion : object
        A model of :mod:`theory.particle.motion` or :class:`theory.particle.learning.OnlineLearner`;
        after each estimate the filter continues with ``motion.observe(chi)``.
    rng : numpy.random.Generator
        The filter's randomness (initial particles, exchange, resampling, propagation).
    bounds : ndarray, shape (2, 2)
        Workspace for the uniform initial particles.
    measurements : ndarray, shape (K + 1, F, N)
        TDOA measurements ``y_i(k)`` (:func:`simulate_measurements`).
    snapshot_steps : tuple of int
        Steps at which to keep the weighted particle sets ``(F, P, 3)`` (x, y, w̄) for figures.

    Returns
    -------
    PfRun
    """
    state = initial_state(len(network.filters), config.particles, bounds, rng)
    estimates, snapshots = [], {}
    for k, y in enumerate(measurements):
        weighted, chi = pf_update(state, y, network, config, rng)
        motion = motion.observe(chi)
        state = propagate(multinomial_resample(weighted, rng), motion, rng)
        estimates.append(chi)
        if k in snapshot_steps:
            snapshots[k] = np.concatenate([weighted.positions, weighted.weights[..., None]], -1)
    chis = np.asarray(estimates)
    errors = np.linalg.norm(chis - np.asarray(path)[:, None, :], axis=-1)
    return PfRun(chis, errors, snapshots, motion)
