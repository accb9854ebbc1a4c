"""Kind ``self-weight-necessary-violated``: seed 000 Thm 5.2.10 (2) fails for every ``w ≥ u`` of a
family ``W(w) = W0 + w·W1``, so no such ``W(w)`` (entrywise ``≥ 0``) is S-detectable.

The theorem: S-detectable only if ``w_aa < 1/r_σ(A_aᵘ)²`` (its proof needs ``W ≥ 0``). A witness
``V`` (``n × k``, rank ``k``) with ``A V = V M`` and ``C_a V = 0`` spans an A-invariant subspace
unobservable to agent ``a``, so every eigenvalue of ``M`` is one of ``A_aᵘ`` and
``r_σ(A_aᵘ)² ≥ μ := max |λ(M)|²``. With ``w_aa(w) = o + f·w``, ``f > 0``, the condition fails
wherever ``w_aa(w) μ ≥ 1``, i.e. on ``[u*, ∞)`` with ``u* = (1/μ − o)/f``.

The eigenvalues of ``M ⊗ M`` are the products ``λ_iλ_j``; among them ``|λ|² = λλ̄`` (``M`` is
real) and no product exceeds ``μ`` in modulus. So, with ``Q = det(zI − M ⊗ M)`` of degree ``d``:

* ``F(x)``: "the condition fails at ``x``" iff ``t = w_aa(x) > 0`` and ``Σ_j q_j t^{d−j} z^j``
  (roots ``t λ_iλ_j``) is not Schur stable (Schur–Cohn, exact);
* ``u*`` is a root of ``Q̃(w) = Σ_j q_j (o + f w)^{d−j}`` (roots ``(1/ρ − o)/f``), because
  ``μ = |λ|²`` is a root of ``Q``.

A claimed ``u`` (a rational, or the one root of a polynomial ``P`` in ``(l, r)``) is shown
``≥ u*`` by ``F(u)`` (rational) or ``F(l)`` (``u > l``). An **exact** claim, ``u = u*`` and ``V``
the whole unobservable subspace (``rank O_a = n − k``, so ``μ = r_σ(A_aᵘ)²``), adds: ``F(l)``
false and ``F(r)`` true (``u* ∈ (l, r]``), ``Q̃(u) = 0`` (``P`` divides ``Q̃``), and ``Q̃`` has
one distinct real root in ``(l, r]`` (Sturm): ``u`` and ``u*`` are that root. For a rational
exact ``u`` the witness gives ``l`` (``below``) and ``r = u``.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd
from typing import Any

from proofs_check import linalg as la
from proofs_check import parse as p
from proofs_check import polynomials as poly
from proofs_check.checks import Check, show
from proofs_check.linalg import Matrix

__all__ = ["MAX_BLOCK", "self_weight_necessary_violated"]

MAX_BLOCK = 6
"""Largest accepted ``k`` (columns of ``V``): ``M ⊗ M`` is ``k² × k²``."""


def _flag(value: Any, where: str) -> bool:
    if not isinstance(value, bool):
        raise p.MalformedError(f"{where}: expected true or false, got {value!r}"[:200])
    return value


def _threshold(claim: dict[str, Any]) -> tuple[Fraction | None, poly.Poly, Fraction, Fraction]:
    """``(u, [], u, u)`` for a rational claim; ``(None, P, l, r)`` for an algebraic one."""
    if "threshold" in claim:
        if "threshold_polynomial" in claim or "threshold_interval" in claim:
            raise p.MalformedError("claim: either threshold or threshold_polynomial, not both")
        u = p.rational(claim["threshold"], "claim.threshold")
        return u, [], u, u
    if "threshold_polynomial" not in claim or "threshold_interval" not in claim:
        raise p.MalformedError("claim: expected threshold, or threshold_polynomial and _interval")
    ends = p.matrix([claim["threshold_interval"]], "claim.threshold_interval", 1, 2)[0]
    coefficients = p.matrix([claim["threshold_polynomial"]], "claim.threshold_polynomial")[0]
    if not ends[0] < ends[1]:
        raise p.MalformedError(f"claim.threshold_interval: expected l < r, got {ends}")
    integers = all(c.denominator == 1 for c in coefficients)
    common = gcd(*(c.numerator for c in coefficients)) if integers else 0
    if len(coefficients) < 3 or not integers or common != 1 or coefficients[-1] <= 0:
        why = "integer coefficients, constant first, gcd 1, leading > 0, degree ≥ 2"
        raise p.MalformedError(f"claim.threshold_polynomial: not canonical ({why})")
    return None, coefficients, ends[0], ends[1]


def _fails(Q: poly.Poly, offset: Fraction, factor: Fraction, x: Fraction) -> bool:
    """``F(x)``: ``w_aa(x) max|λ(M)|² ≥ 1`` (module docstring)."""
    t = offset + factor * x
    d = len(Q) - 1
    return t > 0 and not poly.schur_stable([q * t ** (d - j) for j, q in enumerate(Q)])


def _mapped(Q: poly.Poly, offset: Fraction, factor: Fraction) -> poly.Poly:
    """``Q̃(w) = Σ_j q_j (o + f w)^{d−j}``."""
    out: poly.Poly = []
    power = [Fraction(1)]
    for q in reversed(Q):
        out = poly.add(out, [q * c for c in power])
        power = poly.mul(power, [offset, factor])
    return out


def _kron(M: Matrix) -> Matrix:
    k = len(M)
    return [[M[i][p_] * M[j][q] for p_ in range(k) for q in range(k)]
            for i in range(k) for j in range(k)]  # fmt: skip


def _zero(name: str, matrix: Matrix) -> Check:
    bad = next(((r, c, x) for r, row in enumerate(matrix) for c, x in enumerate(row) if x), None)
    if bad is None:
        return Check(name, True, "every entry is exactly 0")
    r, c, x = bad
    return Check(name, False, f"entry ({r + 1},{c + 1}) is {show(x)}")


def _family_checks(W0: Matrix, W1: Matrix, a: int, at: Fraction) -> list[Check]:
    sums = [(i, sum(r0), sum(r1)) for i, (r0, r1) in enumerate(zip(W0, W1, strict=True))]
    off = [(i, s0, s1) for i, s0, s1 in sums if s0 != 1 or s1 != 0]
    rows = "rows of W0 sum to 1, rows of W1 to 0"
    if off:
        i, s0, s1 = off[0]
        rows = f"row {i + 1}: W0 sums to {show(s0)}, W1 to {show(s1)}"
    W = [[x + at * y for x, y in zip(r0, r1, strict=True)] for r0, r1 in zip(W0, W1, strict=True)]
    negative = [(i, j) for i, row in enumerate(W) for j, x in enumerate(row) if x < 0]
    where = f"w_{negative[0][0] + 1},{negative[0][1] + 1} < 0" if negative else "all w_ij ≥ 0"
    return [
        Check("data: W(w) = W0 + w·W1 row-stochastic for every w", not off, rows),
        Check(
            f"data: w_{a + 1}{a + 1}(w) rises with w (W1_aa > 0)",
            W1[a][a] > 0,
            f"W1_aa = {show(W1[a][a])}",
        ),
        Check(
            f"data: W(w) ≥ 0 at w = {show(at)} ≥ u (the claim is not vacuous)", not negative, where
        ),
    ]


def self_weight_necessary_violated(cert: dict[str, Any]) -> list[Check]:
    """Thm 5.2.10 (2) fails for every ``w ≥ u`` of the family, so none is S-detectable."""
    claim = p.fields(
        cert["claim"], "claim", ("agent", "exact"),
        ("statement", "threshold", "threshold_polynomial", "threshold_interval"),
    )  # fmt: skip
    data = p.fields(cert["data"], "data", ("A", "C", "W0", "W1"))
    exact = _flag(claim["exact"], "claim.exact")
    u, P, low, high = _threshold(claim)
    wants_below = exact and u is not None
    witness = p.fields(cert["witness"], "witness", ("V", "M") + ("below",) * wants_below)
    A, W0 = p.matrix(data["A"], "data.A"), p.matrix(data["W0"], "data.W0")
    n, N = len(A), len(W0)
    if len(A[0]) != n or len(W0[0]) != N:
        raise p.MalformedError("data.A and data.W0: expected square matrices")
    W1 = p.matrix(data["W1"], "data.W1", N, N)
    C = p.matrix_list(data["C"], "data.C", N, None, n)
    a = p.index(claim["agent"], "claim.agent", 1, N) - 1
    V = p.matrix(witness["V"], "witness.V", n)
    k = len(V[0])
    if k > MAX_BLOCK:
        raise p.MalformedError(f"witness.V: {k} columns (limit {MAX_BLOCK})")
    M = p.matrix(witness["M"], "witness.M", k, k)
    if wants_below:
        low = p.rational(witness["below"], "witness.below")
        if not low < u:
            raise p.MalformedError(f"witness.below: expected < {u}, got {low}")
    checks = _family_checks(W0, W1, a, high)
    Vt = la.transpose(V)
    gram = la.determinant(la.matmul(Vt, V))
    checks.append(Check(f"witness: V has rank {k} (det VᵀV ≠ 0)", gram != 0, f"det {show(gram)}"))
    checks.append(_zero("witness: A V − V M = 0 (im V is A-invariant)",
                        la.sub(la.matmul(A, V), la.matmul(V, M))))  # fmt: skip
    checks.append(_zero(f"witness: C_{a + 1} V = 0 (unobservable to agent {a + 1})",
                        la.matmul(C[a], V)))  # fmt: skip
    if exact:
        checks.append(_whole(A, C[a], n, k, a))
    offset, factor = W0[a][a], W1[a][a]
    Q = poly.charpoly(_kron(M))
    mapped = _mapped(Q, offset, factor)
    if P:
        checks.append(_isolating(P, low, high))
    return checks + _threshold_checks(Q, mapped, offset, factor, (u, P, low, high), exact)


def _whole(A: Matrix, C_a: Matrix, n: int, k: int, a: int) -> Check:
    """``rank O_a = n − k``: im V is the whole unobservable subspace (eq. (4.18))."""
    rows, block = [], C_a
    for _ in range(n):
        rows += block
        block = la.matmul(block, A)
    r = la.rank(rows)
    name = f"exact: im V = null O_{a + 1} (rank O_{a + 1} = n − k = {n - k})"
    return Check(name, r == n - k, f"rank O_{a + 1} = {r}")


def _isolating(P: poly.Poly, low: Fraction, high: Fraction) -> Check:
    ends = (poly.evaluate(P, low), poly.evaluate(P, high))
    count = poly.real_roots_in(P, low, high)
    detail = f"P(l) = {show(ends[0])}, P(r) = {show(ends[1])}, {count} roots in (l, r]"
    return Check("claim: exactly one root of P in (l, r), none at l or r",
                 count == 1 and 0 not in ends, detail)  # fmt: skip


def _threshold_checks(Q: poly.Poly, mapped: poly.Poly, offset: Fraction, factor: Fraction,
                      threshold: tuple, exact: bool) -> list[Check]:  # fmt: skip
    """``u ≥ u*`` (and ``u = u*`` when ``exact``), module docstring."""
    u, P, low, high = threshold

    def fails(x: Fraction, expected: bool) -> Check:
        t = offset + factor * x
        verb = "fails" if expected else "holds"
        relation = "≥" if expected else "<"
        name = f"Thm 5.2.10 (2) {verb} at w = {show(x)}: w_aa·max|λ(M)|² {relation} 1"
        return Check(name, _fails(Q, offset, factor, x) is expected,
                     f"w_aa = {show(t)}; Schur–Cohn on the roots w_aa·λ_iλ_j of M ⊗ M")  # fmt: skip

    if not exact:
        return [fails(u if u is not None else low, True)]
    divides = poly.evaluate(mapped, u) == 0 if u is not None else not poly.divide(mapped, P)[1]
    count = poly.real_roots_in(mapped, low, high) if mapped else 0
    what = "Q̃(u) = 0" if u is not None else "P divides Q̃"
    return [
        fails(low, False),
        fails(high, True),
        Check(
            f"exact: {what} (Q̃(w) = det((o + f w)⁻¹ I − M ⊗ M)·(o + f w)^d)",
            divides,
            f"Q̃ of degree {len(mapped) - 1}",
        ),
        Check(
            "exact: Q̃ has exactly one distinct real root in (l, r] (Sturm)",
            count == 1,
            f"{count} roots in ({show(low)}, {show(high)}]",
        ),
    ]
