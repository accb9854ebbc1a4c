"""Seed 000 App. A, Lemma A.1.2 along simulated runs: the constants and inequality (A.24).

Along a run of the averaged EKF with one averaging per ping (``τ = T``, the filter (A.1)–(A.3)),
this module rebuilds the predicted covariances ``P_k = blkdiag(P_k^i)``, the Jacobians ``H_k``
and gains ``K_k`` (A.17) at every ping and reports

* the constants of (A.18)–(A.23): ``ā = ‖A‖``, ``δ = λ_max(BBᵀ)``, ``h̄ = max_k ‖H_k‖``,
  ``p̲``, ``p̄`` (extreme eigenvalues of every ``P_k``), ``σ_w² = λ_min(Q)``, ``σ_v² = r``;
* ``1 − α`` of (A.35) from those constants;
* at every ``k`` the smallest ``c_k`` with
  ``(I − K_kH_k)ᵀ(W⊗A)ᵀP_{k+1}⁻¹(W⊗A)(I − K_kH_k) ≤ c_k P_k⁻¹`` (a generalized eigenvalue), so
  (A.24) holds at ``k`` iff ``c_k ≤ 1 − α``.

The proof's step after (A.32) needs ``I_N ⊗ BQBᵀ ≥ δσ_w² I_{2dN}``; ``BQBᵀ`` has rank ``d`` of
``2d``, so no positive constant can satisfy it, and (A.19) bounds ``BBᵀ`` from *above*, not
below. :func:`lemma_a12_along` reports this (``bqb_lower_bound``) instead of using it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.linalg import block_diag, eigh

from theory.core.tolerances import RANK_TOL
from theory.tdoa.ekf import kalman_gain
from theory.tdoa.measurements import neighbour_lists, tdoa_jacobians
from theory.tdoa.model import cv_discrete
from theory.tdoa.scenario import TdoaRun, hears_at, weights_at
from theory.tdoa.sim_case import TdoaSimSpec

__all__ = ["lemma_a12_along"]


def lemma_a12_along(spec: TdoaSimSpec, run: TdoaRun) -> dict[str, Any]:
    """Constants of Lemma A.1.2, ``1 − α`` of (A.35) and the per-step factor of (A.24).

    Parameters
    ----------
    spec : TdoaSimSpec
        Scenario with ``filter: averaged`` and ``tau = T`` (one averaging per ping).
    run : TdoaRun
        A run of ``spec``.

    Returns
    -------
    dict
        ``constants`` (``a_bar, delta, h_bar, p_low, p_high, sigma_w2, sigma_v2``),
        ``one_minus_alpha`` (A.35), ``factors`` (``c_k`` for ``k = 0 … K−1``), ``holds`` (per
        step), ``bqb_rank`` and ``bqb_lower_bound`` (the largest ``c`` with ``BQBᵀ ≥ cI``: 0).

    Raises
    ------
    ValueError
        If the filter is not the averaged EKF or ``τ ≠ T``.

    References
    ----------
    seed 000, App. A, eqs. (A.1)–(A.3), (A.17)–(A.24), (A.35).
    """
    if spec.filter != "averaged" or spec.rounds != 1:
        raise ValueError("App. A analyses the averaged EKF with one averaging per ping (tau = T)")
    A, B = cv_discrete(spec.T, 3)
    predicted_x, predicted_P = _predictions(spec, run, A, B @ spec.Q @ B.T)
    factors, h_norms = _step_factors(spec, run, A, predicted_x, predicted_P)
    eig = np.linalg.eigvalsh(predicted_P[: len(factors) + 1])
    constants = {
        "a_bar": float(np.linalg.norm(A, 2)),
        "delta": float(np.linalg.eigvalsh(B @ B.T)[-1]),
        "h_bar": max(h_norms),
        "p_low": float(eig.min()),
        "p_high": float(eig.max()),
        "sigma_w2": float(np.linalg.eigvalsh(spec.Q)[0]),
        "sigma_v2": spec.r,
    }
    c = constants
    gain_bound = c["p_high"] * c["h_bar"] / c["sigma_v2"]
    one_minus_alpha = 1.0 / (
        1.0 + c["delta"] * c["sigma_w2"] / (c["p_high"] * (1 + gain_bound) ** 2)
    )
    bqb_eig = np.linalg.eigvalsh(B @ spec.Q @ B.T)
    return {
        "constants": constants,
        "one_minus_alpha": one_minus_alpha,
        "factors": np.array(factors),
        "holds": np.array(factors) <= one_minus_alpha,
        "bqb_rank": int(np.sum(bqb_eig > RANK_TOL * bqb_eig[-1])),
        "bqb_lower_bound": float(max(bqb_eig[0], 0.0)),
    }


def _predictions(
    spec: TdoaSimSpec, run: TdoaRun, A: np.ndarray, BQB: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Predicted estimates ``x̂_k^i`` and covariances ``P_k^i`` (A.1)–(A.2) at every ping, rebuilt
    from the recorded averaged ones (and ``x_0``, ``P_0`` at ping 0)."""
    n = spec.n_agents
    predicted_x = np.vstack([np.tile(spec.x0, (1, n, 1)), run.estimates[:-1] @ A.T])
    predicted_P = np.concatenate(
        [np.tile(spec.P0, (1, n, 1, 1)), np.einsum("ij,knjl,ml->knim", A, run.covariances, A)[:-1]]
    )
    predicted_P[1:] += BQB
    return predicted_x, predicted_P


def _step_factors(
    spec: TdoaSimSpec,
    run: TdoaRun,
    A: np.ndarray,
    predicted_x: np.ndarray,
    predicted_P: np.ndarray,
) -> tuple[list[float], list[float]]:
    """Per ping ``k``: the smallest ``c_k`` of (A.24) (a generalized eigenvalue) and ``‖H_k‖``."""
    n = spec.n_agents
    factors, h_norms = [], []
    for k in range(run.truth.shape[0] - 1):
        positions = run.paths[k * spec.rounds]
        W = weights_at(spec, positions)
        neighbours = neighbour_lists(hears_at(spec, positions))
        H = tdoa_jacobians(predicted_x[k, :, :3], positions, neighbours)
        gains_H = [
            kalman_gain(predicted_P[k, i], H[i], spec.r * np.eye(H[i].shape[0])) @ H[i]
            for i in range(n)
        ]
        I_KH = np.eye(6 * n) - block_diag(*gains_H)
        WA = np.kron(W, A)
        P_next_inv = np.linalg.inv(block_diag(*predicted_P[k + 1]))
        lhs = I_KH.T @ WA.T @ P_next_inv @ WA @ I_KH
        lhs = 0.5 * (lhs + lhs.T)
        P_inv = np.linalg.inv(block_diag(*predicted_P[k]))
        factors.append(float(eigh(lhs, 0.5 * (P_inv + P_inv.T), eigvals_only=True)[-1]))
        h_norms.append(float(np.linalg.norm(block_diag(*H), 2)) if any(h.size for h in H) else 0.0)
    return factors, h_norms
