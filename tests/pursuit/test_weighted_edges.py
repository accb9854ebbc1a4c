"""Weighted digraphs in ``kind: pursuit`` cases: edges ``[s, r, a]`` (seed 003 §II-B's L = D_in − A
with a_rs = a; Lemma 1's reference [28]) in the case format, the Laplacian, the ISS constants, the
iss certificate read by ``proofs_check``, both simulation engines, and the strategies and
properties of eqs. (74)/(75) that draw such digraphs."""

from __future__ import annotations

import copy
import itertools
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given
from typer.testing import CliRunner

import proofs_check
from theory.cli import app
from theory.core.case_file import bundled_cases
from theory.core.errors import CaseError
from theory.kinds import parse_case
from theory.pursuit.certificates import iss_certificate
from theory.pursuit.closed_loop import simulate_dec
from theory.pursuit.iss import coordination_iss
from theory.pursuit.model import exact_laplacian, left_eigenvector
from theory.pursuit.properties import (
    coordination_case,
    coordination_examples,
    coordination_iss_holds,
)
from theory.pursuit.simulation import dec_arguments
from theory.strategies import digraph_laplacians

runner = CliRunner()

WEIGHTED_EDGES = [[2, 1, 0.5], [3, 2, 2], [1, 3], [1, 2, 0.07]]
"""Table I's ring 1 ← 2 ← 3 ← 1 with a_12 = 0.5, a_23 = 2, a_31 = 1 and an edge 1 → 2 of 0.07."""


def _table1(edges: list) -> dict:
    raw = yaml.safe_load(Path(bundled_cases()["pursuit-table1-n3"]).read_text(encoding="utf-8"))
    raw["pursuit"]["edges"] = edges
    raw["pursuit"]["dekf"]["weights"] = "uniform"
    raw.pop("expect")
    return raw


def test_weights_enter_the_laplacian_exactly() -> None:
    spec = parse_case(_table1(WEIGHTED_EDGES)).spec
    F = Fraction
    assert exact_laplacian(spec.laplacian) == [
        [F(1, 2), F(-1, 2), 0],
        [F(-7, 100), F(207, 100), -2],
        [-1, 0, 1],
    ]
    r = left_eigenvector(spec.laplacian)
    assert r == (F(69, 119), F(50, 357), F(100, 357))  # rᵀL = 0, Σr = 1 by hand
    unweighted = parse_case(_table1([e[:2] for e in WEIGHTED_EDGES])).spec
    assert np.array_equal(unweighted.laplacian, unweighted.laplacian.astype(int))
    assert left_eigenvector(unweighted.laplacian) != r


def test_unit_weights_are_the_unweighted_case() -> None:
    unit = parse_case(_table1([[2, 1, 1], [3, 2, 1.0], [1, 3]])).spec
    plain = parse_case(_table1([[2, 1], [3, 2], [1, 3]])).spec
    assert np.array_equal(unit.laplacian, plain.laplacian)
    assert coordination_iss(unit).a_L == pytest.approx(coordination_iss(plain).a_L, rel=1e-12)


@pytest.mark.parametrize(
    ("edges", "field"),
    [
        ([[2, 1, 0]], "pursuit.edges[1][3]"),
        ([[2, 1, -0.5]], "pursuit.edges[1][3]"),
        ([[2, 1, "heavy"]], "pursuit.edges[1][3]"),
        ([[2, 1, True]], "pursuit.edges[1][3]"),
        ([[2, 1, float("inf")]], "pursuit.edges[1][3]"),
        ([[2, 1, 0.5, 1]], "pursuit.edges"),
        ([[2, 1, 0.5], [2, 1]], "pursuit.edges"),
        ([[2, 2, 0.5]], "pursuit.edges[1]"),
        ([[2, 4, 0.5]], "pursuit.edges[1]"),
    ],
)
def test_bad_weights_are_refused_with_the_field(edges: list, field: str) -> None:
    with pytest.raises(CaseError) as info:
        parse_case(_table1(edges))
    assert info.value.field == field


def test_bad_weight_exits_2_without_traceback(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(_table1([[2, 1, -1], [3, 2], [1, 3]])), encoding="utf-8")
    result = runner.invoke(app, ["iss", str(path)])
    assert result.exit_code == 2
    assert "pursuit.edges[1][3]" in result.output and "Traceback" not in result.output


