"""Online learning of the DCRW parameters from a node's own estimates (seed 002 §3.2.2).

From successive estimates ``χ_i(k)`` each node forms headings (eq. 3.17), wrapped turning angles
(eq. 3.18) and step lengths (eq. 3.19), refits ``(μ, γ, κ, λ)`` by maximum likelihood
(:func:`theory.particle.dcrw.fit_dcrw`) and propagates its particles with the fitted DCRW from then
on.
Before its first accepted fit a node propagates with the prior, a :class:`UniformMotion`
("the particle propagation model starts with a uniform distribution at k = 0").

Guards against degenerate early fits (the thesis fits from ``k > 3``, i.e. from one or two turning
angles, where the likelihood of (3.1) is maximised at ``γ → 1``):

- ``min_samples``: no fit until a node has this many turning angles (default 10);
- ``gamma_max``: ``γ`` is clamped to at most this (default 0.95), ``kappa_bounds``: ``κ`` is
  searched inside these bounds (default ``(0.5, 10)``), so one straight or one evenly-stepped
  stretch of estimates cannot freeze the particles onto a single line or step length;
- ``burn_in``: estimates of the first ``burn_in`` steps are not used (default 5): before the
  filter has converged its estimate jumps across the workspace and the "step lengths" it implies
  are not the target's.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from theory.particle.dcrw import fit_dcrw, sample_weibull, sample_wrapped_cauchy, wrap_angle
from theory.particle.motion import UniformMotion

__all__ = ["OnlineLearner", "movement_samples"]


def movement_samples(track: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Turning angles and step lengths implied by successive estimates (eqs. (3.17)–(3.19)).

    Parameters
    ----------
    track : ndarray, shape (K, 2)
        Estimates ``χ(1), …, χ(K)`` of one node.

    Returns
    -------
    (turns, steps) :
        ``φ̂(k) = wrap(θ̂(k) − θ̂(k−1))`` for ``k ≥ 3`` (``K − 2`` values) with
        ``θ̂(k) = atan2(Δy, Δx)``, and ``δ̂(k) = ‖χ(k) − χ(k−1)‖`` for ``k ≥ 2`` (``K − 1``
        values, zeros dropped since eq. (3.2) has support ``δ > 0``).

    References
    ----------
    seed 002, eqs. (3.17)–(3.19).
    """
    moves = np.diff(np.asarray(track, dtype=float), axis=0)
    headings = np.arctan2(moves[:, 1], moves[:, 0])
    steps = np.linalg.norm(moves, axis=1)
    return wrap_angle(np.diff(headings)), steps[steps > 0]


@dataclass(frozen=True, eq=False)
class OnlineLearner:
    """A propagation model that refits a DCRW per node after every estimate (seed 002 §3.2.2).

    Attributes
    ----------
    prior : UniformMotion
        Used by a node until its first accepted fit.
    min_samples : int
        Turning angles needed before a node fits (guard against ``γ → 1``).
    gamma_max : float
        Upper clamp on the fitted ``γ``.
    kappa_bounds : tuple of float
        Search interval for the fitted ``κ``.
    burn_in : int
        Initial estimates ignored.
    history : tuple of ndarray
        Estimates observed so far, each ``(F, 2)``.
    params : ndarray or None
        ``(F, 4)`` fitted ``(μ, γ, κ, λ)``; rows of unfitted nodes are ``nan``.
    """

    prior: UniformMotion
    min_samples: int = 10
    gamma_max: float = 0.95
    kappa_bounds: tuple[float, float] = (0.5, 10.0)
    burn_in: int = 5
    history: tuple[np.ndarray, ...] = ()
    params: np.ndarray | None = None

    @property
    def fitted(self) -> np.ndarray:
        """``(F,)`` bool: which nodes have switched to their learned DCRW."""
        return np.zeros(0, bool) if self.params is None else ~np.isnan(self.params[:, 0])

    def observe(self, estimates: np.ndarray) -> OnlineLearner:
        """Append ``χ(k)`` of every node and refit where there are enough samples.

        ``estimates`` has shape ``(F, 2)``, one row per node; returns the updated learner.
        """
        history = (*self.history, np.asarray(estimates, dtype=float))
        tracks = np.asarray(history[self.burn_in :])
        params = np.full((len(estimates), 4), np.nan)
        for f in range(len(estimates)) if tracks.shape[0] >= 3 else ():
            turns, steps = movement_samples(tracks[:, f])
            if turns.size >= self.min_samples and steps.size:
                fit = fit_dcrw(turns, steps, gamma_max=self.gamma_max)
                kappa = float(np.clip(fit.kappa, *self.kappa_bounds))
                params[f] = (fit.mu, fit.gamma, kappa, _scale_for(steps, kappa))
        return replace(self, history=history, params=params)

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
