"""The consensus Kalman filter of seed 000 ch. 5, both orders, simulated on plain arrays.

``order="consensus-then-filter"`` (eqs. (5.3)–(5.4), (5.7)–(5.9)):
``ξ_i = Σ_j w_ij x̂_j``, ``Π_i = Σ_j w_ij P_j``, ``L_i = AΠ_iC_i'(R_i + C_iΠ_iC_i')⁻¹``,
``x̂_i ← Aξ_i + L_i(y_i − C_iξ_i)``, ``P_i ← AΠ_iA' + Q − AΠ_iC_i'(C_iΠ_iC_i' + R_i)⁻¹C_iΠ_iA'``.

``order="filter-then-consensus"`` (App. C.3, the filter of its ref. [29]): every agent applies
the local step with its own ``x̂_j``, ``P_j``, then averages:
``x̂_i ← Σ_j w_ij [Ax̂_j + L_j(y_j − C_jx̂_j)]``,
``P_i ← Σ_j w_ij [AP_jA' + Q − AP_jC_j'(C_jP_jC_j' + R_j)⁻¹C_jP_jA']``.

The estimation errors ``ε_i = x − x̂_i`` are propagated directly, by (5.5) and its
filter-then-consensus twin ``ε_i ← Σ_j w_ij [(A − L_jC_j)ε_j + ω − L_jv_j]`` (C.4 with noise):
for an unstable ``A`` the state itself overflows the floating-point range long before the
errors do, and ``x − x̂`` computed from two huge numbers would be meaningless.

The covariances and gains come from the one coupled Riccati step of
:mod:`theory.consensus.riccati`; the order names are :data:`theory.consensus.case.ORDERS`. The
case kind ``dkf`` belongs to another module; this one takes the matrices directly.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.consensus.case import ORDERS
from theory.consensus.operators import B2_matrix, B_matrix, closed_loop
from theory.consensus.riccati import coupled_riccati_step, error_noise_covariance

__all__ = [
    "ORDERS",
    "ConsensusKfRun",
    "ch5_examples",
    "simulate_consensus_kf",
    "true_error_covariance",
]


@dataclass(frozen=True, eq=False)
class ConsensusKfRun:
    """Arrays of one run (time index ``k = 0 … K``).

    Attributes
    ----------
    errors : ndarray, shape (K+1, N, n)
        ``ε_i(k) = x(k) − x̂_i(k)``.
    covariances : ndarray, shape (K+1, N, n, n)
    """

    errors: np.ndarray
    covariances: np.ndarray

    @property
    def cov_norms(self) -> np.ndarray:
        """Spectral norms ``‖P_i(k)‖``, shape (K+1, N)."""
        return np.linalg.norm(self.covariances, 2, axis=(2, 3))


def _check_order(order: str) -> None:
    if order not in ORDERS:
        raise ValueError(f"order must be one of {ORDERS}, got {order!r}")


def simulate_consensus_kf(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    *,
    x0: np.ndarray,
    estimate0: np.ndarray,
    P0: np.ndarray,
    steps: int,
    rng: np.random.Generator,
    order: str = "consensus-then-filter",
) -> ConsensusKfRun:
    """Simulate the consensus Kalman filter's errors for ``x(k+1) = Ax + ω``, ``y_i = C_ix + v_i``.

    Parameters
    ----------
    A : ndarray, shape (n, n)
    C : sequence of ndarray
        ``C_i``, shape (p_i, n).
    W : ndarray, shape (N, N)
        Row-stochastic consensus weights.
    Q : ndarray, shape (n, n)
    R : sequence of ndarray
        ``R_i``, shape (p_i, p_i).
    x0 : ndarray, shape (n,)
        Initial state.
    estimate0 : ndarray, shape (n,)
        Every agent's initial estimate (only ``x0 − estimate0`` matters).
    P0 : ndarray, shape (n, n)
        Every agent's initial ``P_i(0)``.
    steps : int
        Number of steps ``K``.
    rng : numpy.random.Generator
        Source of ``ω`` and ``v_i``.
    order : {"consensus-then-filter", "filter-then-consensus"}
        Which filter (see the module docstring).

    Returns
    -------
    ConsensusKfRun

    Raises
    ------
    ValueError
        For an unknown ``order``.

    References
    ----------
    seed 000, eqs. (5.1)–(5.9), App. C.3.
    """
    _check_order(order)
    n, agents = A.shape[0], W.shape[0]
    errors = np.empty((steps + 1, agents, n))
    covariances = np.empty((steps + 1, agents, n, n))
    errors[0], covariances[0] = np.asarray(x0) - np.asarray(estimate0), P0
    for k in range(steps):
        omega = rng.multivariate_normal(np.zeros(n), Q)
        gains, covariances[k + 1] = coupled_riccati_step(A, C, W, Q, R, covariances[k], order=order)
        es = W @ errors[k] if order == "consensus-then-filter" else errors[k]
        es = np.array(
            [
                (A - L @ Ci) @ e + omega - L @ _measurement_noise(rng, Ri)
                for e, L, Ci, Ri in zip(es, gains, C, R, strict=True)
            ]
        )
        errors[k + 1] = W @ es if order == "filter-then-consensus" else es
    return ConsensusKfRun(errors, covariances)


def _measurement_noise(rng: np.random.Generator, R_i: np.ndarray) -> np.ndarray:
    """``v_i ~ N(0, R_i)`` (empty for an agent without sensor)."""
    return rng.multivariate_normal(np.zeros(R_i.shape[0]), R_i) if R_i.shape[0] else np.zeros(0)


def true_error_covariance(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    P0: np.ndarray,
    steps: int,
    *,
    order: str = "consensus-then-filter",
) -> tuple[np.ndarray, np.ndarray]:
    """The exact network error covariance under the filter's own gains, beside its ``P_i``.

    With the gains ``L_i(k)`` of (5.8) computed from the coupled Riccati recursion, the network
    error ``ε = col(ε_i)`` obeys ``ε⁺ = Bε + 1⊗ω − blkdiag(L_i)v`` with
    ``B = diag(A − L_iC_i)(W⊗I)`` (consensus-then-filter, (5.11)) or ``(W⊗I)diag(A − L_iC_i)``
    (filter-then-consensus, (C.5)), so ``Σ⁺ = BΣBᵀ + (11ᵀ⊗Q) + blkdiag(L_iR_iL_iᵀ)``
    (filter-then-consensus:
    the noise term is premultiplied by ``W⊗I`` and postmultiplied by its transpose).
    The initial errors are independent with covariance ``P0`` each.

    Parameters
    ----------
    A, C, W, Q, R : ndarray or sequences
        As in :func:`simulate_consensus_kf`.
    P0 : ndarray, shape (n, n)
    steps : int
    order : {"consensus-then-filter", "filter-then-consensus"}

    Returns
    -------
    traces : ndarray, shape (K+1,)
        ``tr Σ(k)`` (sum over agents of their mean squared errors).
    p_norms : ndarray, shape (K+1, N)
        ``‖P_i(k)‖`` of the Riccati recursion.

    Raises
    ------
    ValueError
        For an unknown ``order``.

    References
    ----------
    seed 000, eqs. (5.5)–(5.11), App. C.3.
    """
    _check_order(order)
    n, agents = A.shape[0], W.shape[0]
    mix = np.kron(W, np.eye(n))
    P = np.tile(P0, (agents, 1, 1))
    Sigma = np.kron(np.eye(agents), P0)
    traces, p_norms = [np.trace(Sigma)], [np.linalg.norm(P, 2, axis=(1, 2))]
    for _ in range(steps):
        gains, P = coupled_riccati_step(A, C, W, Q, R, P, order=order)
        Gamma = closed_loop(A, C, gains)
        noise = error_noise_covariance(Q, R, gains)
        if order == "consensus-then-filter":
            B = B_matrix(W, Gamma)
        else:
            B, noise = B2_matrix(W, Gamma), mix @ noise @ mix.T
        Sigma = B @ Sigma @ B.T + noise
        traces.append(np.trace(Sigma))
        p_norms.append(np.linalg.norm(P, 2, axis=(1, 2)))
    return np.array(traces), np.array(p_norms)


def ch5_examples() -> dict[str, dict[str, Any]]:
    """Seed 000 §5.3 Examples 1–2: matrices, initial data, every W of the text, and the agents
    whose pair ``(A, C_i)`` is not detectable (``unstable_agents``, 0-based)."""
    return {
        "example 1": {
            "A": 2.0 * np.eye(2),
            "C": [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)],
            "R": [0.1 * np.eye(1), 0.1 * np.eye(1), 0.1 * np.eye(2)],
            "Q": 0.1 * np.eye(2),
            "x0": np.array([-15.0, 15.0]),
            "P0": 10.0 * np.eye(2),
            "W_g": [[0.24, 0.76, 0], [0.76, 0.24, 0], [0, 0, 1]],
            "W_c": [[0.25, 0.75, 0], [0.75, 0.25, 0], [0, 0, 1]],
            "W_b": [[0.26, 0.74, 0], [0.74, 0.26, 0], [0, 0, 1]],
            "unstable_agents": [0, 1],
        },
        "example 2": {
            "A": np.array([[0.8147, 0.8147, 0.2785], [0.9058, 0.9058, 0.5469], [0, 0, 0.9575]]),
            "C": [np.eye(3)[[i]] for i in range(3)],
            "R": [np.eye(1)] * 3,
            "Q": np.eye(3),
            "x0": np.array([-2.2691, -2.0143, 1.6173]),
            "P0": 100.0 * np.eye(3),
            "W_g": [[1, 0, 0], [0, 1, 0], [0.34, 0.34, 0.32]],
            "W_b": [[1, 0, 0], [0, 1, 0], [0.33, 0.33, 0.34]],
            "unstable_agents": [2],
        },
    }
