"""A box of pursuit gains (kind ``iss-box``): the claim's box and where each check is evaluated.

The ``iss`` inequalities hold at every point of a box once each holds at one corner, since each
is monotone in the gains (seed 003, corrected; ``docs/certificates.md``, ``iss-box``):

* E2 ``K − λI ⪰ 0``, ``K = diag(sK_p, k_γ)``: ``s_lo K_p ⪰ λI`` with λ > 0 and ``s_lo > 0``
  gives ``K_p ⪰ 0``, so ``sK_p − λI ⪰ s_lo K_p − λI`` for ``s ≥ s_lo``: the lower corner;
* E3 ``k̄_p I − sK_p ⪰ 0``: ``sK_p ⪯ s_hi K_p`` (``K_p ⪰ 0``): the upper end of the scale;
* C6 ``α = k_c a ≤ k_c' a(L)`` for every ``k_c' ≥ k_c``: the lower end of ``k_c``;
* E1 ``ε₁ ≠ 0`` on an interval iff 0 is outside it (``det ΔΔᵀ = ε₁²‖ε‖²`` or ``ε₁²``: the other
  components of ε never enter).

E4, E5 and C1–C5 do not involve the box. A point certificate (kind ``iss``) is the box of one
point (:func:`point`).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from proofs_check import linalg as la
from proofs_check import parse as p
from proofs_check.linalg import Matrix

__all__ = ["GAINS", "Corners", "corners", "gain_matrix", "parse_box", "point"]

GAINS = ("K_p_scale", "k_gamma", "k_c")
"""Box entries that scale a gain: each must lie in (0, ∞) for the reduction to corners."""


@dataclass(frozen=True)
class Corners:
    """The values the checks of ``iss`` use: ``K`` for E2, ``K_p`` for E3, ``k_c`` for C6."""

    epsilon_1: tuple[Fraction, Fraction]
    K_low: Matrix
    K_p_high: Matrix
    k_c_low: Fraction | None
    box: bool


def gain_matrix(K_p: Matrix, k_gamma: Fraction | None) -> Matrix:
    """``K = diag(K_p, k_γ)`` (Type II) or ``K_p`` (Type I, ``k_gamma`` None), seed 003 (66)."""
    if k_gamma is None:
        return K_p
    return [[*row, Fraction(0)] for row in K_p] + [[Fraction(0)] * len(K_p) + [k_gamma]]


def point(K_p: Matrix, k_gamma: Fraction | None, k_c: Fraction | None, e1: Fraction) -> Corners:
    """The corners of a one-point box: the stated gains themselves."""
    return Corners((e1, e1), gain_matrix(K_p, k_gamma), K_p, k_c, box=False)


def parse_box(raw: Any, *, two_stage: bool, coordinated: bool) -> dict[str, tuple[Fraction, ...]]:
    """``claim.box``: ``[lo, hi]`` with ``lo ≤ hi`` per entry, gains in (0, ∞).

    Required: ``K_p_scale`` and ``epsilon_1``; ``k_gamma`` iff Type II; ``k_c`` iff N > 1. An
    empty interval would make the claim vacuous, a gain ≤ 0 would break the reduction to corners:
    both are refused.
    """
    names = ("K_p_scale", "epsilon_1") + ("k_gamma",) * two_stage + ("k_c",) * coordinated
    box = p.fields(raw, "claim.box", names)
    out = {}
    for name in names:
        where = f"claim.box.{name}"
        pair = box[name]
        if not isinstance(pair, list) or len(pair) != 2:
            raise p.MalformedError(f"{where}: expected [lo, hi], two rational strings")
        if name in GAINS:
            why = "a gain of seed 003 is positive, and the checks reduce to corners only then"
            lo, hi = (p.bounded(x, where, "(0, ∞)", why) for x in pair)
        else:
            lo, hi = (p.rational(x, where) for x in pair)
        if lo > hi:
            raise p.MalformedError(f"{where}: lo = {lo} > hi = {hi} (an empty box claims nothing)")
        out[name] = (lo, hi)
    return out


def corners(K_p: Matrix, box: dict[str, tuple[Fraction, ...]]) -> Corners:
    """Where each check is evaluated for ``box`` (module docstring)."""
    s_lo, s_hi = box["K_p_scale"]
    k_gamma = box["k_gamma"][0] if "k_gamma" in box else None
    k_c = box["k_c"][0] if "k_c" in box else None
    low = gain_matrix(la.scale(s_lo, K_p), k_gamma)
    return Corners(box["epsilon_1"], low, la.scale(s_hi, K_p), k_c, box=True)
