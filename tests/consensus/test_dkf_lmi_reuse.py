"""The LMI built once per support (issue 28 item 4): re-solving with ``W`` as a cvxpy Parameter
decides exactly as a fresh build, and one problem serves every ``W`` of one support."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from theory.consensus.s_detectability import (
    LmiCache,
    decide_s_detectability,
    self_weight_family,
)
from theory.consensus.strategies import dkf_problems, self_weight_examples


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(problem=dkf_problems(max_states=2, max_agents=3, integer_data=True), w=st.floats(0, 1))
def test_reuse_decides_as_a_fresh_build(problem, w: float) -> None:
    cache = LmiCache()
    decide_s_detectability(problem.A, list(problem.C), problem.W, problems=cache)  # warm
    W = self_weight_family(problem.W, [0], w) if problem.W[0, 0] < 1 else problem.W
    fresh = decide_s_detectability(problem.A, list(problem.C), W)
    reused = decide_s_detectability(problem.A, list(problem.C), W, problems=cache)
    assert reused.verdict == fresh.verdict
    assert (reused.certificate is None) == (fresh.certificate is None)


def test_one_problem_per_support() -> None:
    cache = LmiCache()
    verdicts = []
    for w in (0.1, 0.2, 0.24, 0.26, 0.3):
        A, C, W = self_weight_examples("example 1", w)
        verdicts.append(decide_s_detectability(A, C, W, problems=cache).verdict)
    assert verdicts == [True, True, True, False, False] and len(cache) == 1
    A, C, W = self_weight_examples("example 1", 1.0)  # w_12 = 0: another support
    assert decide_s_detectability(A, C, W, problems=cache).verdict is False and len(cache) == 2
    assert np.array_equal(W[0], [1, 0, 0])


def test_a_limited_cache_keeps_the_most_recent_problems() -> None:
    cache = LmiCache(limit=1)
    for w in (0.2, 1.0, 0.2):  # two supports, alternating
        A, C, W = self_weight_examples("example 1", w)
        assert decide_s_detectability(A, C, W, problems=cache).verdict is (w < 0.25)
        assert len(cache) == 1


@settings(max_examples=5, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(w=st.sampled_from([0.1, 0.2, 0.24, 0.26]))
def test_a_reused_problem_gives_the_same_bits_as_a_new_one(w: float) -> None:
    """Results never depend on what the process solved before (a report is byte-identical
    whatever the worker count): the solver keeps no warm start between re-solves."""
    A, C, W = self_weight_examples("example 1", w)
    new = decide_s_detectability(A, C, W, problems=LmiCache())
    warm = LmiCache()
    for other in (0.05, 0.3, 0.15):
        decide_s_detectability(A, C, self_weight_examples("example 1", other)[2], problems=warm)
    again = decide_s_detectability(A, C, W, problems=warm)
    assert again.evidence() == new.evidence()
    assert again.certificate == new.certificate


def test_one_problem_serves_every_self_weight_search_of_a_case(monkeypatch) -> None:
    """analyze_dkf's searches (each agent's family, their w = 0 ends, the joint family) share
    one problem built on the case's support with the diagonal, and answer as searches that
    build their own."""
    from theory.consensus import analysis, s_detectability
    from theory.consensus.design import self_weight_design
    from theory.kinds import load_case

    built = []
    original = s_detectability._build_lmi
    monkeypatch.setattr(
        s_detectability, "_build_lmi", lambda *a: built.append(a[2].copy()) or original(*a)
    )
    case = load_case("ch5-example-1-wg")
    result = analysis.analyze_dkf(case)
    support = (case.spec.W != 0) | np.eye(3, dtype=bool)
    assert len(result.searches) == 3 and len(built) <= 2
    assert any(np.array_equal(b, support) for b in built)
    for search, _ in result.searches:
        alone = self_weight_design(case, agents=[a - 1 for a in search.agents])
        assert (search.status, search.supremum) == (alone.status, alone.supremum)


def test_a_weight_outside_the_caches_support_is_refused() -> None:
    A, C, W = self_weight_examples("example 1", 0.2)
    cache = LmiCache(support=W != 0)
    with pytest.raises(ValueError, match="outside"):
        cache.problem(A, C, np.ones_like(W), 1.0)
