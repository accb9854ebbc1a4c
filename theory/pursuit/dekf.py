"""Seed 003: range-only target model, range measurements and the information-form DEKF.

* Target model (7)–(8): ``x_{k+1} = F x_k + w_k`` with ``F = [I, T_s I; 0, I]`` (2-D or 3-D).
* Range measurement (9)–(10): ``y_k^[i] = ‖p_k^[i] − q_k‖ + η_k^[i]``.
* Algorithm 2 (Algorithm 1 is its ``N = 1`` case, Remark 7): correction in information form
  (41), one fusion round with weights ``π^[i,j]`` (43), prediction (44)
  ``Ω_{k+1|k} = W − WF(Ω_{k|k} + FᵀWF)⁻¹FᵀW``, ``x̂_{k+1|k} = F x̂_{k|k}``.
* Tables I–II: the targets' trajectories and the S-T curves (15)–(16) the trackers follow
  once tracking and coordination (38)–(39) have converged.

:func:`dekf_step` is the one implementation of the filter, vectorized over trackers: the closed
loop (:mod:`theory.pursuit.closed_loop`) calls it at every sampling instant, and
:func:`range_dekf` runs it on given trajectories, e.g. :func:`encircling_paths`, which places the
trackers on their desired S-T curves around the *true* target (the steady state the controllers
(45)–(52) are designed to reach).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.pursuit.model import path

__all__ = [
    "RangeDekfRun",
    "dekf_step",
    "encircling_paths",
    "predict",
    "range_dekf",
    "st_curve",
    "table_target",
    "transition_matrix",
]


def table_target(table: str, times: np.ndarray) -> np.ndarray:
    """Target states ``[q; v]`` of seed 003 Table I (2-D) or Table II (3-D) at ``times`` (s).

    Table I: ``q = [20 sin(0.01t + π), 0.3t]``; Table II: ``q = [30 sin(0.01t + π), 0.1t, −0.5t]``.
    """
    t = np.asarray(times, dtype=float)
    s, c = np.sin(0.01 * t + np.pi), np.cos(0.01 * t + np.pi)
    if table == "I":
        q = np.column_stack([20 * s, 0.3 * t])
        v = np.column_stack([0.2 * c, np.full_like(t, 0.3)])
    elif table == "II":
        q = np.column_stack([30 * s, 0.1 * t, -0.5 * t])
        v = np.column_stack([0.3 * c, np.full_like(t, 0.1), np.full_like(t, -0.5)])
    else:
        raise ValueError(f"table must be 'I' or 'II', got {table!r}")
    return np.hstack([q, v])


def st_curve(
    gamma: np.ndarray, radii: tuple[float, ...], gamma0: float, c: float = 1.0
) -> np.ndarray:
    """Spatial path ``r(γ)`` of seed 003 (15) (3-D, ``radii = (r_x, r_y, r_z)``) or (16) (2-D)."""
    r_z = radii[2] if len(radii) == 3 else None
    return path(gamma, radii[0], radii[1], gamma0, r_z, c if r_z is not None else None)


def encircling_paths(
    target: np.ndarray, times: np.ndarray, n: int, radii: tuple[float, ...], omega: float
) -> np.ndarray:
    """Positions (K+1, n, d) of ``n`` trackers on their S-T curves ``q(t) + r(ω̄t + γ0^[i])``,
    ``γ0^[i] = 2π(i−1)/N``, around the true ``target`` states."""
    d = len(radii)
    return np.stack(
        [
            target[:, :d] + st_curve(omega * times, radii, 2 * np.pi * i / n if n > 1 else 0.0)
            for i in range(n)
        ],
        axis=1,
    )


@dataclass(frozen=True, eq=False)
class RangeDekfRun:
    """Filtered estimates x̂_{k|k}^[i] (K+1, N, 2d) and information matrices Ω_{k|k}^[i] of every
    tracker at every step, and the range innovations ``y − ‖q̂_{k|k−1} − p‖`` (K+1, N, 1) with
    their variances ``C Ω_{k|k−1}⁻¹ Cᵀ + 1/V`` (K+1, N, 1, 1) (seed 003 Algorithm 2, (41))."""

    estimates: np.ndarray
    information: np.ndarray
    innovations: np.ndarray
    innovation_covariances: np.ndarray

    def errors(self, target: np.ndarray) -> np.ndarray:
        """Position errors ``‖q̂^[i] − q‖``, shape (K+1, N), against the true ``target`` states
        (shape (K+1, 2d))."""
        d = target.shape[1] // 2
        return np.linalg.norm(self.estimates[:, :, :d] - target[:, None, :d], axis=-1)


def range_dekf(
    trackers: np.ndarray,
    target: np.ndarray,
    *,
    Ts: float,
    noise_var: float,
    V: float,
    Q: np.ndarray,
    fusion: np.ndarray,
    x0: np.ndarray,
    P0: np.ndarray,
    rng: np.random.Generator,
    predictions: int = 1,
) -> RangeDekfRun:
    """Algorithm 2 of seed 003 on given tracker and target trajectories (eqs. (7)–(10), (41)–(44)).

    Ranges every ``Ts`` with noise of variance ``noise_var``; the filter's ``V``, process
    covariance ``Q`` (W = Q⁻¹), fusion weights π^[i,j], and every tracker's x̂_{1|0}, P_{1|0};
    ``predictions`` predictions (44) per ``Ts`` with F(Ts/predictions), ``Q`` per
    Ts/predictions, as :func:`dekf_step` (the closed loop's ``predict_every``).
    """
    steps, n, d = trackers.shape
    F = transition_matrix(d, Ts / predictions)
    W = np.linalg.inv(Q)
    Omega = np.tile(np.linalg.inv(P0), (n, 1, 1))
    x = np.tile(x0, (n, 1))
    estimates = np.empty((steps, n, 2 * d))
    information = np.empty((steps, n, 2 * d, 2 * d))
    innovations = np.empty((steps, n, 1))
    variances = np.empty((steps, n, 1, 1))
    for k in range(steps):
        ranges = np.linalg.norm(trackers[k] - target[k, :d], axis=1)
        y = ranges + np.sqrt(noise_var) * rng.standard_normal(n)
        innovations[k], variances[k] = _range_innovations(x, Omega, trackers[k], y, V)
        estimates[k], information[k], Omega, x = dekf_step(
            x, Omega, trackers[k], y, fusion=fusion, F=F, W=W, V=V, predictions=predictions
        )
    return RangeDekfRun(estimates, information, innovations, variances)


def _range_innovations(
    x_pred: np.ndarray, Omega: np.ndarray, positions: np.ndarray, ranges: np.ndarray, V: float
) -> tuple[np.ndarray, np.ndarray]:
    """``ν = y − ‖q̂ − p‖`` and ``S = C Ω⁻¹ Cᵀ + 1/V`` of every tracker's correction (seed 003
    eqs. (10), (41): the range variance the filter assumes is ``1/V``)."""
    d = positions.shape[1]
    diff = x_pred[:, :d] - positions
    predicted = np.linalg.norm(diff, axis=1)
    C = np.concatenate([diff / predicted[:, None], np.zeros_like(diff)], axis=1)
    spread = np.einsum("ni,ni->n", C, np.linalg.solve(Omega, C[..., None])[..., 0])
    return (ranges - predicted)[:, None], (spread + 1 / V)[:, None, None]


def transition_matrix(dim: int, Ts: float) -> np.ndarray:
    """F = [I, T_s I; 0, I] of seed 003 eq. (8) (Remark 3 in 2-D)."""
    eye = np.eye(dim)
    return np.block([[eye, Ts * eye], [np.zeros((dim, dim)), eye]])


def dekf_step(
    x_pred: np.ndarray,
    Omega: np.ndarray,
    positions: np.ndarray,
    ranges: np.ndarray,
    *,
    fusion: np.ndarray,
    F: np.ndarray,
    W: np.ndarray,
    V: float,
    predictions: int = 1,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """One sampling instant of Algorithm 2 for every tracker: correction, fusion, prediction.

    Correction (41) with C_k = ∂d/∂x at x̂_{k|k−1} = [(q̂ − p)ᵀ/‖q̂ − p‖, 0] and the linearized
    range ỹ = y − d(x̂) + Cx̂; one fusion round (43) z_{k|k} = Σ_j π^[i,j] z̃^[j],
    Ω_{k|k} = Σ_j π^[i,j] Ω̃^[j]; prediction (44) Ω_{k+1|k} = W − WF(Ω_{k|k} + FᵀWF)⁻¹FᵀW,
    x̂_{k+1|k} = F x̂_{k|k} (seed 003 Algorithm 2). Returns x̂_{k|k}, Ω_{k|k}, Ω_{k+1|k}, x̂_{k+1|k}
    from the priors x̂_{k|k−1}, Ω_{k|k−1}, the positions and the measured ranges y_k (10).
    The prediction (44) is applied ``predictions`` times with the given F and W: 1 for the
    paper's F(T_s), or T_s/δ with F(δ) and W per δ as the authors' scripts predict every δ
    between ranges (docs/errata.md, "What makes the Table cases run away").
    """
    d = positions.shape[1]
    diff = x_pred[:, :d] - positions
    predicted = np.linalg.norm(diff, axis=1)
    C = np.concatenate([diff / predicted[:, None], np.zeros_like(diff)], axis=1)
    linearized = ranges - predicted + np.sum(C * x_pred, axis=1)
    z_tilde = np.matmul(Omega, x_pred[..., None])[..., 0] + C * (V * linearized)[:, None]
    Omega_tilde = Omega + V * (C[:, :, None] * C[:, None, :])
    Omega_post = np.einsum("ij,jkl->ikl", fusion, Omega_tilde)
    x_hat = np.linalg.solve(Omega_post, (fusion @ z_tilde)[..., None])[..., 0]
    Omega_next, x_next = predict(Omega_post, x_hat, F=F, W=W, steps=predictions)
    return x_hat, Omega_post, Omega_next, x_next


def predict(
    Omega: np.ndarray, x_hat: np.ndarray, *, F: np.ndarray, W: np.ndarray, steps: int = 1
) -> tuple[np.ndarray, np.ndarray]:
    """``steps`` predictions (44) Ω ← W − WF(Ω + FᵀWF)⁻¹FᵀW, x̂ ← F x̂ (seed 003 Algorithm 2)."""
    lifted = F.T @ W @ F
    for _ in range(steps):
        Omega = W - W @ F @ np.linalg.inv(Omega + lifted) @ F.T @ W
        x_hat = x_hat @ F.T
    return Omega, x_hat
