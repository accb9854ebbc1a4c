"""``iss`` certificates (seed 003): certify → check round trips, tampering, refused cases.

The certificate proves the corrected ISS estimate of docs/theory/pursuit-iss.md §5 through the
exact inequalities E1–E5 and C1–C6 of §7, re-derived by ``proofs_check`` (kind ``iss``).
"""

from __future__ import annotations

import copy
import itertools
import json
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

import proofs_check
from proofs_check.linalg import positive_definite
from theory.cli import app
from theory.core.claims import NotApplicable
from theory.kinds import load_case, parse_case
from theory.pursuit.certificates import iss_certificate
from theory.registry import get_claim
from theory.strategies import pursuit_parameters

runner = CliRunner()
TABLES = ["pursuit-table1-n1", "pursuit-table1-n3", "pursuit-table2-n1", "pursuit-table2-n3"]
EQUALITIES = ("mu_r", "g_e", "gain", "alpha", "g_xi")
"""Witness values the checker recomputes: any change is rejected."""
LOWER = ("lambda", "a", "rho")
"""Witness bounds that are certified from below: raising them is rejected."""
UPPER = ("kp_bar", "s", "b", "kappa")
"""Witness bounds that are certified from above: lowering them is rejected."""


def _valid(cert: dict) -> bool:
    return proofs_check.check_certificate(cert).valid


def _failing(cert: dict) -> list[str]:
    return [c.name for c in proofs_check.check_certificate(cert).checks if not c.valid]


@pytest.fixture(scope="module")
def table_certificates() -> dict[str, dict]:
    return {name: iss_certificate(load_case(name).spec, case=name) for name in TABLES}


@pytest.mark.parametrize("name", TABLES)
def test_certify_then_check_the_table_cases(name: str, tmp_path: Path) -> None:
    out = tmp_path / f"{name}.json"
    result = runner.invoke(app, ["certify", name, "-o", str(out)])
    assert result.exit_code == 0, result.output
    document = json.loads(out.read_text(encoding="utf-8"))
    assert [c["kind"] for c in document["certificates"]] == ["iss"]
    checked = runner.invoke(app, ["check", str(out), "--json"])
    assert checked.exit_code == 0, checked.stdout
    names = [c["name"] for c in json.loads(checked.stdout)["checks"]]
    labels = {n.split("] ", 1)[1].split(":")[0] for n in names}
    expected = {"E1", "E2", "E3", "E4", "E5", "C6"}
    if load_case(name).spec.n_trackers > 1:
        expected |= {"C1", "C2", "C3", "C4", "C5"}
    assert labels == expected


@pytest.mark.parametrize("name", ["pursuit-not-strongly-connected", "pursuit-singular-epsilon"])
def test_failing_conditions_give_no_certificate(name: str, tmp_path: Path) -> None:
    out = tmp_path / "out.json"
    result = runner.invoke(app, ["certify", name, "-o", str(out)])
    assert result.exit_code == 1  # the conditions fail, as trackcert iss reports
    assert "does not hold" in result.output and "conditions" in result.output
    decided = runner.invoke(app, ["iss", name, "--json"])
    assert json.loads(decided.stdout)["holds"] is False  # exit 0: the case expects it
    assert not out.exists()


def test_the_certified_constants_are_those_of_the_analysis(table_certificates) -> None:
    """Table I, N = 3 (docs/theory/pursuit-iss.md §3–§5): λ = 0.2, α = 0.3, g_ξ = 10/3."""
    w = table_certificates["pursuit-table1-n3"]["witness"]
    assert abs(Fraction(w["lambda"]) - Fraction(1, 5)) < Fraction(1, 10**8)
    assert abs(Fraction(w["alpha"]) - Fraction(3, 10)) < Fraction(1, 10**8)
    assert abs(Fraction(w["g_xi"]) - Fraction(10, 3)) < Fraction(1, 10**6)
    assert abs(Fraction(w["gain"]) - Fraction(6504, 10)) < 1


@pytest.mark.parametrize("name", TABLES)
def test_changing_any_witness_number_is_rejected(name: str, table_certificates) -> None:
    cert = table_certificates[name]
    assert _valid(cert)
    for key, value in cert["witness"].items():
        values = value if isinstance(value, list) else [value]
        for k in range(len(values)):
            directions = [Fraction(1001, 1000), Fraction(999, 1000)]
            if key in LOWER:
                directions = directions[:1]
            elif key in UPPER:
                directions = directions[1:]
            for factor in directions:
                tampered = copy.deepcopy(cert)
                changed = str(Fraction(values[k]) * factor + (0 if values[k] != "0" else 1))
                if isinstance(value, list):
                    tampered["witness"][key][k] = changed
                else:
                    tampered["witness"][key] = changed
                assert not _valid(tampered), (key, k, factor)


@pytest.mark.parametrize("name", TABLES)
def test_changing_the_data_is_rejected(name: str, table_certificates) -> None:
    cert = table_certificates[name]
    dim = cert["data"]["dim"]
    cases = {
        "E1": ("epsilon", lambda d: d["epsilon"].__setitem__(0, "0")),
        "E2": ("K_p", lambda d: _scale_diagonal(d["K_p"], min, "999/1000")),
        "E3": ("K_p", lambda d: _scale_diagonal(d["K_p"], max, "1001/1000")),
        "E4": ("paths", lambda d: d["paths"][0].__setitem__("r_x", _times(_widest(d), "2"))),
    }
    if "laplacian" in cert["data"]:
        cases["C1"] = ("laplacian", lambda d: d["laplacian"][0].__setitem__(0, "3"))
        cases["C6"] = ("k_c", lambda d: d.__setitem__("k_c", _times(d["k_c"], "2")))
    for label, (_, change) in cases.items():
        tampered = copy.deepcopy(cert)
        change(tampered["data"])
        failing = _failing(tampered)
        assert any(f.startswith(label) for f in failing), (label, dim, failing)


