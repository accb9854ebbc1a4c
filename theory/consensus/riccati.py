"""Coupled Riccati iterations of the distributed Kalman filter and Lemma 5.2.3's covariance bound.

* ``consensus-then-filter`` (seed 000 eqs. (5.7)–(5.9)): ``Π_i = E_i(P)``,
  ``L_i = A Π_i C_i' (R_i + C_i Π_i C_i')⁻¹``, ``P_i⁺ = Ric_i(Π_i)``;
* ``filter-then-consensus`` (App. C.3, the filter of [29]): ``L_i = A P_i C_i' (R_i + C_i P_i
  C_i')⁻¹`` and ``P_i⁺ = E_i(Ric(P))``,

with ``Ric_i(Π) = A Π A' + Q − A Π C_i' (C_i Π C_i' + R_i)⁻¹ C_i Π A'``. Convergence is declared
when ``max_i ‖P_i(k+1) − P_i(k)‖ ≤ conv_tol · max_i ‖P_i(k)‖``; divergence when the norm exceeds
``blowup`` times its initial value. A limit is *stabilizing* (footnote 5) when its gains give
``r_σ < 1`` for the order's operator (L or J).

Lemma 5.2.3 (second part): with fixed gains, the true error covariances ``Σ_i(k)`` of (5.5) satisfy
``Σ(k) ≤ P(k)`` where ``P_i(k+1) = L_i(P(k)) + Q + L_i R_i L_i'``. We compute ``Σ(k)`` exactly from
the joint covariance of ``[ε_1; …; ε_N]`` (the process noise ω is common to all agents) and
estimate it by Monte Carlo on (5.5).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from theory.consensus.case import Order
from theory.consensus.operators import (
    B_matrix,
    E_map,
    J_map,
    L_map,
    apply_operator,
    closed_loop,
    covariance_operator_matrix,
    gains_stabilize,
    spectral_radius,
)
from theory.core.tolerances import BLOWUP, CONV_TOL, MAX_ITER, PSD_TOL

__all__ = [
    "AveragedBoundCheck",
    "CovarianceBoundCheck",
    "RiccatiRun",
    "bound_iteration",
    "check_averaged_bound",
    "check_covariance_bound",
    "coupled_riccati",
    "coupled_riccati_step",
    "error_noise_covariance",
    "riccati_gains",
]


def _gain(A: np.ndarray, Ci: np.ndarray, Ri: np.ndarray, Pi: np.ndarray) -> np.ndarray:
    """``A Π C_i' (R_i + C_i Π C_i')⁻¹``, ``n × 0`` for an agent without sensor."""
    return np.linalg.solve(Ci @ Pi @ Ci.T + Ri, Ci @ Pi @ A.T).T


def riccati_gains(
    A: np.ndarray, C: Sequence[np.ndarray], R: Sequence[np.ndarray], Pi: np.ndarray
) -> tuple[np.ndarray, ...]:
    """``L_i = A Π_i C_i' (R_i + C_i Π_i C_i')⁻¹`` (seed 000 eq. (5.8)); ``n × 0`` if no sensor."""
    return tuple(_gain(A, Ci, R[i], Pi[i]) for i, Ci in enumerate(C))


def coupled_riccati_step(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    P: np.ndarray,
    *,
    order: Order | str,
) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """One step of the coupled Riccati recursion: the gains ``L_i(k)`` and the symmetrized
    ``P(k+1)`` (seed 000 eqs. (5.7)–(5.9), App. C.3; module docstring)."""
    consensus_first = Order(order) is Order.CONSENSUS_THEN_FILTER
    base = E_map(W, P) if consensus_first else P
    gains = riccati_gains(A, C, R, base)
    nxt = np.stack(
        [A @ Pi @ A.T + Q - Li @ Ci @ Pi @ A.T for Pi, Li, Ci in zip(base, gains, C, strict=True)]
    )
    nxt = (nxt + nxt.transpose(0, 2, 1)) / 2
    return gains, (nxt if consensus_first else E_map(W, nxt))


def error_noise_covariance(
    Q: np.ndarray, R: Sequence[np.ndarray], gains: Sequence[np.ndarray]
) -> np.ndarray:
    """``(11' ⊗ Q) + blkdiag(L_i R_i L_i')``: the noise covariance of ``[ε_1; …; ε_N]`` in (5.5)
    (ω is common to all agents)."""
    N = len(gains)
    LRL = [Li @ Ri @ Li.T for Li, Ri in zip(gains, R, strict=True)]
    return np.kron(np.ones((N, N)), Q) + sla.block_diag(*LRL)


@dataclass(frozen=True, eq=False)
class RiccatiRun:
    """Outcome of :func:`coupled_riccati`: ``status`` (``converged``, ``diverged``, ``max_iter``,
    or ``steps`` with ``fixed_steps``), the last iterate and its gains, whether they stabilize the
    order's operator (exact, :func:`~theory.consensus.operators.gains_stabilize`; None unless
    converged) with its float radius, and ``‖P_i(k)‖₂`` for each k and agent."""

    status: str
    iterations: int
    P: np.ndarray
    gains: tuple[np.ndarray, ...]
    stabilizing: bool | None
    radius: float | None
    agent_norms: np.ndarray
    tolerances: dict

    @property
    def norms(self) -> np.ndarray:
        """``max_i ‖P_i(k)‖₂`` for each k."""
        return self.agent_norms.max(axis=1)


def coupled_riccati(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    P0: np.ndarray,
    *,
    order: Order | str = Order.CONSENSUS_THEN_FILTER,
    max_iter: int = int(MAX_ITER),
    conv_tol: float = CONV_TOL,
    blowup: float = BLOWUP,
    fixed_steps: bool = False,
) -> RiccatiRun:
    """Iterate the coupled Riccati equations from ``P0`` (one matrix: every agent's) until
    convergence, divergence or ``max_iter`` (seed 000 eqs. (5.7)–(5.9), (C.3), footnote 5).

    ``fixed_steps`` runs exactly ``max_iter`` steps, as the consensus Kalman filter does (status
    ``steps``; ``diverged`` early only when the iterates stop being finite or ``C_i P C_iᵀ + R_i``
    becomes numerically singular past ``blowup``).
    """
    N, n = W.shape[0], A.shape[0]
    P = np.broadcast_to(np.asarray(P0, dtype=float), (N, n, n)).copy()
    norms = [np.linalg.norm(P, 2, axis=(1, 2))]
    start = max(float(norms[0].max()), 1.0)
    status, iterations = ("steps" if fixed_steps else "max_iter"), 0
    while iterations < max_iter:
        iterations += 1
        try:
            nxt = coupled_riccati_step(A, C, W, Q, R, P, order=order)[1]
        except np.linalg.LinAlgError:  # C P Cᵀ + R lost R to rounding: P has blown up
            if float(norms[-1].max()) <= blowup * start:
                raise
            status = "diverged"
            break
        step = float(np.max(np.linalg.norm(nxt - P, 2, axis=(1, 2))))
        P = nxt
        norms.append(np.linalg.norm(P, 2, axis=(1, 2)))
        top = float(norms[-1].max())
        if not np.isfinite(top) or (not fixed_steps and top > blowup * start):
            status = "diverged"
            break
        if not fixed_steps and step <= conv_tol * top:
            status = "converged"
            break
    gains = coupled_riccati_step(A, C, W, Q, R, P, order=order)[0] if status != "diverged" else ()
    stabilizing, radius = None, None
    if status == "converged":
        T = covariance_operator_matrix(W, closed_loop(A, C, gains), order)
        radius = spectral_radius(T)
        stabilizing = gains_stabilize(A, C, W, gains, order=order)
    tol = {"conv_tol": conv_tol, "blowup": blowup, "max_iter": max_iter}
    return RiccatiRun(status, iterations, P, gains, stabilizing, radius, np.array(norms), tol)


@dataclass(frozen=True, eq=False)
class CovarianceBoundCheck:
    """Lemma 5.2.3 with fixed gains: ``exact_gap = min_k min_i λ_min(P_i(k) − Σ_i(k)) / max(1,
    ‖P_i(k)‖)`` (holds iff ``≥ −psd_tol``), the Monte Carlo relative error ``‖Σ̂_i − Σ_i‖/‖Σ_i‖``
    and violation ``λ_max(Σ̂_i − P_i)/‖P_i‖`` (a few ``1/√samples`` expected)."""

    exact_gap: float
    holds: bool
    mc_error: float
    mc_violation: float
    samples: int
    steps: int
    seed: int
    psd_tol: float


def check_covariance_bound(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    gains: Sequence[np.ndarray],
    P0: np.ndarray,
    *,
    steps: int = 30,
    samples: int = 4000,
    seed: int = 0,
    psd_tol: float = PSD_TOL,
) -> CovarianceBoundCheck:
    """Check ``Σ(k) ≤ P(k)`` (seed 000 Lemma 5.2.3, eqs. (5.5), (5.15); App. C.1) exactly and by
    Monte Carlo (``samples`` draws from ``default_rng(seed)``) over ``steps`` steps.

    The initial estimates are equal and deterministic, so ``ε_i(0) = x(0) − x̂(0)`` is the same for
    every agent: the joint covariance starts at ``11' ⊗ P0`` and ``P(0) = Σ(0) = (P0, …, P0)``.
    """
    N, n = W.shape[0], A.shape[0]
    Gamma = closed_loop(A, C, gains)
    Bm = B_matrix(W, Gamma)
    LRL = [Li @ Ri @ Li.T for Li, Ri in zip(gains, R, strict=True)]
    noise = error_noise_covariance(Q, R, gains)
    joint = np.kron(np.ones((N, N)), P0)
    P = np.broadcast_to(P0, (N, n, n)).copy()
    rng = np.random.default_rng(seed)
    eps = np.tile(rng.multivariate_normal(np.zeros(n), P0, size=samples), (1, N))
    gap, mc_error, mc_violation = np.inf, 0.0, -np.inf
    for _ in range(steps):
        joint = Bm @ joint @ Bm.T + noise
        P = L_map(W, Gamma, P) + Q + np.stack(LRL)
        eps = eps @ Bm.T + _noise_samples(rng, samples, Q, C, R, gains)
        sample_cov = eps.T @ eps / samples
        for i in range(N):
            block = slice(i * n, (i + 1) * n)
            Sigma = joint[block, block]
            scale = max(1.0, float(np.linalg.norm(P[i], 2)))
            gap = min(gap, float(np.linalg.eigvalsh(P[i] - Sigma)[0]) / scale)
            hat = sample_cov[block, block]
            mc_error = max(
                mc_error,
                float(np.linalg.norm(hat - Sigma, 2) / max(np.linalg.norm(Sigma, 2), 1e-300)),
            )
            mc_violation = max(mc_violation, float(np.linalg.eigvalsh(hat - P[i])[-1]) / scale)
    return CovarianceBoundCheck(
        gap, gap >= -psd_tol, mc_error, mc_violation, samples, steps, seed, psd_tol
    )


def _noise_samples(
    rng: np.random.Generator,
    samples: int,
    Q: np.ndarray,
    C: Sequence[np.ndarray],
    R: Sequence[np.ndarray],
    gains: Sequence[np.ndarray],
) -> np.ndarray:
    n = Q.shape[0]
    omega = rng.multivariate_normal(np.zeros(n), Q, size=samples)
    parts = []
    for Ci, Ri, Li in zip(C, R, gains, strict=True):
        if Ci.shape[0]:
            v = rng.multivariate_normal(np.zeros(Ci.shape[0]), Ri, size=samples)
            parts.append(omega - v @ Li.T)
        else:
            parts.append(omega)
    return np.hstack(parts)


@dataclass(frozen=True)
class AveragedBoundCheck:
    """Seed 000 Lemma A.2.1 on one instance: ``r = max_i λ_max(X_i^{-1/2} f_1^i(M, X)
    X_i^{-1/2})`` (hypothesis ``r < 1``), the least ``α``, ``μ`` with ``P_0 ≤ α X``, ``U ≤ μ X``;
    part 1 ``f_k(M, P_0) ≤ α r^k X`` and part 2 ``P_k ≤ (α + μ/(1 − r)) X`` at every step checked,
    and the worst ratio of ``P_k`` to that bound (≤ 1 expected)."""

    r: float
    alpha: float
    mu: float
    decay_ok: bool
    bound_ok: bool
    worst_ratio: float
    steps: int
    psd_tol: float


def _ratio(P: np.ndarray, X: np.ndarray) -> float:
    """``max_i λ_max(X_i^{-1/2} P_i X_i^{-1/2})``."""
    out = -np.inf
    for Pi, Xi in zip(P, X, strict=True):
        w, V = np.linalg.eigh(Xi)
        root = (V / np.sqrt(w)) @ V.T
        out = max(out, float(np.linalg.eigvalsh(root @ Pi @ root)[-1]))
    return out


def check_averaged_bound(
    W: np.ndarray,
    M: np.ndarray,
    X: np.ndarray,
    P0: np.ndarray,
    U: np.ndarray,
    *,
    steps: int = 200,
    psd_tol: float = PSD_TOL,
) -> AveragedBoundCheck:
    """Check both statements of seed 000 Lemma A.2.1 (eqs. (A.53)–(A.54), Cor. A.2.2) along
    ``steps`` iterations, with ``psd_tol`` relative slack in each inequality.

    ``f_1^i(M, P) = Σ_j w_ij M^j P^j M^j'`` is the operator J of App. C.3 with ``Γ_j = M^j``;
    ``X ≻ 0`` satisfies the hypothesis ``X^i > f_1^i(M, X)``, ``P0, U ⪰ 0``.
    """
    r = _ratio(J_map(W, M, X), X)
    alpha, mu = _ratio(P0, X), _ratio(U, X)
    limit = alpha + mu / (1 - r) if r < 1 else np.inf
    decay_ok, worst = True, -np.inf
    F, P = P0.copy(), P0.copy()
    for k in range(1, steps + 1):
        F = J_map(W, M, F)
        P = J_map(W, M, P) + U
        decay_ok &= _ratio(F, X) <= alpha * r**k * (1 + psd_tol) + psd_tol
        worst = max(worst, _ratio(P, X) / limit)
    return AveragedBoundCheck(
        r, alpha, mu, bool(decay_ok), bool(worst <= 1 + psd_tol), worst, steps, psd_tol
    )


def bound_iteration(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    gains: Sequence[np.ndarray],
    P0: np.ndarray,
    *,
    order: Order | str,
    steps: int,
) -> np.ndarray:
    """``P^L(k+1) = T(P^L(k)) + U`` with fixed gains, shape ``(steps + 1, N, n, n)`` (seed 000
    Lemma 5.2.3, eq. (5.15)): ``T = L``, ``U_i = Q + L_iR_iL_iᵀ`` consensus first; ``T = J`` and
    forcing ``E(U)`` filter first."""
    order = Order(order)
    Gamma = closed_loop(A, C, gains)
    U = np.stack([Q + g @ r @ g.T for g, r in zip(gains, R, strict=True)])
    U = U if order is Order.CONSENSUS_THEN_FILTER else E_map(W, U)
    out = [np.asarray(P0, float)]
    for _ in range(steps):
        out.append(apply_operator(order.operator, W, Gamma, out[-1]) + U)
    return np.array(out)
