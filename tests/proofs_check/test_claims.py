"""A VALID certificate means what its kind says (issue 23): claim-weakening tamper tests.

Each test takes a genuine certificate, moves a number it states about its own claim (ρ, a rate,
a rank, the sampling period, a constant of ``iss``) just past the point where the kind's claim
no longer follows, and recomputes every stated value, so that the witness's inequalities still
hold where they can: the checker must refuse it. Moving the number the other way (a stronger
claim the witness still proves) must stay VALID. Numbers must be canonical rational strings.

The stated values are recomputed here from the paper's formulas in sympy (seed 000 eqs.
(5.12)–(5.13), (C.6), Lemma A.2.1; seed 003 §7 of ``docs/theory/pursuit-iss.md``), not with the
checker's own code.
"""

from __future__ import annotations

import copy
import json
from fractions import Fraction
from math import isqrt
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from proofs_check import MalformedError, check_certificate
from proofs_check.parse import loads, rational
from theory.cli import app
from theory.consensus.s_detectability import decide_s_detectability
from theory.core.case_file import bundled_cases
from theory.core.errors import PropertyFails
from theory.kinds import load_case
from theory.registry import certificate_bundle, certifiers

DATA = Path(__file__).resolve().parents[1] / "data" / "certificates"
TINY = Fraction(1, 10**9)
"""How far past a boundary a tampered number is moved."""


def stored(folder: str, name: str) -> dict:
    return json.loads((DATA / folder / f"{name}.json").read_text(encoding="utf-8"))


def singles(name: str) -> list[dict]:
    """The certificates of a ``valid/`` file (the members of a bundle)."""
    cert = stored("valid", name)
    return cert["certificates"] if cert["kind"] == "bundle" else [cert]


def verdict(cert: dict) -> str:
    """``valid``, ``invalid`` (exit 1) or ``malformed`` (exit 2), after a JSON round trip."""
    try:
        return "valid" if check_certificate(loads(json.dumps(cert))).valid else "invalid"
    except MalformedError:
        return "malformed"


def refusal(cert: dict) -> str:
    with pytest.raises(MalformedError) as error:
        check_certificate(loads(json.dumps(cert)))
    return str(error.value)


def relabel(cert: dict, kind: str) -> dict:
    return {**copy.deepcopy(cert), "kind": kind}


# --- exact recomputation from the papers' formulas ----------------------------------------------


def mat(rows: list[list[str]]) -> sp.Matrix:
    return sp.Matrix([[sp.Rational(x) for x in row] for row in rows])


def text(m: sp.Matrix) -> list[list[str]]:
    return [[str(m[r, c]) for c in range(m.cols)] for r in range(m.rows)]


def image(operator: str, W: sp.Matrix, gammas: list[sp.Matrix], P: list[sp.Matrix]):
    """``T(P)``: eqs. (5.12)–(5.13) for ``L``, (C.6) for ``J``, and their adjoints."""
    N = W.rows

    def mix(i: int, mats: list[sp.Matrix], by_column: bool) -> sp.Matrix:
        weights = [W[j, i] if by_column else W[i, j] for j in range(N)]
        return sum((w * m for w, m in zip(weights, mats, strict=True)), sp.zeros(mats[0].rows))

    if operator == "L":
        return [gammas[i] * mix(i, P, False) * gammas[i].T for i in range(N)]
    if operator == "J":
        return [
            mix(i, [g * p * g.T for g, p in zip(gammas, P, strict=True)], False) for i in range(N)
        ]
    if operator == "L-adjoint":
        return [
            mix(i, [g.T * p * g for g, p in zip(gammas, P, strict=True)], True) for i in range(N)
        ]
    return [gammas[i].T * mix(i, P, True) * gammas[i] for i in range(N)]


def gammas_of(cert: dict) -> list[sp.Matrix]:
    if "Gamma" in cert["data"]:
        return [mat(g) for g in cert["data"]["Gamma"]]
    A = mat(cert["data"]["A"])
    pairs = zip(cert["witness"]["gains"], cert["data"]["C"], strict=True)
    return [A - mat(g) * mat(c) for g, c in pairs]


def with_radius(cert: dict, rho: Fraction) -> dict:
    """``cert`` claiming ``r_σ < ρ`` with the decrease ``ρP_i − T_i(P)`` recomputed."""
    out = copy.deepcopy(cert)
    w = out["witness"]
    P = [mat(p) for p in w["P"]]
    images = image(w["operator"], mat(out["data"]["W"]), gammas_of(out), P)
    out["claim"]["spectral_radius_below"] = str(rho)
    w["decrease"] = [text(sp.Rational(rho) * p - t) for p, t in zip(P, images, strict=True)]
    return out


