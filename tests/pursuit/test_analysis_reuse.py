"""A sweep point's work done once: the ISS analysis memoised per spec, the Theorem 2 estimate
evaluated on a whole run at once, and a summary without files skipping the DEKF metrics — each
giving what the work done afresh, record by record, gives (seed 003 Theorem 2)."""

from __future__ import annotations

import gc
import math
import weakref
from dataclasses import replace

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from theory.kinds import load_case
from theory.pursuit.iss import (
    coordination_iss,
    iss_bound,
    iss_conditions,
    pursuit_iss,
    strongly_connected,
)
from theory.pursuit.simulation import iss_margin_along, run_pursuit_case, summarize_pursuit
from theory.strategies import pursuit_cases

METRIC_COLUMNS = {"anees", "nees_verdict", "mean_nis", "nis_verdict", "mean_ospa"}
"""The per-tracker columns of the DEKF metrics (theory.core.consistency.agent_columns)."""


def _fresh(spec):
    """An equal spec that is another object: the memo cannot answer for it."""
    return replace(spec)


@given(case=pursuit_cases())
def test_memoised_analysis_equals_a_fresh_one(case) -> None:
    """Asked twice, the analysis answers with what a fresh spec of the same data computes."""
    spec = case.spec
    first = iss_conditions(spec)
    again, fresh = iss_conditions(spec), iss_conditions(_fresh(spec))
    assert first == again == fresh
    assert pursuit_iss(spec) is pursuit_iss(spec)
    assert repr(pursuit_iss(spec)) == repr(pursuit_iss(_fresh(spec)))
    if spec.n_trackers > 1:
        assert repr(coordination_iss(spec)) == repr(coordination_iss(_fresh(spec)))


def test_memo_depends_on_the_options_and_lets_specs_go() -> None:
    """A different margin tolerance is a different entry; a dropped spec leaves the memo."""
    spec = _fresh(load_case("pursuit-table1-n3").spec)
    loose = iss_conditions(spec, margin_tol=1.1)
    assert [c.status for c in loose] != [c.status for c in iss_conditions(spec)]
    assert iss_conditions(spec, margin_tol=1.1) == loose
    iss_conditions(spec).append(None)  # the caller's list, not the memo's
    assert None not in iss_conditions(spec)
    gone = weakref.ref(spec)
    del spec, loose
    gc.collect()
    assert gone() is None


def _beta_by_formula(constants: dict, controller: str, n: int, r: float, t: float) -> float:
    """β(r, t) of seed 003 Theorem 2 (corrected) written out with math.exp at one time t."""
    lam = constants["lambda"]
    if n == 1:
        return r * math.exp(-lam * t)
    alpha, kappa = constants["alpha"], constants["kappa"]
    if controller == "I":
        return r * (kappa * math.exp(-alpha * t) + math.exp(-lam * t))
    coupling = constants["b"] / math.sqrt(constants["r_min"])

    def phi(s: float) -> float:
        if math.isclose(alpha, lam, rel_tol=1e-12):
            return s * math.exp(-alpha * s)
        return (math.exp(-lam * s) - math.exp(-alpha * s)) / (alpha - lam)

    same = math.isclose(alpha, lam, rel_tol=1e-12)
    peak = 1 / alpha if same else math.log(alpha / lam) / (alpha - lam)
    psi = phi(peak) if t <= peak else phi(t)
    return r * (kappa * math.exp(-alpha * t) + coupling * psi + math.exp(-lam * t))


@settings(max_examples=30)
@given(case=pursuit_cases())
def test_estimate_on_arrays_equals_the_formula_at_each_time(case) -> None:
    """β and γ on an array of times equal the written-out formula at each time (to rounding)."""
    spec = case.spec
    try:
        estimate = iss_bound(spec)
    except ValueError:  # a condition fails: there is no estimate
        return
    times = np.linspace(0.0, 60.0, 241)
    errors = np.linspace(0.0, 30.0, 241)
    beta, gamma = estimate.beta(7.5, times), estimate.gamma(errors)
    constants, n = estimate.constants, spec.n_trackers
    expected = [_beta_by_formula(constants, spec.controller, n, 7.5, t) for t in times]
    np.testing.assert_allclose(beta, expected, rtol=1e-13, atol=0)
    np.testing.assert_allclose(gamma, estimate.gain * errors, rtol=1e-15, atol=0)
    assert isinstance(estimate.beta(7.5, 1.0), float)


def test_estimate_along_a_run_equals_record_by_record() -> None:
    """The estimate along a Table I run equals β + γ evaluated record by record."""
    spec = load_case("pursuit-table1-n3").spec
    run = run_pursuit_case(spec, np.random.default_rng(0), steps=600)
    along = iss_margin_along(spec, run)
    estimate = iss_bound(spec)
    sup = np.maximum.accumulate(along.x_tilde)
    by_record = [
        float(estimate.beta(along.mu[0], float(t))) + float(estimate.gamma(float(s)))
        for t, s in zip(run.times, sup, strict=True)
    ]
    np.testing.assert_allclose(along.bound, by_record, rtol=1e-15, atol=0)
    assert along.holds


def test_summary_without_metrics_is_the_summary_less_the_metrics() -> None:
    """metrics=False drops exactly the DEKF metrics and their columns, nothing else changes."""
    spec = load_case("pursuit-table1-n1").spec
    runs = [run_pursuit_case(spec, np.random.default_rng(s), steps=300) for s in (0, 1)]
    full, light = summarize_pursuit(spec, runs), summarize_pursuit(spec, runs, metrics=False)
    assert full["metrics"] is not None and light["metrics"] is None
    rest = [{k: v for k, v in s.items() if k not in ("agents", "metrics")} for s in (full, light)]
    np.testing.assert_equal(*rest)  # NaN equals NaN: run 1 runs away
    for shown, kept in zip(full["agents"], light["agents"], strict=True):
        assert METRIC_COLUMNS & set(shown)
        np.testing.assert_equal({k: v for k, v in shown.items() if k not in METRIC_COLUMNS}, kept)


@given(n=st.integers(1, 8), density=st.floats(0.0, 0.7), seed=st.integers(0, 2**32 - 1))
def test_strong_connectivity_equals_scipys(n: int, density: float, seed: int) -> None:
    """The search that replaced scipy.sparse.csgraph (a 17 ms import) decides as it does, on
    random digraphs connected or not."""
    from scipy.sparse.csgraph import connected_components

    adjacency = np.random.default_rng(seed).random((n, n)) < density
    np.fill_diagonal(adjacency, False)
    expected = connected_components(adjacency, connection="strong")[0] == 1
    assert strongly_connected(adjacency) == expected
