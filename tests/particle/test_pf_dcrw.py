"""The DCRW target model (seed 002 eqs. (3.1)–(3.5)): densities, sampling, ML fits."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from scipy import integrate, stats

from theory.particle import dcrw
from theory.particle.case import DcrwParams
from theory.particle.dcrw import (
    fit_weibull,
    fit_wrapped_cauchy,
    sample_dcrw_path,
    sample_weibull,
    sample_wrapped_cauchy,
    standard_errors,
    weibull_logpdf,
    wrap_angle,
    wrapped_cauchy_logpdf,
)

Z_TOL = 4.0  # deviations allowed, in asymptotic standard errors
N = 5000

gammas = st.floats(min_value=0.05, max_value=0.9)
mus = st.floats(min_value=-3.0, max_value=3.0)
kappas = st.floats(min_value=0.5, max_value=5.0)
lams = st.floats(min_value=0.5, max_value=10.0)


@given(mus, gammas)
def test_wrapped_cauchy_density_matches_scipy_and_integrates_to_one(mu: float, gamma: float):
    phi = np.linspace(-np.pi, np.pi, 101)
    ours = np.exp(wrapped_cauchy_logpdf(phi, mu, gamma))
    theirs = stats.wrapcauchy.pdf(np.mod(phi - mu, 2 * np.pi), gamma)
    np.testing.assert_allclose(ours, theirs, rtol=1e-10)
    total, _ = integrate.quad(lambda x: np.exp(wrapped_cauchy_logpdf(x, mu, gamma)), -np.pi, np.pi)
    assert total == pytest.approx(1.0, abs=1e-8)


@given(kappas, lams)
def test_weibull_density_matches_scipy(kappa: float, lam: float):
    delta = np.linspace(0.01, 5 * lam, 50)
    np.testing.assert_allclose(
        weibull_logpdf(delta, kappa, lam),
        stats.weibull_min.logpdf(delta, kappa, scale=lam),
        rtol=1e-10,
        atol=1e-10,
    )


def test_samplers_follow_their_distributions():
    rng = np.random.default_rng(20)
    phi = sample_wrapped_cauchy(rng, 0.5, 0.6, (N,))
    assert np.all((phi > -np.pi) & (phi <= np.pi))
    ks = stats.kstest(np.mod(phi - 0.5, 2 * np.pi), stats.wrapcauchy(0.6).cdf)
    assert ks.pvalue > 1e-3
    delta = sample_weibull(rng, 1.7, 2.5, (N,))
    assert stats.kstest(delta, stats.weibull_min(1.7, scale=2.5).cdf).pvalue > 1e-3


def test_gamma_zero_is_uniform():
    phi = sample_wrapped_cauchy(np.random.default_rng(3), 1.0, 0.0, (N,))
    assert stats.kstest(phi, stats.uniform(-np.pi, 2 * np.pi).cdf).pvalue > 1e-3


@given(mus, gammas, kappas, lams, st.integers(0, 2**32 - 1))
def test_ml_fit_recovers_parameters_within_standard_errors(mu, gamma, kappa, lam, seed):
    rng = np.random.default_rng(seed)
    truth = DcrwParams(mu, gamma, kappa, lam)
    se = standard_errors(truth, N)
    fit_mu, fit_gamma = fit_wrapped_cauchy(sample_wrapped_cauchy(rng, mu, gamma, (N,)))
    fit_kappa, fit_lam = fit_weibull(sample_weibull(rng, kappa, lam, (N,)))
    assert abs(float(wrap_angle(fit_mu - mu))) <= Z_TOL * se["mu"]
    assert abs(fit_gamma - gamma) <= Z_TOL * se["gamma"]
    assert abs(fit_kappa - kappa) <= Z_TOL * se["kappa"]
    assert abs(fit_lam - lam) <= Z_TOL * se["lambda"]


def test_fits_agree_with_scipy_generic_mle():
    rng = np.random.default_rng(11)
    delta = sample_weibull(rng, 2.3, 1.4, (800,))
    kappa, _, lam = stats.weibull_min.fit(delta, floc=0)
    np.testing.assert_allclose(fit_weibull(delta), (kappa, lam), rtol=1e-4)
    phi = sample_wrapped_cauchy(rng, 0.0, 0.5, (800,))
    # scipy's wrapcauchy lives on [0, 2π) with its mode at loc = 0 (our μ = 0).
    result = stats.fit(stats.wrapcauchy, np.mod(phi, 2 * np.pi), bounds={"c": (0, 1)})
    ours_mu, ours_gamma = fit_wrapped_cauchy(phi)
    assert ours_gamma == pytest.approx(result.params.c, abs=0.02)

    def loglik(g: float) -> float:
        return float(np.sum(wrapped_cauchy_logpdf(phi, ours_mu, g)))

    assert loglik(ours_gamma) >= loglik(result.params.c) - 1e-9


def test_fit_is_a_likelihood_maximum():
    rng = np.random.default_rng(5)
    phi = sample_wrapped_cauchy(rng, -1.0, 0.8, (300,))
    mu, gamma = fit_wrapped_cauchy(phi)
    best = np.sum(wrapped_cauchy_logpdf(phi, mu, gamma))
    for dmu, dg in [(0.01, 0), (-0.01, 0), (0, 0.01), (0, -0.01)]:
        assert np.sum(wrapped_cauchy_logpdf(phi, mu + dmu, gamma + dg)) < best


@given(mus, st.floats(min_value=0.0, max_value=0.98), st.integers(3, 120), st.integers(0, 2**16))
def test_newton_fit_is_stationary_and_no_worse_than_bfgs(mu, gamma, n, seed):
    """The Newton iteration reaches a stationary point of eq. (3.1)'s likelihood whose value is
    at least the BFGS fallback's (both from the same moment start)."""
    phi = sample_wrapped_cauchy(np.random.default_rng(seed), mu, gamma, (n,))
    z = np.exp(1j * phi)
    start = dcrw._moment_start(z)
    newton = dcrw._wrapped_cauchy_newton(z, start)
    assert newton is not None and abs(newton) < 1
    bfgs = dcrw._wrapped_cauchy_bfgs(z, start)
    value, grad, _ = dcrw._wrapped_cauchy_derivatives(z, newton)
    assert value <= dcrw._wrapped_cauchy_derivatives(z, bfgs)[0] + 1e-9 * (1 + abs(value))
    assert abs(grad) * (1 - abs(newton)) ** 2 <= 1e-6 * n


