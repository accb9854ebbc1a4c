"""Kind ``iss-box`` (issue 25): the ``iss`` estimate, with one set of constants, over a gain box.

The checker evaluates each monotone check of ``iss`` at its corner (E2 at the lowest K_p scale
and k_γ, E3 at the largest scale, C6 at the lowest k_c, E1 on the whole ε₁ interval;
docs/certificates.md). Every number the claim rests on — a witness bound or a box end — moved just
past the point where the claim becomes false must be rejected; at the limit itself the certificate
stays valid. Table I, N = 3: λ_min(K_p) = 1/5, ‖K_p‖ = 2/5, a(L) = 3/2, r = (1/3, 1/3, 1/3).
"""

from __future__ import annotations

import copy
from fractions import Fraction
from math import isqrt

import pytest

from proofs_check import MalformedError, check_certificate
from theory.kinds import load_case
from theory.pursuit.certificates import box_witness, iss_box_certificate, loop_bounds

TINY = Fraction(1, 10**12)
BOX = {
    "K_p_scale": (Fraction(1), Fraction(2)),
    "epsilon_1": (Fraction(-1), Fraction(-1, 4)),
    "k_gamma": (Fraction(1, 10), Fraction(10)),
    "k_c": (Fraction(1, 10), Fraction(1)),
}
"""λ ≤ min(1·1/5, 1/10) = 1/10 (set by k_γ), k̄_p ≥ 2·2/5 = 4/5, α = a/10."""


def _certificate(name: str = "pursuit-table1-n3", **box: tuple[Fraction, Fraction]) -> dict:
    spec = load_case(name).spec
    bounds = loop_bounds(spec)
    chosen = {k: v for k, v in (BOX | box).items() if k != "k_c" or spec.n_trackers > 1}
    return iss_box_certificate(bounds, chosen, box_witness(bounds, chosen), case=name)


def _valid(cert: dict) -> bool:
    return check_certificate(cert).valid


def _failing(cert: dict) -> list[str]:
    return [c.name for c in check_certificate(cert).checks if not c.valid]


