"""Hypothesis strategies for seed 002's claims: DCRW parameters over the whole parameter space of
eqs. (3.1)–(3.2), and 2-D measurement stars (a node, its TDOA neighbours, a target) in general
position and in the degenerate positions the statement allows."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.particle.case import DcrwParams

__all__ = ["STAR_FAMILIES", "MeasurementStar", "dcrw_parameters", "measurement_stars"]

STAR_FAMILIES = ("general", "collinear-nodes", "target-on-a-node-line")
"""The ``family`` values of :func:`measurement_stars`."""


def dcrw_parameters() -> st.SearchStrategy[DcrwParams]:
    """Any ``(μ, γ, κ, λ)`` of eqs. (3.1)–(3.2): ``μ ∈ (−π, π]``, ``γ ∈ [0, 0.99]`` (``γ → 1``
    is a point mass), ``κ ∈ [0.3, 10]``, ``λ ∈ [0.01, 100]``."""
    return st.builds(
        DcrwParams,
        st.floats(-np.pi, np.pi),
        st.floats(0.0, 0.99),
        st.floats(0.3, 10.0),
        st.floats(-2.0, 2.0).map(lambda e: float(10.0**e)),
    )


@dataclass(frozen=True, eq=False)
class MeasurementStar:
    """A node (row 0 of ``nodes``), the neighbours it takes TDOA measurements with (rows 1…),
    and the target, in integer coordinates (exact); ``family`` of :data:`STAR_FAMILIES`."""

    target: tuple[int, int]
    nodes: tuple[tuple[int, int], ...]
    family: str

    @property
    def measurements(self) -> int:
        """The node's TDOA measurements: one per neighbour."""
        return len(self.nodes) - 1


def _point(draw: st.DrawFn) -> tuple[int, int]:
    return (draw(st.integers(-20, 20)), draw(st.integers(-20, 20)))


def measurement_stars(*, family: str | None = None) -> st.SearchStrategy[MeasurementStar]:
    """A node with 0–3 TDOA neighbours and a target (seed 002 §3.1): distinct nodes, none on
    the target.

    ``general``: any integer points; ``collinear-nodes``: the nodes on one line;
    ``target-on-a-node-line``: the target on the line through two nodes, outside their segment
    (both see it in the same direction). ``None``: any family. ``InvalidArgument`` for another
    ``family``."""
    if family is not None and family not in STAR_FAMILIES:
        raise InvalidArgument(f"family={family!r}; expected one of {STAR_FAMILIES} or None")
    return _stars(family).filter(
        lambda s: s.target not in s.nodes and len(set(s.nodes)) == len(s.nodes)
    )


@st.composite
def _stars(draw: st.DrawFn, family: str | None) -> MeasurementStar:
    family = draw(st.sampled_from(STAR_FAMILIES)) if family is None else family
    count = draw(st.integers(1, 4))
    target = _point(draw)
    if family == "collinear-nodes":
        base, step = _point(draw), _point(draw)
        nodes = [(base[0] + k * step[0], base[1] + k * step[1]) for k in draw(_distinct(count))]
    else:
        nodes = [_point(draw) for _ in range(count)]
        if family == "target-on-a-node-line" and count >= 2:
            a, b, t = nodes[0], nodes[1], draw(st.integers(1, 3))
            target = (a[0] + t * (a[0] - b[0]), a[1] + t * (a[1] - b[1]))
    return MeasurementStar(target, tuple(nodes), family)


def _distinct(count: int) -> st.SearchStrategy[list[int]]:
    return st.lists(st.integers(-4, 4), min_size=count, max_size=count, unique=True)
