"""TDOA model (seed 000 eqs. (4.1)–(4.10)): Jacobians against sympy and finite differences."""

from __future__ import annotations

import numpy as np
import scipy.linalg
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from theory.tdoa.model import (
    cv_continuous,
    cv_discrete,
    cv_discrete_symbolic,
    tdoa_jacobian,
    tdoa_measurement,
)

coordinate = st.floats(-50, 50, allow_nan=False)


def scenes(dim: int, n: int):
    points = st.lists(st.tuples(*[coordinate] * dim), min_size=n + 1, max_size=n + 1)
    return points.map(np.array).filter(lambda p: np.min(np.linalg.norm(p[1:] - p[0], axis=1)) > 1.0)


@given(st.floats(0.01, 10), st.sampled_from([2, 3]))
def test_discrete_model_is_exact_discretization(T: float, dim: int) -> None:
    F, G = cv_continuous(dim)
    A, B = cv_discrete(T, dim)
    np.testing.assert_allclose(A, scipy.linalg.expm(F * T), atol=1e-12 * max(1, T))
    integral = sum(scipy.linalg.expm(F * s) * w for s, w in zip(*_gauss(T), strict=True)) @ G
    np.testing.assert_allclose(B, integral, rtol=1e-10, atol=1e-12)


def _gauss(T: float) -> tuple[np.ndarray, np.ndarray]:
    nodes, weights = np.polynomial.legendre.leggauss(4)
    return 0.5 * T * (nodes + 1), 0.5 * T * weights


def test_symbolic_A_matches_numeric() -> None:
    T = sp.Symbol("T")
    A = cv_discrete_symbolic(T, 3)
    np.testing.assert_array_equal(np.array(A.subs(T, 0.5), dtype=float), cv_discrete(0.5, 3)[0])


@given(scenes(3, 4))
def test_jacobian_matches_finite_differences(points: np.ndarray) -> None:
    target, agents = points[0], points[1:]
    H = tdoa_jacobian(target, agents, 0, [1, 2, 3])
    step = 1e-6
    numeric = np.column_stack(
        [
            (
                tdoa_measurement(target + step * e, agents, 0, [1, 2, 3])
                - tdoa_measurement(target - step * e, agents, 0, [1, 2, 3])
            )
            / (2 * step)
            for e in np.eye(3)
        ]
    )
    np.testing.assert_allclose(H[:, :3], numeric, atol=1e-6)
    np.testing.assert_array_equal(H[:, 3:], 0.0)


def test_jacobian_matches_sympy() -> None:
    p = sp.Matrix(sp.symbols("px py pz", real=True))
    agents = np.array([[-7, 3, 5], [1, -2, -5], [5, -1, 4]], dtype=float)
    h = [(p - sp.Matrix(agents[0])).norm() - (p - sp.Matrix(a)).norm() for a in agents[1:]]
    jac = sp.Matrix(h).jacobian(p)
    target = np.array([17.0, -5.0, -15.0])
    values = np.array(jac.subs(dict(zip(p, target, strict=True))), dtype=float)
    np.testing.assert_allclose(tdoa_jacobian(target, agents, 0, [1, 2])[:, :3], values, rtol=1e-12)
