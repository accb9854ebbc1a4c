"""Window observability of the TDOA error dynamics (seed 000 §4.2.1, seed 001 after eq. (16))."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st

from theory.core.observability import numeric_rank
from theory.registry import get_claim
from theory.tdoa.observability.window import SCENES, mirror_gap, window_observability

coordinate = st.floats(-20, 20, allow_nan=False)
point = st.tuples(coordinate, coordinate, coordinate).map(np.array)


def _fixed(points: np.ndarray):
    return lambda t: points


@given(st.lists(point, min_size=2, max_size=2), point, point)
def test_two_static_receivers_never_see_the_rotation_about_their_baseline(pair, start, velocity):
    """Rotating (q0, v) about the baseline leaves every TDOA unchanged: an exact null vector."""
    receivers = np.array(pair)
    axis = receivers[1] - receivers[0]
    assume(np.linalg.norm(axis) > 1)
    track = start + np.arange(20)[:, None] * velocity
    assume(min(np.linalg.norm(np.cross(q - receivers[0], axis)) for q in track) > 1)
    window, frozen = window_observability(
        _fixed(receivers), start=start, velocity=velocity, pings=20
    )
    axis /= np.linalg.norm(axis)
    null = np.concatenate([np.cross(axis, start - receivers[0]), np.cross(axis, velocity)])
    assume(np.linalg.norm(null) > 1e-3)
    assert np.linalg.norm(window @ null) <= 1e-9 * np.linalg.norm(window) * np.linalg.norm(null)
    assert frozen <= 2


@given(st.lists(point, min_size=3, max_size=3), point, point)
def test_three_static_receivers_are_blind_to_the_mirror_image(triple, start, velocity):
    receivers = np.array(triple)
    normal = np.cross(receivers[1] - receivers[0], receivers[2] - receivers[0])
    assume(np.linalg.norm(normal) > 1)
    track = start + np.arange(20)[:, None] * velocity
    assume(min(np.min(np.linalg.norm(q - receivers, axis=1)) for q in track) > 1)
    gap = mirror_gap(_fixed(receivers), start=start, velocity=velocity, pings=20)
    assert gap <= 1e-9 * (1 + np.abs(track).max() + np.abs(receivers).max())
    _, frozen = window_observability(_fixed(receivers), start=start, velocity=velocity, pings=20)
    assert frozen <= 4  # two TDOA rows: the papers' frozen-pair bound


def test_the_claim_is_corrected_with_the_predicted_ranks():
    (result,) = get_claim("seed000.eq4.16.window").run(None)
    assert result.status == "corrected" and result.margin > 1e3
    scenes = result.evidence["scenes"]
    assert {n: s["window_rank"] for n, s in scenes.items()} == {
        n: predicted for n, (_, predicted) in SCENES.items()
    }
    static3 = scenes["3 static receivers (2 TDOA rows)"]
    assert static3["frozen_pair_rank_max"] == 4 and static3["window_rank"] == 6
    assert result.evidence["mirror_tdoa_gap_3_static"] == 0.0


def test_a_static_target_gives_no_window_gain():
    """Without motion H(k) is constant: the window adds nothing to the frozen pair."""
    receivers, _ = SCENES["3 static receivers (2 TDOA rows)"]
    window, frozen = window_observability(receivers, velocity=np.zeros(3), pings=30)
    assert numeric_rank(window).rank == frozen == 4
