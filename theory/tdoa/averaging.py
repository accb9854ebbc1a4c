"""Average-based consensus on estimates and covariances (seed 000 eqs. (4.28), (4.35), §4.3).

Between two pings the agents average ``x̂_i`` and ``P_i`` with their neighbours every ``τ``
seconds (§4.3): each round is ``x̄_i = Σ_j w_ij x̂_j`` and ``P̄_i = Σ_j w_ij P_j``. The first round
after a ping is exactly (4.28)/(4.35).
"""

from __future__ import annotations

import numpy as np

__all__ = ["average_round"]


def average_round(W: np.ndarray, x: np.ndarray, P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One consensus round ``x̄ = W x`` and ``P̄_i = Σ_j w_ij P_j``.

    Parameters
    ----------
    W : ndarray, shape (N, N)
        Row-stochastic weights.
    x : ndarray, shape (N, n)
        Estimates.
    P : ndarray, shape (N, n, n)
        Covariances.

    Returns
    -------
    x_bar, P_bar : ndarray

    References
    ----------
    seed 000, eqs. (4.28), (4.35).
    """
    return W @ x, np.einsum("ij,jkl->ikl", W, P)
