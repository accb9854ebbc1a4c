"""One TDOA measurement model (seed 000 eqs. (4.3)–(4.10), seed 002 eq. (3.9)) for every consumer.

Before the unification the model ``h``/``H`` was written three times: per agent in
``theory/tdoa/model.py``, for the whole network in ``theory/tdoa/measurements.py`` and over
nodes × particles in ``theory/particle/filter.py``. The three old forms are kept below, verbatim
from ``main`` at 564229f, as frozen references: the one broadcasting implementation must give
the same numbers bit for bit (same arithmetic, so ``array_equal``), on random scenes and networks.
The new functions are also checked against the equations themselves: a scalar loop over pairs,
central finite differences and sympy's symbolic Jacobian.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from theory.particle.case import PfNetwork
from theory.particle.filter import log_likelihood, measure
from theory.particle.pf_vs_ekf import EkfConfig, consensus_weights, ekf_step
from theory.strategies import networks, tdoa_scenes
from theory.tdoa.estimation.filters import average_round, measurement_step
from theory.tdoa.model import (
    neighbour_lists,
    range_difference_gradients,
    range_differences,
    tdoa_jacobian,
    tdoa_jacobians,
    tdoa_measurement,
    tdoa_predictions,
    unit_directions,
)

seeds = st.integers(0, 2**32 - 1)


# --- the three implementations as they were on main (564229f), frozen references -------------


def old_model_measurement(target, positions, agent, neighbours):
    diff = np.asarray(target, float)[None, :] - np.asarray(positions, float)
    ranges = np.linalg.norm(diff, axis=1)
    return ranges[agent] - ranges[list(neighbours)]


def old_model_jacobian(target, positions, agent, neighbours):
    diff = np.asarray(target, dtype=float)[None, :] - np.asarray(positions, dtype=float)
    units = diff / np.linalg.norm(diff, axis=1, keepdims=True)
    position_block = units[agent][None, :] - units[list(neighbours)]
    return np.hstack([position_block, np.zeros_like(position_block)])


def _old_offsets(point, positions):
    return np.broadcast_to(point, positions.shape)[:, None, :] - positions[None, :, :]


def old_network_predictions(point, positions, neighbours):
    ranges = np.linalg.norm(_old_offsets(point, positions), axis=2)
    return [ranges[i, i] - ranges[i, nbrs] for i, nbrs in enumerate(neighbours)]


def old_network_jacobians(point, positions, neighbours):
    diff = _old_offsets(point, positions)
    units = diff / np.linalg.norm(diff, axis=2, keepdims=True)
    rows = [units[i, i][None, :] - units[i, nbrs] for i, nbrs in enumerate(neighbours)]
    return [np.hstack([r, np.zeros_like(r)]) for r in rows]


def old_particle_predictions(positions, nodes, filters):
    ranges = np.linalg.norm(positions[:, :, None, :] - nodes[None, None], axis=-1)
    own = ranges[np.arange(len(filters)), :, list(filters)]
    return own[:, :, None] - ranges


def old_particle_clean_measurement(target, nodes, filters):
    ranges = np.linalg.norm(np.asarray(target, float)[None] - nodes, axis=1)
    own = ranges[list(filters)]
    return own[:, None] - ranges[None, :]


# --- strategies ---------------------------------------------------------------------------------


@st.composite
def networked_scenes(draw, *, dims=(2, 3)):
    """A general-position scene (public strategy) with a drawn network of the same size."""
    dim = draw(st.sampled_from(dims))
    scene = draw(tdoa_scenes(dim=dim, min_agents=2, max_agents=7))
    n = len(scene.agents)
    hears = draw(networks(min_agents=n, max_agents=n, connected=None))
    return scene, hears


# --- old vs new ---------------------------------------------------------------------------------


@given(networked_scenes())
def test_per_agent_model_equals_the_old_one(example) -> None:
    scene, hears = example
    for i, nbrs in enumerate(neighbour_lists(hears)):
        np.testing.assert_array_equal(
            tdoa_measurement(scene.target, scene.agents, i, nbrs),
            old_model_measurement(scene.target, scene.agents, i, nbrs),
        )
        np.testing.assert_array_equal(
            tdoa_jacobian(scene.target, scene.agents, i, nbrs),
            old_model_jacobian(scene.target, scene.agents, i, nbrs),
        )


@given(networked_scenes(), seeds)
def test_network_model_equals_the_old_one(example, seed: int) -> None:
    """One point for all agents and one point per agent (the EKF's predictions)."""
    scene, hears = example
    neighbours = neighbour_lists(hears)
    own_points = scene.target + np.random.default_rng(seed).normal(0, 2, scene.agents.shape)
    for point in (scene.target, own_points):
        for new, old in (
            (tdoa_predictions, old_network_predictions),
            (tdoa_jacobians, old_network_jacobians),
        ):
            for a, b in zip(
                new(point, scene.agents, neighbours),
                old(point, scene.agents, neighbours),
                strict=True,
            ):
                np.testing.assert_array_equal(a, b)


@given(networked_scenes(dims=(2,)), seeds, st.integers(1, 9))
def test_particle_model_equals_the_old_one(example, seed: int, particles: int) -> None:
    scene, _ = example
    rng = np.random.default_rng(seed)
    filters = tuple(sorted(rng.choice(len(scene.agents), rng.integers(1, len(scene.agents) + 1))))
    filters = tuple(dict.fromkeys(filters))
    cloud = scene.target + rng.normal(0, 10, (len(filters), particles, 2))
    np.testing.assert_array_equal(
        range_differences(cloud, scene.agents, np.asarray(filters)[:, None]),
        old_particle_predictions(cloud, scene.agents, filters),
    )
    np.testing.assert_array_equal(
        range_differences(scene.target, scene.agents, np.asarray(filters)),
        old_particle_clean_measurement(scene.target, scene.agents, filters),
    )


@given(networked_scenes(dims=(2,)), seeds)
def test_particle_filter_measurement_and_likelihood_use_the_model(example, seed: int) -> None:
    """``measure`` with zero noise is ``h_i(p)`` on the mask; ``log_likelihood`` is eq. (3.11)
    of the residual against ``tdoa_measurement`` at each particle."""
    scene, hears = example
    network = PfNetwork(scene.agents, hears, tuple(range(len(scene.agents))))
    rng = np.random.default_rng(seed)
    y = measure(scene.target, network, 0.0, rng)
    cloud = scene.target + rng.normal(0, 5, (len(network.filters), 3, 2))
    loglik = log_likelihood(cloud, y, network, 1.5)
    for f, node in enumerate(network.filters):
        nbrs = np.flatnonzero(hears[node])
        np.testing.assert_array_equal(
            y[f, nbrs], tdoa_measurement(scene.target, scene.agents, node, nbrs)
        )
        for q in range(3):
            residual = y[f, nbrs] - tdoa_measurement(cloud[f, q], scene.agents, node, nbrs)
            np.testing.assert_allclose(
                loglik[f, q], -0.5 * residual @ residual / 1.5**2, rtol=1e-12
            )


# --- new model against the equations -------------------------------------------------------------


@given(networked_scenes(), seeds)
def test_broadcasting_equals_the_scalar_equations(example, seed: int) -> None:
    """Eqs. (4.4) and (4.8)–(4.10) pair by pair, at points with two leading axes."""
    scene, _ = example
    n, dim = scene.agents.shape
    rng = np.random.default_rng(seed)
    points = scene.target + rng.normal(0, 3, (2, 3, dim))
    agents = rng.integers(0, n, (2, 1))
    h = range_differences(points, scene.agents, agents)
    grad = range_difference_gradients(points, scene.agents, agents)
    assert h.shape == (2, 3, n) and grad.shape == (2, 3, n, dim)
    for a in range(2):
        for b in range(3):
            p, i = points[a, b], agents[a, 0]
            for j in range(n):
                d_i, d_j = p - scene.agents[i], p - scene.agents[j]
                expected = np.linalg.norm(d_i) - np.linalg.norm(d_j)
                assert abs(h[a, b, j] - expected) <= 1e-12 * max(1.0, abs(expected))
                row = d_i / np.linalg.norm(d_i) - d_j / np.linalg.norm(d_j)
                np.testing.assert_allclose(grad[a, b, j], row, rtol=0, atol=1e-14)


@given(networked_scenes())
def test_gradients_are_central_differences_of_the_measurements(example) -> None:
    scene, _ = example
    n, dim = scene.agents.shape
    agents = np.arange(n)
    points = np.broadcast_to(scene.target, (n, dim))
    step = 1e-6 * float(np.max(np.abs(scene.agents - scene.target)))
    numeric = np.stack(
        [
            (
                range_differences(points + step * e, scene.agents, agents)
                - range_differences(points - step * e, scene.agents, agents)
            )
            / (2 * step)
            for e in np.eye(dim)
        ],
        axis=-1,
    )
    np.testing.assert_allclose(
        range_difference_gradients(points, scene.agents, agents), numeric, rtol=0, atol=1e-7
    )


def test_gradients_match_sympy_in_2d_and_3d() -> None:
    for dim, agents, target in (
        (2, [[0, 30], [-26, -15], [26, -15], [4, 9]], [5, 7]),
        (3, [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]], [17, -5, -15]),
    ):
        p = sp.Matrix(sp.symbols(f"p0:{dim}", real=True))
        rows = [
            [
                (p - sp.Matrix(agents[i])).norm() - (p - sp.Matrix(agents[j])).norm()
                for j in range(len(agents))
            ]
            for i in range(len(agents))
        ]
        at = dict(zip(p, target, strict=True))
        for i, row in enumerate(rows):
            jac = np.array(sp.Matrix(row).jacobian(p).subs(at), dtype=float)
            values = np.array(sp.Matrix(row).subs(at), dtype=float).ravel()
            ours = range_difference_gradients(np.array(target, float), np.array(agents, float), i)
            np.testing.assert_allclose(ours, jac, rtol=1e-13, atol=1e-15)
            np.testing.assert_allclose(
                range_differences(np.array(target, float), np.array(agents, float), i),
                values,
                rtol=1e-13,
                atol=1e-13,
            )


