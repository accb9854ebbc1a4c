"""TDOA measurement model and the constant-velocity target (seed 000 eqs. (4.1)–(4.10)).

The target state is ``x = [p; ṗ]`` with ``p ∈ R^d``, ``d ∈ {2, 3}``. Agent ``i`` with neighbours
``N_i = (j_1, …, j_m)`` measures ``h_{i,j} = ‖p − p_i‖ − ‖p − p_j‖`` (eq. 4.4) and its Jacobian
row is ``(p − p_i)/‖p − p_i‖ − (p − p_j)/‖p − p_j‖`` in the position block, zero in the velocity
block (eqs. 4.7–4.10). Seed 002 writes the same model for its particle filter (eqs. (3.6)–(3.9)).

This module is the only implementation of that model. Its functions broadcast over the leading
axes of the evaluation points and of the measuring agents, so that one call serves

* one agent at one point (the EKF of seed 000 eqs. (4.11)–(4.15), the observability checks):
  ``tdoa_measurement(p, positions, i, N_i)``;
* every agent at its own estimate (the network filters of :mod:`theory.tdoa.filters`):
  ``range_differences(points, positions, np.arange(N))`` with ``points`` of shape ``(N, d)``;
* every filtering node at each of its particles (seed 002 eq. (3.9),
  :mod:`theory.particle.filter`): ``range_differences(particles, nodes, filters[:, None])``
  with ``particles`` of shape ``(F, P, d)``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import sympy as sp

__all__ = [
    "cv_continuous",
    "cv_discrete",
    "cv_discrete_symbolic",
    "range_difference_gradients",
    "range_differences",
    "ranges",
    "tdoa_jacobian",
    "tdoa_measurement",
    "unit_directions",
]


def cv_continuous(dim: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """Continuous-time constant-velocity model ``(F, G)`` in ``dim`` dimensions.

    Seed 000 eq. (4.1).
    """
    eye, zero = np.eye(dim), np.zeros((dim, dim))
    F = np.block([[zero, eye], [zero, zero]])
    G = np.vstack([zero, eye])
    return F, G


def cv_discrete(T: float, dim: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """Discrete-time model ``(A, B)``, period ``T``, ``dim`` dimensions (seed 000 eqs. (4.5)–(4.6)).

    Parameters
    ----------
    T : float
        Sampling period.
    dim : int
        Spatial dimension ``d``.

    Returns
    -------
    A : ndarray, shape (2 dim, 2 dim)
        ``exp(F T)``, exactly (F is nilpotent).
    B : ndarray, shape (2 dim, dim)
        ``[T²/2 I; T I]``.
    """
    eye, zero = np.eye(dim), np.zeros((dim, dim))
    A = np.block([[eye, T * eye], [zero, eye]])
    B = np.vstack([0.5 * T**2 * eye, T * eye])
    return A, B


def cv_discrete_symbolic(T: sp.Expr, dim: int = 3) -> sp.Matrix:
    """The matrix ``A`` of eq. (4.6) with a symbolic sampling period ``T`` in ``dim`` dimensions.

    Parameters
    ----------
    T : sympy.Expr
        Symbolic sampling period.
    dim : int
        Spatial dimension ``d``.

    Returns
    -------
    sympy.Matrix, shape (2 dim, 2 dim)
    """
    import sympy as sp

    eye, zero = sp.eye(dim), sp.zeros(dim, dim)
    return sp.Matrix(sp.BlockMatrix([[eye, T * eye], [zero, eye]]))


def ranges(points: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Distances ``‖p − p_j‖`` from every point to every agent position.

    Parameters
    ----------
    points : ndarray, shape (..., d)
        Evaluation points ``p`` (any leading shape).
    positions : ndarray, shape (N, d)
        Agent positions ``p_j``, one per row.

    Returns
    -------
    ndarray, shape (..., N)

    References
    ----------
    seed 000, eq. (4.4); seed 002, eq. (3.9).
    """
    return np.linalg.norm(_offsets(points, positions), axis=-1)


