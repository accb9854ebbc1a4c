"""The compiled engine (theory/pursuit/kernels.py, compiled_run.py, compiled_replay.py) against
the NumPy reference.

Each kernel computes the same formulas as the NumPy function it replaces, in another order of
operations: the vector field and the DEKF step agree to rounding (relative 1e-9), and whole runs
agree to the integrator's error tolerance (positions and localization errors within rtol·scale,
γ and attitude within 2·rtol, the tolerance the speed-up's regression test holds the integrator
to, tests/pursuit/test_closed_loop.py), with the same stop, over random cases of seed 003 §V.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from dec_loops import dec_loop, random_state
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from theory.core.engines import ENGINE_SETTING, NUMBA_MIN_RECORDS, compiled, resolve_engine
from theory.core.errors import CaseError
from theory.kinds import load_case
from theory.pursuit import kernels
from theory.pursuit.closed_loop import heun_step, simulate_dec
from theory.pursuit.compiled_replay import replay_compiled
from theory.pursuit.compiled_run import loop_arrays
from theory.pursuit.dekf import dekf_step, range_dekf, transition_matrix
from theory.pursuit.strategies import simulated_pursuit_cases

ROUNDING = 1e-9
"""Relative agreement of a kernel and its NumPy twin (the same arithmetic in another order)."""

REPLAY = 1e-6
"""Relative agreement of the two DEKF replays over 40 instants (rounding carried by the EKF)."""

RECORDS = 150
"""Records (15 s) of each random run compared."""


def _loop(spec, steps=RECORDS):
    return dec_loop(spec, steps)


def _close(got, want, what):
    scale = max(1.0, float(np.max(np.abs(want))))
    np.testing.assert_allclose(got, want, rtol=0, atol=ROUNDING * scale, err_msg=what)


SLOW_CASES = settings(
    max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True
)


@SLOW_CASES
@given(case=simulated_pursuit_cases(), seed=st.integers(0, 2**32 - 1))
def test_rates_and_step_equal_the_numpy_loop(case, seed) -> None:
    """kernels.rates is DecLoop.rates (eqs. (2)–(5), (45)–(51)) and kernels.heun_step is
    closed_loop.heun_step, at random states and estimates, to rounding."""
    _, loop = _loop(case.spec)
    rng = np.random.default_rng(seed)
    state = random_state(loop, rng)
    x_hat, t, t_hat, h = rng.normal(0, 20, (loop.n, 2 * loop.dim)), 3.7, 2.0, 0.05
    arrays = loop_arrays(loop)
    z_dot, omega = loop.rates(t, state, x_hat, t_hat)
    got = kernels.rates(t, state.z, state.R, x_hat, t_hat, arrays)
    _close(got[0], z_dot, "ż")
    _close(got[1], omega, "ω")
    stepped, error = heun_step(loop, loop.rates, t, h, state, (z_dot, omega), (x_hat, t_hat))
    z2, R2, error2 = kernels.heun_step(t, h, state.z, state.R, z_dot, omega, x_hat, t_hat, arrays)
    _close(z2, stepped.z, "z after a step")
    _close(R2, stepped.R, "R after a step")
    assert error2 == pytest.approx(error, rel=ROUNDING, abs=ROUNDING)


@SLOW_CASES
@given(
    n=st.integers(1, 4), dim=st.sampled_from([2, 3]), seed=st.integers(0, 2**32 - 1),
    weight=st.floats(0.1, 0.9), predictions=st.integers(1, 3),
)  # fmt: skip
def test_dekf_kernel_equals_algorithm_2(n, dim, seed, weight, predictions) -> None:
    """kernels.dekf_step is dekf.dekf_step (seed 003 Algorithm 2, eqs. (41)–(44)) to rounding."""
    rng = np.random.default_rng(seed)
    m = 2 * dim
    factors = rng.normal(0, 1, (n, m, m))
    Omega = factors @ np.swapaxes(factors, 1, 2) + np.eye(m)
    x_pred, positions = rng.normal(0, 30, (n, m)), rng.normal(0, 30, (n, dim))
    ranges = np.abs(rng.normal(40, 10, n))
    fusion = (1 - weight) * np.eye(n) + weight * np.roll(np.eye(n), 1, axis=1)
    F, W = transition_matrix(dim, 2.0), np.diag(rng.uniform(10, 1e4, m))
    want = dekf_step(
        x_pred, Omega, positions, ranges, fusion=fusion, F=F, W=W, V=4.0, predictions=predictions
    )
    got = kernels.dekf_step(x_pred, Omega, positions, ranges, fusion, F, W, 4.0, predictions)
    for name, a, b in zip(("x̂", "Ω", "Ω_next", "x̂_next"), got, want, strict=True):
        _close(a, b, name)


@SLOW_CASES
@given(
    n=st.integers(1, 4), dim=st.sampled_from([2, 3]), seed=st.integers(0, 2**32 - 1),
    V=st.floats(0.1, 100), weight=st.floats(0.1, 0.9), predictions=st.sampled_from([1, 20]),
)  # fmt: skip
def test_compiled_replay_equals_range_dekf(n, dim, seed, V, weight, predictions) -> None:
    """The compiled replay is dekf.range_dekf (Algorithm 2 on given geometry, innovations of (10),
    (41)) on the same noise over 40 instants of random tracker and target paths, predicting once or
    20 times per T_s (``predict_every``; Q per T_s/20 a twentieth of Q per T_s, as with 20 times
    Q per T_s this random-walk target is so weakly observed that a 1e-15 relative change of the
    input alone moves NumPy's estimates by 0.5 m in 40 instants): each step agrees
    to rounding (test above), and the EKF's linearization at its own estimate carries a step's
    rounding into the next ones, most where one tracker leaves a 3-D target weakly observable
    (2e-9 of the scale seen), so the runs agree to REPLAY of the scale; a wrong formula, order or
    noise draw is off by the scale itself."""
    rng = np.random.default_rng(seed)
    steps, m = 40, 2 * dim
    target = np.cumsum(rng.normal(0, 2, (steps, m)), axis=0)
    trackers = target[:, None, :dim] + rng.uniform(10, 60, (steps, n, dim))
    arguments = {
        "Ts": 2.0, "noise_var": 0.25, "V": V, "predictions": predictions,
        "Q": np.diag(rng.uniform(1e-4, 1e-1, m)) / predictions,
        "fusion": (1 - weight) * np.eye(n) + weight * np.roll(np.eye(n), 1, axis=1),
        "x0": target[0] + rng.normal(0, 3, m), "P0": rng.uniform(1, 50) * np.eye(m),
    }  # fmt: skip
    want = range_dekf(trackers, target, rng=np.random.default_rng(seed), **arguments)
    got = replay_compiled(trackers, target, rng=np.random.default_rng(seed), **arguments)
    for field in dataclasses.fields(want):
        expected = getattr(want, field.name)
        scale = max(1.0, float(np.max(np.abs(expected))))
        np.testing.assert_allclose(
            getattr(got, field.name), expected, rtol=0, atol=REPLAY * scale, err_msg=field.name
        )


def _assert_same_run(fast, slow, scale, rtol) -> None:
    """The records agree to the integrator's tolerance and the runs stop alike."""
    assert fast.stop_cause == slow.stop_cause
    np.testing.assert_array_equal(np.isnan(fast.gammas), np.isnan(slow.gammas))
    for key in ("positions", "localization_errors", "pursuit_errors"):
        np.testing.assert_allclose(
            getattr(fast, key), getattr(slow, key), rtol=0, atol=rtol * scale, err_msg=key
        )
    for key in ("gammas", "headings"):
        np.testing.assert_allclose(
            getattr(fast, key), getattr(slow, key), rtol=0, atol=2 * rtol, err_msg=key
        )


@SLOW_CASES
@given(case=simulated_pursuit_cases(), seed=st.integers(0, 2**32 - 1))
def test_engines_agree_along_random_runs(case, seed) -> None:
    """Both engines integrate random initial conditions and gains to the same trajectory, within
    the integrator's tolerance (rtol·scale in position, 2·rtol in γ and heading)."""
    arguments, loop = _loop(case.spec)
    runs = [
        simulate_dec(rng=np.random.default_rng(seed), engine=engine, **arguments)
        for engine in ("numba", "numpy")
    ]
    _assert_same_run(*runs, loop.scale, arguments["settings"].rtol)


@pytest.mark.parametrize(
    ("name", "seed", "cause"),
    [
        ("pursuit-table1-n3", 2, ""),
        ("pursuit-table2-n1", 2, ""),
        ("pursuit-table2-n1", 9, "runaway"),
    ],
)
def test_engines_agree_on_table_cases_and_a_runaway(name, seed, cause) -> None:
    """200 s of Table cases agree between the engines, stop included: pursuit-table2-n1 with
    ``default_rng(9)`` runs away at 50 s (its one-range DEKF loses the target)."""
    arguments, loop = _loop(load_case(name).spec, steps=2000)
    fast, slow = (
        simulate_dec(rng=np.random.default_rng(seed), engine=engine, **arguments)
        for engine in ("numba", "numpy")
    )
    assert fast.stop_cause == cause
    _assert_same_run(fast, slow, loop.scale, arguments["settings"].rtol)
    assert fast.stop_reason == slow.stop_reason
    np.testing.assert_equal(fast.stopped_at, slow.stopped_at)


def test_engines_agree_when_the_dekf_predicts_every_step() -> None:
    """The published cases' DEKF predicts 20 times per T_s (F and W per 0.1 s): both engines."""
    arguments, loop = _loop(load_case("pursuit-table1-n3").spec, steps=300)
    arguments["settings"] = dataclasses.replace(arguments["settings"], predictions=20)
    fast, slow = (
        simulate_dec(rng=np.random.default_rng(3), engine=engine, **arguments)
        for engine in ("numba", "numpy")
    )
    _assert_same_run(fast, slow, loop.scale, arguments["settings"].rtol)


def test_a_step_floor_stops_both_engines_alike() -> None:
    """A step floor above every step the loop needs stops both engines at the same record with
    the same message."""
    arguments, _ = _loop(load_case("pursuit-table1-n3").spec, steps=50)
    arguments["settings"] = dataclasses.replace(arguments["settings"], min_step=0.09, rtol=1e-9)
    fast, slow = (
        simulate_dec(rng=np.random.default_rng(0), engine=engine, **arguments)
        for engine in ("numba", "numpy")
    )
    assert fast.stop_cause == slow.stop_cause == "step_floor"
    assert (fast.stopped_at, fast.stop_reason) == (slow.stopped_at, slow.stop_reason)


def test_engine_choice(monkeypatch) -> None:
    """The keyword wins, then $TRACKCERT_ENGINE, then numba; an unknown name is a CaseError
    naming where it came from and the engines."""
    monkeypatch.delenv(ENGINE_SETTING, raising=False)
    assert resolve_engine() == "numba"
    monkeypatch.setenv(ENGINE_SETTING, "numpy")
    assert resolve_engine() == "numpy"
    assert resolve_engine("numba") == "numba"
    monkeypatch.setenv(ENGINE_SETTING, "fortran")
    with pytest.raises(CaseError, match=f"{ENGINE_SETTING}.*numba or numpy.*fortran"):
        resolve_engine()
    with pytest.raises(CaseError, match=r"engine.*'numba' or 'numpy'.*'cuda'"):
        resolve_engine("cuda")


def test_a_short_job_runs_on_the_numpy_engine_unless_told(monkeypatch) -> None:
    """Without a choice, fewer than NUMBA_MIN_RECORDS records of work run on NumPy (numba's
    import and cache load would cost more than the run); the keyword and the setting still win."""
    monkeypatch.delenv(ENGINE_SETTING, raising=False)
    assert resolve_engine(records=NUMBA_MIN_RECORDS - 1) == "numpy"
    assert resolve_engine(records=NUMBA_MIN_RECORDS) == "numba"
    assert resolve_engine("numba", records=1) == "numba"
    monkeypatch.setenv(ENGINE_SETTING, "numba")
    assert resolve_engine(records=1) == "numba"
    monkeypatch.setenv(ENGINE_SETTING, "numpy")
    assert resolve_engine(records=10**6) == "numpy"


def test_without_a_writable_cache_folder_the_kernels_compile_in_memory(monkeypatch) -> None:
    """No cache locator applies (numba: "cannot cache function … no locator available"): the
    kernel is compiled without the on-disk cache and computes the same."""
    from numba.core.caching import CacheImpl

    monkeypatch.setattr(CacheImpl, "_locator_classes", [])
    kernel = compiled(kernels._etd_weights.py_func)
    assert not kernel._cache.__class__.__name__ == "FunctionCache"
    assert kernel(500.0, 0.01) == kernels._etd_weights(500.0, 0.01)


@pytest.mark.parametrize(
    "command",
    [
        ["simulate", "pursuit-table1-n3", "--steps", "10", "--runs", "2", "--workers", "2"],
        ["sweep", "pursuit-table1-n3", "-p", "k_c=0.1,0.2", "--steps", "10", "--workers", "2"],
    ],
)
def test_a_bad_engine_setting_is_bad_input_before_any_work(command, monkeypatch, tmp_path):
    """``TRACKCERT_ENGINE=fortran``: exit 2 naming the setting, no traceback, nothing written."""
    from typer.testing import CliRunner

    from theory.cli import app

    monkeypatch.setenv(ENGINE_SETTING, "fortran")
    out = tmp_path / "out"
    result = CliRunner().invoke(app, [*command, "-o", str(out)])
    assert result.exit_code == 2, result.output
    assert f"'{ENGINE_SETTING}': expected numba or numpy, got 'fortran'" in result.output
    assert "Traceback" not in result.output
    assert not out.exists()
