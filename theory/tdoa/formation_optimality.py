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
``seed000.sec4.3.1.platonic`` does for the Platonic solids (:mod:`theory.tdoa.formation_claims`).
"""

from __future__ import annotations

import numpy as np

from theory.core.tolerances import INFORMATION_TOL

__all__ = ["FORMATIONS_RANGE", "FORMATIONS_TDOA", "range_crb_trace", "unit_circle"]


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
    return (
        float("inf")
        if eig[-1] <= 0 or eig[0] <= INFORMATION_TOL * eig[-1]
        else float(np.sum(1 / eig))
    )


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
