"""Hypothesis strategies for your own property tests: TDOA scenes, networks, weights, consensus
filters, state-space pairs and pursuit parameters.

These are the strategies trackcert's own test suite draws from (``theory.strategies``): names
are plural nouns, bounds are keyword-only, conditioning is bounded, and impossible arguments
raise ``hypothesis.errors.InvalidArgument`` naming the value. The values they draw are numpy
arrays or small frozen records of arrays that the functions of :mod:`trackcert` take directly::

    import networkx as nx
    from hypothesis import given
    import trackcert
    from trackcert.strategies import networks, tdoa_scenes

    @given(tdoa_scenes(dim=3, family="cone"))
    def test_receivers_on_a_cone_never_localize(scene):
        graph = nx.complete_graph(len(scene.agents))
        assert trackcert.topology(scene.agents, scene.target, graph).verdict is not True

    @given(networks(min_agents=4, max_agents=6))
    def test_hears_matrices_are_graphs(hears):
        graph = nx.from_numpy_array(hears.astype(int), create_using=nx.DiGraph)
        ...

``tdoa_scenes`` draws :class:`TdoaScene` (``target``, ``agents``, ``family`` of
:data:`SCENE_FAMILIES`); ``networks`` boolean "hears" matrices ``H[r, s]``;
``weight_matrices`` row-stochastic weights of :data:`WEIGHT_KINDS` on a network;
``dkf_problems`` :class:`DkfProblem` (``A``, ``C``, ``W``, gains ``L``, the drawing seed);
``state_space_pairs`` ``(A, C)`` of bounded conditioning; ``pursuit_cases`` and
``simulated_pursuit_cases`` validated seed 003 cases and ``simulated_pursuit_blocks`` their
``pursuit:`` blocks, all of which :func:`trackcert.iss` and :func:`trackcert.simulate` take
(the simulated ones satisfy every ISS condition); ``pursuit_parameters``,
``digraph_laplacians`` and ``tracker_states`` the pieces of seed 003's analysis.
"""

from theory.strategies import (
    SCENE_FAMILIES,
    WEIGHT_KINDS,
    DkfProblem,
    PursuitParameters,
    TdoaScene,
    TrackerState,
    digraph_laplacians,
    dkf_problems,
    is_connected,
    networks,
    pursuit_cases,
    pursuit_parameters,
    simulated_pursuit_blocks,
    simulated_pursuit_cases,
    state_space_pairs,
    tdoa_scenes,
    tracker_states,
    weight_matrices,
)

__all__ = [
    "SCENE_FAMILIES",
    "WEIGHT_KINDS",
    "DkfProblem",
    "PursuitParameters",
    "TdoaScene",
    "TrackerState",
    "digraph_laplacians",
    "dkf_problems",
    "is_connected",
    "networks",
    "pursuit_cases",
    "pursuit_parameters",
    "simulated_pursuit_blocks",
    "simulated_pursuit_cases",
    "state_space_pairs",
    "tdoa_scenes",
    "tracker_states",
    "weight_matrices",
]
