"""The constant-velocity target driven by white acceleration (seed 000 eqs. (4.1), (4.5)).

The discrete model is ``x(k+1) = A x(k) + B w(k)`` with ``w(k) ~ N(0, Q)`` and ``A``, ``B`` of
eq. (4.6) (:func:`theory.tdoa.model.cv_discrete`); sampling it at the ping instants is exact for the
model as the dissertation writes it.
"""

from __future__ import annotations

import numpy as np

from theory.tdoa.model import cv_discrete

__all__ = ["simulate_cv_target"]


def simulate_cv_target(
    x0: np.ndarray, Q: np.ndarray, T: float, steps: int, rng: np.random.Generator
) -> np.ndarray:
    """Sample a target trajectory at the ping instants ``0, T, …, steps·T``.

    Parameters
    ----------
    x0 : ndarray, shape (2d,)
        Initial state ``[p; ṗ]``.
    Q : ndarray, shape (d, d)
        Covariance of the white acceleration ``w(k)``.
    T : float
        Ping period.
    steps : int
        Number of transitions.
    rng : numpy.random.Generator
        Source of the process noise.

    Returns
    -------
    ndarray, shape (steps + 1, 2d)
        States ``x(0), …, x(steps)``.

    References
    ----------
    seed 000, eqs. (4.1), (4.5)–(4.6).
    """
    dim = Q.shape[0]
    A, B = cv_discrete(T, dim)
    noise = rng.multivariate_normal(np.zeros(dim), Q, size=steps, method="cholesky")
    states = np.empty((steps + 1, 2 * dim))
    states[0] = x0
    for k in range(steps):
        states[k + 1] = A @ states[k] + B @ noise[k]
    return states
