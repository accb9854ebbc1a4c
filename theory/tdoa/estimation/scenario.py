"""One closed-loop run of the §4.4 scenario: target, TDOA pings, network filter, moving agents.

Timeline of ping ``k`` (time ``t_k = kT``), seed 000 §4.2.2–4.4:

1. every agent measures its TDOA rows with the neighbours it hears at ``t_k`` (4.2) and updates
   its predicted estimate (4.27), (4.34);
2. for ``j = 0, …, T/τ − 1`` (times ``t_k + jτ``): the agents average ``x̂`` and ``P`` with their
   current neighbours (4.28), (4.35) (round ``j = 0`` is the paper's averaging; the others are the
   fast consensus of §4.3); each agent decides to move iff ``‖P̄_i‖ > b``; then the robots move
   for ``τ`` seconds, tracking ``ζ*`` built from ``x̂_i(t) = exp(F(t − t_k)) x̄_i`` (B.14–B.18);
3. the estimates are predicted to the next ping (4.26), (4.33).

Recorded at ping ``k``: the estimate and covariance after round 0, the true state, and each
update's innovation ``ν = y − h(x̂)`` with ``S = HPH' + rI`` (padded,
:func:`theory.core.consistency.padded`). With
``filter: decentralized`` no averaging happens; with ``centralized`` one EKF uses every agent's
rows.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from theory.core.consistency import padded
from theory.core.network import adjacency_from_range, metropolis_weights, uniform_weights
from theory.tdoa.case import CovNorm, Filter, Linearize, TdoaSimSpec, WeightRule
from theory.tdoa.estimation.agents import (
    braking_control,
    linearizing_control,
    rest_states,
    rk4_step,
)
from theory.tdoa.estimation.filters import average_round, ekf_predict, measurement_step
from theory.tdoa.model import cv_discrete, neighbour_lists, simulate_cv_target, tdoa_readings

__all__ = [
    "TdoaRun",
    "covariance_norms",
    "hears_at",
    "run_tdoa_scenario",
    "run_tdoa_scenarios",
    "weights_at",
]


@dataclass(frozen=True, eq=False)
class TdoaRun:
    """Arrays recorded along one run: at the ``K + 1`` pings, the true states, ``x̄_i``, ``P̄_i``
    after (4.28), (4.35), their norms and each agent's number of TDOA rows; the innovations
    ``(K+1, U, m)`` of the ``U`` updates of a ping (one per agent, one for ``centralized``),
    padded to ``m`` rows, their covariances and dimensions; every ``τ`` (``M + 1`` instants) the
    positions and cumulative distances, and per interval whether each agent tracked
    (``‖P̄_i‖ > b``)."""

    ping_times: np.ndarray
    truth: np.ndarray
    estimates: np.ndarray
    covariances: np.ndarray
    cov_norms: np.ndarray
    degrees: np.ndarray
    innovations: np.ndarray
    innovation_covariances: np.ndarray
    innovation_dims: np.ndarray
    fine_times: np.ndarray
    paths: np.ndarray
    distance: np.ndarray
    moving: np.ndarray

    @property
    def localization_errors(self) -> np.ndarray:
        """``‖p̄_i(k) − p(k)‖``, shape (K+1, N)."""
        return np.linalg.norm(self.estimates[:, :, :3] - self.truth[:, None, :3], axis=-1)


def covariance_norms(P: np.ndarray, norm: CovNorm) -> np.ndarray:
    """``‖P_i‖`` of a stack of symmetric PSD matrices (spectral: the largest eigenvalue)."""
    if CovNorm(norm) is CovNorm.SPECTRAL:
        return np.linalg.eigvalsh(P)[..., -1]
    return np.sqrt(np.einsum("...ij,...ij->...", P, P))


def run_tdoa_scenario(spec: TdoaSimSpec, rng: np.random.Generator) -> TdoaRun:
    """The closed loop of seed 000 §4.3–4.4 once (eqs. (4.1)–(4.35), (4.44)–(4.48), App. B.2)."""
    return run_tdoa_scenarios([spec], [rng])[0]


def run_tdoa_scenarios(
    specs: Sequence[TdoaSimSpec], rngs: Sequence[np.random.Generator]
) -> list[TdoaRun]:
    """Several closed loops in lock step, each equal to :func:`run_tdoa_scenario` with its own
    generator: only the robots' integration between pings is done for all runs' agents in one
    stack. The specs must share :data:`LOCKSTEP_FIELDS` (else ``ValueError``)."""
    clock = _shared_clock(specs, rngs)
    runs = [_Run(spec, rng) for spec, rng in zip(specs, rngs, strict=True)]
    K, m = clock.steps, clock.rounds
    for k in range(K + 1):
        for run in runs:
            run.measure(k)
        for j in range(m):
            _average_all(runs, k, j)
            if k == K:
                break
            _move_all(clock, runs, j * clock.tau)
            for run in runs:
                run.record.fine(k * m + j + 1, run.states, run.travelled, run.moving)
        for run in runs:
            run.predict()
    return [run.record.result(run.spec, run.truth) for run in runs]


def _shared_clock(specs: Sequence[TdoaSimSpec], rngs: Sequence[np.random.Generator]) -> TdoaSimSpec:
    """The first spec, after checking that every spec shares its clock and actuators."""
    if not specs or len(specs) != len(rngs):
        raise ValueError(f"need one generator per scenario, got {len(specs)} and {len(rngs)}")
    first = specs[0]
    for spec in specs[1:]:
        if any(getattr(spec, f) != getattr(first, f) for f in LOCKSTEP_FIELDS):
            raise ValueError(f"lock-step scenarios must share {', '.join(LOCKSTEP_FIELDS)}")
    return first


LOCKSTEP_FIELDS = ("T", "tau", "steps", "substeps", "pole", "max_input", "cov_norm")
"""What lock-step scenarios share: the clock, the actuators and the trigger's norm."""


