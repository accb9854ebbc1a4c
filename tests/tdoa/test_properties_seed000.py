"""The TDOA domain's new properties (issue 27): their strategies draw the classes the papers
state, and their counterexamples are what the mathematics says they are."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from theory.falsify import DEFAULT_EXAMPLES, falsify
from theory.registry import properties_for
from theory.tdoa.estimation.stability import corrected_bound, printed_bound
from theory.tdoa.properties import (
    _ratio,
    frame_deviation,
    is_platonic,
    is_uniform_array,
    lemma_a11_holds,
    stochastic_networks,
)
from theory.tdoa.strategies import formations


@given(stochastic_networks())
def test_weights_are_any_stochastic_matrix_on_the_links(W: np.ndarray) -> None:
    assert np.allclose(W.sum(axis=1), 1) and (np.diag(W) > 0).all() and (W >= 0).all()


@given(st.sampled_from((2, 3)).flatmap(lambda d: formations(dim=d, family="uniform")))
def test_uniform_arrays_and_platonic_solids_reach_the_bound(directions: np.ndarray) -> None:
    assert np.allclose(np.linalg.norm(directions, axis=1), 1)
    assert abs(_ratio(directions, tdoa=True) - 1) < 1e-9
    assert frame_deviation(directions) < 1e-9
    named = is_uniform_array if directions.shape[1] == 2 else is_platonic
    assert named(directions)


@given(formations(dim=2, family="degenerate"))
def test_collinear_formations_have_no_finite_bound(directions: np.ndarray) -> None:
    assert _ratio(directions, tdoa=True) == float("inf")


def test_optimal_formations_beyond_the_named_ones() -> None:
    """The shrunk counterexamples to §4.3.1 and Result 3 reach the bound and are not named."""
    for claim, named, tdoa in (
        ("seed000.sec4.3.1.uniform-array", is_uniform_array, True),
        ("seed000.sec4.3.1.platonic", is_platonic, True),
        ("seed003.result3", is_uniform_array, False),
    ):
        (paper,) = [p for p in properties_for(claim) if p.wording == "paper"]
        found = falsify(paper, examples=DEFAULT_EXAMPLES, seed=0).counterexample
        assert abs(_ratio(found, tdoa) - 1) < 1e-9 and not named(found), claim


def test_lemma_a11_counterexample_is_short_by_mu_over_v_min() -> None:
    (paper,) = properties_for("seed000.lemA.1.1/paper")
    p = falsify(paper, examples=DEFAULT_EXAMPLES, seed=0).counterexample
    assert lemma_a11_holds(p, corrected_bound) and not lemma_a11_holds(p, printed_bound)
    constants = {"v_min": p.v_min, "v_max": p.v_max, "mu": p.mu, "alpha": p.alpha}
    gap = corrected_bound(1, mean_square_0=Fraction(0), **constants) - printed_bound(
        1, mean_square_0=Fraction(0), **constants
    )
    assert gap == p.mu / p.v_min
