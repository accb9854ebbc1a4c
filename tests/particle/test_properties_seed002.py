"""Seed 002's properties (issue 27): the measurement counterexample is the degenerate geometry
of docs/errata.md (§4.1.1), and the ML wordings hold at the reference parameters."""

from __future__ import annotations

from hypothesis import given

from theory.falsify import DEFAULT_EXAMPLES, falsify
from theory.particle.case import DcrwParams
from theory.particle.properties import (
    DcrwDraw,
    distinct_directions,
    fit_deviations,
    local_rank,
)
from theory.particle.strategies import MeasurementStar, measurement_stars
from theory.registry import properties_for


@given(measurement_stars())
def test_stars_have_distinct_nodes_off_the_target(star: MeasurementStar) -> None:
    assert len(set(star.nodes)) == len(star.nodes) and star.target not in star.nodes
    assert local_rank(star) == 2 * min(distinct_directions(star) - 1, 2)


def test_three_non_collinear_nodes_on_a_ray_do_not_localize() -> None:
    (paper,) = properties_for("seed002.sec3.measurements/paper")
    star = falsify(paper, examples=DEFAULT_EXAMPLES, seed=0).counterexample
    (ax, ay), (bx, by), (cx, cy) = star.nodes[:3]
    assert (bx - ax) * (cy - ay) != (by - ay) * (cx - ax)  # non-collinear
    assert distinct_directions(star) == 2 and local_rank(star) == 2


def test_ml_fits_recover_the_reference_parameters() -> None:
    draw = DcrwDraw(DcrwParams(0.4, 0.7, 2.0, 3.0), seed=2)
    for which in ("turn", "step", "path"):
        assert max(fit_deviations(draw, which).values()) < 4, which
