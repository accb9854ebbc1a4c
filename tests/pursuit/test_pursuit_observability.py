"""seed003.eq15.helix and seed003.result2: range-only observability of seed 003's tracker paths.

The claims are run once per module. Hypothesis draws stay away from the degenerate sets by stated
distances and skip the (rare) draws whose rank decision falls inside the tolerance band, so no
test can be flaky.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given
from hypothesis import strategies as st

from theory.core.observability import numeric_rank
from theory.pursuit import observability as po
from theory.registry import get_claim

RADII = st.floats(10.0, 200.0)
PHASES = st.floats(0.0, 2 * math.pi)
DEGENERATE_DISTANCE = 0.05
"""Draws of c keep |c|, |c − 1| and |c + 1| above this (the task's band around {−1, 0, 1})."""


def away_from_degenerate(c: float) -> bool:
    return min(abs(c), abs(c - 1), abs(c + 1)) > DEGENERATE_DISTANCE


@pytest.fixture(scope="module")
def helix_result():
    (result,) = get_claim("seed003.eq15.helix").run(None)
    return result


@pytest.fixture(scope="module")
def result2():
    (result,) = get_claim("seed003.result2").run(None)
    return result


def test_claims_are_registered_at_import() -> None:
    helix = get_claim("seed003.eq15.helix")
    pair = get_claim("seed003.result2")
    assert helix.check is po.check_helix and helix.kinds == ()
    assert pair.check is po.check_result2 and pair.kinds == ()
    assert "seed 003 eq. (15)" in helix.source and "eq. (13)" in pair.source


# ---------------------------------------------------------------------------------------------
# seed003.eq15.helix


def test_helix_claim_is_corrected(helix_result) -> None:
    r = helix_result
    assert (r.claim, r.case, r.method, r.status) == (
        "seed003.eq15.helix",
        "-",
        "symbolic",
        "corrected",
    )
    assert set(r.tolerance) == {"rank_tol", "inconclusive_factor", "mirror_tol"}
    assert r.margin >= po.INCONCLUSIVE_FACTOR
    per_c = r.evidence["per_c"]
    for c, entry in per_c.items():
        planar = c in ("1", "-1")
        assert entry["symbolic"]["planar"] is planar
        assert entry["fim"]["rank"] == (4 if planar else 6) and entry["fim"]["of"] == 6
        assert entry["fim"]["conclusive"]
    for c in ("1", "-1"):
        assert per_c[c]["symbolic"]["det_three_points"] == "0"
        assert per_c[c]["mirror_pair"]["relative_gap"] <= po.MIRROR_TOL
    assert per_c["2"]["mirror_pair"]["relative_gap"] > 1e-2
    assert r.evidence["wronskian_is_rxryrz_(1-1/c^2)_sin(gamma/c+gamma0)"]
    assert set(r.evidence["sampled_aliases_fim_rank"].values()) == {4}
    json.dumps(r.to_json(source="seed 003 eq. (15)"))


def test_wronskian_vanishes_exactly_at_c_squared_one() -> None:
    wronskian, matches = po.helix_wronskian()
    assert matches
    c = next(s for s in wronskian.free_symbols if s.name == "c")
    for value in (1, -1):
        assert sp.simplify(wronskian.subs(c, value)) == 0
    for value in (2, -2, sp.Rational(1, 2), sp.Rational(-3, 7)):
        assert sp.simplify(wronskian.subs(c, value)) != 0


def test_planar_witnesses_are_exactly_nonzero() -> None:
    r_x, r_y, r_z = sp.symbols("r_x r_y r_z", positive=True)
    for c in (2, -2, Fraction(1, 2)):
        evidence = po.helix_planarity(c)
        assert not evidence["planar"]
        det = sp.sympify(evidence["det_three_points"], locals={"r_x": r_x, "r_y": r_y, "r_z": r_z})
        assert det.subs({r_x: 1, r_y: 1, r_z: 1}).evalf() != 0


def test_planar_normal_annihilates_the_sampled_orbit() -> None:
    """The symbolic normal for c = −1, evaluated at Table II and a phase, is ⊥ every sample."""
    gamma0 = 0.7
    _, relative = po.helix_samples(-1.0, gamma0=gamma0)
    r_x, r_y, r_z = (po.TABLE_II_PATH[k] for k in ("r_x", "r_y", "r_z"))
    normal = np.array(
        [-r_y * r_z * math.sin(2 * gamma0), r_x * r_z * math.cos(2 * gamma0), r_x * r_y]
    )
    normal /= np.linalg.norm(normal)
    assert np.max(np.abs(relative @ normal)) <= 1e-12 * np.max(np.abs(relative))


@given(
    c=st.floats(-20.0, 20.0).filter(away_from_degenerate),
    r_x=RADII,
    r_y=RADII,
    r_z=RADII,
    gamma0=PHASES,
)
def test_fim_has_full_rank_away_from_plus_minus_one(c, r_x, r_y, r_z, gamma0) -> None:
    rank = po.helix_fim_rank(c, r_x=r_x, r_y=r_y, r_z=r_z, gamma0=gamma0)
    assume(rank.conclusive(po.INCONCLUSIVE_FACTOR))
    assert rank.rank == 6


@given(sign=st.sampled_from([1.0, -1.0]), r_x=RADII, r_y=RADII, r_z=RADII, gamma0=PHASES)
def test_fim_has_rank_four_and_a_mirror_twin_at_plus_minus_one(sign, r_x, r_y, r_z, gamma0) -> None:
    radii = {"r_x": r_x, "r_y": r_y, "r_z": r_z, "gamma0": gamma0}
    rank = po.helix_fim_rank(sign, **radii)
    assume(rank.conclusive(po.INCONCLUSIVE_FACTOR))
    assert rank.rank == 4
    assert po.mirror_range_gap(sign, **radii)["relative_gap"] <= po.MIRROR_TOL


def test_sampled_aliases_are_planar_and_neighbours_are_not() -> None:
    theta = po.TABLE_II_PATH["omega_bar"] * po.SAMPLING_PERIOD
    for c in po.sampled_aliases():
        step = np.exp(1j * theta / c)
        assert min(abs(step - np.exp(1j * theta)), abs(step - np.exp(-1j * theta))) < 1e-12
        assert po.helix_fim_rank(c).rank == 4
        assert po.helix_fim_rank(1.1 * c).rank == 6


def test_helix_verdict_follows_the_mathematics(monkeypatch) -> None:
    """Known-bad inputs: if c = −1 behaved like c = 2 the claim would be verified; if c = 2
    behaved like c = 1 it would be refuted."""
    samples, planarity = po.helix_samples, po.helix_planarity

    def swap(mapping):
        monkeypatch.setattr(po, "helix_samples", lambda c, **kw: samples(mapping.get(c, c), **kw))
        monkeypatch.setattr(po, "helix_planarity", lambda c: planarity(mapping.get(float(c), c)))

    swap({-1.0: 2.0})
    (result,) = get_claim("seed003.eq15.helix").run(None)
    assert result.status == "verified"
    swap({2.0: 1.0})
    (result,) = get_claim("seed003.eq15.helix").run(None)
    assert result.status == "refuted" and "c = 2" in result.message


def test_helix_samples_reject_bad_arguments() -> None:
    with pytest.raises(ValueError, match="c = 0"):
        po.helix_samples(0.0)
    with pytest.raises(ValueError, match="steps"):
        po.helix_samples(2.0, steps=0)
    with pytest.raises(ValueError, match="c = 0"):
        po.helix_planarity(0)


# ---------------------------------------------------------------------------------------------
# the range model


def test_range_jacobian_is_the_gradient_of_the_range() -> None:
    """Central differences of ‖p_k − q₀ − t_k v‖ against −h_k (residual, not a snapshot)."""
    times, relative = po.helix_samples(2.0, steps=50)
    q0, v = np.array([3.0, -2.0, 1.0]), np.array([0.2, 0.1, -0.3])
    tracker = relative + q0 + times[:, None] * v
    H = po.range_jacobian(relative, times)
    step = 1e-6
    for j in range(6):
        delta = np.zeros(6)
        delta[j] = step

        def ranges(d, delta=delta):
            x = np.concatenate([q0, v]) + d * delta
            return np.linalg.norm(tracker - x[:3] - times[:, None] * x[3:], axis=1)

        numeric = (ranges(1) - ranges(-1)) / (2 * step)
        assert np.allclose(numeric, -H[:, j], rtol=0, atol=1e-6 * (1 + times.max()))


def test_fisher_information_is_jacobian_gram_over_sigma_squared() -> None:
    times, relative = po.helix_samples(2.0, steps=30)
    H = po.range_jacobian(relative, times)
    fim = po.fisher_information(relative, times, sigma=2.0)
    assert np.allclose(fim, H.T @ H / 4.0)


def test_range_jacobian_rejects_bad_input() -> None:
    with pytest.raises(ValueError, match="one time per sample"):
        po.range_jacobian(np.ones((3, 2)), np.arange(4.0))
    with pytest.raises(ValueError, match="coincides"):
        po.range_jacobian(np.zeros((1, 2)), np.zeros(1))


def test_squared_range_regressor_reproduces_the_squared_ranges() -> None:
    times = po.SAMPLING_PERIOD * np.arange(60)
    tracker = 20 * np.stack([np.sin(0.05 * times), np.cos(0.05 * times)], axis=1)
    q0, v = np.array([4.0, -1.0]), np.array([0.3, -0.2])
    theta = np.concatenate([q0, v, [q0 @ q0, q0 @ v, v @ v]])
    t = times[:, None]
    unscaled = np.hstack([-2 * tracker, -2 * t * tracker, np.ones_like(t), 2 * t, t**2])
    scaled = po.squared_range_regressor(tracker, times)
    assert np.allclose(scaled * np.linalg.norm(unscaled, axis=0), unscaled)
    target = q0 + t * v
    lhs = np.sum((tracker - target) ** 2, axis=1) - np.sum(tracker**2, axis=1)
    assert np.allclose(unscaled @ theta, lhs)


# ---------------------------------------------------------------------------------------------
# seed003.result2


def test_result2_claim_is_corrected(result2) -> None:
    r = result2
    assert (r.claim, r.case, r.method, r.status) == (
        "seed003.result2",
        "-",
        "symbolic",
        "corrected",
    )
    assert set(r.tolerance) == {"rank_tol", "inconclusive_factor"}
    assert r.margin >= po.INCONCLUSIVE_FACTOR
    assert r.evidence["sufficiency_identity_holds"] == {"2d": True, "3d": True}
    for name, scenario in r.evidence["counterexamples"].items():
        dim = 3 if name.startswith("3d") else 2
        assert scenario["O_coefficient_rank_in_basis_1_t"] == 2
        assert scenario["O_sampled_rank_exact"] == 2 == scenario["O_sampled_rank_numeric"]
        assert scenario["fim_tracker1"]["rank"] == 2 * dim == scenario["fim_both"]["rank"]
        assert scenario["squared_range_regressor_rank"] == 2 * dim + 3
    rest = r.evidence["counterexamples"]["2d_target_at_rest"]
    assert rest["O_t_symbolic"] == "[1, 0, t - t0, 0]"
    formation = r.evidence["paper_formation_N2"]
    assert formation["O_rank"] == 4 and formation["fim_both_rank"] == 4
    json.dumps(r.to_json(source="seed 003 eq. (13)"))


@given(
    radius=st.floats(5.0, 100.0),
    rate=st.floats(0.02, 0.5),
    phase=PHASES,
    centre=st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5)),
    offset=st.tuples(st.floats(-10.0, 10.0), st.floats(-10.0, 10.0)).filter(
        lambda d: math.hypot(*d) > 0.1
    ),
)
def test_constant_offset_pairs_break_only_if(radius, rate, phase, centre, offset) -> None:
    """Any circling tracker 1 with p² = p¹ + constant: (13) is rank-deficient, the FIM is not."""
    times = po.SAMPLING_PERIOD * np.arange(200)
    angle = rate * times + phase
    p1 = radius * (np.array(centre) + np.stack([np.sin(angle), np.cos(angle)], axis=1))
    difference = np.broadcast_to(np.array(offset), p1.shape)  # p² − p¹, exactly
    o_rank = numeric_rank(po.o_matrix(difference, times))
    fim = numeric_rank(po.range_jacobian(p1, times))
    assume(o_rank.conclusive(po.INCONCLUSIVE_FACTOR) and fim.conclusive(po.INCONCLUSIVE_FACTOR))
    assert o_rank.rank == 2 and fim.rank == 4


@given(radius1=RADII, radius2=RADII, phase1=PHASES, phase2=PHASES, rate=st.floats(0.02, 0.5))
def test_independent_columns_give_full_information(radius1, radius2, phase1, phase2, rate) -> None:
    """The direction Result 2 gets right: full-rank (13) ⇒ full-rank FIM of both trackers."""
    times = po.SAMPLING_PERIOD * np.arange(200)
    angle = rate * times
    p1 = radius1 * np.stack([np.cos(angle + phase1), np.sin(angle + phase1)], axis=1)
    p2 = radius2 * np.stack([np.cos(angle + phase2), np.sin(angle + phase2)], axis=1)
    # only pairs meeting (13): this skips p² ≈ p¹, drawn when radii and phases (nearly) coincide
    assume(np.abs(p2 - p1).max() > 1e-6)
    o_rank = numeric_rank(po.o_matrix(p2 - p1, times))
    assume(o_rank.conclusive(po.INCONCLUSIVE_FACTOR) and o_rank.rank == 4)
    both = numeric_rank(po.range_jacobian(np.vstack([p1, p2]), np.concatenate([times, times])))
    assert both.conclusive(po.INCONCLUSIVE_FACTOR) and both.rank == 4
