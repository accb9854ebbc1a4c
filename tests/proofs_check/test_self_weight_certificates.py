"""Kind ``self-weight-necessary-violated`` (seed 000 Thm 5.2.10 (2) for every ``w ≥ u``): genuine
certificates from the hand-written cases of ``tests/data/dkf`` (an irrational real bound, a complex
largest root with a rational and with an irrational bound) and Example 1 are VALID; each number
moved past where the claim breaks is refused (exit 1: a check fails; exit 2: not canonical).

The expected thresholds are computed here in sympy from the eigenvalues (``1/|λ|²``), not with the
checker's polynomials."""

from __future__ import annotations

import copy
import json
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from typer.testing import CliRunner

from proofs_check import MalformedError, check_certificate
from theory.cli import app
from theory.consensus.design import exact_system, self_weight_family_exact
from theory.consensus.self_weight_bound import self_weight_threshold
from theory.kinds import load_case

CASES = Path(__file__).resolve().parents[1] / "data" / "dkf"
TINY = Fraction(1, 10**9)
"""How far past the threshold a tampered number is moved."""


def _certificate(case_name: str, agent: int = 0) -> dict:
    """The certificate of agent ``agent``'s self-weight family (rows rescaled)."""
    path = CASES / f"{case_name}.yaml"
    case = load_case(str(path) if path.exists() else case_name)
    A, C, W = exact_system(case)
    family = self_weight_family_exact(W, [agent])
    W0, slope = family.affine()
    offset, factor = W0[agent][agent], slope[agent][agent]
    threshold = self_weight_threshold(A, C[agent], agent, offset, factor)
    cert = threshold.certificate(A, C, W0, slope, case.name)
    assert cert is not None
    return cert


@pytest.fixture(scope="module")
def certs() -> dict[str, dict]:
    names = ("self-weight-irrational-real", "self-weight-complex-root",
             "self-weight-complex-irrational", "ch5-example-1-wg")  # fmt: skip
    return {name: _certificate(name) for name in names}


def _valid(cert: dict) -> bool:
    return check_certificate(cert).valid


def _root(cert: dict) -> sp.Expr:
    """The one root of the claimed polynomial in the claimed interval (sympy)."""
    w = sp.Symbol("w")
    P = sum(sp.Rational(c) * w**j for j, c in enumerate(cert["claim"]["threshold_polynomial"]))
    lo, hi = (sp.Rational(x) for x in cert["claim"]["threshold_interval"])
    roots = [r for r in sp.real_roots(sp.Poly(P, w)) if lo < r < hi]
    assert len(roots) == 1
    return roots[0]


def test_genuine_certificates_are_valid_and_state_the_exact_threshold(certs) -> None:
    assert all(_valid(c) for c in certs.values())
    # 1/(1 + √2)² = 3 − 2√2; the complex pair 1 ± i: 1/|λ|² = 1/2; x³ + x² − x − 3: the
    # complex pair's 1/|λ|² = ρ/3 with ρ the real root.
    assert sp.simplify(_root(certs["self-weight-irrational-real"]) - (3 - 2 * sp.sqrt(2))) == 0
    assert certs["self-weight-complex-root"]["claim"]["threshold"] == "1/2"
    x = sp.Symbol("x")
    real = sp.real_roots(x**3 + x**2 - x - 3)[0]
    assert abs(sp.N(_root(certs["self-weight-complex-irrational"]) - real / 3, 40)) < 1e-35
    assert certs["ch5-example-1-wg"]["claim"]["threshold"] == "1/4"


def test_trackcert_check_accepts_them_with_exit_0(certs, tmp_path: Path) -> None:
    for name, cert in certs.items():
        path = tmp_path / f"{name}.json"
        path.write_text(json.dumps(cert), encoding="utf-8")
        result = CliRunner().invoke(app, ["check", str(path)])
        assert result.exit_code == 0, result.stdout


def _tampered(cert: dict, change) -> dict:
    out = copy.deepcopy(cert)
    change(out)
    return out


def _set_threshold(value: Fraction, exact: bool):
    def change(cert: dict) -> None:
        cert["claim"]["threshold"], cert["claim"]["exact"] = str(value), exact
        cert["witness"].pop("below", None)
        if exact:
            cert["witness"]["below"] = str(value - 2 * TINY)

    return change


@pytest.mark.parametrize("exact", [True, False])
def test_a_threshold_below_the_exact_one_is_refused(certs, exact: bool) -> None:
    for name in ("ch5-example-1-wg", "self-weight-complex-root"):
        u = Fraction(certs[name]["claim"]["threshold"])
        assert not _valid(_tampered(certs[name], _set_threshold(u - TINY, exact)))


def test_a_threshold_above_is_valid_only_when_not_claimed_exact(certs) -> None:
    u = Fraction(certs["ch5-example-1-wg"]["claim"]["threshold"])
    assert _valid(_tampered(certs["ch5-example-1-wg"], _set_threshold(u + TINY, False)))
    assert not _valid(_tampered(certs["ch5-example-1-wg"], _set_threshold(u + TINY, True)))


