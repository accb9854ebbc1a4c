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
``u_0 − u_j``, receiver 0 the reference) along a constant-velocity target, and the claim
``seed000.eq4.16.window`` decides its rank for three geometries:

- 3 static receivers (2 TDOA rows per ping, frozen rank 4): the window rank is 6, so the
  linearised error dynamics are observable; globally the target is still confused with its
  mirror image in the receivers' plane, which yields the same TDOAs at every ping;
- 2 static receivers (1 row): rank 5, the rotation about their baseline is never seen;
- 2 moving receivers (1 row): rank 6.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from theory.core.claims import ClaimResult, ClaimSet, Context, Method, Status
from theory.core.observability import RANK_TOL, numeric_rank, observability_matrix
from theory.core.tolerances import INCONCLUSIVE_FACTOR
from theory.tdoa.model import cv_discrete, tdoa_jacobian, tdoa_measurement

__all__ = ["SCENES", "claims", "mirror_gap", "window_claim", "window_observability"]

claims = ClaimSet()

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
    """``𝒪_K`` (rows ``H(k) A^k``, ``H(k)`` of eqs. (4.7)–(4.10) at the target's position at ping
    ``k``) of a constant-velocity target seen by ``receivers(t)`` (receiver 0 the reference), and
    ``max_k rank [H(k); H(k)A; …; H(k)A⁵]``, the frozen pair the papers examine."""
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
    """Largest TDOA difference over the window between the target and its mirror image in the
    plane of three static receivers (0 up to rounding: the two cannot be told apart)."""
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


@claims.register(
    "seed000.eq4.16.window",
    source="seed 000 §4.2.1 before Def. 4.2.1 and Thm 4.2.3 (necessity); seed 001 after eq. (16) "
    "and Theorem 1 (necessity)",
    statement="the error dynamics of (4.16) are stable iff the pair (A, H_i(k)) is observable; "
    "with fewer than 3 TDOA rows (fewer than 4 agents) the target cannot be localized even "
    "centrally",
)
def window_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """Window rank of ``𝒪_K`` for :data:`SCENES` against the frozen-pair rank: ``corrected`` when
    every window rank is the predicted one and the mirror ambiguity holds."""
    scenes = {}
    for name, (receivers, predicted) in SCENES.items():
        window, frozen = window_observability(receivers)
        rank = numeric_rank(window, rank_tol=RANK_TOL)
        scenes[name] = {
            "frozen_pair_rank_max": frozen,
            "window_rank": rank.rank,
            "predicted_window_rank": predicted,
            "singular_values": list(rank.singular_values),
            "rank_margin": rank.margin,
            "conclusive": rank.conclusive(),
        }
    gap = mirror_gap(SCENES["3 static receivers (2 TDOA rows)"][0])
    as_predicted = all(s["window_rank"] == s["predicted_window_rank"] for s in scenes.values())
    conclusive = all(s["conclusive"] for s in scenes.values())
    status = Status.CORRECTED if conclusive else Status.INCONCLUSIVE
    status = status if as_predicted else Status.REFUTED
    return [
        ClaimResult(
            status,
            Method.NUMERIC,
            {
                "scenes": scenes,
                "target": {"start": START, "velocity": VELOCITY, "pings": PINGS, "T": PERIOD},
                "mirror_tdoa_gap_3_static": gap,
                "corrected_statement": "the frozen pair (A, H(k)) decides nothing for a moving "
                "target: the time-varying error dynamics need observability over a window, "
                "rank [H(0); H(1)A; …; H(K−1)A^{K−1}] = 6, which 3 static receivers (2 TDOA rows, "
                "every frozen pair of rank 4) already give locally; what fewer than 4 agents "
                "cannot remove is the global mirror ambiguity in the plane of 3 receivers",
            },
            margin=min(s["rank_margin"] for s in scenes.values()),
            tolerance={"rank_tol": RANK_TOL, "inconclusive_factor": INCONCLUSIVE_FACTOR},
            message="window ranks "
            + "; ".join(
                f"{n}: {s['window_rank']} (frozen {s['frozen_pair_rank_max']})"
                for n, s in scenes.items()
            )
            + f"; mirror image TDOA gap {gap:.1e}",
        )
    ]