def test_unit_directions_broadcast_over_points() -> None:
    agents = np.array([[0.0, 0.0, 0.0], [3.0, 4.0, 0.0]])
    points = np.array([[[0.0, 0.0, 2.0]], [[3.0, 0.0, 0.0]]])
    units = unit_directions(points, agents)
    assert units.shape == (2, 1, 2, 3)
    np.testing.assert_allclose(units[0, 0], [[0, 0, 1], np.array([-3, -4, 2]) / np.sqrt(29)])
    np.testing.assert_allclose(np.linalg.norm(units, axis=-1), 1.0)


# --- one filter for the EKF consumers -------------------------------------------------------------


@given(seeds)
def test_pf_comparison_ekf_step_is_the_tdoa_filter(seed: int) -> None:
    """The averaged EKF that seed 002's comparison runs (``pf_vs_ekf.ekf_step``) is the network
    filter of :mod:`theory.tdoa.estimation.filters` on the filtering nodes, then one averaging
    round: the PF package can use the one TDOA filter instead of its own loop."""
    rng = np.random.default_rng(seed)
    nodes = rng.uniform(-40, 40, (5, 2))
    hears = np.zeros((5, 5), bool)
    for i, j in ((0, 1), (0, 2), (1, 2), (2, 3), (3, 4)):
        hears[i, j] = hears[j, i] = True
    network = PfNetwork(nodes, hears, (0, 2, 3))
    x = np.hstack([rng.uniform(-30, 30, (3, 2)), rng.normal(0, 1, (3, 2))])
    L = rng.normal(0, 1, (3, 4, 4))
    P = L @ L.transpose(0, 2, 1) + np.eye(4)
    y = measure(rng.uniform(-30, 30, 2), network, 1.0, rng)
    config = EkfConfig(sigma=0.8)
    W = consensus_weights(network)
    expected = ekf_step(x, P, y, network, config, W)
    neighbours = [np.flatnonzero(hears[node]) for node in network.filters]
    readings = [y[f, nbrs] for f, nbrs in enumerate(neighbours)]
    corrected = measurement_step(
        "decentralized",
        x,
        P,
        readings,
        nodes,
        neighbours,
        config.sigma**2,
        agents=np.asarray(network.filters),
    )
    got = average_round(W, *corrected)
    for a, b in zip(got, expected, strict=True):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12)