def with_rate(cert: dict, rate: Fraction) -> dict:
    """A ``covariance-bound`` certificate claiming ``rate`` with ``r Xⁱ − f₁ⁱ(M, X)`` recomputed
    (eq. (A.54)); modes given as ``M`` or as ``M^j = A(I − K^j H^j)`` (eq. (A.55))."""
    out = copy.deepcopy(cert)
    X = [mat(x) for x in out["witness"]["X"]]
    W = mat(out["data"]["W"])
    decreases = []
    for mode in out["data"]["modes"]:
        if "M" in mode:
            M = [mat(m) for m in mode["M"]]
        else:
            A = mat(out["data"]["A"])
            M = [
                A * (sp.eye(A.rows) - mat(k) * mat(h))
                for k, h in zip(mode["K"], mode["H"], strict=True)
            ]
        images = image("J", W, M, X)
        decreases.append([text(sp.Rational(rate) * x - t) for x, t in zip(X, images, strict=True)])
    out["claim"]["rate"] = str(rate)
    out["witness"]["decrease"] = decreases
    return out


def with_multiplier_radius(cert: dict, rho: Fraction) -> dict:
    """Farkas multipliers at ``ρ``: ``Ψ_i,11 = Σ_j (w_ij/ρ) Λ_j`` recomputed, the rest kept."""
    out = copy.deepcopy(cert)
    W = mat(out["data"]["W"])
    Lam = [mat(x) for x in out["witness"]["Lambda"]]
    n = Lam[0].rows
    for i, raw in enumerate(out["witness"]["Psi"]):
        Psi = mat(raw)
        Psi[:n, :n] = sum((W[i, j] / sp.Rational(rho) * Lam[j] for j in range(W.cols)), sp.zeros(n))
        out["witness"]["Psi"][i] = text(Psi)
    out["claim"]["spectral_radius_below"] = str(rho)
    return out


radii = st.fractions(min_value=Fraction(1, 100), max_value=3, max_denominator=10**6)


# --- s-detectability and gains-radius-below -----------------------------------------------------

GAINS = [
    "s-detectability-ch5-example1-Wg",
    "s-detectability-ch5-example1-w0.249999999-exact",
    "s-detectability-ch5-example2-Wg-dual",
    "s-detectability-ch5-example2-Wg-lmi",
]


def test_the_forged_example1_certificate_of_issue_23_is_refused() -> None:
    """Seed 000 Example 1 at w₁₁ = w₂₂ = 0.3 is not S-detectable (a blind agent with
    λ² w₁₁ = 1.2 ≥ 1). Zero gains, P = I and ρ = 5 prove r_σ(L) < 5, which the kind
    ``gains-radius-below`` says and ``s-detectability`` must refuse; at ρ = 1 the witness fails."""
    honest = stored("valid", "gains-radius-below-ch5-example1-w0.3-zero-gains")
    assert honest["claim"]["spectral_radius_below"] == "5"
    assert verdict(honest) == "valid"
    forged = relabel(honest, "s-detectability")
    written = stored("malformed", "s-detectability-forged-rho5-ch5-example1-w0.3")
    assert (written["kind"], written["data"], written["witness"]) == (
        "s-detectability",
        honest["data"],
        honest["witness"],
    )
    message = refusal(forged)
    assert "claim.spectral_radius_below" in message and "(0, 1]" in message and "5" in message
    assert verdict(with_radius(forged, Fraction(1))) == "invalid"
    path = DATA / "malformed" / "s-detectability-forged-rho5-ch5-example1-w0.3.json"
    result = CliRunner().invoke(app, ["check", str(path)])
    assert result.exit_code == 2 and "VALID" not in result.output
    C = [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)]
    W = np.array([[0.3, 0.7, 0], [0.7, 0.3, 0], [0, 0, 1]])
    decision = decide_s_detectability(2 * np.eye(2), C, W)
    assert decision.verdict is False
    assert decision.certificate["kind"] == "s-detectability-infeasible"
    assert verdict(decision.certificate) == "valid"


