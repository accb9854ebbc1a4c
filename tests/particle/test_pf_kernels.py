"""The online learner's compiled refit (theory/particle/kernels.py) against the NumPy reference.

Same inputs, same outputs to rounding: the kernel's (μ, γ, κ, λ) equal the reference's
(``dcrw.movement_samples`` + ``fit_dcrw`` + the learner's clamp) within ``RTOL`` on random
tracks and on every track the learner meets in runs of the bundled pf cases. Whole filter runs
are not compared number by number: the learner's closed loop amplifies a 1e-13 difference about
tenfold every ten steps (docs/particle-filter.md, *Engines*), so beyond the fits the engines agree
in the Monte Carlo verdicts (tests/report -k pf), not run by run.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.core.case_file import bundled_cases
from theory.kinds import load_case
from theory.particle.case import Model
from theory.particle.experiments import monte_carlo, one_run
from theory.particle.filter import OnlineLearner, UniformMotion, build_motion

RTOL = 1e-9
"""Relative tolerance of a fit: Newton stops within 1e-10·(1 − |ψ|) of the optimum, the profile
root within 1e-12·κ, and the sums differ in order (loops against pairwise/BLAS sums)."""

PF_CASES = sorted(name for name in bundled_cases() if name.startswith("pf-") and "tdoa" not in name)


def _both(learner: OnlineLearner, track: np.ndarray) -> tuple:
    """The reference's and the kernel's refit of one track."""
    return learner._fit_reference(track), learner._fit_compiled(track)


def _assert_same_fit(reference: tuple | None, compiled: tuple | None) -> None:
    """Both skip, or both fit and agree within RTOL (μ on the circle)."""
    assert (reference is None) == (compiled is None)
    if reference is None:
        return
    ref, got = np.array(reference), np.array(compiled)
    mu_gap = np.angle(np.exp(1j * (ref[0] - got[0])))
    assert abs(mu_gap) <= RTOL * np.pi
    np.testing.assert_allclose(got[1:], ref[1:], rtol=RTOL, atol=0)


@given(
    st.integers(0, 2**32 - 1),
    st.integers(3, 100),
    st.floats(0.05, 20.0),
    st.sampled_from(["walk", "line", "repeats", "even"]),
)
def test_kernel_fit_equals_reference_on_random_tracks(seed: int, length: int, scale: float, shape):
    rng = np.random.default_rng(seed)
    moves = scale * rng.standard_normal((length - 1, 2))
    if shape == "line":  # one heading: every turn 0, the tie branch (γ = gamma_max)
        moves = np.abs(moves[:, :1]) * np.array([[0.6, 0.8]])
    elif shape == "repeats":  # zero steps dropped, repeated headings
        moves[::3] = 0.0
    elif shape == "even":  # equal step lengths: κ at its upper bound
        moves /= np.linalg.norm(moves, axis=1, keepdims=True)
    track = np.vstack([np.zeros((1, 2)), np.cumsum(moves, axis=0)])
    learner = OnlineLearner(UniformMotion(8.0), gamma_max=0.95, kappa_bounds=(0.5, 10.0))
    _assert_same_fit(*_both(learner, track))


@pytest.mark.parametrize("name", PF_CASES)
def test_kernel_fit_equals_reference_along_bundled_runs(name: str):
    """Every refit of the learner in two reference runs of the case, replayed on both engines."""
    spec = load_case(name).spec
    learner = build_motion(spec, Model.LEARNED, "numpy")
    fits = 0
    for r in range(2):
        run = one_run(spec, spec.config, Model.LEARNED, [spec.seed, r], engine="numpy")[2]
        tracks = run.estimates[learner.burn_in :]
        for k in range(3, tracks.shape[0] + 1):
            for f in range(tracks.shape[1]):
                reference, compiled = _both(learner, np.ascontiguousarray(tracks[:k, f]))
                _assert_same_fit(reference, compiled)
                fits += reference is not None
    assert fits > 0


@pytest.mark.parametrize("name", PF_CASES)
def test_engines_agree_bit_for_bit_where_nothing_is_fitted(name: str):
    """The case's own model on both engines: the engine only changes the learner's refits, so
    fixed models give identical runs, and learned ones are identical up to the first fit."""
    spec = load_case(name).spec
    runs = {e: monte_carlo(spec, runs=2, engine=e) for e in ("numpy", "numba")}
    a, b = runs["numpy"], runs["numba"]
    np.testing.assert_array_equal(a.paths, b.paths)
    if spec.model is not Model.LEARNED:
        np.testing.assert_array_equal(a.estimates, b.estimates)
        np.testing.assert_array_equal(a.nees, b.nees)
        return
    learning = build_motion(spec, Model.LEARNED)
    first = learning.burn_in + learning.min_samples + 1  # the first step that can refit
    np.testing.assert_array_equal(a.estimates[:, : first + 1], b.estimates[:, : first + 1])


def test_unknown_engine_is_refused():
    spec = load_case("pf-learning").spec
    with pytest.raises(Exception, match="engine"):
        build_motion(spec, Model.LEARNED, "fortran")
