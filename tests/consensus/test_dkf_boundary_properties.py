"""Seed 000 ch. 5 near its thresholds (issue 17 item 1): the registered boundary properties of
:mod:`theory.consensus.properties` in CI's bounded profile, their independent truths
checked against the closed forms, and the claims whose bands became exact decisions."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given

from theory.consensus.analysis import riccati_converges
from theory.consensus.properties import (
    ScaledProblem,
    SelfWeightPoint,
    projected_self_weight,
    scaling_consistent,
    self_weight_truth,
    unit_circle_problem,
)
from theory.consensus.s_detectability import decide_s_detectability
from theory.consensus.strategies import DkfProblem
from theory.core.claims import NotApplicable
from theory.kinds import parse_case
from theory.registry import all_properties, get_claim

PROPERTIES = {
    p.id: p
    for p in all_properties()
    if p.id.startswith(("seed000.def5.2.4", "seed000.lem5.2.2"))
    and any(k in p.id for k in ("boundary", "unit-circle", "scal"))
}


def test_the_boundary_properties_are_registered_for_falsify() -> None:
    assert set(PROPERTIES) == {
        "seed000.def5.2.4.boundary/corrected",
        "seed000.lem5.2.2.boundary/corrected",
        "seed000.def5.2.4.unit-circle/corrected",
        "seed000.def5.2.4.scaling/corrected",
    }


@pytest.mark.parametrize("name", sorted(PROPERTIES))
def test_boundary_property_holds(name: str) -> None:
    prop = PROPERTIES[name]

    @given(example=prop.examples)
    def run(example) -> None:
        assert prop.holds(example), prop.to_case(example)

    run()


def test_truths_are_the_closed_forms() -> None:
    """4w < 1 (Example 1) and w·1.7205² < 1, i.e. w < 4·10⁶/11840481 (Example 2), on the
    decimals as written; 0.249999999 sums with 0.750000001 to exactly 1, so nothing moves."""
    assert projected_self_weight(SelfWeightPoint("example 1", 0.249999999)) == Fraction(
        249999999, 10**9
    )
    assert self_weight_truth(SelfWeightPoint("example 1", 0.249999999))
    assert not self_weight_truth(SelfWeightPoint("example 1", 0.25))
    threshold = Fraction(4 * 10**6, 11840481)
    below, above = float(threshold) * (1 - 1e-12), float(threshold) * (1 + 1e-12)
    assert self_weight_truth(SelfWeightPoint("example 2", below))
    assert not self_weight_truth(SelfWeightPoint("example 2", above))


@pytest.mark.parametrize("lam", [0.9999999999999999, 1.0, -1.0, 1.0000000000000002, -0.999999999])
def test_unit_circle_mode_is_decided_exactly(lam: float) -> None:
    problem = unit_circle_problem(lam)
    result = decide_s_detectability(problem.A, list(problem.C), problem.W)
    assert result.verdict is (abs(Fraction(repr(lam))) < 1)


def test_similarity_and_noise_scaling_on_example_1() -> None:
    """Example 1 at w = 0.249999999 and at 0.25 in sheared coordinates with Q, R scaled by 1000."""
    C = (np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2))
    for w in (0.249999999, 0.25):
        W = np.array([[w, 1 - w, 0], [1 - w, w, 0], [0, 0, 1]])
        problem = DkfProblem(0, 2 * np.eye(2), C, W, tuple(np.zeros((2, c.shape[0])) for c in C))
        assert scaling_consistent(ScaledProblem(problem, 1e3, np.array([[1, 2], [0, 1]])))


def _case(W: list) -> object:
    return parse_case(
        {
            "name": "lemma-boundary",
            "kind": "dkf",
            "dkf": {
                "A": [[2, 0], [0, 2]],
                "C": [[[1, 0]], [[0, 1]], [[1, 0], [0, 1]]],
                "W": W,
                "Q": [[0.1, 0], [0, 0.1]],
                "R": [[[0.1]], [[0.1]], [[0.1, 0], [0, 0.1]]],
                "L": [[[2], [0]], [[0], [2]], [[2, 0], [0, 2]]],
            },
        }
    )


def test_lemma_522_lyapunov_side_is_exact_next_to_one() -> None:
    """r_σ(L) = 4w = 1 − 4e-9 with the case's gains: inside the old 1e-6 band, decided now."""
    case = _case([[0.249999999, 0.750000001, 0], [0.750000001, 0.249999999, 0], [0, 0, 1]])
    (result,) = get_claim("seed000.lem5.2.2").run(case)
    assert result.status == "verified"
    assert result.evidence["lyapunov_characterization"] is True
    assert result.evidence["lyapunov_exact"] is True


def test_lemma_a21_hypothesis_is_exact_on_the_boundary() -> None:
    """r_σ(J) = 4w = 1 exactly at w = 1/4: the hypothesis fails, decided exactly (it used to be
    'within hypothesis_tol of 1: undecided')."""
    with pytest.raises(NotApplicable, match="decided exactly"):
        get_claim("seed000.lemA.2.1").run(_case([[0.25, 0.75, 0], [0.75, 0.25, 0], [0, 0, 1]]))


@pytest.mark.parametrize(
    ("status", "verdict", "expected"),
    [
        ("converged", True, True),
        ("max_iter", True, None),  # a budget that ran out decides nothing
        ("diverged", True, None),  # against a positive certificate: a float artifact
        ("max_iter", False, False),  # footnote 5: not S-detectable ⇒ unbounded
        ("converged", False, False),
        ("converged", None, None),
    ],
)
def test_riccati_converges_rests_on_the_exact_verdict(status, verdict, expected) -> None:
    assert riccati_converges(status, verdict) is expected