def _root_above(x: Fraction) -> Fraction:
    scale = 10**12
    return Fraction(isqrt(x.numerator * scale**2 // x.denominator) + 1, scale)


def _with(cert: dict, box: dict | None = None, **changes: Fraction) -> dict:
    """``cert`` with box ends or witness bounds changed and the derived constants recomputed
    (E4's s from k̄_p when only k̄_p changes, E5, C6 with the box's lowest k_c)."""
    out = copy.deepcopy(cert)
    for name, (lo, hi) in (box or {}).items():
        out["claim"]["box"][name] = [str(lo), str(hi)]
    w = {k: Fraction(v) for k, v in out["witness"].items() if k != "r"} | changes
    if "kp_bar" in changes and "s" not in changes:
        w["s"] = _root_above(w["kp_bar"] ** 2 + 1 + w["mu_r"])
    w["g_e"] = w["gain"] = w["s"] / w["lambda"]
    if "a" in w:
        w["alpha"] = Fraction(out["claim"]["box"]["k_c"][0]) * w["a"]
        w["g_xi"] = w["b"] / (w["rho"] * w["alpha"])
        w["gain"] = w["g_e"] * (1 + w["g_xi"])
    out["witness"] |= {k: str(v) for k, v in w.items()}
    return out


@pytest.fixture(scope="module")
def cert() -> dict:
    return _certificate()


def test_the_built_certificate_is_valid_and_names_its_corners(cert) -> None:
    names = [c.name for c in check_certificate(cert).checks]
    assert "E2: K − λI ⪰ 0 at the lowest gains" in names
    assert "E3: k̄_p I − K_p ⪰ 0 at the largest K_p scale" in names
    assert _valid(cert)
    assert Fraction(cert["witness"]["lambda"]) == Fraction(1, 10)


@pytest.mark.parametrize(
    ("key", "at_limit", "past"),
    [
        ("lambda", Fraction(1, 10), Fraction(1, 10) + TINY),
        ("kp_bar", Fraction(4, 5), Fraction(4, 5) - TINY),
        ("a", Fraction(3, 2), Fraction(3, 2) + TINY),
    ],
)
def test_each_witness_bound_holds_at_its_limit_and_fails_just_past_it(
    cert, key: str, at_limit: Fraction, past: Fraction
) -> None:
    assert _valid(_with(cert, **{key: at_limit}))
    assert not _valid(_with(cert, **{key: past}))


@pytest.mark.parametrize("key", ["mu_r", "g_e", "gain", "alpha", "g_xi"])
def test_stated_constants_are_recomputed_not_trusted(cert, key: str) -> None:
    for delta in (TINY, -TINY):
        tampered = copy.deepcopy(cert)
        tampered["witness"][key] = str(Fraction(cert["witness"][key]) + delta)
        assert not _valid(tampered), (key, delta)


def test_widening_the_box_past_the_lowest_k_gamma_is_rejected(cert) -> None:
    """λ = 1/10 = k_γ,lo: a box reaching below 1/10 contains gains whose decay rate is < λ."""
    exact = _with(cert, **{"lambda": Fraction(1, 10)})
    assert _valid(exact)
    lower = _with(exact, box={"k_gamma": (Fraction(1, 10) - TINY, Fraction(10))})
    assert _failing(lower) == ["E2: K − λI ⪰ 0 at the lowest gains"]


def test_widening_the_k_p_scale_either_way_is_rejected() -> None:
    """With k_γ ≥ 10, λ = s_lo·λ_min(K_p) = 1/5 and k̄_p = s_hi·‖K_p‖ = 4/5 at their limits."""
    cert = _certificate(k_gamma=(Fraction(10), Fraction(20)))
    exact = _with(cert, **{"lambda": Fraction(1, 5), "kp_bar": Fraction(4, 5)})
    assert _valid(exact)
    low = _with(exact, box={"K_p_scale": (1 - TINY, Fraction(2))})
    assert _failing(low) == ["E2: K − λI ⪰ 0 at the lowest gains"]
    high = _with(exact, box={"K_p_scale": (Fraction(1), 2 + TINY)})
    assert _failing(high) == ["E3: k̄_p I − K_p ⪰ 0 at the largest K_p scale"]


def test_lowering_k_c_is_rejected_raising_the_upper_ends_is_not(cert) -> None:
    """α = k_c,lo·a bounds k_c a(L) only from k_c,lo up; larger gains keep every bound."""
    lower = copy.deepcopy(cert)
    lower["claim"]["box"]["k_c"] = [str(Fraction(1, 10) - TINY), "1"]
    assert "C6: α = k_c a" in _failing(lower)
    wider = copy.deepcopy(cert)
    for name in ("k_gamma", "k_c"):
        wider["claim"]["box"][name][1] = "1000000"
    assert _valid(wider)


def test_an_epsilon_interval_reaching_zero_is_rejected(cert) -> None:
    near = _with(cert, box={"epsilon_1": (Fraction(-5), -TINY)})
    assert _valid(near)
    touching = _with(cert, box={"epsilon_1": (Fraction(-5), Fraction(0))})
    assert _failing(touching) == ["E1: ε₁ ≠ 0 (ΔΔᵀ is invertible)"]


def _malformed(cert: dict, change) -> str:
    tampered = copy.deepcopy(cert)
    change(tampered)
    with pytest.raises(MalformedError) as error:
        check_certificate(tampered)
    return str(error.value)


@pytest.mark.parametrize(
    ("change", "where"),
    [
        (lambda c: c["claim"]["box"].__setitem__("k_c", ["1", "1/10"]), "empty box"),
        (lambda c: c["claim"]["box"].__setitem__("K_p_scale", ["0", "2"]), "claim.box.K_p_scale"),
        (lambda c: c["claim"]["box"].__setitem__("k_gamma", ["-1", "2"]), "claim.box.k_gamma"),
        (lambda c: c["claim"]["box"].pop("k_gamma"), "missing field 'k_gamma'"),
        (lambda c: c["claim"]["box"].__setitem__("omega_bar", ["1", "2"]), "unknown field"),
        (lambda c: c["claim"]["box"].__setitem__("epsilon_1", ["-1"]), "[lo, hi]"),
        (lambda c: c["claim"].pop("box"), "missing field 'box'"),
        (lambda c: c["claim"].__setitem__("tolerance", "1/10"), "unknown field"),
        (lambda c: c["data"].__setitem__("k_gamma", "500"), "unknown field"),
        (lambda c: c["data"].__setitem__("controller", "I"), "unknown field 'k_gamma'"),
        (lambda c: c["data"].pop("laplacian"), "laplacian iff N > 1"),
    ],
)
def test_claim_weakening_or_ambiguous_fields_are_refused(cert, change, where: str) -> None:
    assert where in _malformed(cert, change)


def test_a_single_tracker_3d_certificate_has_no_coordination_checks() -> None:
    cert = _certificate("pursuit-table2-n1")
    labels = {c.name.split(":")[0] for c in check_certificate(cert).checks}
    assert labels == {"E1", "E2", "E3", "E4", "E5", "C6"}
    assert _valid(cert)
