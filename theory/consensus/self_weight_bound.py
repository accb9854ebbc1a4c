"""Thm 5.2.10 (2) along a weight family: the exact threshold of a rising self-weight and the
certificate (kind ``self-weight-necessary-violated``) that no ``w`` at or above it is S-detectable.

For a self-weight ``w_aa(w) = o + f·w`` (``f > 0``) and agent ``a``'s unobservable part ``M``
(``A V = V M``, ``V`` a rational basis of ``null O_a``; :func:`~theory.consensus.conditions.
exact_unobservable_basis`), the condition ``w_aa r_σ(M)² < 1`` fails exactly on ``[u, ∞)`` with
``u = (1/μ − o)/f``, ``μ = max |λ(M)|²``. ``μ = λλ̄`` is a root of ``Q = det(zI − M ⊗ M)`` (roots
``λ_iλ_j``), real or complex ``λ`` alike, so ``u`` is a root of ``Q̃(w) = Σ_j q_j (o + f w)^{d−j}``.
The root is chosen without floats: ``Q̃``'s real roots are isolated (sympy) and ``u`` is the first
whose isolating interval ends where the condition fails (Schur–Cohn, exact), having started where
it holds. ``u`` is then a rational or the root of an irreducible factor of ``Q̃`` in an interval of
width ``≤ 10⁻²⁰``; ``proofs_check`` re-derives all of it (``docs/certificates.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import sympy

from theory.consensus.conditions import exact_unobservable_basis, schur_stable
from theory.core.certificate_format import checked, envelope, strings
from theory.core.exact import Matrix, fraction_strings, fractions_of, rational_matrix, to_fmpq

__all__ = ["SOURCE", "SelfWeightThreshold", "isolated_root", "self_weight_threshold"]

SOURCE = "seed 000 Thm 5.2.10 (2); docs/certificates.md (self-weight-necessary-violated)"
EPS = Fraction(1, 10**20)
"""Width of the isolating intervals."""


@dataclass(frozen=True)
class SelfWeightThreshold:
    """``u`` for agent ``a`` (0-based): ``rational``, or the root of ``polynomial`` (integer
    coefficients, constant first) in ``interval``; ``below`` a rational with the condition holding
    and no other root of ``Q̃`` in ``(below, u]``; the witness ``V``, ``M``; ``Q`` of ``M ⊗ M``."""

    agent: int
    offset: Fraction
    factor: Fraction
    V: Matrix
    M: Matrix
    Q: tuple[Fraction, ...]
    rational: Fraction | None
    polynomial: tuple[int, ...] | None
    interval: tuple[Fraction, Fraction]
    below: Fraction

    def fails(self, x: Fraction) -> bool:
        """Whether ``w_aa(x) max|λ(M)|² ≥ 1`` (Schur–Cohn on the roots ``w_aa λ_iλ_j``)."""
        return _fails(self.Q, self.offset + self.factor * x)

    def certificate(self, A: np.ndarray, C: list[np.ndarray], W0: Matrix, W1: Matrix,
                    case: str | None = None) -> dict[str, Any] | None:  # fmt: skip
        """The ``self-weight-necessary-violated`` certificate for the family ``W0 + w·W1``
        (exact threshold), or None if ``proofs_check`` refuses it."""
        n = len(self.V)
        C_q = [
            rational_matrix(np.asarray(c, float).reshape(-1, n)) if np.size(c) else [] for c in C
        ]
        claim: dict[str, Any] = {
            "statement": f"(A, C, W(w)) is not S-detectable for any w ≥ u with W(w) ≥ 0: "
            f"agent {self.agent + 1}'s self-weight violates seed 000 Thm 5.2.10 (2); u exact",
            "agent": self.agent + 1,
            "exact": True,
        }
        witness: dict[str, Any] = {"V": fraction_strings(self.V), "M": fraction_strings(self.M)}
        if self.rational is not None:
            claim["threshold"] = str(self.rational)
            witness["below"] = str(self.below)
        else:
            claim["threshold_polynomial"] = [str(c) for c in self.polynomial or ()]
            claim["threshold_interval"] = [str(x) for x in self.interval]
        data = {
            "A": fraction_strings(rational_matrix(A)),
            "C": strings([c if c else [[Fraction(0)] * n] for c in C_q]),
            "W0": fraction_strings(W0),
            "W1": fraction_strings(W1),
        }
        cert = envelope("self-weight-necessary-violated", claim, data, witness, source=SOURCE,
                        case=case)  # fmt: skip
        return cert if checked(cert) is None else None


def _sympy(x: Fraction) -> sympy.Rational:
    return sympy.Rational(x.numerator, x.denominator)


def _fraction(x: sympy.Rational) -> Fraction:
    return Fraction(int(x.p), int(x.q))


Root = tuple[Fraction | None, tuple[int, ...] | None, tuple[Fraction, Fraction]]
"""``(rational, polynomial, interval)`` of :func:`isolated_root`."""


def isolated_root(poly: sympy.Poly, left: Fraction, right: Fraction) -> Root | None:
    """The one root of ``poly`` in ``[left, right]``: ``(q, None, (q, q))`` if rational, else
    ``(None, P, (l, r))`` with ``P`` its minimal polynomial (primitive, constant first) and
    ``(l, r) ⊆ [left, right]`` isolating, of width ``≤ 10⁻²⁰``; None if none is."""
    lo, hi = _sympy(left), _sympy(right)
    for factor, _ in poly.factor_list()[1]:
        if factor.count_roots(lo, hi) != 1:
            continue
        if factor.degree() == 1:
            a, b = factor.all_coeffs()
            q = _fraction(-b / a)
            return q, None, (q, q)
        for (a, b), _ in factor.intervals(eps=_sympy(EPS), inf=lo, sup=hi):
            primitive = factor.primitive()[1]
            if primitive.LC() < 0:
                primitive = -primitive
            coefficients = tuple(int(c) for c in reversed(primitive.all_coeffs()))
            return None, coefficients, (_fraction(a), _fraction(b))
    return None


def _fails(Q: tuple[Fraction, ...], t: Fraction) -> bool:
    """``t > 0`` and some root ``t λ_iλ_j`` of ``Σ_j q_j t^{d−j} z^j`` is outside the open unit
    disk: ``t max|λ(M)|² ≥ 1``."""
    d = len(Q) - 1
    return t > 0 and not schur_stable([q * t ** (d - j) for j, q in enumerate(Q)])


def _kron(M: Matrix) -> Matrix:
    k = len(M)
    return [[M[i][p] * M[j][q] for p in range(k) for q in range(k)]
            for i in range(k) for j in range(k)]  # fmt: skip


def self_weight_threshold(A: np.ndarray, C_a: np.ndarray, agent: int, offset: Fraction,
                          factor: Fraction) -> SelfWeightThreshold | None:  # fmt: skip
    """The exact ``u`` of Thm 5.2.10 (2) for ``w_aa(w) = offset + factor·w`` (module docstring);
    None if agent ``a`` observes everything, ``M`` is nilpotent or ``factor ≤ 0``."""
    V, A_u = exact_unobservable_basis(A, C_a)
    if not V or factor <= 0:
        return None
    M = fractions_of(A_u)
    Q = tuple(Fraction(int(c.p), int(c.q)) for c in to_fmpq(_kron(M)).charpoly().coeffs())
    w = sympy.Symbol("w")
    d = len(Q) - 1
    mapped = sympy.Poly(
        sum(_sympy(q) * (_sympy(offset) + _sympy(factor) * w) ** (d - j) for j, q in enumerate(Q)),
        w,
    )
    if mapped.degree() < 1:
        return None

    def fails(x: Fraction) -> bool:
        return _fails(Q, offset + factor * x)

    previous = None
    for (a, b), _ in mapped.sqf_part().intervals(eps=_sympy(EPS)):
        left, right = _fraction(a), _fraction(b)
        if not fails(right):
            previous = right
            continue
        below = left if left < right else left - EPS
        if previous is not None and previous >= below:
            below = (previous + right) / 2
        if fails(below):
            return None
        root = isolated_root(mapped, below if left == right else left, right)
        if root is None:
            return None
        rational, polynomial, interval = root
        below = interval[0] if rational is None else below
        return SelfWeightThreshold(
            agent, offset, factor, V, M, Q, rational, polynomial, interval, below
        )
    return None
