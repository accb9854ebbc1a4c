"""The independent checker ``proofs_check``: exact linear algebra, limits, bad and good files."""

from __future__ import annotations

import ast
import json
import random
import subprocess
import sys
import time
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from proofs_check.__main__ import main
from proofs_check.linalg import determinant, positive_definite
from proofs_check.parse import MalformedError, loads

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parents[1] / "data" / "certificates"
EXPECTED_EXIT = {"valid": 0, "invalid": 1, "malformed": 2}

small = st.fractions(min_value=-5, max_value=5, max_denominator=7)


@st.composite
def rational_matrices(draw, *, min_size: int = 1, max_size: int = 5, symmetric: bool = False):
    """Square matrices of small rationals (symmetric ones when asked)."""
    n = draw(st.integers(min_size, max_size))
    rows = [[draw(small) for _ in range(n)] for _ in range(n)]
    if symmetric:
        rows = [[rows[max(r, c)][min(r, c)] for c in range(n)] for r in range(n)]
    return rows


@given(rational_matrices(symmetric=True), st.fractions(min_value=-3, max_value=30))
def test_positive_definite_agrees_with_sylvester_in_sympy(a, shift) -> None:
    """Exact LDLᵀ pivots: positive iff every leading principal minor (sympy) is positive."""
    n = len(a)
    a = [[x + (shift if r == c else 0) for c, x in enumerate(row)] for r, row in enumerate(a)]
    result = positive_definite(a)
    minors = [
        sp.Matrix(k, k, lambda i, j: sp.Rational(str(a[i][j]))).det() for k in range(1, n + 1)
    ]
    assert result.positive == all(m > 0 for m in minors)
    if not result.positive:
        k = result.order
        assert all(m > 0 for m in minors[: k - 1]) and minors[k - 1] <= 0
        previous = minors[k - 2] if k > 1 else 1
        assert sp.Rational(str(result.pivot)) == minors[k - 1] / previous


@given(rational_matrices(max_size=6))
def test_determinant_agrees_with_sympy(a) -> None:
    n = len(a)
    expected = sp.Matrix(n, n, lambda i, j: sp.Rational(str(a[i][j]))).det()
    assert sp.Rational(str(determinant(a))) == expected


def test_checker_imports_only_the_standard_library_and_stays_small() -> None:
    """``proofs_check`` never imports ``theory`` (nor numpy/sympy/flint) and stays < 2,000 lines
    (1,150 until issue 25: the TDOA design kinds of ``observability.py`` and the ``iss-box``
    kind's box parsing and corner reduction; 1,700 until the kind
    ``self-weight-necessary-violated`` and its exact polynomials, Sturm and Schur–Cohn)."""
    allowed = {"__future__", "argparse", "dataclasses", "fractions", "json", "math", "re", "sys"}
    allowed |= {"collections", "contextlib", "itertools", "time", "typing", "proofs_check"}
    total = 0
    for path in sorted((ROOT / "proofs_check").glob("*.py")):
        source = path.read_text(encoding="utf-8")
        total += len(source.splitlines())
        for node in ast.walk(ast.parse(source)):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            for name in names:
                assert name.split(".")[0] in allowed, f"{path.name} imports {name}"
    assert total < 2000


def _files() -> list[Path]:
    return sorted(DATA.glob("*/*.json"))


def test_every_expected_folder_has_files() -> None:
    for folder in EXPECTED_EXIT:
        assert list((DATA / folder).glob("*.json")), folder


@pytest.mark.parametrize("path", _files(), ids=lambda p: f"{p.parent.name}/{p.name}")
def test_known_certificate_files(path: Path, capsys) -> None:
    """Known-good files are accepted, known-bad ones rejected, malformed ones refused."""
    code = main([str(path), "--json"])
    assert code == EXPECTED_EXIT[path.parent.name]
    out = json.loads(capsys.readouterr().out)
    assert out["valid"] is (code == 0)
    if code == 1:
        failed = [c for c in out["checks"] if not c["valid"]]
        assert failed and all(c["detail"] for c in failed)


def _mjls(P: str = "1", decrease: str = "3/4") -> dict:
    return {
        "format": "trackcert-certificate/1",
        "kind": "mjls-stability",
        "claim": {"spectral_radius_below": "1"},
        "data": {"W": [["1"]], "Gamma": [[["1/2"]]]},
        "witness": {"operator": "L", "P": [[[P]]], "decrease": [[[decrease]]]},
    }


def _write(tmp_path: Path, content: str | bytes) -> Path:
    path = tmp_path / "cert.json"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    return path


