"""The vectorized DEC simulator against its oracles (seed 003 §V; theory.pursuit.closed_loop).

* the stacked vector field equals the per-tracker model (:func:`model.closed_loop_rates`);
* a short run with the vectorized field equals the run with the per-tracker field (1e-9);
* one sampling interval of the adaptive integrator agrees with DOP853 at rtol 1e-11;
* Table II with k_γ = 5, which the held-input scheme of 0.02 s drove to NaN, stays bounded.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from dec_oracle import dop853_interval, per_tracker_field

from theory.core.case_file import load_case, parse_case
from theory.pursuit.closed_loop import (
    LoopState,
    StepControl,
    build_loop,
    integrate_until,
    simulate_dec,
)
from theory.pursuit.simulation import dec_arguments

TABLES = ("pursuit-table1-n1", "pursuit-table1-n3", "pursuit-table2-n1", "pursuit-table2-n3")
REL_TOL = 1e-9
"""Vectorized against per-tracker: the same arithmetic in another order."""


def _type_i(spec):
    return dataclasses.replace(spec, controller="I")


def _loop(spec, steps=20):
    arguments = dec_arguments(spec, steps)
    loop = build_loop(
        arguments["settings"], arguments["paths"], arguments["in_neighbours"], spec.dim
    )
    return arguments, loop


def _random_state(loop, rng):
    n, d = loop.n, loop.dim
    angles = rng.uniform(-np.pi, np.pi, (n, 1 if d == 2 else 3))
    from theory.pursuit.model import exp_skew

    return LoopState.of(
        rng.uniform(-60, 60, (n, d)), exp_skew(angles), rng.uniform(-5, 5, n), rng.normal(0, 0.3, n)
    )


@pytest.mark.parametrize("name", TABLES)
@pytest.mark.parametrize("controller", ["I", "II"])
def test_stacked_field_equals_per_tracker_model(name: str, controller: str) -> None:
    spec = load_case(name).spec
    spec = spec if controller == "II" else _type_i(spec)
    arguments, loop = _loop(spec)
    reference = per_tracker_field(loop, arguments["paths"], controller)
    rng = np.random.default_rng(7)
    for _ in range(5):
        state = _random_state(loop, rng)
        if controller == "I":
            state.e_gamma[:] = 0.0
        x_hat = rng.normal(0, 20, (loop.n, 2 * loop.dim))
        fast, slow = loop.rates(3.0, state, x_hat, 1.0), reference(3.0, state, x_hat, 1.0)
        for a, b in zip(fast, slow, strict=True):
            np.testing.assert_allclose(a, b, rtol=REL_TOL, atol=REL_TOL * np.abs(b).max())


@pytest.mark.parametrize("name", ["pursuit-table1-n3", "pursuit-table2-n3"])
def test_vectorized_run_equals_per_tracker_run(name: str) -> None:
    """The regression oracle: same records, to 1e-9 relative, over 4 s (two DEKF samples)."""
    spec = load_case(name).spec
    arguments, loop = _loop(spec, steps=40)
    fast = simulate_dec(rng=np.random.default_rng(2), **arguments)
    field = per_tracker_field(loop, arguments["paths"], spec.controller)
    slow = simulate_dec(rng=np.random.default_rng(2), field=field, **arguments)
    assert (fast.steps, fast.rejected) == (slow.steps, slow.rejected)
    for key in ("positions", "pursuit_errors", "localization_errors", "gammas", "gamma_errors"):
        np.testing.assert_allclose(getattr(fast, key), getattr(slow, key), rtol=REL_TOL, atol=1e-9)


@pytest.mark.parametrize("name", TABLES)
def test_one_interval_agrees_with_dop853(name: str) -> None:
    """From the case's initial state and estimate, 2 s (the sharpest transient: turn rates up to
    30 rad/s) of the adaptive integrator against DOP853 at rtol 1e-11: positions within
    rtol·(largest semi-axis), attitude entries and γ within 2·rtol (measured: 3 mm, 2.5e-4 and
    8e-5 at the default rtol 3e-4; the global error falls in proportion to rtol)."""
    spec = load_case(name).spec
    arguments, loop = _loop(spec)
    settings = arguments["settings"]
    state = LoopState.of(
        arguments["initial_positions"],
        build_rotation(arguments["initial_headings"], spec.dim),
        arguments["initial_gammas"],
        np.zeros(spec.n_trackers),
    )
    x_hat = np.broadcast_to(arguments["x0"], (spec.n_trackers, 2 * spec.dim)).copy()
    reference = dop853_interval(loop, state, 0.0, 2.0, (x_hat, 0.0))
    control, current = StepControl(settings.dt, settings.dt), state
    for k in range(20):
        current, _, _, _ = integrate_until(
            loop, loop.rates, 0.1 * k, 0.1 * (k + 1), current, (x_hat, 0.0), control, settings
        )
    assert np.abs(current.p - reference.p).max() <= settings.rtol * loop.scale
    assert np.abs(current.R - reference.R).max() <= 2 * settings.rtol
    assert np.abs(current.gamma - reference.gamma).max() <= 2 * settings.rtol


def build_rotation(headings, dim):
    from theory.pursuit.model import euler_rotation, exp_skew

    headings = np.asarray(headings, dtype=float)
    return exp_skew(headings[:, None]) if dim == 2 else euler_rotation(headings)


def test_small_k_gamma_table_ii_stays_bounded() -> None:
    """The disagreement of issue 15: Table II, N = 3, k_γ = 5. The held-input 0.02 s scheme
    reached NaN (~1e116 m); integrated with error control the pursuit errors contract."""
    case = load_case("pursuit-table2-n3")
    spec = dataclasses.replace(case.spec, k_gamma=5.0)
    run = simulate_dec(rng=np.random.default_rng(0), **dec_arguments(spec, 200))
    assert run.completed and np.isfinite(run.pursuit_errors).all()
    assert run.pursuit_errors[-1].max() < 0.5 * run.pursuit_errors[0].max()


def test_a_run_that_needs_too_small_steps_stops_with_nan_records() -> None:
    """min_step: the integration stops (``completed`` false) and later records are NaN."""
    spec = load_case("pursuit-table1-n1").spec
    arguments = dec_arguments(spec, 30)
    arguments["settings"] = dataclasses.replace(arguments["settings"], min_step=0.05)
    run = simulate_dec(rng=np.random.default_rng(0), **arguments)
    assert not run.completed and "below" in run.stop_reason
    assert np.isnan(run.pursuit_errors[-1]).all()


def test_full_gain_and_process_matrices_are_used() -> None:
    """A non-diagonal K_p and Q reach the simulator (not only their diagonals)."""
    case = load_case("pursuit-table1-n1")
    block = {
        "dim": 2, "controller": "II", "omega_bar": 0.05, "epsilon": [-0.5, 0],
        "K_p": [[0.4, 0.1], [0.1, 0.2]], "k_gamma": 500,
        "trackers": [{"r_x": 30, "r_y": 30, "gamma0": 0}],
        "target": {"velocity": [0, 0.3]},
        "dekf": {"Ts": 2, "sigma": 0.5, "V": 10,
                 "Q": [[1e-3, 2e-4, 0, 0], [2e-4, 1e-3, 0, 0], [0, 0, 1e-4, 0], [0, 0, 0, 1e-4]]},
    }  # fmt: skip
    full = parse_case({"name": "full", "kind": "pursuit", "pursuit": block}).spec
    arguments = dec_arguments(full, 5)
    np.testing.assert_array_equal(arguments["settings"].Kp, full.K_p)
    np.testing.assert_array_equal(arguments["settings"].Q, full.dekf.Q)
    assert case.spec.dim == 2


def _held_input_radius(k_gamma: float, k_p: float, r_prime_sq: float, h: float) -> float:
    """Spectral radius of the former held-input step linearized at e = 0 along Rᵀr′:
    x⁺ = (1 − hk_p)x − h‖r′‖y, y⁺ = e^{−k_γh}y + ((1 − e^{−k_γh})/k_γ)‖r′‖x (x = e_p·Rᵀr′/‖r′‖,
    y = e_γ; e_p by forward Euler, e_γ exactly with its input held)."""
    a, b = math.exp(-k_gamma * h), math.sqrt(r_prime_sq)
    step = np.array([[1 - h * k_p, -h * b], [(1 - a) / k_gamma * b, a]])
    return float(np.max(np.abs(np.linalg.eigvals(step))))


def test_held_input_scheme_linearization_explains_the_blowup() -> None:
    """docs/theory/pursuit-iss.md §8: Table II (sup‖r′‖² = 80² + 25² = 7025, k_p = 0.2) with
    k_γ = 5 and h = 0.02 s has radius 1.89 (the NaN run), with k_γ = 200 it has 0.84 (why Table II
    ran at 0.02 s) and 1.87 at h = 0.1 s (why 3-D needed 0.02 s); stability needs h below about
    (k_γ + k_p)/sup‖r′‖² = 7.4e-4 s for k_γ = 5."""
    assert _held_input_radius(5.0, 0.2, 7025.0, 0.02) == pytest.approx(1.891, abs=1e-3)
    assert _held_input_radius(200.0, 0.2, 7025.0, 0.02) == pytest.approx(0.841, abs=1e-3)
    assert _held_input_radius(200.0, 0.2, 7025.0, 0.1) == pytest.approx(1.874, abs=1e-3)
    assert (
        _held_input_radius(5.0, 0.2, 7025.0, 6e-4) < 1 < _held_input_radius(5.0, 0.2, 7025.0, 1e-3)
    )
