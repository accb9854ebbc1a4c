"""Observability of the time-varying TDOA error dynamics over a window (seed 000 §4.2.1).

Seed 000 (before Def. 4.2.1) and seed 001 (after eq. (16)) state that the error
``x̃(k+1) = A(I − K(k)H(k)) x̃(k) + η(k)`` is stable iff "the pair ``(A, H(k))`` is observable",
then show that this frozen pair is unobservable with fewer than 3 TDOA rows, and conclude in the
necessity part of Thm 4.2.3 / Theorem 1 that fewer than 4 agents cannot localize "centrally, let
alone distributively". For a moving target ``H(k)`` changes from ping to ping, and what a
time-varying filter needs is observability over a window: the rank of
``𝒪_K = [H(0); H(1)A; …; H(K−1)A^{K−1}]`` (uniform complete observability). That can be full
when every frozen pair is rank-deficient.

:func:`window_observability` builds ``𝒪_K`` for a centralized receiver set (each row
``u_0 − u_j``, receiver 0 the reference, ``u`` the unit vector from a receiver to the target)
along a constant-velocity target, and the claim ``seed000.eq4.16.window``
(:mod:`theory.tdoa.window_observability_claims`) decides its rank for three geometries:

- 3 static receivers (2 TDOA rows per ping, frozen rank 4): the window rank is 6, so the
  linearised error dynamics are observable; globally the target is still confused with its
  mirror image in the receivers' plane, which yields the same TDOAs at every ping;
- 2 static receivers (1 row): rank 5, the rotation about their baseline is never seen;
- 2 moving receivers (1 row): rank 6.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from theory.core.observability import numeric_rank, observability_matrix
from theory.tdoa.model import cv_discrete, tdoa_jacobian, tdoa_measurement

__all__ = ["SCENES", "mirror_gap", "window_observability"]

Receivers = Callable[[float], np.ndarray]

START = np.array([8.0, -5.0, 6.0])
VELOCITY = np.array([0.5, 0.4, -0.3])
PINGS = 100
PERIOD = 1.0


def _static(*points: tuple[float, float, float]) -> Receivers:
    fixed = np.array(points, dtype=float)
    return lambda t: fixed


def _orbiting(t: float) -> np.ndarray:
    return np.array(
        [
            [10 * np.cos(t / 10), 10 * np.sin(t / 10), 3 * np.sin(t / 13)],
            [-10 * np.cos(t / 7), 2 * np.sin(t / 5), 10 * np.sin(t / 7)],
        ]
    )


SCENES: dict[str, tuple[Receivers, int]] = {
    "3 static receivers (2 TDOA rows)": (_static((0, 0, 0), (10, 0, 0), (0, 10, 0)), 6),
    "2 static receivers (1 TDOA row)": (_static((0, 0, 0), (10, 0, 0)), 5),
    "2 moving receivers (1 TDOA row)": (_orbiting, 6),
}
"""Scene name → (receiver positions at time t, window rank the mathematics predicts)."""


def window_observability(
    receivers: Receivers,
    *,
    start: np.ndarray = START,
    velocity: np.ndarray = VELOCITY,
    pings: int = PINGS,
    period: float = PERIOD,
) -> tuple[np.ndarray, int]:
    """``𝒪_K`` of a constant-velocity target and the largest frozen-pair rank along the window.

    Parameters
    ----------
    receivers : callable
        ``receivers(t)`` → positions ``(M, 3)``; receiver 0 is the TDOA reference.
    start, velocity : ndarray, shape (3,)
        The target's position at ``t = 0`` and its constant velocity.
    pings : int
        Window length ``K``.
    period : float
        Time between pings ``T`` (seed 000 eq. (4.6)).

    Returns
    -------
    window : ndarray, shape (K·(M−1), 6)
        Rows ``H(k) A^k``, ``H(k)`` of eqs. (4.7)–(4.10) at the target's position at ping ``k``.
    frozen_rank : int
        ``max_k rank [H(k); H(k)A; …; H(k)A⁵]`` (the pair the papers examine).
    """
    A = cv_discrete(period, 3)[0]
    blocks, frozen = [], 0
    for k in range(pings):
        H = _rows(receivers, start, velocity, k * period)
        blocks.append(H @ np.linalg.matrix_power(A, k))
        frozen = max(frozen, numeric_rank(observability_matrix(A, H)).rank)
    return np.vstack(blocks), frozen


def _rows(receivers: Receivers, start: np.ndarray, velocity: np.ndarray, t: float) -> np.ndarray:
    positions = receivers(t)
    return tdoa_jacobian(start + velocity * t, positions, 0, range(1, len(positions)))


def mirror_gap(
    receivers: Receivers,
    *,
    start: np.ndarray = START,
    velocity: np.ndarray = VELOCITY,
    pings: int = PINGS,
    period: float = PERIOD,
) -> float:
    """Largest TDOA difference between the target and its mirror image in the plane of three
    static receivers (0 up to rounding: the two trajectories cannot be told apart).

    Parameters
    ----------
    receivers : callable
        Three static receivers (``receivers(t)`` is the same for every ``t``).
    start, velocity : ndarray, shape (3,)
        As in :func:`window_observability`.
    pings : int
        Window length.
    period : float
        Time between pings.

    Returns
    -------
    float
        ``max_k ‖z(q_k) − z(q̄_k)‖_∞`` over the window, ``q̄`` the mirrored trajectory.
    """
    p = receivers(0.0)
    normal = np.cross(p[1] - p[0], p[2] - p[0])
    normal /= np.linalg.norm(normal)
    gap = 0.0
    for k in range(pings):
        q = start + velocity * k * period
        mirrored = q - 2 * ((q - p[0]) @ normal) * normal
        gap = max(gap, float(np.max(np.abs(_tdoa(q, p) - _tdoa(mirrored, p)))))
    return gap


def _tdoa(target: np.ndarray, positions: np.ndarray) -> np.ndarray:
    return tdoa_measurement(target, positions, 0, range(1, len(positions)))