@pytest.mark.parametrize("name", GAINS)
def test_s_detectability_at_rho_just_above_one_is_refused(name: str) -> None:
    """ρ = 1 + 10⁻⁹ with ``ρP − T(P)`` recomputed: the witness proves r_σ(L) < ρ (valid as
    ``gains-radius-below``) but not S-detectability."""
    for cert in singles(name):
        assert verdict(cert) == "valid"
        tampered = with_radius(cert, 1 + TINY)
        assert verdict(relabel(tampered, "gains-radius-below")) == "valid"
        assert "claim.spectral_radius_below" in refusal(tampered)


@given(rho=radii)
def test_s_detectability_is_gains_radius_below_with_rho_at_most_one(rho: Fraction) -> None:
    """For every ρ the two kinds agree on the same witness when ρ ≤ 1; above 1 only
    ``gains-radius-below`` may hold, and it does (ρP − T(P) ⪰ P − T(P) ≻ 0)."""
    (cert,) = singles("s-detectability-ch5-example1-Wg")
    tampered = with_radius(cert, rho)
    general = verdict(relabel(tampered, "gains-radius-below"))
    assert verdict(tampered) == (general if rho <= 1 else "malformed")
    if rho >= 1:
        assert general == "valid"


# --- s-detectability-infeasible and gains-radius-below-infeasible ------------------------------

MULTIPLIERS = [
    "s-detectability-infeasible-ch5-example1-Wb",
    "s-detectability-infeasible-ch5-example1-Wc",
    "s-detectability-infeasible-ch5-example2-Wb",
]


def test_multipliers_below_one_do_not_refute_s_detectability() -> None:
    """Example 1 at w = 0.24 is S-detectable (a valid certificate), yet no gains give
    r_σ(L) < 0.96 = λ²w₁₁. Those multipliers, labelled ``s-detectability-infeasible``, would
    make two VALID certificates contradict each other: they are refused."""
    detectable = stored("valid", "s-detectability-ch5-example1-Wg")
    bound = stored("valid", "gains-radius-below-infeasible-ch5-example1-w0.24-rho0.96")
    assert bound["data"] == detectable["data"]
    assert bound["claim"]["spectral_radius_below"] == "24/25"
    assert verdict(detectable) == verdict(bound) == "valid"
    relabelled = relabel(bound, "s-detectability-infeasible")
    assert "[1, ∞)" in refusal(relabelled)
    stored_forgery = stored("malformed", "s-detectability-infeasible-rho0.96-ch5-example1-w0.24")
    assert verdict(stored_forgery) == "malformed"


@pytest.mark.parametrize("name", MULTIPLIERS)
def test_infeasibility_at_rho_just_below_one_is_refused(name: str) -> None:
    """ρ = 1 − 10⁻⁹ with ``Ψ_i,11`` recomputed (it grows, so Ψ_i ⪰ 0 still): the multipliers
    exclude r_σ(L) < ρ (valid as ``gains-radius-below-infeasible``), not S-detectability."""
    (cert,) = singles(name)
    assert verdict(cert) == "valid"
    tampered = with_multiplier_radius(cert, 1 - TINY)
    assert verdict(relabel(tampered, "gains-radius-below-infeasible")) == "valid"
    assert "claim.spectral_radius_below" in refusal(tampered)


@given(rho=radii)
def test_infeasibility_is_the_radius_kind_with_rho_at_least_one(rho: Fraction) -> None:
    (cert,) = singles("s-detectability-infeasible-ch5-example1-Wc")
    tampered = with_multiplier_radius(cert, rho)
    general = verdict(relabel(tampered, "gains-radius-below-infeasible"))
    assert verdict(tampered) == (general if rho >= 1 else "malformed")
    if rho <= 1:
        assert general == "valid"


# --- mjls-stability and covariance-bound --------------------------------------------------------


@pytest.mark.parametrize(
    "name", ["mjls-stability-scalar", "mjls-stability-three-agents", "mjls-stability-rate-bound"]
)
def test_mjls_stability_claims_at_most_radius_one(name: str) -> None:
    """Raising ρ to 1 keeps the claim (r_σ(L) < 1) and the witness; 1 + 10⁻⁹ is refused."""
    (cert,) = singles(name)
    assert verdict(with_radius(cert, Fraction(1))) == "valid"
    assert "(0, 1]" in refusal(with_radius(cert, 1 + TINY))
    assert verdict(with_radius(cert, Fraction(0))) == "malformed"


@given(rho=st.fractions(min_value=1, max_value=10, max_denominator=10**6).filter(lambda x: x > 1))
def test_mjls_stability_above_one_is_always_refused(rho: Fraction) -> None:
    (cert,) = singles("mjls-stability-scalar")
    assert verdict(with_radius(cert, rho)) == "malformed"


