"""The model claims: eq. (4.6) proved symbolically; Metropolis weights checked exactly."""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from theory.core.case_file import bundled_cases
from theory.core.claims import Context
from theory.core.network import exact_metropolis_weights, metropolis_weights
from theory.kinds import load_case, parse_case
from theory.registry import get_claim
from theory.tdoa import model
from theory.tdoa.model import cv_discrete
from theory.tdoa.observability import weights


def test_discretization_claim_is_verified() -> None:
    (result,) = get_claim("seed000.eq4.6").run(None)
    assert result.status == "verified" and result.method == "symbolic" and result.case == "-"
    for dim in ("2d", "3d"):
        evidence = result.evidence[dim]
        assert evidence["A_exact"] and evidence["B_exact"] and evidence["library_exact"]
        T = sp.Symbol("T", positive=True)
        d = 2 if dim == "2d" else 3
        expected_cov = sp.Matrix(
            sp.BlockMatrix(
                [
                    [T**3 / 3 * sp.eye(d), T**2 / 2 * sp.eye(d)],
                    [T**2 / 2 * sp.eye(d), T * sp.eye(d)],
                ]
            )
        )
        assert sp.simplify(
            evidence["integral_white_noise_covariance"] - expected_cov
        ).is_zero_matrix


def test_discretization_claim_refutes_a_wrong_printed_A(monkeypatch) -> None:
    def wrong(T, dim):
        eye, zero = sp.eye(dim), sp.zeros(dim, dim)
        return sp.Matrix(sp.BlockMatrix([[eye, T / 2 * eye], [zero, eye]]))

    monkeypatch.setattr(model, "cv_discrete_symbolic", wrong)
    (result,) = model.discretization_claim(None, Context())
    assert result.status == "refuted" and not result.evidence["3d"]["A_exact"]


def test_discretization_claim_refutes_a_wrong_floating_model(monkeypatch) -> None:
    def rounded(T, dim=3):
        A, B = cv_discrete(T, dim)
        return A, B * (1 + 1e-15)

    monkeypatch.setattr(model, "cv_discrete", rounded)
    (result,) = model.discretization_claim(None, Context())
    assert result.status == "refuted" and not result.evidence["2d"]["library_exact"]


@st.composite
def undirected_graphs(draw, *, min_nodes: int = 2, max_nodes: int = 12):
    n = draw(st.integers(min_nodes, max_nodes))
    p = draw(st.floats(0.1, 1.0))
    graph = nx.gnp_random_graph(n, p, seed=draw(st.integers(0, 2**32 - 1)))
    return nx.to_numpy_array(graph, dtype=bool)


@given(undirected_graphs())
def test_exact_metropolis_is_symmetric_doubly_stochastic(adjacency: np.ndarray) -> None:
    exact = exact_metropolis_weights(adjacency)
    n = len(exact)
    W = np.array([[float(w) for w in row] for row in exact])
    assert all(sum(row) == 1 for row in exact)
    assert all(sum(exact[i][j] for i in range(n)) == 1 for j in range(n))
    assert all(exact[i][j] == exact[j][i] for i in range(n) for j in range(n))
    assert all(exact[i][i] > 0 for i in range(n))
    eigenvalues = np.linalg.eigvalsh(W)
    assert eigenvalues.min() > -1 and eigenvalues.max() <= 1 + 1e-12
    assert np.abs(metropolis_weights(adjacency) - W).max() <= weights.ROUNDING_TOL


def test_metropolis_claim_on_the_bundled_cases() -> None:
    claim = get_claim("seed000.sec4.2.2.metropolis")
    ran = 0
    for path in bundled_cases().values():
        case = load_case(path)
        if case.kind != "tdoa":
            continue
        results = claim.run(case)
        if case.spec.weights_rule != "metropolis":
            assert results == []
            continue
        ran += 1
        (result,) = results
        assert result.status == "verified", result.message
        assert result.margin == pytest.approx(
            min(float(np.diag(w).min()) for w in case.spec.weights), rel=1e-12
        )
    assert ran >= 1


def test_metropolis_claim_refutes_wrong_floating_weights() -> None:
    case = load_case(bundled_cases()["fig43-case-d"])
    case.spec.weights[0, 0, 0] += 1e-12
    (result,) = weights.metropolis_claim(case, Context())
    assert result.status == "refuted"
    assert result.evidence["steps_shown"][0]["max_float_deviation"] > weights.ROUNDING_TOL


def test_metropolis_claim_does_not_apply_to_uniform_weights() -> None:
    data = {
        "name": "u",
        "source": "test",
        "kind": "tdoa",
        "tdoa": {
            "T": 1.0,
            "target": [1, 2, 3],
            "agents": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
            "edges": [[1, 2], [2, 3]],
            "weights": "uniform",
        },
    }
    assert weights.metropolis_claim(parse_case(data), Context()) == []


def test_exact_weights_are_the_design_rule() -> None:
    path = np.array([[0, 1, 0], [1, 0, 1], [0, 1, 0]], dtype=bool)
    third = Fraction(1, 3)
    assert exact_metropolis_weights(path) == [
        [1 - third, third, 0],
        [third, third, third],
        [0, third, 1 - third],
    ]


def test_metropolis_claim_checks_every_step_of_a_time_varying_network() -> None:
    data = {
        "name": "moving",
        "source": "test",
        "kind": "tdoa",
        "tdoa": {
            "T": 1.0,
            "target": [[17, -5, -15], [16, -4, -14], [15, -3, -13]],
            "agents": [
                [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]],
                [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [30, 4, -2]],
                [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]],
            ],
            "comm_range": 12,
        },
    }
    case = parse_case(data)
    (result,) = weights.metropolis_claim(case, Context())
    steps = result.evidence["steps_shown"]
    assert result.status == "verified" and result.evidence["n_steps"] == 3
    assert steps[0]["W"] != steps[1]["W"]
    assert steps[1]["W"][3] == ["0", "0", "0", "1"]
