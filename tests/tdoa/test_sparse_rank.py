"""The network rank of large components (``theory.tdoa.observability.sparse_rank``: the blind
agents' invariant subspace and the inertia of W) against the staircase rank of the whole
(W⊗A, D_H) of seed 000 eq. (4.36), formed densely, on random networks where both run."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st
from test_topology import dense_blocks
from topology_strategies import edge_lists, scenes, spec_of

from theory.core.network import pairs_within_range
from theory.core.sparse_weights import SparseWeights
from theory.kinds import load_case
from theory.tdoa.model import cv_discrete, unit_directions
from theory.tdoa.observability import topology
from theory.tdoa.observability.network import analyze_network
from theory.tdoa.observability.sparse_rank import sparse_network_rank
from theory.tdoa.observability.spectral import spectral_network_rank, symmetrizing_scale


def sparse_rank(spec):
    """The sparse method on the whole network (it needs no connectivity)."""
    W = spec.links[0]
    units = unit_directions(spec.target[0], spec.agents[0])
    vectors = units[W.receiver] - units[W.sender]
    return sparse_network_rank(W, W.receiver, vectors, scale=symmetrizing_scale(W))


def _eigenvalues(values) -> list[float]:
    return sorted(round(complex(z).real, 6) for z in values)


@given(scenes(max_agents=6), st.data(), st.sampled_from(["metropolis", "uniform"]))
def test_sparse_rank_is_the_dense_rank(scene, data, weights) -> None:
    agents, target = scene
    spec = spec_of(agents, target, data.draw(edge_lists(len(agents))), weights=weights)
    result = sparse_rank(spec)
    A, _ = cv_discrete(spec.T, spec.dim)
    dense = analyze_network(A, spec.weights[0], dense_blocks(spec))
    assume(dense.conclusive and result is not None and result.margin >= 1e3)
    assert result.rank == dense.network_rank
    assert _eigenvalues(result.unobservable_eigenvalues) == _eigenvalues(
        dense.unobservable_eigenvalues
    )


def test_fig43_star_loses_its_kernel_and_the_hub_free_eigenvectors() -> None:
    """Fig. 4.3 (a): every O_i has full rank, yet rank O = 15 of 24 (W singular: 3 velocity
    directions; eigenvalue 3/4 twice on the leaves: 3 position/velocity pairs)."""
    spec = load_case("fig43-case-a").spec
    result = sparse_rank(spec)
    assert result is not None and result.rank == 15 and result.margin >= 1e3
    assert _eigenvalues(result.unobservable_eigenvalues) == [0.0] * 3 + [0.75] * 6


def test_random_geometric_network_with_blind_agents_matches_the_spectral_rank() -> None:
    """120 agents, mean degree ≈ 4: many agents hear fewer than 3 others (blind), some W are
    singular; the sparse rank equals the eigen-decomposition's on every seed."""
    for seed in range(4):
        rng = np.random.default_rng(seed)
        positions = np.round(rng.uniform(0, 100, size=(120, 3)), 3)
        spec = spec_of(positions, [50.5, 50.5, 50.5], [], weights="metropolis")
        pairs = pairs_within_range(positions, 24.0)
        W = SparseWeights.named(
            120, np.concatenate(pairs), np.concatenate(pairs[::-1]), "metropolis"
        )
        spec = type(spec)(**{**vars(spec), "links": (W,)})
        units = unit_directions(spec.target[0], spec.agents[0])
        vectors = units[W.receiver] - units[W.sender]
        spectral = spectral_network_rank(W.dense(), W.receiver, vectors, scale=np.ones(120))
        result = sparse_rank(spec)
        assert result is not None and result.rank == spectral.rank
        assert _eigenvalues(result.unobservable_eigenvalues) == _eigenvalues(
            spectral.unobservable_eigenvalues
        )


def _geometric(n: int, radius: float, seed: int):
    """A seeded random geometric network of ``n`` agents in a cube of side 100 (3 decimals)."""
    rng = np.random.default_rng(seed)
    positions = np.round(rng.uniform(0, 100, size=(n, 3)), 3)
    return spec_of(positions, [50.5, 50.5, 50.5], [], weights="metropolis"), positions, radius


def test_a_component_of_600_agents_is_ranked_by_the_sparse_method_as_by_the_spectrum() -> None:
    """The command's route for components > 500 agents, end to end, against the eigen-
    decomposition of the dense W of the same network."""
    spec, positions, radius = _geometric(600, 16.0, 7)
    i, j = pairs_within_range(positions, radius)
    W = SparseWeights.named(600, np.concatenate([i, j]), np.concatenate([j, i]), "metropolis")
    spec = type(spec)(**{**vars(spec), "links": (W,)})
    assert np.bincount(W.component_labels()).max() > topology.SPECTRAL_MAX_AGENTS
    result = topology.analyze_topology(spec)
    assert result.network.method.startswith("sparse")
    units = unit_directions(spec.target[0], spec.agents[0])
    vectors = units[W.receiver] - units[W.sender]
    spectral = spectral_network_rank(W.dense(), W.receiver, vectors, scale=np.ones(600))
    assert result.network.rank == spectral.rank


def test_an_eigenvalue_of_w_inside_the_band_makes_the_kernel_count_inconclusive() -> None:
    """With ``cluster_tol`` at the smallest |μ| of W (so t/F ≤ |μ| < t·F), the inertia counts at
    ±t/F and ±t·F differ: margin below F, never a silent verdict."""
    spec, positions, radius = _geometric(120, 24.0, 1)
    i, j = pairs_within_range(positions, radius)
    W = SparseWeights.named(120, np.concatenate([i, j]), np.concatenate([j, i]), "metropolis")
    smallest = float(np.abs(np.linalg.eigvalsh(W.dense())).min())
    assert smallest > 1e-6  # this W is nonsingular
    units = unit_directions(spec.target[0], spec.agents[0])
    vectors = units[W.receiver] - units[W.sender]
    clear = sparse_network_rank(W, W.receiver, vectors, scale=np.ones(120))
    assert clear is not None and clear.margin >= 1e3
    inside = sparse_network_rank(
        W, W.receiver, vectors, scale=np.ones(120), cluster_tol=smallest * 2.0
    )
    assert inside is not None and inside.margin < 1e3
