"""The distributed TDOA particle filter (seed 002 §3.2.1): each step against a plain reference."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy import stats

from theory.kinds import load_case
from theory.particle.case import DcrwParams, ExchangeWeights, Model, PfConfig, PfNetwork
from theory.particle.dcrw import sample_dcrw_path
from theory.particle.filter import (
    DcrwMotion,
    GaussianMotion,
    PfState,
    UniformMotion,
    build_motion,
    consensus_exchange,
    estimate,
    initial_state,
    log_likelihood,
    measure,
    multinomial_resample,
    normalise_log_weights,
    particle_tdoa,
    propagate,
    run_filter,
    simulate_measurements,
    truncated_normal,
)
from theory.tdoa.model import range_differences

TRIANGLE = np.array([[0.0, 30.0], [-26.0, -15.0], [26.0, -15.0]])
seeds = st.integers(0, 2**32 - 1)


def _hears(n: int, edges: list[tuple[int, int]]) -> np.ndarray:
    hears = np.zeros((n, n), bool)
    for i, j in edges:
        hears[i, j] = hears[j, i] = True
    return hears


def _random_state(rng: np.random.Generator, filters: int, particles: int) -> PfState:
    weights = rng.random((filters, particles)) ** 3
    return PfState(
        rng.normal(0, 20, (filters, particles, 2)),
        rng.uniform(-np.pi, np.pi, (filters, particles)),
        weights / weights.sum(1, keepdims=True),
    )


@given(seeds)
def test_log_likelihood_matches_eqs_3_9_to_3_11_loop(seed: int):
    rng = np.random.default_rng(seed)
    nodes = rng.uniform(-50, 50, (5, 2))
    hears = _hears(5, [(0, 1), (0, 2), (3, 4), (0, 3)])
    network = PfNetwork(nodes, hears, (0, 3, 4))
    particles = rng.uniform(-60, 60, (3, 7, 2))
    y = measure(rng.uniform(-40, 40, 2), network, 1.0, rng)
    ours = log_likelihood(particles, y, network, 2.0)
    for f, i in enumerate(network.filters):
        for n in range(7):
            c = particles[f, n]
            d = [
                np.linalg.norm(c - nodes[i]) - np.linalg.norm(c - nodes[j])
                for j in np.flatnonzero(hears[i])
            ]
            eps = np.linalg.norm(y[f, hears[i]] - np.array(d))
            assert ours[f, n] == pytest.approx(-0.5 * (eps / 2.0) ** 2, rel=1e-10, abs=1e-10)


def test_measurements_are_unbiased_tdoa():
    rng = np.random.default_rng(1)
    network = PfNetwork(TRIANGLE, _hears(3, [(0, 1), (0, 2)]), (0, 1, 2))
    target = np.array([5.0, 3.0])
    ys = np.array([measure(target, network, 0.5, rng) for _ in range(4000)])
    ranges = np.linalg.norm(target - TRIANGLE, axis=1)
    exact = np.where(network.measurement_mask, ranges[:, None] - ranges[None, :], 0.0)
    se = 0.5 / np.sqrt(4000)
    assert np.all(np.abs(ys.mean(0) - exact) <= 4 * se)
    assert np.all(ys[:, ~network.measurement_mask] == 0)


def test_normalise_log_weights_never_underflows():
    w = normalise_log_weights(np.array([[-1e6, -1e6 - 1, -1e6 - 2], [-5.0, -5.0, -5.0]]))
    assert np.all(np.isfinite(w))
    np.testing.assert_allclose(w.sum(1), 1.0)
    np.testing.assert_allclose(w[1], 1 / 3)
    assert w[0, 0] / w[0, 1] == pytest.approx(np.e)


@given(seeds)
def test_estimate_is_weighted_mean_of_top_fifth(seed: int):
    rng = np.random.default_rng(seed)
    state = _random_state(rng, 3, 50)
    ours = estimate(state, 0.2)
    for f in range(3):
        top = np.argsort(-state.weights[f])[:10]
        w = state.weights[f, top]
        expected = w @ state.positions[f, top] / w.sum()
        np.testing.assert_allclose(ours[f], expected, rtol=1e-12, atol=1e-12)


def test_multinomial_resampling_draws_in_proportion_to_weights():
    rng = np.random.default_rng(4)
    weights = np.array([[0.5, 0.3, 0.2, 0.0], [0.0, 0.0, 0.1, 0.9]])
    positions = np.broadcast_to(np.arange(4.0)[None, :, None], (2, 4, 2)).copy()
    state = PfState(positions, np.zeros((2, 4)), weights)
    counts = np.zeros((2, 4))
    for _ in range(500):
        drawn = multinomial_resample(state, rng).positions[..., 0].astype(int)
        for f in range(2):
            counts[f] += np.bincount(drawn[f], minlength=4)
    assert counts[0, 3] == 0 and counts[1, :2].sum() == 0
    for f in range(2):
        support = weights[f] > 0
        expected = weights[f, support] * counts[f].sum()
        assert stats.chisquare(counts[f, support], expected).pvalue > 1e-3


@given(seeds)
def test_resampling_keeps_particles_whole(seed: int):
    rng = np.random.default_rng(seed)
    state = _random_state(rng, 3, 20)
    drawn = multinomial_resample(state, rng)
    np.testing.assert_allclose(drawn.weights, 1 / 20)
    for f in range(3):
        for c, h in zip(drawn.positions[f], drawn.headings[f], strict=True):
            match = np.flatnonzero(np.all(state.positions[f] == c, axis=1))
            assert match.size and state.headings[f, match[0]] == h


def _path_network() -> PfNetwork:
    nodes = np.array([[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]])
    return PfNetwork(nodes, _hears(3, [(0, 1), (1, 2)]), (0, 1, 2))


@given(seeds)
def test_consensus_replaces_lowest_with_neighbours_top_m(seed: int):
    rng = np.random.default_rng(seed)
    network = _path_network()
    config = PfConfig(particles=30, share=4)
    state = _random_state(rng, 3, 30)
    y = np.zeros((3, 3))
    after = consensus_exchange(state, network, config, rng, y=y)
    np.testing.assert_allclose(after.weights.sum(1), 1.0)
    for f, degree in enumerate((1, 2, 1)):
        lowest = np.argsort(state.weights[f], kind="stable")[: degree * 4]
        kept = np.setdiff1d(np.arange(30), lowest)
        np.testing.assert_array_equal(after.positions[f, kept], state.positions[f, kept])
        for j in np.flatnonzero(network.hears[f]):
            for n in np.argsort(-state.weights[j])[:4]:
                assert np.any(np.all(after.positions[f] == state.positions[j, n], axis=1))
        received = after.weights[f, lowest] * state.weights[f, kept].sum()
        senders_w = np.sort(
            np.concatenate(
                [np.sort(state.weights[j])[-4:] for j in np.flatnonzero(network.hears[f])]
            )
        )
        np.testing.assert_allclose(
            np.sort(received) / np.sort(received).sum(), senders_w / senders_w.sum(), rtol=1e-9
        )


def test_consensus_off_and_isolated_nodes_unchanged():
    rng = np.random.default_rng(0)
    state = _random_state(rng, 3, 30)
    network = PfNetwork(_path_network().nodes, _hears(3, [(0, 1)]), (0, 1, 2))
    off = consensus_exchange(state, network, PfConfig(particles=30, share=0), rng, y=None)
    assert off is state
    on = consensus_exchange(state, network, PfConfig(particles=30, share=3), rng, y=None)
    np.testing.assert_array_equal(on.positions[2], state.positions[2])


def test_consensus_refuses_m_times_degree_at_least_p():
    rng = np.random.default_rng(0)
    state = _random_state(rng, 3, 8)
    with pytest.raises(ValueError, match="m < P/N"):
        consensus_exchange(state, _path_network(), PfConfig(particles=8, share=4), rng, y=None)


def test_second_round_forwards_received_particles():
    rng = np.random.default_rng(2)
    P, m = 20, 3
    weights = np.full((3, P), 1e-3)
    weights[0, :m] = 1.0  # node 1's best particles, at (100, 100 + n)
    positions = rng.normal(0, 1, (3, P, 2))
    positions[0, :m] = [[100.0, 100.0 + n] for n in range(m)]
    state = PfState(positions, np.zeros((3, P)), weights / weights.sum(1, keepdims=True))

    def reached_end(rounds: int) -> bool:
        config = PfConfig(particles=P, share=m, exchange_rounds=rounds)
        after = consensus_exchange(state, _path_network(), config, rng, y=None)
        return bool(np.any(after.positions[2, :, 0] == 100.0))

    assert not reached_end(1)
    assert reached_end(2)


def test_local_reweighting_uses_receivers_likelihood():
    rng = np.random.default_rng(3)
    network = _path_network()
    config = PfConfig(particles=20, share=2, exchange_weights="local", sigma=1.0)
    state = _random_state(rng, 3, 20)
    y = measure(np.array([5.0, 7.0]), network, 0.0, rng)
    after = consensus_exchange(state, network, config, rng, y=y)
    lowest = np.argsort(state.weights[0], kind="stable")[:2]
    loglik = log_likelihood(after.positions, y, network, 1.0)[0, lowest]
    own = log_likelihood(state.positions, y, network, 1.0)[0]
    expected = np.exp(loglik - own.max()) / np.exp(own - own.max()).sum()
    kept = np.setdiff1d(np.arange(20), lowest)
    ratio = after.weights[0, lowest] / after.weights[0, kept].sum()
    np.testing.assert_allclose(ratio, expected / state.weights[0, kept].sum(), rtol=1e-9)


def test_uniform_received_heading_is_redrawn():
    rng = np.random.default_rng(5)
    state = _random_state(rng, 3, 30)
    config = PfConfig(particles=30, share=5, received_heading="uniform")
    after = consensus_exchange(state, _path_network(), config, rng, y=None)
    lowest = np.argsort(state.weights[0], kind="stable")[:5]
    assert not np.any(np.isin(after.headings[0, lowest], state.headings))


@pytest.mark.parametrize(
    "motion", [DcrwMotion(DcrwParams(0.1, 0.6, 2.0, 3.0)), GaussianMotion(), UniformMotion(4.0)]
)
def test_propagation_moves_by_the_sampled_step_along_the_new_heading(motion):
    rng = np.random.default_rng(8)
    state = _random_state(rng, 2, 500)
    turn, step = motion.sample(np.random.default_rng(1), (2, 500))
    moved = propagate(state, motion, np.random.default_rng(1))
    np.testing.assert_allclose(moved.headings, state.headings + turn)
    np.testing.assert_allclose(np.linalg.norm(moved.positions - state.positions, axis=-1), step)
    assert np.all(step >= 0) and np.all(np.abs(turn) <= np.pi)


def test_gaussian_baseline_matches_the_thesis_parameters():
    turn, step = GaussianMotion().sample(np.random.default_rng(6), (1, 20000))
    assert abs(turn.mean()) < 4 * (np.pi / 4) / np.sqrt(20000)
    assert turn.std() == pytest.approx(np.pi / 4, rel=0.03)
    truncated = stats.truncnorm(-2.0, np.inf, loc=2.0, scale=1.0)
    assert stats.kstest(step.ravel(), truncated.cdf).pvalue > 1e-3


def test_initial_particles_fill_the_workspace():
    state = initial_state(2, 5000, np.array([[-10.0, 30.0], [0.0, 5.0]]), np.random.default_rng(0))
    assert state.positions[..., 0].min() >= -10 and state.positions[..., 0].max() <= 30
    assert state.positions[..., 1].mean() == pytest.approx(2.5, abs=0.1)


def _errors(network: PfNetwork, share: int, runs: int) -> np.ndarray:
    truth = DcrwParams(0.0, 0.7, 2.0, 2.0)
    tails = []
    for r in range(runs):
        rng = np.random.default_rng([7, r])
        path = sample_dcrw_path(truth, 40, rng, start=np.zeros(2))
        y = simulate_measurements(path, network, 1.0, rng)
        run = run_filter(
            path,
            network,
            PfConfig(particles=100, share=share),
            DcrwMotion(truth),
            rng,
            bounds=np.array([[-40, 40], [-40, 40]]),
            measurements=y,
        )
        tails.append(run.errors[20:].mean(0))
    return np.asarray(tails)


def test_two_measurements_localize_and_exchange_helps_a_one_measurement_node():
    # node 1 hears nodes 2 and 3 (two TDOA); node 4 at (0, -40) hears only node 3 (one TDOA).
    nodes = np.vstack([TRIANGLE, [[0.0, -40.0]]])
    hears = _hears(4, [(0, 1), (0, 2), (2, 3)])
    alone = PfNetwork(nodes, hears, (0, 3))
    linked = PfNetwork(nodes, _hears(4, [(0, 1), (0, 2), (2, 3), (0, 3)]), (0, 3))
    isolated = np.median(_errors(alone, 10, 8), axis=0)
    joined = np.median(_errors(linked, 10, 8), axis=0)
    assert isolated[0] < 3.0, isolated  # two TDOA measurements: metres of error at σ = 1 m
    assert isolated[1] > 3 * isolated[0], isolated  # one measurement: a hyperbola, not a point
    assert joined[1] < 3.0, joined  # exchanging with node 1 localizes node 4


@given(seeds)
def test_eq_3_13_as_printed_shrinks_the_estimate(seed: int):
    # χ = W^T C with the top-20 % weights not renormalised (seed 002 eq. (3.13) as printed)
    # equals (Σ W) · χ_ours: it is pulled towards the origin whenever Σ W < 1 (docs/errata.md).
    rng = np.random.default_rng(seed)
    state = _random_state(rng, 2, 50)
    state = PfState(state.positions + 100.0, state.headings, state.weights)
    top = np.argsort(-state.weights, axis=1)[:, :10]
    w = np.take_along_axis(state.weights, top, axis=1)
    literal = np.einsum("fq,fqd->fd", w, np.take_along_axis(state.positions, top[..., None], 1))
    np.testing.assert_allclose(literal, w.sum(1, keepdims=True) * estimate(state, 0.2))
    assert np.all(w.sum(1) < 1)
    assert np.all(np.linalg.norm(literal, axis=1) < np.linalg.norm(estimate(state, 0.2), axis=1))


@given(
    st.integers(3, 6).flatmap(
        lambda n: st.tuples(
            st.just(n),
            st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=10),
            st.integers(0, 2**32 - 1),
        )
    )
)
def test_exchange_on_random_graphs_keeps_sets_whole(data):
    n, raw_edges, seed = data
    rng = np.random.default_rng(seed)
    hears = _hears(n, [(i, j) for i, j in raw_edges if i != j])
    network = PfNetwork(rng.uniform(-30, 30, (n, 2)), hears, tuple(range(n)))
    state = _random_state(rng, n, 40)
    after = consensus_exchange(state, network, PfConfig(particles=40, share=3), rng, y=None)
    assert after.positions.shape == state.positions.shape
    np.testing.assert_allclose(after.weights.sum(1), 1.0)
    for f in range(n):
        tops = [
            state.positions[j, np.argsort(-state.weights[j])[:3]] for j in np.flatnonzero(hears[f])
        ]
        own = state.positions[f]
        for c, h in zip(after.positions[f], after.headings[f], strict=True):
            mine = np.all(own == c, axis=1)
            if mine.any():
                assert state.headings[f, np.argmax(mine)] == h  # kept with its own heading
            else:
                assert any(np.any(np.all(t == c, axis=1)) for t in tops)


@given(
    st.floats(-6.0, -0.1),
    st.one_of(st.floats(0.1, 6.0), st.just(np.inf)),
    st.floats(-5.0, 5.0),
    st.floats(0.1, 3.0),
    st.integers(0, 2**16),
)
def test_truncated_normal_is_scipys_truncnorm_draw_for_draw(a, b, loc, scale, seed):
    """The Gaussian baseline's sampler (seed 002 §3.3.2) gives scipy's truncnorm numbers exactly,
    from the same generator state."""
    expected = stats.truncnorm.rvs(
        a, b, loc=loc, scale=scale, size=(3, 50), random_state=np.random.default_rng(seed)
    )
    got = truncated_normal(np.random.default_rng(seed), a, b, loc, scale, (3, 50))
    np.testing.assert_array_equal(got, expected)


def test_truncated_normal_needs_a_negative_lower_bound():
    with pytest.raises(ValueError, match="a < 0"):
        truncated_normal(np.random.default_rng(0), 0.5, 1.0, 0.0, 1.0, (2,))


@pytest.mark.parametrize(
    "make",
    [
        lambda spec: PfConfig(exchange_weights="sendr"),
        lambda spec: PfConfig(received_heading="uniformly"),
        lambda spec: build_motion(spec, "kalman"),
    ],
)
def test_misspelt_choices_are_refused(make):
    """The filter's closed vocabularies raise on a value outside them instead of falling back."""
    with pytest.raises(ValueError):
        make(load_case("pf-path3").spec)


