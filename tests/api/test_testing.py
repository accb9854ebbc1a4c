"""``trackcert.testing``: each helper returns the result when the property holds and otherwise
raises ``AssertionError`` naming the failing agent or condition, its numbers and the tolerances;
an inconclusive verdict fails too."""

from __future__ import annotations

import networkx as nx
import numpy as np
import pytest

from trackcert.testing import assert_iss, assert_observable, assert_s_detectable

FIG43_D = np.array([[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]])
TARGET = [17, -5, -15]
A = 2 * np.eye(2)
C = [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)]
Q = 0.1 * np.eye(2)
R = [0.1 * np.eye(1), 0.1 * np.eye(1), 0.1 * np.eye(2)]


def test_assert_observable_passes_and_names_the_agents_that_cannot_localize() -> None:
    assert assert_observable(FIG43_D, TARGET, nx.path_graph(4)).verdict is True
    with pytest.raises(AssertionError) as failure:
        assert_observable(FIG43_D, TARGET, nx.Graph([(0, 1), (1, 2)]))  # agent 4 alone
    message = str(failure.value)
    assert "agents [1, 2, 3, 4] cannot localize" in message
    assert "agent 4 (component 2): rank O_i = 0 of 6" in message
    assert "rank_tol" in message


def test_assert_observable_explains_a_heuristic_that_is_wrong() -> None:
    with pytest.raises(AssertionError, match=r"agent 1 .*rank O_i = 4 of 6.*heuristic says True"):
        assert_observable("cone-agents-unobservable")


def test_an_inconclusive_verdict_fails_with_its_reason() -> None:
    with pytest.raises(AssertionError, match=r"INCONCLUSIVE.*\n  undecided: "):
        assert_observable(FIG43_D, TARGET, nx.path_graph(4), inconclusive_factor=1e12)


def test_assert_s_detectable_names_the_violated_bounds_and_the_certificate() -> None:
    W_g = [[0.24, 0.76, 0], [0.76, 0.24, 0], [0, 0, 1]]
    assert assert_s_detectable(A, C, W_g, Q, R).verdict is True
    W_b = [[0.26, 0.74, 0], [0.74, 0.26, 0], [0, 0, 1]]
    with pytest.raises(AssertionError) as failure:
        assert_s_detectable(A, C, W_b, Q, R)
    message = str(failure.value)
    assert "not S-detectable" in message
    assert "agent 1: self-weight w_ii = 0.26 is not below 1/r(A_i^u)^2 = 0.25" in message
    assert "blind set [1]" in message and "s-detectability-infeasible certificate" in message


def test_assert_iss_lists_the_failing_conditions_not_the_inapplicable_ones() -> None:
    assert assert_iss("pursuit-table1-n3").verdict is True
    with pytest.raises(AssertionError) as failure:
        assert_iss("pursuit-singular-epsilon")
    message = str(failure.value)
    assert "delta_full_rank: fails (value 0" in message and "ε₁ = 0" in message
    assert "graph_strongly_connected" not in message.split("\n", 1)[1]  # N = 1: not applicable


def test_assert_iss_takes_the_block_as_keywords() -> None:
    from trackcert import iss

    block = iss("pursuit-table1-n1").to_case()["pursuit"]
    assert assert_iss(**block).verdict is True
    with pytest.raises(AssertionError, match="delta_full_rank"):
        assert_iss(**{**block, "epsilon": [0, 0]})