class _Run:
    """The state of one run between the lock-step phases of :func:`run_tdoa_scenarios`."""

    def __init__(self, spec: TdoaSimSpec, rng: np.random.Generator) -> None:
        n = spec.n_agents
        self.spec, self.rng = spec, rng
        A, B = cv_discrete(spec.T, 3)
        self.A, self.BQB = A, B @ spec.Q @ B.T
        self.truth = simulate_cv_target(spec.target, spec.Q, spec.T, spec.steps, rng)
        self.x = np.tile(spec.x0, (n, 1))
        self.P = np.tile(spec.P0, (n, 1, 1))
        self.states = rest_states(spec.agents)
        self.travelled = np.zeros(n)
        self.moving = np.zeros(n, dtype=bool)
        self.norms = np.zeros(n)
        self.neighbours: list[np.ndarray] = []
        fixed = spec.hears is not None or isinstance(spec.weights, np.ndarray)
        self.fixed_weights = weights_at(spec, spec.agents) if fixed else None
        self.record = _Recorder(n, spec.steps, spec.rounds, spec.filter == Filter.CENTRALIZED)
        self.record.fine(0, self.states, self.travelled)

    def measure(self, k: int) -> None:
        """Step 1 of ping ``k``: TDOA readings and every agent's measurement update."""
        spec, positions = self.spec, self.states[:, :3]
        self.neighbours = neighbour_lists(hears_at(spec, positions))
        readings = tdoa_readings(self.truth[k, :3], positions, self.neighbours, spec.r, self.rng)
        at = self.truth[k, :3] if spec.linearize == Linearize.TRUTH else None
        updates: list = []
        self.x, self.P = measurement_step(
            spec.filter,
            self.x,
            self.P,
            readings,
            positions,
            self.neighbours,
            spec.r,
            linearize_at=at,
            innovations=updates,
        )
        self.record.updates(k, updates)

    def average(self) -> bool:
        """A consensus round (4.28), (4.35) of step 2; whether this filter averages at all."""
        spec = self.spec
        if spec.filter != Filter.AVERAGED:
            return False
        W = self.fixed_weights
        if W is None:
            W = weights_at(spec, self.states[:, :3])
        self.x, self.P = average_round(W, self.x, self.P)
        return True

    def trigger(self, k: int, j: int) -> None:
        """The trigger ``‖P̄_i‖ > b`` of round ``j`` (``self.norms`` is current), the record at
        ``j = 0``."""
        if j == 0:
            degrees = [len(nb) for nb in self.neighbours]
            self.record.ping(k, self.x, self.P, self.norms, degrees)
        self.moving = self.norms > self.spec.b

    def predict(self) -> None:
        """Step 3: predict the estimates to the next ping (4.26), (4.33)."""
        self.x, self.P = ekf_predict(self.x, self.P, self.A, self.BQB)


def _average_all(runs: list[_Run], k: int, j: int) -> None:
    """Round ``j`` after ping ``k`` for every run; the norms of all changed ``P̄`` in one call.

    Without averaging (``decentralized``, ``centralized``) ``P`` is the same in every round
    after the ping's, and so are its norms: they are computed at ``j = 0`` only.
    """
    changed = [run for run in runs if run.average() or j == 0]
    if changed:
        sizes = np.cumsum([run.spec.n_agents for run in changed])[:-1]
        norms = covariance_norms(np.concatenate([run.P for run in changed]), runs[0].spec.cov_norm)
        for run, part in zip(changed, np.split(norms, sizes), strict=True):
            run.norms = part
    for run in runs:
        run.trigger(k, j)


def _move_all(clock: TdoaSimSpec, runs: list[_Run], since_ping: float) -> None:
    """Integrate every run's robots over one ``τ`` as one stack of agents."""
    sizes = np.cumsum([run.spec.n_agents for run in runs])[:-1]
    states, travelled = _move(
        clock,
        np.concatenate([run.states for run in runs]),
        np.concatenate([run.x for run in runs]),
        np.concatenate([run.spec.offsets for run in runs]),
        np.concatenate([run.moving for run in runs]),
        since_ping,
        np.concatenate([run.travelled for run in runs]),
    )
    for run, s, d in zip(runs, np.split(states, sizes), np.split(travelled, sizes), strict=True):
        run.states, run.travelled = s, d


