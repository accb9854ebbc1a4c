"""Optimal planar formations: uniform arrays reach the Fisher bounds, but not only they."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from theory.registry import get_claim
from theory.tdoa.geometry.crb import crb_trace, optimal_crb_trace, range_crb_trace, unit_circle

bearings = st.lists(st.floats(0, 360, allow_nan=False), min_size=3, max_size=8)
polygons = st.lists(st.tuples(st.integers(3, 5), st.floats(0, 360)), min_size=1, max_size=3)


def _union(parts: list[tuple[int, float]]) -> list[float]:
    """Bearings of regular k-gons, each turned by its own angle."""
    return [turn + 360 * j / k for k, turn in parts for j in range(k)]


@given(bearings)
def test_the_range_bound_holds_with_equality_iff_the_double_angles_cancel(degrees):
    ratio = range_crb_trace(unit_circle(degrees)) * len(degrees) / 4
    resultant = abs(np.exp(2j * np.radians(degrees)).sum()) / len(degrees)
    assert ratio >= 1 - 1e-9
    if resultant < 1e-9:
        assert abs(ratio - 1) < 1e-6
    if resultant > 1e-3:
        assert ratio > 1 + 1e-7


@given(bearings)
def test_the_tdoa_bound_holds_for_every_formation(degrees):
    assert crb_trace(np.zeros(2), unit_circle(degrees)) >= optimal_crb_trace(len(degrees), 2) * (
        1 - 1e-9
    )


@given(polygons)
def test_turned_regular_polygons_reach_both_bounds(parts):
    """Any union of regular polygons (uniform only by accident) is optimal for range and TDOA."""
    degrees = _union(parts)
    positions = unit_circle(degrees)
    assert abs(range_crb_trace(positions) * len(degrees) / 4 - 1) < 1e-9
    bound = optimal_crb_trace(len(degrees), 2)
    assert abs(crb_trace(np.zeros(2), positions) / bound - 1) < 1e-9


def test_the_claims_are_corrected_with_non_uniform_optima():
    for claim in ("seed003.result3", "seed000.sec4.3.1.uniform-array"):
        (result,) = get_claim(claim).run(None)
        assert result.status == "corrected" and result.margin < 1e-9
        assert result.evidence["optimal_non_uniform"]
        for name in result.evidence["optimal_non_uniform"]:
            assert not result.evidence["formations"][name]["uniform"]
