"""Desired formation offsets ``d_i`` of eq. (4.45) (seed 000 §4.3.1, §4.4).

The dissertation asks for "a cube, i.e. a Platonic solid with 8 vertices, with the radius of the
underlying sphere set to 10" and, for the distance rule, a "deformed" formation it does not give.
Choices made here (documented in ``docs/simulation.md``):

* the cube is axis-aligned, its vertices ``(±1, ±1, ±1)·ρ/√3`` (circumradius ``ρ``);
* the deformed formation is a *crown*: 8 points on a horizontal circle of radius ``ρ`` at
  angles ``45°·k``, alternately at heights ``±h``. With ``ρ = 16``, ``h = 5`` and the rule
  "distance < 21", each agent keeps exactly its two ring neighbours (15.8 m away; the next are
  22.6 m away), so the graph is a non-planar 8-cycle and no agent has three TDOA rows;
* agent ``i`` gets the vertex assigned to it by a minimum-total-distance matching between the
  initial positions (relative to their centroid) and the vertices.
"""

from __future__ import annotations

import itertools

import numpy as np
from scipy.optimize import linear_sum_assignment

__all__ = ["assign_offsets", "crown_vertices", "cube_vertices"]


def cube_vertices(radius: float) -> np.ndarray:
    """The 8 vertices of the axis-aligned cube inscribed in a sphere of ``radius``, shape (8, 3)."""
    signs = np.array(list(itertools.product((-1.0, 1.0), repeat=3)))
    return signs * radius / np.sqrt(3.0)


def crown_vertices(n: int, radius: float, height: float) -> np.ndarray:
    """``n`` points on a circle of ``radius`` at heights alternating ``±height``, shape (n, 3).

    Parameters
    ----------
    n : int
        Number of points, at angles ``2πk/n`` (``k = 0, …, n−1``) around the vertical axis.
    radius : float
        Radius ``ρ`` of the horizontal circle.
    height : float
        ``h``: point ``k`` is at height ``+h`` for even ``k`` and ``−h`` for odd ``k``.

    Returns
    -------
    ndarray, shape (n, 3)
    """
    angles = 2.0 * np.pi * np.arange(n) / n
    z = height * np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    return np.column_stack([radius * np.cos(angles), radius * np.sin(angles), z])


def assign_offsets(initial: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Offsets ``d_i``: the vertex matched to each agent (minimum total distance from centroid).

    Parameters
    ----------
    initial : ndarray, shape (N, d)
        Initial agent positions.
    vertices : ndarray, shape (N, d)
        Formation vertices relative to the target.

    Returns
    -------
    ndarray, shape (N, d)
        Row ``i`` is ``d_i``.
    """
    relative = initial - initial.mean(axis=0)
    cost = np.linalg.norm(relative[:, None, :] - vertices[None, :, :], axis=-1)
    rows, cols = linear_sum_assignment(cost)
    offsets = np.empty_like(vertices)
    offsets[rows] = vertices[cols]
    return offsets
