"""Seed 000 App. C.2: the printed gap identity is refuted, the corrected one proved and checked."""

from __future__ import annotations

from fractions import Fraction

import flint
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from theory.consensus import suboptimal_gains as sg
from theory.registry import get_claim


def mat(rows) -> flint.fmpq_mat:
    flat = [Fraction(x) for row in rows for x in row]
    return flint.fmpq_mat(
        len(rows), len(rows[0]), [flint.fmpq(x.numerator, x.denominator) for x in flat]
    )


def eye(n: int) -> flint.fmpq_mat:
    return mat([[int(i == j) for j in range(n)] for i in range(n)])


rationals = st.fractions(min_value=-5, max_value=5, max_denominator=4)


@st.composite
def matrices(draw, rows: int, cols: int) -> flint.fmpq_mat:
    return mat([[draw(rationals) for _ in range(cols)] for _ in range(rows)])


@st.composite
def instances(draw) -> dict:
    """Agent data with ``Π ⪰ Π* ⪰ 0`` (``E_i`` is a non-negative combination, so ``P ≥ P*``
    gives ``Π − Π* ⪰ 0``) and ``R ≻ 0``."""
    n, p = draw(st.integers(1, 3)), draw(st.integers(1, 2))
    B, D, F = (draw(matrices(n, n)) for _ in range(3))
    G = draw(matrices(p, p))
    Pi_star = B * B.transpose()
    return {
        "A": draw(matrices(n, n)),
        "C": draw(matrices(p, n)),
        "R": G * G.transpose() + eye(p),
        "Q": F * F.transpose(),
        "L": draw(matrices(n, p)),
        "Pi": Pi_star + D * D.transpose(),
        "Pi_star": Pi_star,
    }


def gap(d: dict) -> flint.fmpq_mat:
    """``P_i(k+1) − P*_i(k+1)`` straight from (5.15) and (C.2)."""
    K = sg.optimal_gain(d["A"], d["C"], d["R"], d["Pi_star"])
    return sg.bound_step(d["A"], d["C"], d["R"], d["Q"], d["L"], d["Pi"]) - sg.bound_step(
        d["A"], d["C"], d["R"], d["Q"], K, d["Pi_star"]
    )


def args(d: dict) -> tuple:
    return d["A"], d["C"], d["R"], d["L"], d["Pi"], d["Pi_star"]


def test_the_claim_is_corrected_with_the_scalar_counterexample() -> None:
    (result,) = get_claim("seed000.appC.2").run(None)
    assert (result.status, result.method, result.case) == ("corrected", "symbolic", "-")
    ce = result.evidence["counterexample"]
    assert ce["L_star"] == "1/2"
    assert ce["true_P_star_minus_P"] == "-3/2" and ce["printed_right_side"] == "-1"
    assert ce["corrected_right_side_for_P_minus_P_star"] == "3/2"
    assert result.margin == 0.5
    randoms = result.evidence["random_instances"]
    assert randoms["all_exact_checks_hold"]
    assert randoms["printed_failures"] == len(randoms["instances"]) == 12


def test_scalar_counterexample_by_hand() -> None:
    """A = C = R = 1, Q = 0, E(P*) = 1, E(P) = 2, L = 0, in plain fractions."""
    L_star = Fraction(1) * 1 * 1 / (1 + 1 * 1 * 1)
    P_star = (1 - L_star) ** 2 * 1 + L_star**2
    P = (1 - 0) ** 2 * 2 + 0
    printed = (1 - L_star) * (1 - 2) * (1 - L_star) - (0 - L_star) * (1 + 2) * (0 - L_star)
    corrected = (1 - 0) * (2 - 1) * (1 - 0) + (0 - L_star) * (1 + 1) * (0 - L_star)
    assert (L_star, P_star - P, printed, corrected) == (
        Fraction(1, 2),
        Fraction(-3, 2),
        -1,
        Fraction(3, 2),
    )


def test_free_algebra_proof_has_zero_residuals() -> None:
    residuals = sg.free_algebra_residuals()
    assert residuals["corrected_residual"] == "0"
    assert residuals["printed_residual"] == "0"


