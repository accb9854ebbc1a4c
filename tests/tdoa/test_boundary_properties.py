"""Never wrong near a boundary (issue 17): the topology verdicts at 0, 10⁻¹², 10⁻⁹, 10⁻³ from
coplanarity, collinearity, the receivers' plane and the communication range, judged by the
independent exact oracle of :mod:`theory.tdoa.observability.properties`."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given

from theory.tdoa.case import parse_tdoa
from theory.tdoa.observability.properties import (
    FAMILIES,
    BoundaryScene,
    _sqrt_sum_is_zero,
    boundary_scenes,
    invariant,
    moved_scenes,
    never_wrong,
    scene_block,
    truth,
)
from theory.tdoa.observability.topology import analyze_topology

F = Fraction


@pytest.mark.parametrize("family", FAMILIES)
def test_verdicts_are_correct_or_inconclusive(family) -> None:
    @given(boundary_scenes(family))
    def check(scene: BoundaryScene) -> None:
        assert never_wrong(scene), truth(scene)

    check()


def _complete(n):
    return tuple((i, j) for i in range(1, n + 1) for j in range(i + 1, n + 1))


def _plane_scene(delta: Fraction) -> BoundaryScene:
    agents = ((F(0), F(0), F(0)), (F(5), F(0), F(0)), (F(0), F(5), F(0)), (F(3), F(4), delta))
    return BoundaryScene("plane", delta, agents, (F(1), F(2), F(7)), _complete(4))


@pytest.mark.parametrize("k", [3, 9, 12])
def test_fourth_agent_a_hair_off_the_plane_is_not_coplanar(k) -> None:
    """Regression: at 10⁻⁹ and 10⁻¹² the float hull called these agents coplanar and the
    target mirror-ambiguous; exactly, they are neither."""
    scene = _plane_scene(F(1, 10**k))
    result = analyze_topology(parse_tdoa(scene_block(scene)))
    assert all(a.heuristic_4_noncoplanar and not a.mirror_ambiguous for a in result.agents)
    assert never_wrong(scene, result)


def test_fourth_agent_on_the_plane_is_coplanar_and_mirror_ambiguous() -> None:
    result = analyze_topology(parse_tdoa(scene_block(_plane_scene(F(0)))))
    assert all(not a.heuristic_4_noncoplanar and a.mirror_ambiguous for a in result.agents)
    assert result.agents[0].mirror_point == (1.0, 2.0, -7.0)


@pytest.mark.parametrize("k", [9, 12])
def test_target_a_hair_above_the_receivers_plane_is_inconclusive_not_wrong(k) -> None:
    """Exactly observable (full rank) but ill-conditioned: exit 3, never a confident verdict."""
    agents = ((F(0), F(0), F(0)), (F(5), F(0), F(0)), (F(0), F(5), F(0)), (F(4), F(6), F(0)))
    scene = BoundaryScene("mirror", F(1, 10**k), agents, (F(1), F(1), F(1, 10**k)), _complete(4))
    result = analyze_topology(parse_tdoa(scene_block(scene)))
    assert truth(scene)["observable"] == [True] * 4
    assert not result.conclusive and "ill-conditioned" in result.inconclusive[0]
    assert all(a.observable and a.mirror_ambiguous for a in result.agents)


def test_target_in_the_receivers_plane_is_exactly_unobservable() -> None:
    agents = ((F(0), F(0), F(0)), (F(5), F(0), F(0)), (F(0), F(5), F(0)), (F(4), F(6), F(0)))
    scene = BoundaryScene("mirror", F(0), agents, (F(1), F(1), F(0)), _complete(4))
    result = analyze_topology(parse_tdoa(scene_block(scene)))
    assert result.conclusive and not any(a.observable for a in result.agents)
    assert not any(a.mirror_ambiguous for a in result.agents)


@pytest.mark.parametrize(("delta", "linked"), [(F(0), False), (F(1, 10**12), True)])
def test_a_pair_at_exactly_the_range_is_not_linked(delta, linked) -> None:
    """Strict ``<`` on the decimals written: 0.3 and 0.7 apart by exactly 0.4 (not in floats)."""
    agents = ((F(3, 10), F(0)), (F(7, 10), F(0)))
    scene = BoundaryScene("split", delta, agents, (F(1, 2), F(3)), None, F(4, 10) + delta)
    result = analyze_topology(parse_tdoa(scene_block(scene)))
    assert (result.agents[0].component == result.agents[1].component) == linked


def test_oracle_sums_of_square_roots() -> None:
    p = 2**61 - 1
    assert _sqrt_sum_is_zero([(F(1), F(8)), (F(-2), F(2))])
    assert _sqrt_sum_is_zero([(F(1), F(2 * p * p)), (F(-p), F(2))])
    assert not _sqrt_sum_is_zero([(F(1), F(2)), (F(1), F(3)), (F(-1), F(5))])
    assert not _sqrt_sum_is_zero([(F(1), F(10**24 + 1, 10**24)), (F(-1), F(1))])


@given(moved_scenes())
def test_rational_motions_keep_every_boundary_verdict(example) -> None:
    assert invariant(example)
