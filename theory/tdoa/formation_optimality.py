"""Which planar formations are optimal for localization (seed 000 §4.3.1, seed 003 Result 3).

Both papers name one optimal formation: seed 000 §4.3.1 (and seed 001 §IV.A) "the optimum 2D
formation is that of a uniform angular array" for TDOA on a complete network, seed 003 Result 3
"the trackers' positions are distributed uniformly around the target and the angle made by …
two adjacent trackers … is 2π/N" for range measurements. The Fisher information decides it:

- range, unit directions ``u_k = (cos θ_k, sin θ_k)``: ``J = Σ u_k u_kᵀ/σ²`` has trace ``N/σ²``,
  so ``tr J⁻¹ ≥ 4σ²/N`` (and ``det J ≤ N²/4σ⁴``) with equality iff ``J = (N/2σ²) I``, i.e.
  ``Σ e^{2iθ_k} = 0``;
- TDOA on all pairs: ``J = (N Σ u_k u_kᵀ − (Σ u_k)(Σ u_k)ᵀ)/σ²`` (eq. (4.39)), so
  ``tr J⁻¹ ≥ d²σ²/N²`` with equality iff ``Σ u_k = 0`` and ``Σ u_k u_kᵀ = (N/2) I``.

Uniform arrays meet these conditions, but so do others: three trackers at 0°, 60°, 120° (all on
one side of the target) for range, two equilateral triangles turned 20° apart for TDOA. The
claims ``seed003.result3`` and ``seed000.sec4.3.1.uniform-array`` report both, as the 3-D
``seed000.sec4.3.1.platonic`` does for the Platonic solids.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from theory.core.claims import ClaimResult, register
from theory.tdoa.crb import crb_trace, optimal_crb_trace

__all__ = ["FORMATIONS_RANGE", "FORMATIONS_TDOA", "range_crb_trace", "unit_circle"]

BOUND_RTOL = 1e-9
"""Relative distance from the bound within which a formation counts as optimal."""


def unit_circle(degrees: list[float]) -> np.ndarray:
    """Points on the unit circle around the origin at the given bearings.

    Parameters
    ----------
    degrees : list of float
        Bearings in degrees.

    Returns
    -------
    ndarray, shape (N, 2)
    """
    angles = np.radians(np.asarray(degrees, dtype=float))
    return np.column_stack([np.cos(angles), np.sin(angles)])


def range_crb_trace(directions: np.ndarray) -> float:
    """``tr J⁻¹`` of range-only measurements (``σ = 1``) from the unit ``directions``.

    Parameters
    ----------
    directions : ndarray, shape (N, 2)
        Unit vectors from the target to the trackers.

    Returns
    -------
    float
        ``inf`` when ``J`` is singular.
    """
    eig = np.linalg.eigvalsh(directions.T @ directions)
    return float("inf") if eig[0] <= 1e-12 * eig[-1] else float(np.sum(1 / eig))


FORMATIONS_RANGE = {
    "uniform, N = 3 (0°, 120°, 240°)": [0, 120, 240],
    "half circle, N = 3 (0°, 60°, 120°)": [0, 60, 120],
    "uniform, N = 4": [0, 90, 180, 270],
    "quarter turns, N = 4 (0°, 45°, 90°, 135°)": [0, 45, 90, 135],
}
"""Range formations: the uniform ones of Result 3 and non-uniform ones that reach the bound."""

FORMATIONS_TDOA = {
    "uniform hexagon": [0, 60, 120, 180, 240, 300],
    "two triangles turned 20°": [0, 120, 240, 20, 140, 260],
    "uniform pentagon": [0, 72, 144, 216, 288],
}
"""TDOA formations (complete network): the uniform arrays and two triangles that also reach it."""


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
