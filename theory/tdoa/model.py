"""TDOA measurement model and the constant-velocity target (seed 000 eqs. (4.1)–(4.10)).

The target state is ``x = [p; ṗ]`` with ``p ∈ R^d``, ``d ∈ {2, 3}``. Agent ``i`` with neighbours
``N_i = (j_1, …, j_m)`` measures ``h_{i,j} = ‖p − p_i‖ − ‖p − p_j‖`` (eq. 4.4) and its Jacobian
row is ``(p − p_i)/‖p − p_i‖ − (p − p_j)/‖p − p_j‖`` in the position block, zero in the velocity
block (eqs. 4.7–4.10).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

__all__ = [
    "cv_continuous",
    "cv_discrete",
    "cv_discrete_symbolic",
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
    eye, zero = sp.eye(dim), sp.zeros(dim, dim)
    return sp.Matrix(sp.BlockMatrix([[eye, T * eye], [zero, eye]]))


def unit_directions(target: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Rows ``(p − p_i)/‖p − p_i‖``: unit vectors from ``positions`` towards ``target``.

    Parameters
    ----------
    target : ndarray, shape (d,)
        Target position ``p``.
    positions : ndarray, shape (N, d)
        Agent positions ``p_i``, one per row.

    Returns
    -------
    ndarray, shape (N, d)
    """
    diff = np.asarray(target, dtype=float)[None, :] - np.asarray(positions, dtype=float)
    return diff / np.linalg.norm(diff, axis=1, keepdims=True)


def tdoa_measurement(
    target: np.ndarray, positions: np.ndarray, agent: int, neighbours: Sequence[int]
) -> np.ndarray:
    """``h_i(p)`` of eqs. (4.3)–(4.4) at ``target``: range to ``agent`` minus range to neighbours.

    Parameters
    ----------
    target : ndarray, shape (d,)
        Target position ``p``.
    positions : ndarray, shape (N, d)
        Agent positions, one per row.
    agent : int
        The measuring agent ``i`` (index into ``positions``).
    neighbours : Sequence of int
        Its neighbours ``N_i`` (indices into ``positions``), in measurement order.

    Returns
    -------
    ndarray, shape (len(neighbours),)
        ``‖p − p_i‖ − ‖p − p_j‖`` for each ``j`` in ``neighbours``.
    """
    ranges = np.linalg.norm(
        np.asarray(target, float)[None, :] - np.asarray(positions, float), axis=1
    )
    return ranges[agent] - ranges[list(neighbours)]


def tdoa_jacobian(
    target: np.ndarray, positions: np.ndarray, agent: int, neighbours: Sequence[int]
) -> np.ndarray:
    """``H_i`` of eqs. (4.7)–(4.10) at ``target``, shape ``(|N_i|, 2·dim)``.

    Parameters
    ----------
    target : ndarray, shape (d,)
        Target position ``p``.
    positions : ndarray, shape (N, d)
        Agent positions, one per row.
    agent : int
        The measuring agent ``i`` (index into ``positions``).
    neighbours : Sequence of int
        Its neighbours ``N_i`` (indices into ``positions``); one row each, in this order.

    Returns
    -------
    ndarray, shape (len(neighbours), 2 d)
        Position block ``u_i − u_j`` (unit directions, see :func:`unit_directions`); the
        velocity block is zero.
    """
    units = unit_directions(target, positions)
    position_block = units[agent][None, :] - units[list(neighbours)]
    return np.hstack([position_block, np.zeros_like(position_block)])
