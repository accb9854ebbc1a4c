"""What one check reports, and the exact positive-definiteness check every kind uses."""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from proofs_check import linalg as la
from proofs_check.linalg import Matrix

__all__ = ["Check", "definite", "show"]


@dataclass(frozen=True)
class Check:
    """One verified inequality or identity: its name, verdict and the numbers behind it."""

    name: str
    valid: bool
    detail: str


def show(x: Fraction) -> str:
    """``x`` exactly when short, else its size; always a decimal approximation."""
    if x == 0:
        return "0"
    digits = [
        len(str(abs(v))) if v.bit_length() < 1000 else None for v in (x.numerator, x.denominator)
    ]
    exponent = math.log10(abs(x.numerator)) - math.log10(x.denominator)
    power = math.floor(exponent)
    if abs(power) < 300:
        approx = f"{float(x):.6g}"
    else:
        approx = f"{'-' if x < 0 else ''}{10 ** (exponent - power):.6g}e{power:+d}"
    if None in digits or sum(digits) > 60:
        sizes = [f"~{v.bit_length() * 0.30103:.0f}" for v in (abs(x.numerator), x.denominator)]
        return f"≈{approx} (exact value: {sizes[0]}-digit / {sizes[1]}-digit integers)"
    return f"{x} (≈{approx})"


def definite(name: str, matrix: Matrix, *, semi: bool = False) -> Check:
    """The exact check "``matrix`` is symmetric positive (semi)definite", with the failing pivot."""
    asym = la.first_asymmetry(matrix)
    if asym is not None:
        r, c, diff = asym
        pair = f"({r + 1},{c + 1}) and ({c + 1},{r + 1})"
        return Check(name, False, f"not symmetric: entries {pair} differ by {show(diff)}")
    result = la.positive_definite(matrix, semi=semi)
    if result.positive:
        detail = f"all {len(matrix)} LDLᵀ pivots {'≥' if semi else '>'} 0"
        return Check(name, True, f"{detail}; smallest {show(result.pivot)}")
    if semi:
        why = f"LDLᵀ pivot {result.order} is {show(result.pivot)}"
        return Check(name, False, why + (" < 0" if result.pivot else " with a non-zero row"))
    minor = f"leading principal minor of order {result.order} is not positive"
    return Check(name, False, f"{minor}: LDLᵀ pivot {show(result.pivot)} ≤ 0")
