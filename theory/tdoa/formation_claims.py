"""Claims on optimal formations: uniform arrays (2-D) and Platonic solids (3-D) against the CRB.

* ``seed003.result3`` — range-based: uniform formations are optimal (seed 003 Result 3);
* ``seed000.sec4.3.1.uniform-array`` — TDOA: the uniform angular array is optimal (2-D);
* ``seed000.sec4.3.1.platonic`` — TDOA: the Platonic solids are optimal (3-D).

Each is ``corrected``: the bound is reached, but by other formations too
(:mod:`theory.tdoa.formation_optimality` explains why).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from theory.core.claims import ClaimResult, register
from theory.core.tolerances import BOUND_RTOL
from theory.tdoa.crb import crb_trace, optimal_crb_trace, platonic_solids
from theory.tdoa.formation_optimality import (
    FORMATIONS_RANGE,
    FORMATIONS_TDOA,
    range_crb_trace,
    unit_circle,
)

__all__ = ["check_platonic", "check_range_formations", "check_tdoa_formations"]


def _uniform(degrees: list[float]) -> bool:
    bearings = sorted(d % 360 for d in degrees)
    gaps = np.diff([*bearings, bearings[0] + 360])
    return bool(np.allclose(gaps, 360 / len(degrees)))


def _ratios(formations: dict[str, list[float]], trace, bound) -> dict[str, dict[str, Any]]:
    return {
        name: {
            "bearings_deg": degrees,
            "uniform": _uniform(degrees),
            "crb_over_bound": trace(unit_circle(degrees)) / bound(len(degrees)),
        }
        for name, degrees in formations.items()
    }


def _result(claim: str, table: dict[str, dict[str, Any]], bound: str) -> ClaimResult:
    optimal = {n: abs(r["crb_over_bound"] - 1) <= BOUND_RTOL for n, r in table.items()}
    non_uniform = [n for n in table if optimal[n] and not table[n]["uniform"]]
    status = "corrected" if all(optimal.values()) and non_uniform else "inconclusive"
    return ClaimResult(
        claim=claim,
        case="-",
        method="numeric",
        status=status,
        evidence={"formations": table, "bound": bound, "optimal_non_uniform": non_uniform},
        margin=max(abs(r["crb_over_bound"] - 1) for r in table.values()),
        tolerance={"bound_rtol": BOUND_RTOL},
        message=f"the bound is reached by uniform arrays and by {', '.join(non_uniform)}: the "
        "optimal formations are not unique",
    )


@register(
    "seed003.result3",
    source="seed 003 §III-B.3 (Result 3, citing [5] Proposition 3)",
    statement="with N ≥ 3 trackers the optimal 2-D formations for range-based estimation are the "
    "ones with trackers distributed uniformly around the target (adjacent angle 2π/N)",
)
def check_range_formations(case: Any = None) -> list[ClaimResult]:
    """Range FIM bound ``tr J⁻¹ ≥ 4σ²/N`` on uniform and non-uniform formations.

    Parameters
    ----------
    case : None
        Model claim (no case).

    Returns
    -------
    list of ClaimResult
        ``corrected`` when a non-uniform formation reaches the bound too (module docstring).
    """
    table = _ratios(FORMATIONS_RANGE, range_crb_trace, lambda n: 4 / n)
    bound = "tr(J^-1) >= 4 sigma^2 / N, equality iff sum_k exp(2 i theta_k) = 0"
    return [_result("seed003.result3", table, bound)]


@register(
    "seed000.sec4.3.1.uniform-array",
    source="seed 000 §4.3.1 (citing [62]); seed 001 §IV.A",
    statement="the optimum 2-D formation of a complete network is the uniform angular array",
)
def check_tdoa_formations(case: Any = None) -> list[ClaimResult]:
    """TDOA CRB bound ``tr J⁻¹ ≥ d²σ²/N²`` (eq. (4.43)) on uniform and non-uniform formations.

    Parameters
    ----------
    case : None
        Model claim (no case).

    Returns
    -------
    list of ClaimResult
        ``corrected`` when a non-uniform formation reaches the bound too (module docstring).
    """
    table = _ratios(
        FORMATIONS_TDOA,
        lambda positions: crb_trace(np.zeros(2), positions),
        lambda n: optimal_crb_trace(n, dim=2),
    )
    bound = "tr(J^-1) >= d^2 sigma^2 / N^2, equality iff sum u_k = 0 and sum u_k u_k' = (N/d) I"
    return [_result("seed000.sec4.3.1.uniform-array", table, bound)]


@register(
    "seed000.sec4.3.1.platonic",
    source="seed 000, §4.3.1 (after eq. 4.43)",
    statement="In 3D the optimal formations for a complete network are the Platonic solids.",
)
def check_platonic(case: Any = None) -> list[ClaimResult]:
    """Each Platonic solid reaches ``tr(J⁻¹) = 9σ²/N²``; so does the (non-Platonic) square
    antiprism, so "the" optimal formations are the balanced tight frames, not only the solids.

    Parameters
    ----------
    case : None
        Model claim (no case).
    """
    ratios = {
        name: crb_trace(np.zeros(3), v) / optimal_crb_trace(len(v))
        for name, v in platonic_solids().items()
    }
    h = 1 / math.sqrt(3)
    angles = np.arange(8) * math.pi / 4
    antiprism = np.column_stack(
        [
            math.sqrt(1 - h * h) * np.cos(angles),
            math.sqrt(1 - h * h) * np.sin(angles),
            np.where(np.arange(8) % 2 == 0, h, -h),
        ]
    )
    ratios["square antiprism"] = crb_trace(np.zeros(3), antiprism) / optimal_crb_trace(8)
    reached = all(abs(r - 1) <= BOUND_RTOL for r in ratios.values())
    return [
        ClaimResult(
            claim="seed000.sec4.3.1.platonic",
            case="-",
            method="numeric",
            status="corrected" if reached else "inconclusive",
            evidence={
                "crb_over_bound": ratios,
                "bound": "tr(J^-1) >= d^2 sigma^2 / N^2, equality iff sum g_i = 0 and "
                "sum g_i g_i' = (N/d) I",
            },
            margin=max(abs(r - 1) for r in ratios.values()),
            tolerance={"bound_rtol": BOUND_RTOL},
            message="Platonic solids are optimal but not the only optimal formations "
            "(the square antiprism reaches the same bound).",
        )
    ]