def _times(value: str, factor: str) -> str:
    return str(Fraction(value) * Fraction(factor))


def _scale_diagonal(K_p: list, pick, factor: str) -> None:
    """Scale the smallest (``pick=min``) or largest diagonal entry of a diagonal ``K_p``."""
    i = pick(range(len(K_p)), key=lambda k: Fraction(K_p[k][k]))
    K_p[i][i] = _times(K_p[i][i], factor)


def _widest(data: dict) -> str:
    return str(max(Fraction(p[k]) for p in data["paths"] for k in ("r_x", "r_y")))


@pytest.mark.parametrize("name", ["pursuit-table1-n3", "pursuit-table2-n1"])
def test_dropped_blocks_are_refused(name: str, table_certificates) -> None:
    cert = table_certificates[name]
    for part in ("data", "witness"):
        for key in cert[part]:
            tampered = copy.deepcopy(cert)
            del tampered[part][key]
            with pytest.raises(proofs_check.MalformedError):
                proofs_check.check_certificate(tampered)
    tampered = copy.deepcopy(cert)
    del tampered["data"]["K_p"][-1]
    with pytest.raises(proofs_check.MalformedError, match="K_p"):
        proofs_check.check_certificate(tampered)
    if "r" in cert["witness"]:
        tampered = copy.deepcopy(cert)
        del tampered["witness"]["r"][-1]
        with pytest.raises(proofs_check.MalformedError, match=r"witness\.r"):
            proofs_check.check_certificate(tampered)


@st.composite
def pursuit_cases(draw):
    """A pursuit case from :func:`theory.strategies.pursuit_parameters`, N = 1 … 4 trackers on a
    directed ring (strongly connected) with optional extra edges, Type I or II."""
    dim = draw(st.sampled_from([2, 3]))
    params = draw(pursuit_parameters(dim=dim))
    n = draw(st.integers(1, 4))
    path = {"r_x": params.radius[0], "r_y": params.radius[1]}
    if dim == 3:
        path |= {"r_z": params.radius[2], "c": draw(st.floats(1.2, 5.0))}
    block = {
        "dim": dim,
        "controller": draw(st.sampled_from(["I", "II"])),
        "omega_bar": params.omega_bar,
        "epsilon": list(params.epsilon),
        "K_p": [[params.K_p[i] if i == j else 0.0 for j in range(dim)] for i in range(dim)],
        "k_gamma": params.k_gamma,
        "trackers": [path] * n,
    }
    if n > 1:
        ring = [[(i + 1) % n + 1, i + 1] for i in range(n)]
        pairs = [[i, j] for i in range(1, n + 1) for j in range(1, n + 1) if i != j]
        extra = draw(st.lists(st.sampled_from(pairs), max_size=3, unique_by=tuple))
        edges = ring + [e for e in extra if e not in ring]
        block |= {"k_c": params.k_c, "edges": edges}
    return parse_case({"name": "random", "kind": "pursuit", "pursuit": block})


@given(case=pursuit_cases())
def test_random_pursuit_parameters_certify_and_check(case) -> None:
    cert = iss_certificate(case.spec, case=case.name)
    assert _valid(json.loads(json.dumps(cert)))
    tampered = copy.deepcopy(cert)
    tampered["witness"]["lambda"] = _times(cert["witness"]["lambda"], "1001/1000")
    assert "E2: K − λI ⪰ 0" in _failing(tampered)


@given(
    gram=st.lists(st.lists(st.integers(-3, 3), min_size=4, max_size=4), min_size=1, max_size=4),
    shift=st.sampled_from([Fraction(0), Fraction(-1, 50), Fraction(1, 50)]),
)
def test_semidefinite_test_agrees_with_all_principal_minors(gram, shift) -> None:
    """``positive_definite(semi=True)`` (Bareiss with the zero-pivot rule) against the definition:
    ``A ⪰ 0`` iff every principal minor is ``≥ 0``; ``A = GᵀG + shift·I`` is often singular."""
    G = sp.Matrix(gram)
    A = G.T * G + shift * sp.eye(4)
    a = [[Fraction(str(A[i, j])) for j in range(4)] for i in range(4)]
    minors = [
        A.extract(list(rows), list(rows)).det()
        for k in range(1, 5)
        for rows in itertools.combinations(range(4), k)
    ]
    assert positive_definite(a, semi=True).positive == all(m >= 0 for m in minors)


def test_the_claim_reports_the_certificate() -> None:
    claim = get_claim("seed003.thm2.certified")
    (result,) = claim.run(load_case("pursuit-table1-n3"))
    assert (result.method, result.status) == ("exact", "verified")
    assert abs(result.evidence["gain_approx"] - 650.4) < 0.1
    with pytest.raises(NotApplicable, match="delta_full_rank"):
        claim.run(load_case("pursuit-singular-epsilon"))


def test_zero_coordination_gain_is_rejected(table_certificates) -> None:
    """k_c = 0 stops the coordination decay (α = 0): consistent derived values do not help."""
    cert = copy.deepcopy(table_certificates["pursuit-table1-n3"])
    cert["data"]["k_c"] = "0"
    cert["witness"] |= {"alpha": "0", "g_xi": "0", "gain": cert["witness"]["g_e"]}
    assert _failing(cert) == ["C6: k_c > 0"]