def test_choices_given_as_words_become_members():
    config = PfConfig(exchange_weights="local")
    assert config.exchange_weights is ExchangeWeights.LOCAL
    spec = load_case("pf-path3").spec
    assert isinstance(build_motion(spec, "gaussian"), GaussianMotion)
    assert isinstance(build_motion(spec, Model.DCRW), DcrwMotion)


@pytest.mark.parametrize("name", ["pf-topology-b", "pf-path3"])
def test_particle_tdoa_is_range_differences_bit_for_bit(name: str):
    """The filter's eq. (3.9) by indexing equals theory.tdoa.model.range_differences exactly."""
    network = load_case(name).spec.network
    positions = np.random.default_rng(4).uniform(-60, 60, (len(network.filters), 50, 2))
    filters = np.asarray(network.filters)[:, None]
    expected = range_differences(positions, network.nodes, filters)
    np.testing.assert_array_equal(particle_tdoa(positions, network), expected)


def test_simulate_measurements_is_measure_step_by_step_bit_for_bit():
    """One draw of the whole path's noise equals the draws of each step's (eqs. (3.6)–(3.8))."""
    spec = load_case("pf-topology-b").spec
    path = sample_dcrw_path(spec.target, 30, np.random.default_rng(6), start=np.zeros(2))
    batched = simulate_measurements(path, spec.network, 1.0, np.random.default_rng(7))
    rng = np.random.default_rng(7)
    stepwise = np.asarray([measure(p, spec.network, 1.0, rng) for p in path])
    np.testing.assert_array_equal(batched, stepwise)
