"""Necessary conditions (seed 000 Thm 5.2.10, W-detectability, blind sets) against the LMI."""

from __future__ import annotations

import control
import numpy as np
from hypothesis import assume, event, given
from hypothesis import strategies as st

from theory.consensus.conditions import (
    necessary_conditions,
    schur_stable,
    self_weight_bounds,
    source_components,
    unobservable_partition,
    w_detectability,
)
from theory.consensus.s_detectability import decide_s_detectability
from theory.core.observability import numeric_rank, unobservable_eigenvalues
from theory.kinds import load_case
from theory.strategies import dkf_problems


def test_example_1_radii_and_bounds_to_printed_digits():
    s = load_case("ch5-example-1-wg").spec
    bounds = self_weight_bounds(s.A, s.C, s.W)
    assert [round(b.radius, 4) for b in bounds] == [2.0, 2.0, 0.0]
    assert [b.bound for b in bounds[:2]] == [0.25, 0.25]
    assert [c.agents for c in source_components(s.A, s.C, s.W)] == [(1, 2), (3,)]


def test_example_2_radius_and_bound_to_printed_digits():
    s = load_case("ch5-example-2-wg").spec
    third = self_weight_bounds(s.A, s.C, s.W)[2]
    assert round(third.radius, 4) == 1.7205
    assert round(third.bound, 4) == 0.3378
    assert third.unobservable_dim == 2


def test_boundary_weight_numeric_inconclusive_exact_decides():
    """W_c: w_ii r² = 0.25 · 4 = 1 exactly: floats cannot tell, exact arithmetic can (violated)."""
    s = load_case("ch5-example-1-wc").spec
    bounds = self_weight_bounds(s.A, s.C, s.W)[:2]
    assert [b.numeric_ok for b in bounds] == [None, None]
    assert [b.exact_ok for b in bounds] == [False, False]
    assert [b.ok for b in bounds] == [False, False]


@given(dkf_problems(max_states=4, max_agents=4, integer_data=True))
def test_exact_self_weight_agrees_with_numeric_when_conclusive(problem):
    for bound in self_weight_bounds(problem.A, problem.C, problem.W):
        if bound.numeric_ok is not None:
            assert bound.exact_ok == bound.numeric_ok


@given(st.lists(st.fractions(-3, 3, max_denominator=7), min_size=1, max_size=6), st.fractions(1, 3))
def test_schur_cohn_matches_numpy_roots(lower, lead):
    coefficients = [*lower, lead]
    roots = np.roots([float(c) for c in reversed(coefficients)])
    largest = max(abs(roots)) if roots.size else 0.0
    assume(abs(largest - 1) > 1e-6)
    assert schur_stable(coefficients) == bool(largest < 1)


@given(dkf_problems(max_states=4, max_agents=3, integer_data=True))
def test_kalman_decomposition_matches_pbh_and_python_control(problem):
    for Ci in problem.C:
        split = unobservable_partition(problem.A, Ci)
        if Ci.shape[0]:
            assert split.rank == numeric_rank(np.asarray(control.obsv(problem.A, Ci))).rank
        assert split.invariance_residual <= 1e-9
        ours = np.sort_complex(np.linalg.eigvals(split.A_u)) if split.A_u.size else []
        pbh = np.sort_complex(np.array(unobservable_eigenvalues(problem.A, Ci)))
        if split.rank_margin > 1e3 and len(pbh) == len(ours):
            assert np.allclose(ours, pbh, atol=1e-6)


@given(dkf_problems(max_states=3, max_agents=4, integer_data=True))
def test_w_detectability_equals_detectable_sources(problem):
    """With w_ii > 0, every (A, O_i) is detectable iff every source component is (docs Lemma 4)."""
    A, C, W = problem.A, problem.C, problem.W
    sources = [s.detectable for s in source_components(A, C, W)]
    w_det = w_detectability(A, C, W)
    if None not in sources and None not in w_det:
        assert all(sources) == all(w_det)


@given(dkf_problems(max_states=3, max_agents=4))
def test_blind_set_condition_implies_the_papers(problem):
    cond = necessary_conditions(problem.A, problem.C, problem.W)
    if cond.blind_set_condition is True:
        assert cond.paper_conditions is not False


@given(dkf_problems(max_states=3, max_agents=4, a_bound=1.3))
def test_lmi_feasible_implies_every_necessary_condition(problem):
    A, C, W = problem.A, problem.C, problem.W
    result = decide_s_detectability(A, C, W)
    cond = necessary_conditions(A, C, W)
    event(f"lmi={result.verdict} paper={cond.paper_conditions} blind={cond.blind_set_condition}")
    if result.verdict is True:
        assert cond.paper_conditions is not False
        assert cond.blind_set_condition is not False
        assert False not in w_detectability(A, C, W)


def test_blind_cycle_case_separates_the_conditions():
    s = load_case("ch5-blind-cycle").spec
    cond = necessary_conditions(s.A, s.C, s.W)
    assert cond.paper_conditions is True
    assert cond.blind_set_condition is False
    assert decide_s_detectability(s.A, s.C, s.W).verdict is False
