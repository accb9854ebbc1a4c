"""Cramér–Rao bounds for TDOA localization (seed 000 §4.3.1, eqs. (4.38)–(4.43)), the posterior
CRB of the tracking problem, and which formations are optimal.

Static CRB: with independent pair measurements of variance ``σ²`` over the pairs ``I``,
``J = G G'/σ²`` with columns ``g_i − g_j``, ``g_i = (p − p_i)/‖p − p_i‖`` (4.39)–(4.42). For the
complete set of pairs ``J = (N Σ g_ig_i' − s s')/σ²`` with ``s = Σ g_i``, so ``tr J ≤ N²/σ²`` and,
since ``tr(J⁻¹) ≥ d²/tr J``, ``tr(J⁻¹) ≥ d²σ²/N²``, with equality iff ``s = 0`` and
``Σ g_ig_i' = (N/d) I`` (a balanced tight frame of directions). For range measurements
``J = Σ u_k u_kᵀ/σ²`` has trace ``N/σ²``, so ``tr J⁻¹ ≥ 4σ²/N`` in the plane, with equality iff
``Σ e^{2iθ_k} = 0``.

Seed 000 §4.3.1 (and seed 001 §IV.A) names the uniform angular array optimal in 2-D and the
Platonic solids in 3-D; seed 003 Result 3 the uniform formation for range. They reach the bounds,
but so do others: three trackers at 0°, 60°, 120° for range, two equilateral triangles turned 20°
apart for TDOA, the square antiprism in 3-D. Each claim is therefore ``corrected``.

Posterior CRB (Tichavský et al. 1998) for ``x(k+1) = Ax + Bw`` and TDOA rows with independent
noise: ``J(k) = (A J(k−1)⁻¹ A' + BQB')⁻¹ + Σ_i H_i' R_i⁻¹ H_i`` with ``H_i`` at the true state.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from theory.core.claims import ClaimResult, ClaimSet, Context, Method, Status
from theory.core.tolerances import BOUND_RTOL, INFORMATION_TOL
from theory.tdoa.model import tdoa_jacobians, unit_directions

__all__ = [
    "FORMATIONS_RANGE",
    "FORMATIONS_TDOA",
    "claims",
    "crb_trace",
    "optimal_crb_trace",
    "pcrb_along",
    "platonic_claim",
    "platonic_solids",
    "range_crb_trace",
    "range_formations_claim",
    "tdoa_fisher",
    "tdoa_formations_claim",
    "unit_circle",
]

claims = ClaimSet()


def tdoa_fisher(
    target: np.ndarray,
    positions: np.ndarray,
    pairs: Sequence[tuple[int, int]] | None = None,
    sigma2: float = 1.0,
) -> np.ndarray:
    """Fisher information ``J = G G'/σ²`` over the 0-based ``pairs`` (default all ``i < j``);
    seed 000 eqs. (4.38)–(4.42)."""
    g = unit_directions(target, positions)
    if pairs is None:
        pairs = list(itertools.combinations(range(len(positions)), 2))
    G = np.array([g[i] - g[j] for i, j in pairs]).T
    return G @ G.T / sigma2


def crb_trace(
    target: np.ndarray,
    positions: np.ndarray,
    pairs: Sequence[tuple[int, int]] | None = None,
    sigma2: float = 1.0,
) -> float:
    """``tr(J⁻¹)`` of eq. (4.43); ``inf`` when ``J`` is singular.

    Singularity is decided exactly when the pairs connect the agents they use (all pairs do):
    ``rank J = dim aff{u_j}`` (:func:`~theory.tdoa.geometry.exact.exact_direction_rank`), so a
    near-singular but full-rank geometry gets its finite trace ``σ² Σ 1/s_i²`` from the singular
    values of ``G`` (not of ``J``, which would square their ratio). Other pair sets use the float
    test ``λ_min ≤ information_tol · λ_max``.
    """
    pairs = list(itertools.combinations(range(len(positions)), 2)) if pairs is None else pairs
    nodes = _connected_nodes(pairs)
    if nodes is None:
        eig = np.linalg.eigvalsh(tdoa_fisher(target, positions, pairs, sigma2))
        if eig[-1] <= 0 or eig[0] <= INFORMATION_TOL * eig[-1]:
            return float("inf")
        return float(np.sum(1.0 / eig))
    from theory.tdoa.geometry.exact import exact_direction_rank  # python-flint: on use

    dim = len(target)
    if exact_direction_rank(list(target), [list(positions[j]) for j in nodes]) < dim:
        return float("inf")
    g = unit_directions(target, positions)
    s = np.linalg.svd(np.array([g[i] - g[j] for i, j in pairs]), compute_uv=False)
    return float(sigma2 * np.sum(1.0 / s[:dim] ** 2)) if s[dim - 1] > 0 else float("inf")


def _connected_nodes(pairs: Sequence[tuple[int, int]]) -> list[int] | None:
    """The agents the pairs use, when the pairs connect them (else ``None``)."""
    nodes = sorted({int(k) for pair in pairs for k in pair})
    if not nodes:
        return None
    neighbours: dict[int, set[int]] = {k: set() for k in nodes}
    for i, j in pairs:
        neighbours[int(i)].add(int(j))
        neighbours[int(j)].add(int(i))
    seen, frontier = {nodes[0]}, [nodes[0]]
    while frontier:
        fresh = neighbours[frontier.pop()] - seen
        seen |= fresh
        frontier.extend(fresh)
    return nodes if len(seen) == len(nodes) else None


def optimal_crb_trace(n_agents: int, dim: int = 3, sigma2: float = 1.0) -> float:
    """The lower bound ``d²σ²/N²`` of ``tr(J⁻¹)`` over all formations (complete pair set)."""
    return dim**2 * sigma2 / n_agents**2


def platonic_solids() -> dict[str, np.ndarray]:
    """Vertices of the five Platonic solids on the unit sphere (4, 6, 8, 12, 20 vertices)."""
    phi = (1 + np.sqrt(5)) / 2
    tetra = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    octa = np.vstack([np.eye(3), -np.eye(3)])
    cube = np.array(list(itertools.product((-1.0, 1.0), repeat=3)))
    ico = np.array(
        [
            v
            for a, b in itertools.product((-1.0, 1.0), repeat=2)
            for v in ([0, a, b * phi], [a, b * phi, 0], [b * phi, 0, a])
        ]
    )
    dodeca = np.vstack(
        [
            cube,
            *(
                [
                    np.roll([0, a / phi, b * phi], shift)
                    for a, b in itertools.product((-1.0, 1.0), repeat=2)
                ]
                for shift in range(3)
            ),
        ]
    )
    solids = {
        "tetrahedron": tetra,
        "octahedron": octa,
        "cube": cube,
        "icosahedron": ico,
        "dodecahedron": dodeca,
    }
    return {k: v / np.linalg.norm(v, axis=1, keepdims=True) for k, v in solids.items()}


def pcrb_along(
    truth: np.ndarray,
    positions: np.ndarray,
    neighbours: Sequence[Sequence[np.ndarray]],
    A: np.ndarray,
    BQB: np.ndarray,
    r: float,
    P0: np.ndarray,
) -> np.ndarray:
    """Posterior CRB matrices ``J(k)⁻¹`` at the pings of ``truth`` (K+1, n), every agent's rows
    at ``positions[k]`` with neighbours ``neighbours[k][i]``, ``R_i = r I``, prior ``P0``."""
    dim = positions.shape[2]
    out = np.empty((truth.shape[0], *P0.shape))
    predicted = P0
    for k in range(truth.shape[0]):
        H = np.vstack(tdoa_jacobians(truth[k, :dim], positions[k], list(neighbours[k])))
        info = np.linalg.inv(predicted) + H.T @ H / r
        out[k] = np.linalg.inv(info)
        predicted = A @ out[k] @ A.T + BQB
    return out


def unit_circle(degrees: list[float]) -> np.ndarray:
    """Points on the unit circle at the given bearings (degrees), shape (N, 2)."""
    angles = np.radians(np.asarray(degrees, dtype=float))
    return np.column_stack([np.cos(angles), np.sin(angles)])


def range_crb_trace(directions: np.ndarray) -> float:
    """``tr J⁻¹`` of range-only measurements (``σ = 1``) from unit ``directions`` (``inf`` if
    singular)."""
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


def _uniform(degrees: list[float]) -> bool:
    bearings = sorted(d % 360 for d in degrees)
    gaps = np.diff([*bearings, bearings[0] + 360])
    return bool(np.allclose(gaps, 360 / len(degrees)))


def _ratios(
    formations: dict[str, list[float]],
    trace: Callable[[np.ndarray], float],
    bound: Callable[[int], float],
) -> dict[str, dict[str, Any]]:
    return {
        name: {
            "bearings_deg": degrees,
            "uniform": _uniform(degrees),
            "crb_over_bound": trace(unit_circle(degrees)) / bound(len(degrees)),
        }
        for name, degrees in formations.items()
    }


def _result(table: dict[str, dict[str, Any]], bound: str) -> ClaimResult:
    optimal = {n: abs(r["crb_over_bound"] - 1) <= BOUND_RTOL for n, r in table.items()}
    non_uniform = [n for n in table if optimal[n] and not table[n]["uniform"]]
    status = Status.CORRECTED if all(optimal.values()) and non_uniform else Status.INCONCLUSIVE
    return ClaimResult(
        status,
        Method.NUMERIC,
        {"formations": table, "bound": bound, "optimal_non_uniform": non_uniform},
        margin=max(abs(r["crb_over_bound"] - 1) for r in table.values()),
        tolerance={"bound_rtol": BOUND_RTOL},
        message=f"the bound is reached by uniform arrays and by {', '.join(non_uniform)}: the "
        "optimal formations are not unique",
    )


@claims.register(
    "seed003.result3",
    source="seed 003 §III-B.3 (Result 3, citing [5] Proposition 3)",
    statement="with N ≥ 3 trackers the optimal 2-D formations for range-based estimation are the "
    "ones with trackers distributed uniformly around the target (adjacent angle 2π/N)",
)
def range_formations_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """Range bound ``tr J⁻¹ ≥ 4σ²/N`` on uniform and non-uniform formations."""
    table = _ratios(FORMATIONS_RANGE, range_crb_trace, lambda n: 4 / n)
    return [_result(table, "tr(J^-1) >= 4 sigma^2 / N, equality iff sum_k exp(2 i theta_k) = 0")]


@claims.register(
    "seed000.sec4.3.1.uniform-array",
    source="seed 000 §4.3.1 (citing [62]); seed 001 §IV.A",
    statement="the optimum 2-D formation of a complete network is the uniform angular array",
)
def tdoa_formations_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """TDOA bound ``tr J⁻¹ ≥ d²σ²/N²`` (eq. (4.43)) on uniform and non-uniform formations."""
    table = _ratios(
        FORMATIONS_TDOA,
        lambda positions: crb_trace(np.zeros(2), positions),
        lambda n: optimal_crb_trace(n, dim=2),
    )
    bound = "tr(J^-1) >= d^2 sigma^2 / N^2, equality iff sum u_k = 0 and sum u_k u_k' = (N/d) I"
    return [_result(table, bound)]


@claims.register(
    "seed000.sec4.3.1.platonic",
    source="seed 000, §4.3.1 (after eq. 4.43)",
    statement="In 3D the optimal formations for a complete network are the Platonic solids.",
)
def platonic_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """Each Platonic solid reaches ``tr(J⁻¹) = 9σ²/N²``; so does the square antiprism: the
    optimal formations are the balanced tight frames, not only the solids."""
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
    evidence = {
        "crb_over_bound": ratios,
        "bound": "tr(J^-1) >= d^2 sigma^2 / N^2, equality iff sum g_i = 0 and "
        "sum g_i g_i' = (N/d) I",
    }
    return [
        ClaimResult(
            Status.CORRECTED if reached else Status.INCONCLUSIVE,
            Method.NUMERIC,
            evidence,
            margin=max(abs(r - 1) for r in ratios.values()),
            tolerance={"bound_rtol": BOUND_RTOL},
            message="Platonic solids are optimal but not the only optimal formations "
            "(the square antiprism reaches the same bound).",
        )
    ]