@pytest.mark.parametrize(("n", "p"), [(1, 1), (2, 1)])
def test_entrywise_proof(n: int, p: int) -> None:
    assert sg.entrywise_proof(n, p)


@pytest.mark.slow
@pytest.mark.parametrize(("n", "p"), [(2, 2), (3, 1)])
def test_entrywise_proof_larger(n: int, p: int) -> None:
    assert sg.entrywise_proof(n, p)


@given(instances())
def test_corrected_identity_holds_exactly(d) -> None:
    assert gap(d) == sg.corrected_gap(*args(d))


@given(instances())
def test_printed_identity_fails_exactly_by_the_cross_term(d) -> None:
    """printed − (P* − P) = −(M C Δ G' + G Δ C' M'): the printed identity holds iff that
    (non-identically-zero) rational function vanishes."""
    printed = sg.printed_gap(*args(d))
    discrepancy = sg.printed_discrepancy(*args(d))
    assert printed + gap(d) == discrepancy
    assert (printed == -gap(d)) == (
        discrepancy == flint.fmpq_mat(discrepancy.nrows(), discrepancy.ncols())
    )


@given(instances())
def test_the_printed_identity_holds_on_its_null_set_l_equal_l_star(d) -> None:
    d = {**d, "L": sg.optimal_gain(d["A"], d["C"], d["R"], d["Pi_star"])}
    assert sg.printed_gap(*args(d)) == -gap(d)


@given(instances())
def test_conclusion_and_c3(d) -> None:
    """Π ⪰ Π* gives P_i(k+1) ⪰ P*_i(k+1); (C.3) is (5.15) with the gain (C.2)."""
    assert sg.is_psd(gap(d))
    K = sg.optimal_gain(d["A"], d["C"], d["R"], d["Pi_star"])
    assert sg.bound_step(d["A"], d["C"], d["R"], d["Q"], K, d["Pi_star"]) == sg.riccati_form(
        d["A"], d["C"], d["R"], d["Q"], d["Pi_star"]
    )


def test_printed_identity_fails_on_generic_instances() -> None:
    rng = np.random.default_rng(7)
    for n, p, agents in [(2, 1, 2), (3, 2, 3), (4, 4, 2)]:  # n = p: the untransposed reading
        d = sg.random_instance(rng, n, p, agents)
        assert gap(d) == sg.corrected_gap(*args(d))
        assert sg.printed_gap(*args(d)) != -gap(d)
        untransposed_M = d["L"] - sg.optimal_gain(d["A"], d["C"], d["R"], d["Pi_star"])
        if n == p:  # as printed, without the transpose: also wrong
            G = d["A"] - (d["L"] - untransposed_M) * d["C"]
            S = d["R"] + d["C"] * d["Pi"] * d["C"].transpose()
            literal = G * (d["Pi_star"] - d["Pi"]) * G.transpose() - untransposed_M * S * (
                untransposed_M
            )
            assert literal != -gap(d)


def test_is_psd() -> None:
    assert sg.is_psd(mat([[2, 1], [1, 1]]))
    assert sg.is_psd(mat([[1, 1], [1, 1]]))
    assert sg.is_psd(mat([[0, 0], [0, 0]]))
    assert not sg.is_psd(mat([[1, 2], [2, 1]]))
    assert not sg.is_psd(mat([[0, 0], [0, -1]]))  # leading minors alone would accept this
    assert not sg.is_psd(mat([[1, 1], [0, 1]]))


def test_a_wrong_gain_makes_the_claim_refuted(monkeypatch) -> None:
    """Known-bad input: with L* = A Π* C' R⁻¹ (the S* dropped) the corrected identity fails."""

    def wrong(A, C, R, Pi_star):
        return A * Pi_star * C.transpose() * R.inv()

    monkeypatch.setattr(sg, "optimal_gain", wrong)
    (result,) = get_claim("seed000.appC.2").run(None)
    assert result.status == "refuted"
    assert not result.evidence["random_instances"]["all_exact_checks_hold"]
