"""Particle propagation models for the distributed PF (seed 002 step 6, eqs. (3.14)–(3.16)).

Every model draws a turning angle and a step length for each particle of each node, as arrays of
shape ``(nodes, particles)``, and has ``observe(estimates)`` returning the model to use at the next
step (fixed models return themselves; the online learner of :mod:`theory.particle.learning` refits).

- :class:`DcrwMotion`: the true DCRW (wrapped Cauchy turns, Weibull steps; eqs. (3.1)–(3.2)).
- :class:`GaussianMotion`: the thesis's mis-specified model (§3.3.2): turning angle normal
  ``N(0, (π/4)²)`` truncated to ``(−π, π]``, step normal ``N(2, 1)`` truncated to ``δ ≥ 0``.
- :class:`UniformMotion`: the learner's prior "uniform distribution at k = 0" (§3.3.2): turns
  uniform on ``(−π, π]``, steps uniform on ``[0, max_step]`` (``max_step`` is ours; the thesis
  does not give the range).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

from theory.particle.dcrw import DcrwParams, sample_weibull, sample_wrapped_cauchy

__all__ = ["DcrwMotion", "GaussianMotion", "UniformMotion"]


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
    """Truncated-normal turning angle and step (seed 002 §3.3.2, the Gaussian baseline).

    Attributes
    ----------
    turn_sigma : float
        Standard deviation of the turning angle (π/4), truncated to ``(−π, π]``.
    step_mean, step_sigma : float
        Mean (2) and standard deviation (1) of the step, truncated to ``δ ≥ 0``.
    """

    turn_sigma: float = np.pi / 4
    step_mean: float = 2.0
    step_sigma: float = 1.0

    def sample(self, rng: np.random.Generator, shape: tuple[int, int]) -> tuple:
        """Turning angles on ``(−π, π]`` and steps ``≥ 0``, each of ``shape``, drawn from
        ``rng``."""
        bound = np.pi / self.turn_sigma
        turn = stats.truncnorm.rvs(
            -bound, bound, scale=self.turn_sigma, size=shape, random_state=rng
        )
        low = -self.step_mean / self.step_sigma
        step = stats.truncnorm.rvs(
            low, np.inf, loc=self.step_mean, scale=self.step_sigma, size=shape, random_state=rng
        )
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
