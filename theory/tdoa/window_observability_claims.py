"""Claim ``seed000.eq4.16.window``: window observability of the TDOA error dynamics.

The mathematics (``𝒪_K``, the scenes, the mirror gap) is in
:mod:`theory.tdoa.window_observability`; this module registers the claim that decides it.
"""

from __future__ import annotations

from typing import Any

from theory.core.claims import ClaimResult, register
from theory.core.observability import RANK_TOL, numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR
from theory.tdoa.window_observability import (
    PERIOD,
    PINGS,
    SCENES,
    START,
    VELOCITY,
    mirror_gap,
    window_observability,
)

__all__ = ["check_window_observability"]


@register(
    "seed000.eq4.16.window",
    source="seed 000 §4.2.1 before Def. 4.2.1 and Thm 4.2.3 (necessity); seed 001 after eq. (16) "
    "and Theorem 1 (necessity)",
    statement="the error dynamics of (4.16) are stable iff the pair (A, H_i(k)) is observable; "
    "with fewer than 3 TDOA rows (fewer than 4 agents) the target cannot be localized even "
    "centrally",
)
def check_window_observability(case: Any = None) -> list[ClaimResult]:
    """Window rank of ``𝒪_K`` for :data:`SCENES` against the frozen-pair rank (module docstring).

    Parameters
    ----------
    case : None
        Model claim (no case).

    Returns
    -------
    list of ClaimResult
        One ``numeric`` result: ``corrected`` when every window rank is the predicted one and the
        mirror ambiguity holds (margins and tolerances stated), ``inconclusive`` when a rank
        lies inside its tolerance, ``refuted`` when a rank differs from the prediction.
    """
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
    status = "refuted" if not as_predicted else "corrected" if conclusive else "inconclusive"
    return [
        ClaimResult(
            claim="seed000.eq4.16.window",
            case="-",
            method="numeric",
            status=status,
            evidence={
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