def unit_directions(target: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Rows ``(p − p_i)/‖p − p_i‖``: unit vectors from ``positions`` towards ``target``.

    Parameters
    ----------
    target : ndarray, shape (..., d)
        Target position ``p`` (any leading shape: one point, or one per agent or particle).
    positions : ndarray, shape (N, d)
        Agent positions ``p_i``, one per row.

    Returns
    -------
    ndarray, shape (..., N, d)

    References
    ----------
    seed 000, eqs. (4.8)–(4.10), (4.42).
    """
    diff = _offsets(target, positions)
    return diff / np.linalg.norm(diff, axis=-1, keepdims=True)


def range_differences(
    points: np.ndarray, positions: np.ndarray, agents: int | np.ndarray
) -> np.ndarray:
    """``h_{a,j}(p) = ‖p − p_a‖ − ‖p − p_j‖`` of measuring agent ``a`` against every agent ``j``.

    Parameters
    ----------
    points : ndarray, shape (..., d)
        Evaluation points ``p``.
    positions : ndarray, shape (N, d)
        Agent positions.
    agents : int or ndarray of int
        The measuring agent ``a`` (index into ``positions``), broadcast against the leading
        shape of ``points`` (e.g. one per point, or one per row of particles).

    Returns
    -------
    ndarray, shape (S..., N)
        ``S`` is the broadcast of ``points.shape[:-1]`` and ``agents``'s shape; entry ``j`` is
        the TDOA of the pair ``(a, j)`` (0 for ``j = a``). An agent's measurement vector
        ``h_a`` of eq. (4.3) is the sub-vector over its neighbours ``N_a``.

    References
    ----------
    seed 000, eqs. (4.3)–(4.4); seed 002, eq. (3.9).
    """
    distances = ranges(points, positions)
    return _own(distances, agents, tail=0) - distances


def range_difference_gradients(
    points: np.ndarray, positions: np.ndarray, agents: int | np.ndarray
) -> np.ndarray:
    """``∂h_{a,j}/∂p = u_a − u_j`` (``u_i`` of :func:`unit_directions`) against every agent ``j``.

    Parameters
    ----------
    points, positions, agents : ndarray, ndarray, int or ndarray of int
        As in :func:`range_differences`.

    Returns
    -------
    ndarray, shape (S..., N, d)
        Row ``j`` is the position block of the Jacobian row of the pair ``(a, j)``.

    References
    ----------
    seed 000, eqs. (4.7)–(4.10), (4.41)–(4.42).
    """
    units = unit_directions(points, positions)
    return _own(units, agents, tail=1) - units


def tdoa_measurement(
    target: np.ndarray, positions: np.ndarray, agent: int | np.ndarray, neighbours: Sequence[int]
) -> np.ndarray:
    """``h_i(p)`` of eqs. (4.3)–(4.4) at ``target``: range to ``agent`` minus range to neighbours.

    Parameters
    ----------
    target : ndarray, shape (..., d)
        Target position ``p`` (leading axes broadcast as in :func:`range_differences`).
    positions : ndarray, shape (N, d)
        Agent positions, one per row.
    agent : int or ndarray of int
        The measuring agent ``i`` (index into ``positions``).
    neighbours : Sequence of int
        Its neighbours ``N_i`` (indices into ``positions``), in measurement order.

    Returns
    -------
    ndarray, shape (..., len(neighbours))
        ``‖p − p_i‖ − ‖p − p_j‖`` for each ``j`` in ``neighbours``.
    """
    return range_differences(target, positions, agent)[..., _index(neighbours)]


def tdoa_jacobian(
    target: np.ndarray, positions: np.ndarray, agent: int | np.ndarray, neighbours: Sequence[int]
) -> np.ndarray:
    """``H_i`` of eqs. (4.7)–(4.10) at ``target``, shape ``(|N_i|, 2·dim)``.

    Parameters
    ----------
    target, positions, agent, neighbours : ndarray, ndarray, int, sequence of int
        As in :func:`tdoa_measurement` (one Jacobian row per neighbour, in this order).

    Returns
    -------
    ndarray, shape (..., len(neighbours), 2 d)
        Position block ``u_i − u_j`` (:func:`range_difference_gradients`); the velocity block
        is zero.
    """
    position_block = range_difference_gradients(target, positions, agent)[
        ..., _index(neighbours), :
    ]
    return np.concatenate([position_block, np.zeros_like(position_block)], axis=-1)


def _offsets(points: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """``p − p_j`` for every point and position, shape ``(..., N, d)``."""
    return np.asarray(points, dtype=float)[..., None, :] - np.asarray(positions, dtype=float)


def _own(values: np.ndarray, agents: int | np.ndarray, *, tail: int) -> np.ndarray:
    """The measuring agent's entry of ``values`` (axis ``−1 − tail`` runs over agents), kept as an
    axis of length 1 and broadcast against the leading shape of ``agents``."""
    lead = np.broadcast_shapes(values.shape[: values.ndim - 1 - tail], np.shape(agents))
    full = np.broadcast_to(values, lead + values.shape[values.ndim - 1 - tail :])
    index = np.broadcast_to(np.asarray(agents, dtype=int), lead)
    index = index.reshape(lead + (1,) * (1 + tail))
    return np.take_along_axis(full, index, axis=-1 - tail)


def _index(neighbours: Sequence[int]) -> np.ndarray:
    """``neighbours`` as an integer index array (empty sequences allowed)."""
    return np.asarray(list(neighbours), dtype=int)
