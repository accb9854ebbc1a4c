"""Seed 003's ISS conditions near their thresholds (issue 17 item 1): exact decisions, never wrong.

The boundary properties of :mod:`theory.pursuit.properties` run here in CI's bounded profile (and
in ``trackcert falsify``); the exact predicates of :mod:`theory.pursuit.iss` are checked
against independent computations (sympy eigenvalues, scipy's a(L) away from 0).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from hypothesis import given

from theory.falsify import properties_for
from theory.kinds import load_case, parse_case
from theory.pursuit.certificates import safe_constant
from theory.pursuit.iss import (
    gain_matrix_definite,
    generalized_algebraic_connectivity,
    iss_conditions,
    pursuit_iss,
    r_perp_connectivity_positive,
    region_argument_sound,
)
from theory.pursuit.model import left_eigenvector
from theory.pursuit.properties import (
    RegionPoint,
    certificate_sound,
    region_case,
    region_sound,
)
from theory.strategies import digraph_laplacians

PROPERTIES = {
    p.id: p
    for name in ("seed003.thm1", "seed003.thm2")
    for p in properties_for(name)
    if "boundary" in p.id
}


def test_the_boundary_properties_are_registered_for_falsify() -> None:
    assert set(PROPERTIES) == {
        "seed003.thm1.boundary/corrected",
        "seed003.thm2.certificate-boundary/corrected",
    }


@given(point=PROPERTIES["seed003.thm1.boundary/corrected"].examples)
def test_region_verdict_is_exact_through_lambda_min_one(point) -> None:
    assert region_sound(point), point


@given(point=PROPERTIES["seed003.thm2.certificate-boundary/corrected"].examples)
def test_certificate_exists_iff_epsilon_1_nonzero(point) -> None:
    assert certificate_sound(point), point


def test_rotated_gain_on_the_float_boundary_is_decided_by_its_decimals() -> None:
    """K_p = Q diag(1, 2) Qᵀ computed in floats: numpy's least eigenvalue is 1.0, the decimals'
    is below 1 (sympy), so the printed region (72) does not follow from the argument."""
    point = RegionPoint("rotated", 1.0)
    spec = parse_case(region_case(point)).spec
    K_p = sp.Matrix([[sp.Rational(repr(float(x))) for x in row] for row in spec.K_p])
    exact_min = min(K_p.eigenvals())
    assert np.linalg.eigvalsh(spec.K_p)[0] >= 1.0 and sp.N(exact_min, 30) < 1
    assert pursuit_iss(spec).printed_region_sound is False


@pytest.mark.parametrize(
    ("K", "symmetric", "definite"),
    [
        ([[1.0, 0.0], [0.0, 1e-11]], True, True),
        ([[1.0, 1.0], [1.0, 1.0]], True, False),
        ([[1.0, 2.0], [2.0, 1.0]], True, False),
        ([[2.0, 1e-10], [0.0, 2.0]], False, True),
    ],
)
def test_gain_matrix_definiteness_is_exact(K, symmetric, definite) -> None:
    assert gain_matrix_definite(np.array(K)) == (symmetric, definite)


def test_region_argument_is_exact_at_one() -> None:
    assert region_argument_sound(np.diag([1.0, 3.0]))
    assert not region_argument_sound(np.diag([0.9999999999999999, 3.0]))


@given(laplacian=digraph_laplacians(max_agents=6))
def test_exact_connectivity_agrees_with_the_float_value(laplacian) -> None:
    """Strongly connected digraphs have a(L) > 0 (Lemma 1, Definition 1): the exact test says so,
    and scipy's a(L) is positive too (far from 0 for these small integer graphs)."""
    r = left_eigenvector(laplacian)
    assert r is not None
    a = generalized_algebraic_connectivity(laplacian.astype(float), np.array([float(x) for x in r]))
    assert r_perp_connectivity_positive(laplacian, r) and a > 1e-3


def test_bundled_conditions_are_decided_exactly() -> None:
    statuses = {
        name: {c.name: c.status for c in iss_conditions(load_case(name).spec)}
        for name in ("pursuit-table1-n3", "pursuit-table2-n3", "pursuit-not-strongly-connected")
    }
    assert statuses["pursuit-table1-n3"]["K_positive_definite"] == "holds"
    assert statuses["pursuit-table2-n3"]["algebraic_connectivity_positive"] == "holds"
    assert statuses["pursuit-not-strongly-connected"]["graph_strongly_connected"] == "fails"


def test_safe_constant_moves_in_the_safe_direction() -> None:
    assert safe_constant(Fraction(3), lambda x: x <= 1, towards_zero=True) == Fraction(3, 4)
    assert safe_constant(Fraction(1), lambda x: x >= 5, towards_zero=False) == 8
    assert safe_constant(Fraction(1), lambda x: x < 0, towards_zero=True) is None