def test_dekf_edges_stay_pairs() -> None:
    raw = _table1(WEIGHTED_EDGES)
    raw["pursuit"]["dekf"]["edges"] = [[2, 1, 0.5]]
    with pytest.raises(CaseError) as info:
        parse_case(raw)
    assert info.value.field == "pursuit.dekf.edges"


@pytest.fixture(scope="module")
def weighted_certificate() -> dict:
    return iss_certificate(parse_case(_table1(WEIGHTED_EDGES)).spec)


def test_certificate_carries_the_weighted_laplacian(weighted_certificate: dict) -> None:
    L = weighted_certificate["data"]["laplacian"]
    assert L[1] == ["-7/100", "207/100", "-2"]
    assert proofs_check.check_certificate(weighted_certificate).valid


@pytest.mark.parametrize(("i", "j"), [(0, 1), (1, 0), (1, 2), (2, 0)])
@pytest.mark.parametrize("factor", [Fraction(1, 2), Fraction(3, 2)])
def test_moving_an_edge_weight_is_refused(
    weighted_certificate: dict, i: int, j: int, factor: Fraction
) -> None:
    """Every weight a_ij moved (its diagonal moved with it, so L1 = 0 still holds) breaks
    rᵀL = 0 and the certificate is refused (C1)."""
    tampered = copy.deepcopy(weighted_certificate)
    L = tampered["data"]["laplacian"]
    old = Fraction(L[i][j])
    L[i][j] = str(old * factor)
    L[i][i] = str(Fraction(L[i][i]) + old - old * factor)
    report = proofs_check.check_certificate(tampered)
    assert not report.valid
    assert any(c.name.startswith("C1: rᵀL = 0") and not c.valid for c in report.checks)


def test_engines_agree_and_use_the_weights() -> None:
    """ω_d(0) = ω̄ − k_c Lγ(0) with the weighted L (eq. (45)); NumPy and numba runs agree."""
    spec = parse_case(_table1(WEIGHTED_EDGES)).spec
    runs = {
        engine: simulate_dec(rng=np.random.default_rng(1), engine=engine, **dec_arguments(spec, 40))
        for engine in ("numpy", "numba")
    }
    expected = spec.omega_bar - spec.k_c * spec.laplacian @ dec_arguments(spec, 1)["initial_gammas"]
    for run in runs.values():
        assert run.gamma_rates[0] == pytest.approx(expected, abs=1e-12)
    numpy_run, numba_run = runs["numpy"], runs["numba"]
    assert np.max(np.abs(numpy_run.gammas - numba_run.gammas)) < 1e-9
    assert np.max(np.abs(numpy_run.positions - numba_run.positions)) < 1e-7


@given(digraph_laplacians(min_agents=2, max_agents=6, weighted=True))
def test_weighted_laplacians_are_exact_laplacians(L: np.ndarray) -> None:
    exact = exact_laplacian(L)
    assert all(sum(row) == 0 for row in exact)
    assert all(exact[i][j] <= 0 for i in range(len(L)) for j in range(len(L)) if i != j)
    r = left_eigenvector(L)
    assert r is not None and all(x > 0 for x in r)  # strongly connected: Lemma 1


def test_digraphs_without_a_hamiltonian_cycle_are_drawn() -> None:
    """Two triangles sharing vertex 0 (strongly connected, no Hamiltonian cycle) is reachable."""
    from hypothesis import find

    def hamiltonian(L: np.ndarray) -> bool:
        n = len(L)
        return any(
            all(L[p[(k + 1) % n], p[k]] < 0 for k in range(n))
            for p in itertools.permutations(range(n))
        )

    L = find(digraph_laplacians(min_agents=5, max_agents=5), lambda L: not hamiltonian(L))
    assert left_eigenvector(L) is not None


@given(coordination_examples(weighted=True))
def test_weighted_counterexamples_reload_as_cases(example) -> None:
    """A drawn weighted example becomes a valid case with the same Laplacian (exactly)."""
    spec = parse_case(coordination_case(example)).spec
    assert exact_laplacian(spec.laplacian) == exact_laplacian(example.laplacian)
    assert coordination_iss_holds(example)