@given(st.floats(-0.9, 0.9), st.floats(-0.9, 0.9), st.integers(0, 2**16))
def test_newton_derivatives_match_finite_differences(x, y, seed):
    psi = complex(x, y)
    assume(abs(psi) < 0.95)
    z = np.exp(1j * np.random.default_rng(seed).uniform(-np.pi, np.pi, 20))
    _, grad, (hxx, hxy, hyy) = dcrw._wrapped_cauchy_derivatives(z, psi)
    h = 1e-6
    for e, g_e, h_row in [(1.0, grad.real, (hxx, hxy)), (1j, grad.imag, (hxy, hyy))]:
        up, down = (dcrw._wrapped_cauchy_derivatives(z, psi + s * h * e) for s in (1, -1))
        assert (up[0] - down[0]) / (2 * h) == pytest.approx(g_e, rel=1e-5, abs=1e-5)
        d_grad = (up[1] - down[1]) / (2 * h)
        assert d_grad.real == pytest.approx(h_row[0], rel=1e-4, abs=1e-3)
        assert d_grad.imag == pytest.approx(h_row[1], rel=1e-4, abs=1e-3)


@given(kappas, lams, st.integers(2, 120), st.integers(0, 2**16))
def test_weibull_fit_solves_the_profile_equation(kappa, lam, n, seed):
    """Seed 002 eq. (3.2): at the ML shape the profile-likelihood equation vanishes (its root is
    unique, the equation increasing), and ``λ = (mean δ^κ)^{1/κ}``."""
    delta = sample_weibull(np.random.default_rng(seed), kappa, lam, (n,))
    assume(np.ptp(np.log(delta)) > 1e-2)  # keeps the root inside the default bounds
    k_hat, lam_hat = fit_weibull(delta)
    logs = np.log(delta)
    weights = delta**k_hat / np.sum(delta**k_hat)
    assert weights @ logs - 1 / k_hat - logs.mean() == pytest.approx(0, abs=1e-9)
    assert lam_hat == pytest.approx(np.mean(delta**k_hat) ** (1 / k_hat), rel=1e-9)


def test_degenerate_fits_are_clamped():
    mu, gamma = fit_wrapped_cauchy(np.array([0.3, 0.3, 0.3]), gamma_max=0.95)
    assert gamma == 0.95 and mu == pytest.approx(0.3)
    # Kent & Tyler: an angle carrying half the sample puts the supremum at γ = 1 ...
    mu, gamma = fit_wrapped_cauchy(np.array([np.pi / 2, -np.pi / 2] * 4), gamma_max=0.95)
    assert gamma == 0.95 and abs(mu) == pytest.approx(np.pi / 2)
    # ... and below half the maximum is interior.
    mu, gamma = fit_wrapped_cauchy(np.array([0.3, 0.3, 1.0, -1.0, 2.0]), gamma_max=0.999)
    assert 0 < gamma < 0.999
    kappa, lam = fit_weibull(np.array([2.0, 2.0, 2.0]), kappa_bounds=(0.5, 10.0))
    assert kappa == 10.0 and lam == pytest.approx(2.0)


def test_path_follows_eqs_3_3_to_3_5():
    rng = np.random.default_rng(9)
    params = DcrwParams(0.2, 0.7, 2.0, 3.0)
    path = sample_dcrw_path(params, 50, rng, start=np.array([1.0, -2.0]), heading=0.0)
    assert path.shape == (51, 2)
    np.testing.assert_allclose(path[0], [1.0, -2.0])
    replay = np.random.default_rng(9)
    turns = sample_wrapped_cauchy(replay, 0.2, 0.7, (50,))
    steps = sample_weibull(replay, 2.0, 3.0, (50,))
    np.testing.assert_allclose(np.linalg.norm(np.diff(path, axis=0), axis=1), steps)
    headings = np.arctan2(*np.diff(path, axis=0).T[::-1])
    np.testing.assert_allclose(wrap_angle(headings - np.cumsum(turns)), 0.0, atol=1e-9)


def test_invalid_parameters_raise():
    with pytest.raises(ValueError, match="γ"):
        DcrwParams(0.0, 1.0, 2.0, 3.0)
    with pytest.raises(ValueError):
        fit_weibull(np.array([1.0, 0.0]))