@pytest.mark.parametrize("name", ["covariance-bound-two-modes", "covariance-bound-ekf-gains"])
def test_covariance_bound_claims_a_rate_at_most_one(name: str) -> None:
    """Lemma A.2.1 needs f₁ⁱ(M, X) ≺ r Xⁱ with r ≤ 1: r = 1 + 10⁻⁹ is refused, r = 1 kept."""
    (cert,) = singles(name)
    assert verdict(with_rate(cert, Fraction(1))) == "valid"
    assert "claim.rate" in refusal(with_rate(cert, 1 + TINY))
    assert verdict(with_rate(cert, Fraction(0))) == "malformed"


# --- generic-rank -------------------------------------------------------------------------------


def test_a_rank_above_the_generic_rank_is_never_certified() -> None:
    """seed002-fig32-split: agent 4's only TDOA partner is agent 5, so every row of O_4 is a
    multiple of [g, kTg] (g = u_4 − u_5) and its generic rank is 2 of 4. Claiming 3 with any
    further row and column: the minor is 0, and the certificate is invalid for that reason."""
    (cert,) = singles("generic-rank-seed002-fig32-split-agent4")
    assert (cert["claim"]["agent"], cert["claim"]["rank_at_least"]) == (4, 2)
    assert verdict(cert) == "valid"
    dim, agents = cert["data"]["dim"], len(cert["data"]["W"])
    rows = sum(len(nb) for nb in cert["data"]["neighbours"]) * 2 * dim * agents
    block = range(2 * dim * 3 + 1, 2 * dim * 4 + 1)
    for row in set(range(1, rows + 1)) - set(cert["witness"]["rows"]):
        for col in set(block) - set(cert["witness"]["cols"]):
            tampered = copy.deepcopy(cert)
            tampered["claim"]["rank_at_least"] = 3
            tampered["witness"] |= {"minor": "0"}
            tampered["witness"]["rows"].append(row)
            tampered["witness"]["cols"].append(col)
            failed = [c.name for c in check_certificate(tampered).checks if not c.valid]
            assert failed == ["3×3 minor ≠ 0"], (row, col)


@given(T=st.fractions(min_value=-5, max_value=0, max_denominator=100))
def test_the_sampling_period_is_positive(T: Fraction) -> None:
    (cert,) = singles("generic-rank-seed002-fig32-split-agent4")
    tampered = copy.deepcopy(cert)
    tampered["data"]["T"] = str(T)
    assert "data.T" in refusal(tampered)


def test_claiming_another_agents_block_is_refused() -> None:
    (cert,) = singles("generic-rank-seed002-fig32-split-agent4")
    for agent in (1, 3, 5):
        tampered = copy.deepcopy(cert)
        tampered["claim"]["agent"] = agent
        assert "witness.cols" in refusal(tampered)


# --- iss ----------------------------------------------------------------------------------------


def iss_with(cert: dict, **changes: Fraction) -> dict:
    """``cert`` with witness bounds changed and the derived constants recomputed (§7: E5, C6):
    ``g_e = s/λ``, ``α = k_c a``, ``g_ξ = b/(ρα)``, gain ``= g_e(1 + g_ξ)`` (N = 1: ``g_e``)."""
    out = copy.deepcopy(cert)
    w = {k: Fraction(v) for k, v in out["witness"].items() if k != "r"} | changes
    w["g_e"] = w["s"] / w["lambda"]
    w["gain"] = w["g_e"]
    if "a" in w:
        w["alpha"] = Fraction(out["data"]["k_c"]) * w["a"]
        w["g_xi"] = w["b"] / (w["rho"] * w["alpha"])
        w["gain"] = w["g_e"] * (1 + w["g_xi"])
    out["witness"] |= {k: str(v) for k, v in w.items()}
    return out