def hears_at(spec: TdoaSimSpec, positions: np.ndarray) -> np.ndarray:
    """``hears[i, j]`` for agents at ``positions`` (N, 3): fixed edges, or the range rule."""
    if spec.hears is not None:
        return spec.hears
    return adjacency_from_range(positions, spec.comm_range)


def weights_at(spec: TdoaSimSpec, positions: np.ndarray) -> np.ndarray:
    """The consensus matrix ``W`` for agents at ``positions`` (fixed, or by the spec's rule)."""
    if isinstance(spec.weights, np.ndarray):
        return spec.weights
    hears = hears_at(spec, positions)
    metropolis = spec.weights == WeightRule.METROPOLIS
    return metropolis_weights(hears) if metropolis else uniform_weights(hears)


def _move(
    spec: TdoaSimSpec,
    states: np.ndarray,
    estimates: np.ndarray,
    offsets: np.ndarray,
    moving: np.ndarray,
    since_ping: float,
    travelled: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Integrate the robots over one ``τ`` (tracking where ``moving``, braking elsewhere).

    ``spec`` gives the clock and actuators; ``offsets`` are the agents' formation offsets.
    """
    dt = spec.tau / spec.substeps
    tracked = estimates[moving, :3], estimates[moving, 3:], offsets[moving]
    for s in range(spec.substeps):
        control = _controller(spec, tracked, moving, since_ping + s * dt)
        new = rk4_step(states, control, dt)
        travelled = travelled + np.linalg.norm(new[:, :3] - states[:, :3], axis=1)
        states = new
    return states, travelled


def _controller(
    spec: TdoaSimSpec,
    tracked: tuple[np.ndarray, np.ndarray, np.ndarray],
    moving: np.ndarray,
    start: float,
) -> Callable[[float, np.ndarray], np.ndarray]:
    """``u(s, r)`` over one RK4 step from ``start`` (time since the ping).

    The moving agents (``tracked``: their estimated positions, velocities and formation
    offsets) follow ``ζ*`` of (B.14)–(B.18) with the law (B.11); the others brake.
    """
    position, velocity, offsets = tracked
    everyone = bool(moving.all())

    def control(offset: float, r: np.ndarray) -> np.ndarray:
        flat = np.zeros((position.shape[0], 3, 3))
        flat[:, 0] = position + (start + offset) * velocity + offsets
        flat[:, 1] = velocity
        if everyone:
            return linearizing_control(r, flat, spec.pole, max_input=spec.max_input)
        u = braking_control(r, spec.pole)
        if position.shape[0]:
            u[moving] = linearizing_control(r[moving], flat, spec.pole, max_input=spec.max_input)
        return u

    return control


class _Recorder:
    """Preallocated arrays filled along the run."""

    def __init__(self, n: int, K: int, m: int, centralized: bool) -> None:
        updates, rows = (1, n * (n - 1)) if centralized else (n, n - 1)
        self.innovations = np.zeros((K + 1, updates, rows))
        self.innovation_covariances = np.tile(np.eye(rows), (K + 1, updates, 1, 1))
        self.innovation_dims = np.zeros((K + 1, updates), dtype=int)
        self.estimates = np.empty((K + 1, n, 6))
        self.covariances = np.empty((K + 1, n, 6, 6))
        self.cov_norms = np.empty((K + 1, n))
        self.degrees = np.empty((K + 1, n), dtype=int)
        self.paths = np.empty((K * m + 1, n, 3))
        self.distance = np.empty((K * m + 1, n))
        self.moving = np.zeros((K * m, n), dtype=bool)
        self.m = m

    def ping(self, k: int, x: np.ndarray, P: np.ndarray, norms: np.ndarray, deg: list) -> None:
        self.estimates[k], self.covariances[k], self.cov_norms[k] = x, P, norms
        self.degrees[k] = deg

    def updates(self, k: int, updates: list[tuple[np.ndarray, np.ndarray]]) -> None:
        rows = self.innovations.shape[-1]
        for u, (nu, S) in enumerate(updates):
            self.innovations[k, u], self.innovation_covariances[k, u] = padded(nu, S, rows)
            self.innovation_dims[k, u] = nu.shape[0]

    def fine(
        self,
        index: int,
        states: np.ndarray,
        travelled: np.ndarray,
        moving: np.ndarray | None = None,
    ) -> None:
        self.paths[index], self.distance[index] = states[:, :3], travelled
        if moving is not None:
            self.moving[index - 1] = moving

    def result(self, spec: TdoaSimSpec, truth: np.ndarray) -> TdoaRun:
        K = truth.shape[0] - 1
        return TdoaRun(
            ping_times=spec.T * np.arange(K + 1),
            truth=truth,
            estimates=self.estimates,
            covariances=self.covariances,
            cov_norms=self.cov_norms,
            degrees=self.degrees,
            innovations=self.innovations,
            innovation_covariances=self.innovation_covariances,
            innovation_dims=self.innovation_dims,
            fine_times=spec.tau * np.arange(K * self.m + 1),
            paths=self.paths,
            distance=self.distance,
            moving=self.moving,
        )
