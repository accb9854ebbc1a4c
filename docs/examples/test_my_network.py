"""An example test suite for your own robot network: copy it beside your code and edit the
numbers. Run it with ``python -m pytest test_my_network.py``.

It checks, before anyone goes to the lake, that

* every agent of the 6-robot formation can localize a target anywhere in the work area, also
  after losing any one communication link (seed 000 Thm 4.2.3, decided exactly);
* the consensus Kalman filter the robots run on the same graph is S-detectable (seed 000
  Def. 5.2.4), and that the suite notices when the sensors are chosen badly;
* the pursuit gains keep the coordination loop ISS over the whole range you may tune them in
  (seed 003, Theorem 2 as corrected).

Agents are rows of a numpy array and graph nodes are those row indices (0-based); the failure
messages name agents by 1-based ids, as the papers and case files do.
"""

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import trackcert
from trackcert.testing import assert_iss, assert_observable, assert_s_detectable

# The formation: six robots near the surface (x, y, z in metres; z < 0 is depth).
AGENTS = np.array(
    [[0, 0, -2], [40, 5, -8], [55, 45, -3], [20, 70, -10], [-20, 50, -5], [-30, 15, -12]],
    dtype=float,
)
# Acoustic links: a ring with one chord across it.
GRAPH = nx.cycle_graph(6)
GRAPH.add_edge(0, 3)
# Where the target may be: x in [-50, 80], y in [-20, 90], depth 20 to 60 m.
WORK_AREA = [(-50.0, 80.0), (-20.0, 90.0), (-60.0, -20.0)]

# Positions to the centimetre (a 1e-300 m coordinate is not a position; trackcert refuses it).
targets = st.tuples(*(st.floats(low, high).map(lambda v: round(v, 2)) for low, high in WORK_AREA))


def test_every_agent_localizes_a_target_in_the_middle() -> None:
    result = assert_observable(AGENTS, [10, 30, -40], GRAPH)
    assert all(agent["rank"] == 6 for agent in result.agents)


@settings(max_examples=25, deadline=None)
@given(target=targets)
def test_every_agent_localizes_the_target_anywhere_in_the_work_area(target) -> None:
    assert_observable(AGENTS, target, GRAPH)


@pytest.mark.parametrize("lost", sorted(GRAPH.edges))
def test_losing_any_one_link_keeps_every_agent_localizing(lost) -> None:
    damaged = GRAPH.copy()
    damaged.remove_edge(*lost)
    assert_observable(AGENTS, [10, 30, -40], damaged)


def test_two_halves_that_cannot_hear_each_other_fail_loudly() -> None:
    halves = nx.Graph([(0, 1), (1, 2), (3, 4), (4, 5)])
    with pytest.raises(AssertionError, match="cannot localize"):
        assert_observable(AGENTS, [10, 30, -40], halves)


def test_the_verdict_comes_with_a_certificate_anyone_can_recheck() -> None:
    certificate = trackcert.certify(trackcert.topology(AGENTS, [10, 30, -40], GRAPH))
    assert certificate.verdict is True
    assert trackcert.check(certificate).verdict is True


# The consensus Kalman filter on the same graph: a slowly diverging 2-state drift model,
# robots 1 and 4 measure x, robots 2 and 5 measure y, robots 3 and 6 only relay.
A = np.array([[1.02, 0.1], [0.0, 1.01]])
Q = 0.01 * np.eye(2)
X, Y, NONE = np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.zeros((0, 2))
W = trackcert.consensus_weights(GRAPH)  # Metropolis weights on the graph


def noise(C: list[np.ndarray]) -> list[np.ndarray]:
    return [0.1 * np.eye(len(c)) for c in C]


def test_the_consensus_filter_is_s_detectable() -> None:
    C = [X, Y, NONE, X, Y, NONE]
    assert_s_detectable(A, C, W, Q, noise(C))


def test_measuring_only_y_cannot_see_the_unstable_x_drift() -> None:
    C = [Y, Y, NONE, Y, Y, NONE]
    with pytest.raises(AssertionError, match="not S-detectable"):
        assert_s_detectable(A, C, W, Q, noise(C))


# Three trackers pursuing the target on a directed ring (seed 003 Table I's parameters).
PURSUIT = {
    "dim": 2,
    "controller": "II",
    "omega_bar": 0.05,
    "epsilon": [-0.5, 0],
    "K_p": [0.4, 0.2],
    "k_gamma": 500,
    "k_c": 0.2,
    "trackers": [{"r_x": 30, "r_y": 30, "gamma0": 2 * np.pi * k / 3} for k in range(3)],
    "edges": [[2, 1], [3, 2], [1, 3]],
}


@settings(max_examples=10, deadline=None)
@given(k_gamma=st.floats(10, 1000), k_c=st.floats(0.05, 2.0))
def test_the_pursuit_loop_is_iss_for_every_gain_we_may_tune(k_gamma, k_c) -> None:
    assert_iss(**{**PURSUIT, "k_gamma": k_gamma, "k_c": k_c})
