"""Seed 000 Lemma A.1.1: the printed bound (A.11) fails, the bound with the sum from l = 0 holds
(and is attained); exact laws of linear processes."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from theory.core.claims import Context
from theory.registry import get_claim
from theory.tdoa.estimation import stability as ss

ONE = Fraction(1)


def mean_square(law: dict[Fraction, Fraction]) -> Fraction:
    return sum((p * z * z for z, p in law.items()), Fraction(0))


def test_the_claim_is_corrected() -> None:
    (result,) = get_claim("seed000.lemA.1.1").run(None)
    assert (result.status, result.method, result.case) == ("corrected", "exact", "-")
    assert result.margin == 1.0
    ce = result.evidence["counterexample"]
    assert (ce["printed_bound_k1"], ce["E_norm_sq_k1"]) == ("0", "1")
    assert all(result.evidence["tight_when_alpha_is_1_minus_a2"])
    for process in result.evidence["processes"]:
        assert process["A10_holds_at_every_atom"]
        assert all(row["corrected_holds"] for row in process["steps"])
    assert all(
        ks == list(range(1, ss.STEPS + 1)) for ks in result.evidence["printed_fails_at_k"].values()
    )
    note = result.evidence["bounded_with_probability_one"]
    stay = list(note["d=1_sigma=1_M=5"]["P(stay ≤ 5)"].values())
    assert note["statement"].startswith("false") and stay == sorted(stay, reverse=True)


def test_survey_counterexample() -> None:
    """ζ_0 = 0, ζ_k i.i.d. with E‖ζ_k‖² = μ, α = ½: the printed bound is μ(1 − 2^{1−k}) < μ."""
    mu, half = Fraction(3), Fraction(1, 2)
    constants = {"v_min": ONE, "v_max": ONE, "mu": mu, "alpha": half, "mean_square_0": 0}
    assert ss.printed_bound(1, **constants) == 0
    for k in range(1, 10):
        assert ss.printed_bound(k, **constants) == mu * (1 - half ** (k - 1)) < mu
        assert ss.corrected_bound(k, **constants) == 2 * mu * (1 - half**k) >= mu
    assert ss.printed_bound(0, **constants) == ss.corrected_bound(0, **constants) == 0


@given(
    k=st.integers(1, 30),
    v_min=st.fractions(min_value=Fraction(1, 10), max_value=3),
    ratio=st.fractions(min_value=1, max_value=4),
    mu=st.fractions(min_value=Fraction(1, 10), max_value=5),
    alpha=st.fractions(min_value=Fraction(1, 100), max_value=1),
    m0=st.fractions(min_value=0, max_value=10),
)
def test_corrected_minus_printed_is_mu_over_v_min(k, v_min, ratio, mu, alpha, m0) -> None:
    assume(alpha > 0)
    c = {"v_min": v_min, "v_max": v_min * ratio, "mu": mu, "alpha": alpha, "mean_square_0": m0}
    assert ss.corrected_bound(k, **c) - ss.printed_bound(k, **c) == mu / v_min
    r = 1 - alpha
    closed = ratio * m0 * r**k + mu * (1 - r**k) / (v_min * alpha)
    assert ss.corrected_bound(k, **c) == closed


@st.composite
def processes(draw):
    """(a, s, ζ_0, α) with |a| < 1, s ≠ 0 and 0 < α ≤ 1 − a²."""
    a = draw(
        st.fractions(min_value=Fraction(-9, 10), max_value=Fraction(9, 10), max_denominator=10)
    )
    s = draw(st.fractions(min_value=Fraction(1, 4), max_value=3, max_denominator=4))
    z0 = draw(st.fractions(min_value=-3, max_value=3, max_denominator=4))
    slack = draw(st.fractions(min_value=0, max_value=Fraction(7, 8), max_denominator=8))
    alpha = (1 - a * a) * (1 - slack)
    return a, s, z0, alpha


@given(processes(), st.integers(0, 7))
def test_exact_law_obeys_the_corrected_bound(process, k) -> None:
    a, s, z0, alpha = process
    law = ss.rademacher_law(a, s, z0, k)
    assert sum(law.values()) == 1
    c = {"v_min": ONE, "v_max": ONE, "mu": s * s, "alpha": alpha, "mean_square_0": z0 * z0}
    ev = mean_square(law)
    assert ev == a ** (2 * k) * z0 * z0 + s * s * sum(a ** (2 * l) for l in range(k))
    assert ev <= ss.corrected_bound(k, **c)
    for z in law:  # (A.10) at every atom
        drift = ((a * z + s) ** 2 + (a * z - s) ** 2) / 2 - z * z
        assert drift <= s * s - alpha * z * z
    if alpha == 1 - a * a:  # the sharpest rate: tight, and the printed bound fails
        assert ev == ss.corrected_bound(k, **c)
        assert (ev <= ss.printed_bound(k, **c)) == (k == 0)


def test_symbolic_proof_and_gaussian_drift() -> None:
    proof = ss.symbolic_proof()
    assert proof["recursion_residual"] == proof["closed_form_residual"] == "0"
    assert proof["corrected_minus_printed"] == "mu/v_min"
    for d in (1, 2):
        assert ss.gaussian_drift(d)["equals"]


@pytest.mark.parametrize(
    "bad",
    [
        {"alpha": Fraction(0)},
        {"alpha": Fraction(3, 2)},
        {"mu": Fraction(0)},
        {"v_min": Fraction(0)},
        {"v_max": Fraction(1, 2)},
    ],
)
def test_bad_constants_raise(bad) -> None:
    c = {"v_min": ONE, "v_max": ONE, "mu": ONE, "alpha": Fraction(1, 2), "mean_square_0": ONE}
    with pytest.raises(ValueError, match=r"Lemma A\.1\.1 needs"):
        ss.corrected_bound(2, **{**c, **bad})


def test_negative_k_raises() -> None:
    c = {"v_min": ONE, "v_max": ONE, "mu": ONE, "alpha": ONE, "mean_square_0": ONE}
    with pytest.raises(ValueError, match="k must be"):
        ss.printed_bound(-1, **c)
    with pytest.raises(ValueError, match="k must be"):
        ss.rademacher_law(ONE, ONE, ONE, -1)


def test_the_printed_bound_in_place_of_the_corrected_one_is_refuted(monkeypatch) -> None:
    """Known-bad input: if the suite believed (A.11) as printed, the exact laws break it."""
    monkeypatch.setattr(ss, "corrected_bound", ss.printed_bound)
    (result,) = ss.lemma_a11_claim(None, Context())
    assert result.status == "refuted"
