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
from scipy import special
from scipy.stats._continuous_distns import _log_gauss_mass

from theory.particle.dcrw import DcrwParams, sample_weibull, sample_wrapped_cauchy

__all__ = ["DcrwMotion", "GaussianMotion", "UniformMotion", "truncated_normal"]


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

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness (one ``uniform`` draw of ``shape``).
    a, b : float
        Standardised truncation bounds, ``a < 0 < b`` (``b`` may be ``inf``).
    loc, scale : float
        Mean and standard deviation of the untruncated normal.
    shape : tuple of int
        Output shape.
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
