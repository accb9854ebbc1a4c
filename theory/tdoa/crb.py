"""Cramér–Rao bounds for TDOA localization (seed 000 §4.3.1, eqs. (4.38)–(4.43)) and the
posterior CRB of the tracking problem.

Static CRB: with independent pair measurements of variance ``σ²`` over the pairs ``I``,
``J = G G'/σ²`` with columns ``g_i − g_j``, ``g_i = (p − p_i)/‖p − p_i‖`` (4.39)–(4.42). For the
complete set of pairs ``J = (N Σ g_ig_i' − s s')/σ²`` with ``s = Σ g_i``, so ``tr J ≤ N²/σ²`` and,
since ``tr(J⁻¹) ≥ d²/tr J`` in dimension ``d``, ``tr(J⁻¹) ≥ d²σ²/N²``, with equality iff ``s = 0``
and ``Σ g_ig_i' = (N/d) I`` (a balanced tight frame of directions). Platonic solids centred on
the target satisfy both — and so do other formations (e.g. the square antiprism), which is the
correction recorded in ``docs/errata.md``.

Posterior CRB (Tichavský et al. 1998) for ``x(k+1) = Ax + Bw`` and TDOA rows with independent
noise: ``J(k) = (A J(k−1)⁻¹ A' + BQB')⁻¹ + Σ_i H_i' R_i⁻¹ H_i`` with ``H_i`` at the true state
(the measurement model is additive Gaussian, so the expectation is over the true trajectory;
computed here along a given trajectory and agent paths).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np

from theory.core.tolerances import INFORMATION_TOL
from theory.tdoa.exact_geometry import exact_direction_rank
from theory.tdoa.measurements import tdoa_jacobians
from theory.tdoa.model import unit_directions

__all__ = [
    "crb_trace",
    "optimal_crb_trace",
    "pcrb_along",
    "platonic_solids",
    "tdoa_fisher",
]


def tdoa_fisher(
    target: np.ndarray,
    positions: np.ndarray,
    pairs: Sequence[tuple[int, int]] | None = None,
    sigma2: float = 1.0,
) -> np.ndarray:
    """Fisher information ``J = G G'/σ²`` of eq. (4.39) (all pairs ``i < j`` by default).

    Parameters
    ----------
    target : ndarray, shape (d,)
    positions : ndarray, shape (N, d)
    pairs : sequence of (int, int), optional
        0-based pairs ``I`` used for estimation (4.40); default all ``N(N−1)/2`` pairs.
    sigma2 : float
        Measurement variance ``σ_v²``.

    Returns
    -------
    ndarray, shape (d, d)

    References
    ----------
    seed 000, eqs. (4.38)–(4.42).
    """
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
    """``tr(J⁻¹)`` of eq. (4.43); ``inf`` when ``J`` is singular (rank below ``d``).

    Singularity is decided exactly when the pairs connect the agents they use (the default, all
    pairs, does): ``rank J = rank G = dim aff{u_j}``
    (:func:`theory.tdoa.exact_geometry.exact_direction_rank`, coordinates as written), so a
    near-singular but full-rank geometry gets its finite (huge) trace ``σ² Σ 1/s_i²`` from the
    singular values ``s_i`` of ``G`` (not of ``J = G Gᵀ/σ²``, which would square their ratio).
    For other pair sets it is the float test ``λ_min ≤ information_tol · λ_max``.

    Parameters
    ----------
    target : ndarray, shape (d,)
    positions : ndarray, shape (N, d)
    pairs : sequence of (int, int), optional
        0-based pairs used (default all).
    sigma2 : float
        Measurement variance ``σ_v²``.

    Returns
    -------
    float
    """
    pairs = list(itertools.combinations(range(len(positions)), 2)) if pairs is None else pairs
    nodes = _connected_nodes(pairs)
    if nodes is None:
        eig = np.linalg.eigvalsh(tdoa_fisher(target, positions, pairs, sigma2))
        if eig[-1] <= 0 or eig[0] <= INFORMATION_TOL * eig[-1]:
            return float("inf")
        return float(np.sum(1.0 / eig))
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
    """The lower bound ``d²σ²/N²`` of ``tr(J⁻¹)`` over all formations (complete pair set).

    Parameters
    ----------
    n_agents : int
        ``N``.
    dim : int
        ``d`` (2 or 3).
    sigma2 : float
        Measurement variance ``σ_v²``.

    Returns
    -------
    float
    """
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
    """Posterior CRB matrices ``J(k)⁻¹`` along a trajectory (every agent's TDOA rows).

    Parameters
    ----------
    truth : ndarray, shape (K+1, n)
        True states at the pings.
    positions : ndarray, shape (K+1, N, d)
        Agent positions at the pings.
    neighbours : sequence of sequences of ndarray
        ``neighbours[k][i]``: 0-based neighbours heard by agent ``i`` at ping ``k``.
    A, BQB : ndarray
        Transition and process-noise covariance.
    r : float
        TDOA variance (``R_i = r I``).
    P0 : ndarray
        Prior covariance (``J(−1)⁻¹``, predicted to ping 0 unchanged).

    Returns
    -------
    ndarray, shape (K+1, n, n)
        The bound on the error covariance of any estimator at each ping.
    """
    dim = positions.shape[2]
    out = np.empty((truth.shape[0], *P0.shape))
    predicted = P0
    for k in range(truth.shape[0]):
        H = np.vstack(tdoa_jacobians(truth[k, :dim], positions[k], list(neighbours[k])))
        info = np.linalg.inv(predicted) + H.T @ H / r
        out[k] = np.linalg.inv(info)
        predicted = A @ out[k] @ A.T + BQB
    return out
