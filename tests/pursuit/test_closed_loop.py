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
from dec_loops import dec_loop, random_state
from dec_oracle import dop853_interval, per_tracker_field

from theory.kinds import load_case, parse_case
from theory.pursuit.closed_loop import (
    LoopState,
    StepControl,
    heun_step,
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
    return dec_loop(spec, steps)


@pytest.mark.parametrize("name", TABLES)
@pytest.mark.parametrize("controller", ["I", "II"])
def test_stacked_field_equals_per_tracker_model(name: str, controller: str) -> None:
    spec = load_case(name).spec
    spec = spec if controller == "II" else _type_i(spec)
    arguments, loop = _loop(spec)
    reference = per_tracker_field(loop, arguments["paths"], controller)
    rng = np.random.default_rng(7)
    for _ in range(5):
        state = random_state(loop, rng)
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
    assert not run.completed and "below" in run.stop_reason and run.stop_cause == "step_floor"
    assert np.isnan(run.pursuit_errors[-1]).all()


def test_a_nan_attitude_is_an_error_not_an_accepted_step() -> None:
    """When the body rates turn NaN at the predicted state, the corrected attitude is NaN while
    positions and γ stay finite: the step's error is NaN (refused, the step shrinks) rather than
    the largest finite difference, which would accept a NaN attitude."""
    spec = load_case("pursuit-table2-n3").spec
    _, loop = _loop(spec)
    state = random_state(loop, np.random.default_rng(3))
    x_hat = np.zeros((loop.n, 2 * loop.dim))

    def field(t, current, x_hat, t_hat):
        z_dot, omega = loop.rates(t, current, x_hat, t_hat)
        return z_dot, omega if t == 0.0 else np.full_like(omega, np.nan)

    rates = field(0.0, state, x_hat, 0.0)
    corrected, error = heun_step(loop, field, 0.0, 0.01, state, rates, (x_hat, 0.0))
    assert np.isfinite(corrected.z).all() and np.isnan(corrected.R).all()
    assert math.isnan(error)


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


RECORDED = {
    "pursuit-table1-n1": {
        "gammas": [[-0.913347318], [0.755600019], [2.757997749]],
        "localization_errors": [[4.465420308], [1.069591003], [1.817239899]],
        "positions": [
            [[11.112186687, -19.752097574]],
            [[10.414779776, 38.557430192]],
            [[-43.556115136, 42.906262781]],
        ],
        "pursuit_errors": [[3.341370818], [0.563392885], [1.503933618]],
        "steps": (2153, 49),
    },
    "pursuit-table1-n3": {
        "gammas": [
            [1.039772402, 1.007750781, 1.028272797],
            [3.02935587, 3.02549471, 3.031289658],
            [5.029209709, 5.033378255, 5.029660027],
        ],
        "localization_errors": [
            [0.475187819, 0.405511475, 0.53473132],
            [0.17834289, 0.15654876, 0.149296781],
            [0.195513981, 0.214370099, 0.253741174],
        ],
        "positions": [
            [
                [10.952560314, 32.193677891],
                [-35.033066072, 7.959095495],
                [9.924925128, -19.777931265],
            ],
            [
                [-41.302541896, 22.075603628],
                [0.045246469, -9.573532083],
                [6.610122157, 41.964823563],
            ],
            [
                [-8.223598432, 1.329400143],
                [3.283954377, 51.954282721],
                [-46.302905365, 36.686325887],
            ],
        ],
        "pursuit_errors": [
            [0.916037695, 1.205614917, 0.819490592],
            [0.412988352, 0.307287103, 0.268341928],
            [0.326247028, 0.186387752, 0.29282489],
        ],
        "steps": (2206, 56),
    },
    "pursuit-table2-n1": {
        "gammas": [[0.001558223], [3.890263127], [7.921234676]],
        "localization_errors": [[4.868990544], [7.570596649], [8.99063302]],
        "positions": [
            [[77.985017811, 12.349004421, -18.174269587]],
            [[-77.480018439, -54.569177004, 10.916640251]],
            [[-31.220190336, 87.208339811, -96.674443686]],
        ],
        "pursuit_errors": [[14.18899648], [8.589332474], [10.796155488]],
        "steps": (2730, 274),
    },
    "pursuit-table2-n3": {
        "gammas": [
            [2.191374894, 2.192197799, 2.208678538],
            [6.204238931, 6.202776099, 6.203531871],
            [10.202309969, 10.207656595, 10.204337548],
        ],
        "localization_errors": [
            [3.615649531, 5.83491204, 1.901137722],
            [1.333890713, 1.716381489, 1.44262581],
            [2.262721642, 2.203070377, 2.370755399],
        ],
        "positions": [
            [
                [-56.077689733, 71.742561761, 27.065840189],
                [-44.017122157, -66.611559652, -20.725245406],
                [69.921822376, 13.532824243, -57.344176739],
            ],
            [
                [63.907635843, -0.505935593, -26.219813665],
                [-50.592050806, 80.411538567, -72.835350291],
                [-63.597869239, -59.190718208, 14.064920849],
            ],
            [
                [-85.618302604, -45.993512377, -94.491102608],
                [50.52058417, -12.084591931, -8.452107467],
                [-46.653898151, 88.867626986, -41.122135636],
            ],
        ],
        "pursuit_errors": [
            [8.89343258, 10.072035344, 7.791409404],
            [1.894788027, 1.908802715, 1.869955199],
            [2.849116711, 2.780940587, 2.810925625],
        ],
        "steps": (2789, 270),
    },
}
"""Records 200, 600 and 1000 (t = 20, 60, 100 s) of each Table case, run with
``default_rng(2)``, as the simulator computed them on 2026-12-03 (commit 725a9f4) before its
speed-up: positions, γ, localization and pursuit errors (rounded to 1e-9), then (accepted,
rejected) integration steps."""
CHECKED = (200, 600, 1000)


@pytest.mark.parametrize("name", TABLES)
def test_trajectories_equal_those_recorded_before_the_speed_up(name: str) -> None:
    """Same errors after the speed-up: the records agree with :data:`RECORDED` to the integrator
    tolerance (positions and errors within rtol·scale, γ within 2·rtol), and the integrator took
    the same steps."""
    spec = load_case(name).spec
    arguments, loop = _loop(spec, steps=CHECKED[-1])
    run = simulate_dec(rng=np.random.default_rng(2), **arguments)
    recorded, rtol = RECORDED[name], arguments["settings"].rtol
    for key in ("positions", "localization_errors", "pursuit_errors"):
        got = getattr(run, key)[list(CHECKED)]
        np.testing.assert_allclose(got, recorded[key], rtol=0, atol=rtol * loop.scale, err_msg=key)
    np.testing.assert_allclose(run.gammas[list(CHECKED)], recorded["gammas"], rtol=0, atol=2 * rtol)
    assert (run.steps, run.rejected) == recorded["steps"]
