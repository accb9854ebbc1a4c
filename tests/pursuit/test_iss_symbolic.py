"""Symbolic checks of seed 003's error algebra (sympy, exact), 2D and 3D, Type I and II."""

from __future__ import annotations

import pytest
import sympy as sp

from theory.pursuit.derivations import (
    cayley_rotation,
    delta_check,
    delta_matrix,
    error_dynamics_check,
    lyapunov_derivative_check,
    rotation_rate_check,
    skew,
)
from theory.registry import all_claims, get_claim

CASE_CLAIMS = ("seed003.thm1", "seed003.lem4", "seed003.lem3", "seed003.thm2")
MODEL_CLAIMS = (
    "seed003.eq4",
    "seed003.eq21",
    "seed003.eq22.delta-bar",
    "seed003.lem2",
    "seed003.eq70",
    "seed003.eq71",
    "seed003.eq72",
    "seed003.eq74",
    "seed003.eq75",
)


@pytest.mark.parametrize("dim", [2, 3])
def test_rdot_is_r_times_standard_skew(dim: int) -> None:
    check = rotation_rate_check(dim)
    assert check.holds, check.residual


def test_printed_skew_of_eq4_fails_rdot() -> None:
    check = rotation_rate_check(3, printed=True)
    assert not check.holds
    assert any(sp.simplify(x) != 0 for x in check.residual)


@pytest.mark.parametrize("dim", [2, 3])
def test_delta_of_eq22_follows_from_standard_skew_only(dim: int) -> None:
    check = delta_check(dim)
    assert check.standard_consistent
    assert check.printed_consistent is (dim == 2)


@pytest.mark.parametrize("dim", [2, 3])
def test_gram_determinant_needs_epsilon1(dim: int) -> None:
    eps = sp.symbols(f"epsilon1:{dim + 1}", real=True)
    expected = eps[0] ** 2 * (sum(e**2 for e in eps) if dim == 3 else 1)
    check = delta_check(dim)
    assert sp.expand(check.gram_determinant - expected) == 0
    # Remark 6 claims ε ≠ 0 suffices: a non-zero ε with ε₁ = 0 makes ΔΔᵀ singular
    witness = check.nonzero_epsilon_singular
    assert any(witness["epsilon"]) and witness["det_gram"] == 0


def test_delta_matrix_gives_minus_skew_epsilon_plus_v() -> None:
    v1, p, q, r = sp.symbols("v1 p q r")
    eps = sp.Matrix(sp.symbols("e1:4"))
    lhs = delta_matrix(eps) * sp.Matrix([v1, p, q, r])
    rhs = -skew(sp.Matrix([p, q, r])) * eps + sp.Matrix([v1, 0, 0])
    assert sp.expand(lhs - rhs) == sp.zeros(3, 1)


def test_cayley_rotation_is_orthogonal() -> None:
    a = sp.Matrix(sp.symbols("a1:4"))
    rotation = cayley_rotation(a)
    assert sp.simplify(rotation * rotation.T - sp.eye(3)) == sp.zeros(3, 3)
    assert sp.simplify(rotation.det()) == 1


@pytest.mark.parametrize("dim", [2, 3])
def test_cayley_rotation_closed_form_is_the_transform(dim: int) -> None:
    """The closed form equals (I − A)⁻¹(I + A) as rational functions, in 2D and 3D."""
    a = sp.Matrix(sp.symbols("a1:4")[: 3 if dim == 3 else 1])
    eye, skew_a = sp.eye(dim), skew(a)
    difference = cayley_rotation(a) - (eye - skew_a).inv() * (eye + skew_a)
    assert difference.applyfunc(sp.cancel) == sp.zeros(dim, dim)


@pytest.mark.parametrize("dim", [2, 3])
def test_error_dynamics_eq21(dim: int) -> None:
    check = error_dynamics_check(dim)
    assert check.holds, check.residual


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("controller", ["I", "II"])
@pytest.mark.parametrize("estimated", [False, True])
def test_lyapunov_derivative_cancellation(dim: int, controller: str, estimated: bool) -> None:
    """Lemma 2 (V̇ = −eᵀKe) and eq. (70), exactly; a wrong expectation leaves a residual."""
    check = lyapunov_derivative_check(dim, controller, estimated)
    assert check.holds, check.residual
    assert sp.simplify(sp.cancel(check.lhs - check.rhs)) == 0
    # the check can fail: dropping the −eᵀKe term leaves a non-zero residual
    e1 = sp.Symbol("ep1", real=True)
    k11 = sp.Symbol("k11", real=True)
    assert sp.simplify(sp.cancel(check.lhs - (check.rhs + k11 * e1**2))) != 0


def test_every_seed003_claim_is_registered() -> None:
    ids = {claim.id for claim in all_claims()}
    assert set(MODEL_CLAIMS) | set(CASE_CLAIMS) <= ids
    for claim_id in CASE_CLAIMS:
        assert get_claim(claim_id).kinds == ("pursuit",)
    for claim_id in MODEL_CLAIMS:
        assert get_claim(claim_id).kinds == ()


@pytest.mark.parametrize(
    ("claim_id", "status"),
    [
        ("seed003.eq4", "corrected"),
        ("seed003.eq21", "verified"),
        ("seed003.eq22.delta-bar", "corrected"),
        ("seed003.lem2", "verified"),
        ("seed003.eq70", "verified"),
        ("seed003.eq71", "corrected"),
        ("seed003.eq72", "corrected"),
        ("seed003.eq74", "corrected"),
        ("seed003.eq75", "corrected"),
    ],
)
def test_model_claim_statuses(claim_id: str, status: str) -> None:
    (result,) = get_claim(claim_id).run(None)
    assert result.status == status
    assert result.case == "-"
    assert result.to_json(get_claim(claim_id).source)["evidence"]