HOSTILE = {
    "truncated": json.dumps(_mjls())[:-7],
    "empty": "",
    "top-level list": "[]",
    "wrong version": json.dumps({**_mjls(), "format": "trackcert-certificate/2"}),
    "no version": json.dumps({k: v for k, v in _mjls().items() if k != "format"}),
    "unknown kind": json.dumps({**_mjls(), "kind": "lyapunov"}),
    "unknown field": json.dumps({**_mjls(), "extra": 1}),
    "missing witness": json.dumps({k: v for k, v in _mjls().items() if k != "witness"}),
    "JSON float": json.dumps(_mjls()).replace('"3/4"', "0.75"),
    "JSON number for a matrix entry": json.dumps(_mjls()).replace('"3/4"', "3"),
    "NaN": json.dumps(_mjls()).replace('"3/4"', "NaN"),
    "exponent string": json.dumps(_mjls(decrease="1e5")),
    "zero denominator": json.dumps(_mjls(decrease="1/0")),
    "spaces": json.dumps(_mjls(decrease=" 3/4")),
    "matrix not a list": json.dumps({**_mjls(), "data": {"W": "1", "Gamma": [[["1"]]]}}),
    "ragged matrix": json.dumps({**_mjls(), "data": {"W": [["1"], ["1", "0"]], "Gamma": []}}),
    "huge JSON integer": '{"format": ' + "9" * 5000 + "}",
    "deep nesting": "[" * 100_000 + "]" * 100_000,
    "10^6-digit rational": json.dumps(_mjls(P="7" * 1_000_000 + "/3")),
    "bound above 1": json.dumps({**_mjls(), "claim": {"spectral_radius_below": "2"}}),
    "wrong operator": json.dumps({**_mjls(), "witness": {**_mjls()["witness"], "operator": "B"}}),
    "not UTF-8": b"\xff\xfe{}",
}


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_malformed_input_is_refused_with_exit_2(name: str, tmp_path: Path, capsys) -> None:
    start = time.monotonic()
    code = main([str(_write(tmp_path, HOSTILE[name]))])
    assert code == 2
    assert "malformed" in capsys.readouterr().err
    assert time.monotonic() - start < 10


def test_oversized_file_is_refused_unread(tmp_path: Path, capsys) -> None:
    path = _write(tmp_path, " " * 5_000_000 + "{}")
    assert main([str(path)]) == 2
    assert "larger than" in capsys.readouterr().err


def test_costly_certificate_is_refused_by_the_work_limit(tmp_path: Path, capsys) -> None:
    """A dense 64-agent network of 64 × 64 matrices is refused before any arithmetic."""
    n, agents = 64, 64
    block = [["1"] * n for _ in range(n)]
    cert = _mjls()
    cert["data"] = {"W": [["1/64"] * agents] * agents, "Gamma": [block] * agents}
    cert["witness"] = {"operator": "L", "P": [block] * agents, "decrease": [block] * agents}
    with pytest.raises(MalformedError, match="estimated work"):
        from proofs_check import check_certificate

        check_certificate(cert)


def test_module_entry_point_exit_codes(tmp_path: Path) -> None:
    """``python -m proofs_check`` in a fresh process: 0 valid, 1 invalid, 2 malformed."""
    for content, expected in ((_mjls(), 0), (_mjls(decrease="1"), 1), ({"format": "x"}, 2)):
        path = _write(tmp_path, json.dumps(content))
        run = subprocess.run(
            [sys.executable, "-m", "proofs_check", str(path)],
            cwd=ROOT,
            capture_output=True,
            text=True,
            timeout=60,
        )
        assert run.returncode == expected, run.stderr


def test_invalid_check_says_where_and_by_how_much() -> None:
    from proofs_check import check_certificate

    verdict = check_certificate(loads(json.dumps(_mjls(decrease="1"))))
    failed = {c.name: c.detail for c in verdict.checks if not c.valid}
    assert failed == {
        "stated P_1 − L_1(P) = recomputed": failed["stated P_1 − L_1(P) = recomputed"]
    }
    assert "off by 1/4" in failed["stated P_1 − L_1(P) = recomputed"]
    gamma_two = _mjls(decrease="-3")
    gamma_two["data"]["Gamma"] = [[["2"]]]
    verdict = check_certificate(gamma_two)
    details = [c.detail for c in verdict.checks if not c.valid]
    assert any("pivot -3" in d for d in details)
    assert not verdict.valid


def test_rational_parsing_is_exact() -> None:
    from proofs_check.parse import rational

    assert rational("-3/7", "x") == Fraction(-3, 7)
    assert rational("0", "x") == 0
    for bad in ("+1", "01", "1/-2", "1.5", "1/02", "", "--1"):
        with pytest.raises(MalformedError):
            rational(bad, "x")


def test_time_budget_refuses_arithmetic_that_grows(tmp_path: Path, capsys) -> None:
    """Coprime denominators make exact sums grow; the budget refuses such a file with exit 2."""
    rng = random.Random(1)

    def block() -> list[list[str]]:
        return [
            [str(Fraction(rng.randint(1, 10**30), rng.randint(1, 10**30))) for _ in range(12)]
        ] * 12

    cert = _mjls()
    cert["data"] = {"W": [["1/6"] * 6] * 6, "Gamma": [block() for _ in range(6)]}
    cert["witness"] = {
        "operator": "L",
        "P": [block() for _ in range(6)],
        "decrease": [block() for _ in range(6)],
    }
    path = _write(tmp_path, json.dumps(cert))
    start = time.monotonic()
    assert main([str(path), "--time-limit", "0.5"]) == 2
    assert "time budget" in capsys.readouterr().err
    assert time.monotonic() - start < 10


def test_huge_exact_values_are_shown_by_size() -> None:
    from proofs_check.kinds import show

    text = show(Fraction(3**10000, 7**5000))
    assert text.startswith("≈") and "digit" in text
    assert show(Fraction(-3, 7)) == "-3/7 (≈-0.428571)"