def test_an_algebraic_threshold_moved_below_is_refused(certs) -> None:
    """The interval shifted down by 10⁻⁹ (and the polynomial shifted with it, u → u − 10⁻⁹):
    the claimed root is now below the exact threshold."""
    cert = certs["self-weight-irrational-real"]
    w = sp.Symbol("w")
    P = sum(sp.Rational(c) * w**j for j, c in enumerate(cert["claim"]["threshold_polynomial"]))
    shifted = sp.Poly(P.subs(w, w + sp.Rational(1, 10**9)), w)
    coefficients = [str(c) for c in reversed(shifted.clear_denoms()[1].primitive()[1].all_coeffs())]

    def change(c: dict) -> None:
        c["claim"]["threshold_polynomial"] = coefficients
        c["claim"]["threshold_interval"] = [
            str(Fraction(x) - TINY) for x in cert["claim"]["threshold_interval"]
        ]

    for exact in (True, False):
        tampered = _tampered(cert, change)
        tampered["claim"]["exact"] = exact
        assert not _valid(tampered)


@pytest.mark.parametrize("name", ["self-weight-irrational-real", "self-weight-complex-irrational"])
def test_a_wrong_polynomial_or_an_interval_that_does_not_isolate_is_refused(certs, name) -> None:
    cert = certs[name]
    coefficients = [int(c) for c in cert["claim"]["threshold_polynomial"]]
    wrong = [str(c + (1 if k == 1 else 0)) for k, c in enumerate(coefficients)]
    hi = Fraction(cert["claim"]["threshold_interval"][1])
    beyond = [str(hi), str(hi + Fraction(1, 1000))]  # no root
    for change in (
        lambda c: c["claim"].__setitem__("threshold_polynomial", wrong),
        lambda c: c["claim"].__setitem__("threshold_interval", ["-10", "10"]),  # several roots
        lambda c: c["claim"].__setitem__("threshold_interval", beyond),
    ):
        assert not _valid(_tampered(cert, change))


def test_the_witness_must_be_invariant_and_unobservable(certs) -> None:
    cert = certs["self-weight-complex-root"]

    def move_V(c: dict) -> None:
        c["witness"]["V"][0][0] = str(Fraction(c["witness"]["V"][0][0]) + 1)

    def agent_sees_x1(c: dict) -> None:
        c["data"]["C"][0] = [["1", "0", "0"]]

    def larger_M(c: dict) -> None:  # claims a larger block radius than A has
        c["witness"]["M"] = [[str(2 * Fraction(x)) for x in row] for row in c["witness"]["M"]]

    for change in (move_V, agent_sees_x1, larger_M):
        assert not _valid(_tampered(cert, change))


def test_a_falling_self_weight_or_a_non_stochastic_family_is_refused(certs) -> None:
    cert = certs["ch5-example-1-wg"]

    def falling(c: dict) -> None:  # W(w) row 1 = [1 − w, w, 0]: the self-weight falls
        c["data"]["W0"][0] = ["1", "0", "0"]
        c["data"]["W1"][0] = ["-1", "1", "0"]

    def leaking(c: dict) -> None:
        c["data"]["W1"][0][1] = "-1/2"

    for change in (falling, leaking):
        assert not _valid(_tampered(cert, change))


def test_exact_needs_the_whole_unobservable_subspace() -> None:
    """``A = diag(2, 3)``, agent 1 blind to both: a witness on ``x₁`` alone (``M = 2``) proves
    only ``u = 1/4 ≥ 1/9``, the exact threshold; claimed exact it is refused."""
    cert = {
        "format": "trackcert-certificate/1",
        "kind": "self-weight-necessary-violated",
        "claim": {"agent": 1, "exact": False, "threshold": "1/4"},
        "data": {
            "A": [["2", "0"], ["0", "3"]],
            "C": [[["0", "0"]], [["1", "0"], ["0", "1"]]],
            "W0": [["0", "1"], ["1/2", "1/2"]],
            "W1": [["1", "-1"], ["0", "0"]],
        },
        "witness": {"V": [["1"], ["0"]], "M": [["2"]]},
    }
    assert _valid(cert)
    assert not _valid(_tampered(cert, _set_threshold(Fraction(1, 4), True)))


@pytest.mark.parametrize(
    "change",
    [
        lambda c: c["claim"].__setitem__("threshold", "2/8"),
        lambda c: c["claim"].__setitem__("threshold", "0.25"),
        lambda c: c["witness"].__setitem__("below", "-0"),
        lambda c: c["witness"].__setitem__("below", "1/4"),  # not below the threshold
        lambda c: c["claim"].__setitem__("exact", "true"),
        lambda c: c["witness"].pop("below"),
        lambda c: c["claim"].__setitem__("threshold_interval", ["0", "1"]),  # both forms
    ],
)
def test_non_canonical_or_ill_formed_rational_claims_are_refused(certs, change) -> None:
    with pytest.raises(MalformedError):
        check_certificate(_tampered(certs["ch5-example-1-wg"], change))


@pytest.mark.parametrize(
    "change",
    [
        lambda c: c["claim"].__setitem__("threshold_polynomial", ["2", "-12", "2"]),  # gcd 2
        lambda c: c["claim"].__setitem__("threshold_polynomial", ["-1", "6", "-1"]),  # leading < 0
        lambda c: c["claim"].__setitem__("threshold_polynomial", ["1/2", "-3", "1/2"]),
        lambda c: c["claim"].__setitem__("threshold_polynomial", ["-1", "6"]),  # degree 1
        lambda c: c["claim"].__setitem__("threshold_interval", ["1/5", "1/6"]),  # l > r
    ],
)
def test_non_canonical_algebraic_claims_are_refused(certs, change) -> None:
    with pytest.raises(MalformedError):
        check_certificate(_tampered(certs["self-weight-irrational-real"], change))
