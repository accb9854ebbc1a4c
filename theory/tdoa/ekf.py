"""Extended Kalman filter steps (seed 000 eqs. (4.11)–(4.15), (4.26)–(4.27), (4.32)–(4.34)).

The update uses the Joseph form (4.15)/(4.34), which keeps ``P`` symmetric positive definite in
floating point; the gain is (4.13)/(4.32).
"""

from __future__ import annotations

import numpy as np

__all__ = ["ekf_predict", "ekf_update", "kalman_gain"]


def kalman_gain(P: np.ndarray, H: np.ndarray, R: np.ndarray) -> np.ndarray:
    """The gain ``K = P H'(H P H' + R)⁻¹`` of eqs. (4.13), (4.32), (A.17).

    Parameters
    ----------
    P : ndarray, shape (n, n)
        Predicted covariance ``P(k|k−1)``.
    H : ndarray, shape (m, n)
        Jacobian (``m = 0`` allowed: the gain is ``n × 0``).
    R : ndarray, shape (m, m)
        Measurement noise covariance.

    Returns
    -------
    ndarray, shape (n, m)

    References
    ----------
    seed 000, eqs. (4.13), (4.32), (A.17).
    """
    if H.shape[0] == 0:
        return np.zeros((P.shape[0], 0))
    return np.linalg.solve(H @ P @ H.T + R, H @ P).T


def ekf_update(
    x: np.ndarray, P: np.ndarray, innovation: np.ndarray, H: np.ndarray, R: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Measurement update with gain ``K = P H'(H P H' + R)⁻¹`` and the Joseph covariance.

    Parameters
    ----------
    x : ndarray, shape (n,)
        Predicted estimate ``x̂(k|k−1)``.
    P : ndarray, shape (n, n)
        Predicted covariance ``P(k|k−1)``.
    innovation : ndarray, shape (m,)
        ``y − h(x̂(k|k−1))``.
    H : ndarray, shape (m, n)
        Jacobian at ``x̂(k|k−1)``.
    R : ndarray, shape (m, m)
        Measurement noise covariance.

    Returns
    -------
    x_new, P_new : ndarray
        ``x̂(k|k)`` and ``P(k|k)``; unchanged when ``m = 0``.

    References
    ----------
    seed 000, eqs. (4.12)–(4.15), (4.27), (4.32), (4.34).
    """
    if H.shape[0] == 0:
        return x, P
    K = kalman_gain(P, H, R)
    I_KH = np.eye(P.shape[0]) - K @ H
    P_new = I_KH @ P @ I_KH.T + K @ R @ K.T
    return x + K @ innovation, 0.5 * (P_new + P_new.T)


def ekf_predict(
    x: np.ndarray, P: np.ndarray, A: np.ndarray, BQB: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Time update ``x̂ ← A x̂``, ``P ← A P A' + BQB'`` for a stack of agents (eqs. (4.26), (4.33)).

    Parameters
    ----------
    x : ndarray, shape (N, n)
        Estimates (one row per agent).
    P : ndarray, shape (N, n, n)
        Covariances.
    A : ndarray, shape (n, n)
        State transition.
    BQB : ndarray, shape (n, n)
        Process noise covariance ``B Q B'``.

    Returns
    -------
    x_pred, P_pred : ndarray
    """
    return x @ A.T, np.einsum("ij,njk,lk->nil", A, P, A) + BQB