def root(x: Fraction, *, above: bool) -> Fraction:
    """A rational within 10⁻¹² of √x, strictly above or strictly below it."""
    scale = 10**12
    low = Fraction(isqrt(x.numerator * scale**2 // x.denominator), scale)
    return low + Fraction(1, scale) if above else low - Fraction(1, scale)


TABLE1 = "iss-pursuit-table1-n3"
"""K_p = diag(2/5, 1/5), k_γ = 500, r_x = r_y = 30, directed ring of 3, r = 1/3 each, k_c = 1/5:
λ ≤ 1/5, k̄_p ≥ 2/5, μ_r = 900, s² ≥ k̄_p² + 901, a ≤ 3/2, b² ≥ 1/3, ρ² ≤ 1/3, κ ≥ 1."""


def _table1_bounds() -> dict[str, tuple[Fraction, Fraction]]:
    """Per witness constant: (a value at the exact bound, one just past it)."""
    (cert,) = singles(TABLE1)
    kp_bar = Fraction(cert["witness"]["kp_bar"])
    s2 = kp_bar**2 + 1 + 900
    return {
        "lambda": (Fraction(1, 5), Fraction(1, 5) + TINY),
        "kp_bar": (Fraction(2, 5), Fraction(2, 5) - TINY),
        "s": (root(s2, above=True), root(s2, above=False)),
        "a": (Fraction(3, 2), Fraction(3, 2) + TINY),
        "b": (root(Fraction(1, 3), above=True), root(Fraction(1, 3), above=False)),
        "rho": (root(Fraction(1, 3), above=False), root(Fraction(1, 3), above=True)),
        "kappa": (Fraction(1), 1 - TINY),
    }


@pytest.mark.parametrize("key", sorted(_table1_bounds()))
def test_each_iss_bound_holds_at_its_limit_and_fails_just_past_it(key: str) -> None:
    (cert,) = singles(TABLE1)
    at_limit, past = _table1_bounds()[key]
    assert verdict(iss_with(cert, **{key: at_limit})) == "valid"
    assert verdict(iss_with(cert, **{key: past})) == "invalid"


@pytest.mark.parametrize("kappa", [Fraction(-1), Fraction(-1000000001, 10**9), Fraction(0)])
def test_a_non_positive_kappa_is_refused(kappa: Fraction) -> None:
    """κ² min r_i ≥ max r_i also holds for κ = −1, but ‖ξ(t)‖ ≤ κe^{−αt}‖ξ(0)‖ + … is then false."""
    (cert,) = singles(TABLE1)
    checks = check_certificate(iss_with(cert, kappa=kappa)).checks
    assert [c.name for c in checks if not c.valid] == ["C5: κ > 0, κ² min r_i ≥ max r_i"]


def test_a_negative_path_radius_does_not_shrink_mu_r() -> None:
    """r_x = −30, r_y = 1: sup‖r′‖² = 900 (seed 003 eq. (16)), not max(r_x, r_y)² = 1."""
    tampered = stored("invalid", "iss-negative-radius-mu-r-understated")
    assert {p["r_x"] for p in tampered["data"]["paths"]} == {"-30"}
    assert tampered["witness"]["mu_r"] == "1"
    failed = [c.name for c in check_certificate(tampered).checks if not c.valid]
    assert failed[0].startswith("E4: μ_r") and len(failed) == 2
    assert verdict(iss_with(tampered, mu_r=Fraction(900))) == "invalid"


DERIVED = [
    (name, key)
    for name in (TABLE1, "iss-pursuit-table2-n1")
    for key in ("mu_r", "g_e", "gain", "alpha", "g_xi")
    if key in stored("valid", name)["witness"]
]
"""The constants ``iss`` recomputes (E4, E5, C6): N = 1 has no ``α``, ``g_ξ``."""


@pytest.mark.parametrize(("name", "key"), DERIVED)
def test_stated_iss_constants_are_recomputed_not_trusted(name: str, key: str) -> None:
    (cert,) = singles(name)
    for delta in (TINY, -TINY):
        tampered = copy.deepcopy(cert)
        tampered["witness"][key] = str(Fraction(cert["witness"][key]) + delta)
        assert verdict(tampered) == "invalid", (key, delta)


def test_the_3d_single_tracker_bounds_hold_at_their_limits() -> None:
    """Table II, N = 1 (Type II, 3D): λ ≤ λ_min(K), k̄_p ≥ ‖K_p‖, s² ≥ k̄_p² + 1 + μ_r."""
    (cert,) = singles("iss-pursuit-table2-n1")
    K_p = mat(cert["data"]["K_p"])
    K = sp.diag(K_p, sp.Rational(cert["data"]["k_gamma"]))
    lam = Fraction(str(min(K.eigenvals())))
    top = Fraction(str(max(K_p.eigenvals())))
    s2 = Fraction(cert["witness"]["kp_bar"]) ** 2 + 1 + Fraction(cert["witness"]["mu_r"])
    for key, at_limit, past in (
        ("lambda", lam, lam + TINY),
        ("kp_bar", top, top - TINY),
        ("s", root(s2, above=True), root(s2, above=False)),
    ):
        assert verdict(iss_with(cert, **{key: at_limit})) == "valid", key
        assert verdict(iss_with(cert, **{key: past})) == "invalid", key


# --- canonical numbers --------------------------------------------------------------------------

NOT_CANONICAL = ["2/2", "4/2", "-0", "0/3", "-0/5", "3/1", "6/4", "-6/4", "-2/2"]
NOT_RATIONAL = ["+1", "01", "1/02", " 1", "1 ", "1.0", "1e3", "−1", "1/-2", "0x1", "1_000", ""]


@pytest.mark.parametrize("spelling", NOT_CANONICAL + NOT_RATIONAL)
def test_only_canonical_rational_strings_are_read(spelling: str) -> None:
    with pytest.raises(MalformedError, match=r"data\.W\[2\]\[1\]"):
        rational(spelling, "data.W[2][1]")


@pytest.mark.parametrize("spelling", ["0", "1", "-1", "12", "-3/7", "355/113"])
def test_canonical_rational_strings_are_read_exactly(spelling: str) -> None:
    assert str(rational(spelling, "x")) == spelling


def test_a_negative_zero_json_integer_is_refused() -> None:
    with pytest.raises(MalformedError, match="-0"):
        loads('{"format": -0}')


WORDS = ("statement", "produced_by", "operator", "model", "controller", "graph", "items")
"""Keys whose strings are words, not rationals."""


def rational_leaves(cert: dict) -> list[tuple]:
    """Paths of every rational string of claim, data and witness (bundle members included)."""
    out = []

    def walk(value, path):
        if isinstance(value, dict):
            for key, item in value.items():
                if key not in WORDS:
                    walk(item, (*path, key))
        elif isinstance(value, list):
            for index, item in enumerate(value):
                walk(item, (*path, index))
        elif isinstance(value, str) and {"claim", "data", "witness"} & set(path):
            out.append(path)

    walk(cert, ())
    return out


def respelled(value: str, k: int) -> str:
    """The same rational, not canonical: ``kp/kq`` (k ≥ 2) or ``-0``."""
    x = Fraction(value)
    return f"{k * x.numerator}/{k * x.denominator}" if x else "-0"


VALID_FILES = sorted(path.stem for path in (DATA / "valid").glob("*.json"))


@given(name=st.sampled_from(VALID_FILES), data=st.data(), k=st.integers(2, 7))
def test_a_non_canonical_spelling_of_any_number_is_refused(name: str, data, k: int) -> None:
    """Every number of every known-good file goes through the canonical reader."""
    cert = stored("valid", name)
    path = data.draw(st.sampled_from(rational_leaves(cert)))
    tampered = copy.deepcopy(cert)
    node = tampered
    for key in path[:-1]:
        node = node[key]
    spelling = respelled(node[path[-1]], k)
    node[path[-1]] = spelling
    message = refusal(tampered)
    assert "not canonical" in message and repr(spelling[:60]) in message, path


# --- every certificate the suite writes for the bundled cases -----------------------------------

NOT_HOLDING = {
    "ch5-blind-cycle",
    "ch5-example-1-wb",
    "ch5-example-1-wc",
    "ch5-example-2-wb",
    "pursuit-not-strongly-connected",
    "pursuit-singular-epsilon",
}
"""Bundled cases whose certified property is decided false (``trackcert certify`` exits 1)."""

CERTIFIABLE = sorted(
    name for name, path in bundled_cases().items() if load_case(path).kind in certifiers()
)


@pytest.mark.parametrize("name", CERTIFIABLE)
def test_every_certificate_of_a_bundled_case_is_canonical_and_valid(name: str) -> None:
    """What ``trackcert certify`` writes passes the stricter checker, spelled canonically; a dkf
    case that is not S-detectable gets a valid ``s-detectability-infeasible`` at ρ = 1."""
    case = load_case(bundled_cases()[name])
    if name in NOT_HOLDING:
        with pytest.raises(PropertyFails):
            certificate_bundle(case)
    else:
        document = certificate_bundle(case)
        assert verdict(document) == "valid"
        for path in rational_leaves(document):
            node = document
            for key in path:
                node = node[key]
            assert str(Fraction(node)) == node, (path, node)
    if case.kind == "dkf":
        spec = case.spec
        decision = decide_s_detectability(spec.A, spec.C, spec.W, order=spec.order)
        kind = "s-detectability-infeasible" if name in NOT_HOLDING else "s-detectability"
        assert decision.certificate["kind"] == kind
        assert decision.certificate["claim"]["spectral_radius_below"] == "1"
        assert verdict(decision.certificate) == "valid"
