"""The largest S-detectable weight of a one-parameter family ``W(w)`` (seed 000 §5.3, issue 25
item 1): ``trackcert design self-weight`` as a library call.

**The family.** By default the self-weight of the agents ``a`` (0-based) is ``w``, their other
weights rescaled by ``(1 − w)/(1 − w_aa)`` (seed 000 Examples 5.3.1–5.3.2), ``w ∈ [0, 1]``; or
the user's links ``W.i.j = A + B·w`` (:func:`theory.core.links.parse_link_expr`, as ``trackcert
sweep`` reads them), ``w`` ranging where every linked weight lies in ``[0, 1]``, every row summing
to 1 for every ``w``. Every ``W(w)`` is exact (rows of Fractions from the data as written).

**Exact supremum.** Two necessary conditions are decided exactly along the family. (1) A linked
self-weight ``w_aa(w) = A + B·w`` with ``B > 0`` must satisfy Thm 5.2.10 (2), ``w_aa r_σ(A_aᵘ)² <
1``: with ``μ_a = r_σ(A_aᵘ)²`` (a real or a complex largest eigenvalue), it fails for every ``w ≥
u_a = (1/μ_a − A)/B`` (monotone in ``w``); ``u_a`` is exact and certified for every ``w ≥ u_a`` by
:mod:`theory.consensus.self_weight_bound`. (2) The blind-set condition (Theorem 4 of
``docs/theory/s-detectability.md``) for a rational eigenvalue λ and a blind set S the family
changes: ``λ² r_σ(W_SS(w)) < 1`` iff every leading principal minor of ``I − λ² W_SS(w)`` is
positive; ``u_S`` is the first root of a minor in ``(lo, hi]``, kept only when the condition fails
at rational points between every later root, so on all of ``[u_S, hi]``. ``u`` is the least bound: a
rational, or an algebraic number given by its minimal polynomial and an isolating interval (sympy,
exact), re-checked by the condition's exact test at the interval's upper end. It is reported as the
supremum when an ``s-detectability`` certificate holds at a rational ``w`` within ``width`` below
it; the refuted side carries the bound's ``self-weight-necessary-violated`` certificate (1), or an
``s-detectability-infeasible`` certificate at ``u`` or a rational just above when a rational blind
set gives one (2). What is then proven: ``sup ∈ [below.w, u]`` for the width asked, which any width
makes as narrow as one likes; that every ``w < u`` is S-detectable is the paper's tightness
(``docs/theory/s-detectability.md`` §8 proves it for Examples 1 and 2, Theorem 6 for scalar
systems).

**Otherwise a bracket.** Exact decisions
(:func:`~theory.consensus.s_detectability.decide_s_detectability`) at rational points, bisected
to the user's ``width`` between a certified S-detectable ``low`` and a refuted ``high``
(certificate, or the exact refutation of a bound that was not tight). The bisection presumes
one threshold; every probe is listed.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import sympy

from theory.consensus.infeasibility import blind_flats, infeasibility_certificate
from theory.consensus.operators import nonnegative_radius_below
from theory.consensus.s_detectability import LmiCache, decide_s_detectability
from theory.consensus.self_weight_bound import (
    SelfWeightThreshold,
    isolated_root,
    self_weight_threshold,
)
from theory.core.case_file import Case
from theory.core.errors import COMMAND_LINE, CaseError
from theory.core.exact import (
    Matrix,
    RationalizationError,
    rational_eigenvalues,
    rational_matrix,
    stochastic_matrix,
)
from theory.core.links import parse_link_expr
from theory.core.tolerances import WEIGHT_TOL

__all__ = [
    "Family",
    "Probe",
    "SelfWeightDesign",
    "Supremum",
    "exact_system",
    "link_family",
    "self_weight_design",
    "self_weight_family_exact",
]

SOURCE = "seed 000 Thm 5.2.10 (2), §5.3; docs/design.md (self-weight)"
PARAMETER = "w"
"""The name a ``--link`` expression uses for the family's parameter."""


def exact_system(case: Case) -> tuple[np.ndarray, list[np.ndarray], Matrix]:
    """``A``, ``C_i`` (floats, read as the decimals written) and ``W`` exact, rows summing to 1."""
    spec = case.spec
    n = spec.A.shape[0]
    C = [np.asarray(c, dtype=float).reshape(-1, n) for c in spec.C]
    return np.asarray(spec.A, dtype=float), C, stochastic_matrix(spec.W)


@dataclass(frozen=True)
class Family:
    """``W(w) = base`` with ``W[i][j] = offset + factor·w`` on ``entries``, ``w ∈ [lo, hi]``."""

    base: Matrix
    entries: dict[tuple[int, int], tuple[Fraction, Fraction]]
    lo: Fraction
    hi: Fraction
    description: str

    def at(self, w: Fraction) -> Matrix:
        """The exact ``W(w)``."""
        out = [list(row) for row in self.base]
        for (i, j), (offset, factor) in self.entries.items():
            out[i][j] = offset + factor * w
        return out

    def affine(self) -> tuple[Matrix, Matrix]:
        """``(W0, W1)`` with ``W(w) = W0 + w·W1``."""
        W0, W1 = self.at(Fraction(0)), self.at(Fraction(1))
        return W0, [
            [y - x for x, y in zip(r0, r1, strict=True)] for r0, r1 in zip(W0, W1, strict=True)
        ]

    def support(self) -> np.ndarray:
        """Where some ``W(w)`` of the family is nonzero: ``W0``'s and ``W1``'s supports."""
        W0, W1 = self.affine()
        return np.array([[x != 0 or y != 0 for x, y in zip(*rows, strict=True)]
                         for rows in zip(W0, W1, strict=True)])  # fmt: skip

    def rising_diagonal(self) -> list[tuple[int, Fraction, Fraction]]:
        """``(a, offset, factor)`` of each self-weight that grows with ``w``."""
        return [(i, o, f) for (i, j), (o, f) in self.entries.items() if i == j and f > 0]


def self_weight_family_exact(W: Matrix, agents: Sequence[int]) -> Family:
    """Agents' self-weights ``w ∈ [0, 1]``, their other weights rescaled (seed 000 §5.3)."""
    entries = {}
    for a in agents:
        rest = 1 - W[a][a]
        if rest <= 0:
            raise CaseError(
                "--agent", "an agent with some weight on others (w_aa < 1)", a + 1,
                file=COMMAND_LINE, hint=f"agent {a + 1} has w_aa = 1: nothing to rescale",
            )  # fmt: skip
        for j, x in enumerate(W[a]):
            if j != a and x:
                entries[(a, j)] = (x / rest, -x / rest)
        entries[(a, a)] = (Fraction(0), Fraction(1))
    ids = ", ".join(str(a + 1) for a in agents)
    return Family(
        W, entries, Fraction(0), Fraction(1), f"self-weight of agent(s) {ids}, rows rescaled"
    )


def link_family(W: Matrix, links: Sequence[str]) -> Family:
    """The family of the ``--link W.i.j=EXPR`` texts (``EXPR`` affine in ``w``), ``w`` where every
    linked weight lies in ``[0, 1]``; rows must sum to 1 for every ``w``."""
    N = len(W)
    entries: dict[tuple[int, int], tuple[Fraction, Fraction]] = {}
    lo, hi = Fraction(-(10**18)), Fraction(10**18)
    for text in links:
        link = parse_link_expr(text, (PARAMETER,), source="w, the family's parameter")
        parts = link.path.split(".")
        if (
            len(parts) != 3
            or parts[0] != "W"
            or not all(p.isdigit() and int(p) < N for p in parts[1:])
        ):
            raise CaseError(
                "--link", f"a weight W.i.j with 0 ≤ i, j < {N}", link.path, file=COMMAND_LINE
            )
        offset, factor = link.exact()
        entries[(int(parts[1]), int(parts[2]))] = (offset, factor)
        if factor == 0:
            continue
        ends = sorted(((0 - offset) / factor, (1 - offset) / factor))
        lo, hi = max(lo, ends[0]), min(hi, ends[1])
    family = Family(W, entries, lo, hi, "links " + ", ".join(links))
    if not any(factor for _, factor in entries.values()) or lo >= hi:
        raise CaseError(
            "--link", "links that leave an interval of w with every weight in [0, 1]",
            ", ".join(links), file=COMMAND_LINE,
        )  # fmt: skip
    for i, row in enumerate(family.at(lo)):
        factors = sum((entries[(i, j)][1] for j in range(N) if (i, j) in entries), Fraction(0))
        if sum(row) != 1 or factors != 0:
            raise CaseError(
                "--link", f"row {i} of W summing to 1 for every w", f"{', '.join(links)}",
                file=COMMAND_LINE, hint="link the row's other weights too, e.g. W.0.1=1-w",
            )  # fmt: skip
    return family


@dataclass(frozen=True)
class Supremum:
    """``exact``: the value is ``rational``, or the root of ``polynomial`` (integer
    coefficients, constant first) in ``interval``; otherwise ``interval`` is the certified
    bracket."""

    exact: bool
    value: float
    interval: tuple[Fraction, Fraction]
    rational: Fraction | None = None
    polynomial: tuple[int, ...] | None = None

    def to_json(self) -> dict[str, Any]:
        """The contract's ``supremum`` record (exact numbers as ``"p/q"`` strings)."""
        out: dict[str, Any] = {"exact": self.exact, "value": self.value}
        if self.rational is not None:
            out["rational"] = str(self.rational)
        if self.polynomial is not None:
            out["polynomial"] = [str(c) for c in self.polynomial]
        out["interval"] = [str(x) for x in self.interval]
        return out


@dataclass(frozen=True)
class Probe:
    """An exact decision at the rational ``w``: ``verdict`` and the certificate it rests on."""

    w: Fraction
    verdict: bool | None
    certificate: dict[str, Any] | None
    reason: str

    def to_json(self) -> dict[str, Any]:
        """``{"w", "value", "verdict", "certificate"}``."""
        return {
            "w": str(self.w),
            "value": float(self.w),
            "verdict": self.verdict,
            "certificate": self.certificate,
        }


@dataclass(frozen=True)
class SelfWeightDesign:
    """The answer: ``status`` ``exact``, ``bracket``, ``always`` (S-detectable over the whole
    family), ``never`` (not at its smallest ``w``) or ``inconclusive``; ``below`` a certified
    S-detectable point, ``at_or_above`` a refuted one; ``condition`` what refutes every
    ``w ≥ supremum`` when exact."""

    case: str
    agents: tuple[int, ...]
    family: str
    status: str
    supremum: Supremum | None
    below: Probe | None
    at_or_above: Probe | None
    width: Fraction
    condition: str
    note: str
    probes: tuple[Probe, ...] = field(default=())

    @property
    def verdict(self) -> bool | None:
        """True when some ``w`` is certified S-detectable, False when ``never``, else None."""
        if self.below is not None:
            return True
        return False if self.status == "never" else None

    @property
    def certificates(self) -> list[dict[str, Any]]:
        """The certificates the answer rests on."""
        ends = (self.below, self.at_or_above)
        return [p.certificate for p in ends if p is not None and p.certificate is not None]

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert design self-weight --json`` record (agents 1-based)."""
        return {
            "case": self.case,
            "agent": list(self.agents),
            "family": self.family,
            "status": self.status,
            "supremum": None if self.supremum is None else self.supremum.to_json(),
            "below": None if self.below is None else self.below.to_json(),
            "at_or_above": None if self.at_or_above is None else self.at_or_above.to_json(),
            "width": str(self.width),
            "condition": self.condition,
            "note": self.note,
            "verdict": self.verdict,
            "probes": [{"w": str(p.w), "verdict": p.verdict} for p in self.probes],
        }


@dataclass(frozen=True)
class _Bound:
    """``u`` (``value``): the necessary ``condition`` fails for every ``w ≥ u`` of the family;
    ``fails(w)`` decides it exactly at a rational ``w``; ``threshold`` when it is Thm 5.2.10 (2)
    (its certificate covers every ``w ≥ u``)."""

    value: Supremum
    condition: str
    fails: Callable[[Fraction], bool]
    threshold: SelfWeightThreshold | None = None


def _fraction(x: sympy.Rational) -> Fraction:
    """A sympy rational as a Fraction."""
    return Fraction(int(x.p), int(x.q))


def _algebraic(poly: sympy.Poly, left: Fraction, right: Fraction) -> Supremum | None:
    """The one root of ``poly`` in ``[left, right]``: rational, or its minimal polynomial and an
    isolating interval of width ``≤ 10⁻²⁰`` (:func:`~theory.consensus.self_weight_bound.
    isolated_root`)."""
    root = isolated_root(poly, left, right)
    if root is None:
        return None
    rational, polynomial, interval = root
    if rational is not None:
        return Supremum(True, float(rational), interval, rational=rational)
    return Supremum(True, float(sum(interval) / 2), interval, polynomial=polynomial)


def _self_weight_bound(A: np.ndarray, C: np.ndarray, a: int, offset: Fraction,
                       factor: Fraction) -> _Bound | None:  # fmt: skip
    """Thm 5.2.10 (2) for the rising self-weight ``w_aa = offset + factor·w``: ``u = (1/μ −
    offset)/factor``, ``μ = max |λ(A_aᵘ)|²`` (a real or a complex ``λ``), with the
    ``self-weight-necessary-violated`` certificate (:mod:`theory.consensus.self_weight_bound`)."""
    threshold = self_weight_threshold(A, C, a, offset, factor)
    if threshold is None:
        return None
    if threshold.rational is not None:
        q = threshold.rational
        sup = Supremum(True, float(q), (q, q), rational=q)
    else:
        interval = threshold.interval
        sup = Supremum(True, float(sum(interval) / 2), interval, polynomial=threshold.polynomial)
    condition = (
        f"Thm 5.2.10 (2) for agent {a + 1}: w_aa r_σ(A_aᵘ)² < 1 fails exactly for every "
        f"w ≥ {sup.value:.10g} (Schur–Cohn; monotone in w)"
    )
    return _Bound(sup, condition, threshold.fails, threshold)


def _blind_set_bounds(A: np.ndarray, C: list[np.ndarray], family: Family) -> list[_Bound]:
    """Theorem 4 (docs/theory/s-detectability.md) for every rational eigenvalue and blind set S
    that the family changes: ``u`` the first root in ``(lo, hi]`` of a leading principal minor of
    ``I − λ² W_SS(w)``, kept when the condition fails on all of ``[u, hi]`` (exact signs at
    rational points between the roots)."""
    A_q = rational_matrix(A)
    C_q = [rational_matrix(c) if c.size else [] for c in C]
    w = sympy.Symbol("w")
    out = []
    for lam in rational_eigenvalues(A_q):
        if lam == 0:
            continue
        for _, S in blind_flats(A_q, C_q, lam):
            if not any(i in S and j in S for i, j in family.entries):
                continue
            bound = _blind_set_bound(family, lam, S, w)
            if bound is not None:
                out.append(bound)
    return out


def _blind_set_bound(family: Family, lam: Fraction, S: tuple[int, ...], w: sympy.Symbol
                     ) -> _Bound | None:  # fmt: skip
    """Theorem 4's bound for one rational ``λ`` and blind set ``S`` (None: not exact here)."""
    square = sympy.Rational(lam.numerator, lam.denominator) ** 2
    M = sympy.Matrix([[int(i == j) - square * _value(family, i, j, w) for j in S] for i in S])
    minors = [sympy.Poly(M[:k, :k].det(), w) for k in range(1, len(S) + 1)]
    product = sympy.Poly(sympy.prod(m.as_expr() for m in minors if m.degree() > 0) or 1, w)
    if product.degree() < 1:
        return None
    lo, hi = (sympy.Rational(x.numerator, x.denominator) for x in (family.lo, family.hi))
    roots = [(a, b) for (a, b), _ in product.sqf_part().intervals(eps=sympy.Rational(1, 10**20))
             if b > lo and a <= hi]  # fmt: skip
    if not roots or roots[0][0] <= lo or roots[-1][0] <= hi < roots[-1][1]:
        return None

    def fails(x: Fraction) -> bool:
        W_SS = [[lam * lam * _value(family, i, j, x) for j in S] for i in S]
        return not nonnegative_radius_below(W_SS)

    ends = [_fraction(b) for _, b in roots]
    starts = [_fraction(a) for a, _ in roots[1:]] + [_fraction(hi)]
    samples = [(e + s_) / 2 for e, s_ in zip(ends, starts, strict=True) if e < s_]
    if not all(fails(x) for x in samples):
        return None
    sup = _algebraic(product, _fraction(roots[0][0]), _fraction(roots[0][1]))
    if sup is None:
        return None
    condition = (
        f"blind-set condition (Theorem 4) for λ = {lam}, agents "
        f"{', '.join(str(i + 1) for i in S)}: λ² r_σ(W_SS(w)) < 1 fails exactly for every "
        f"w ≥ {sup.value:.10g} (signs of the leading minors of I − λ² W_SS(w))"
    )
    return _Bound(sup, condition, fails)


def _value(family: Family, i: int, j: int, w: Any) -> Any:
    """``w_ij(w)`` of the family, for a rational ``w`` or a sympy symbol."""
    offset, factor = family.entries.get((i, j), (family.base[i][j], Fraction(0)))
    return offset + factor * w


def _exact_bound(A: np.ndarray, C: list[np.ndarray], family: Family) -> _Bound | None:
    """The least exact bound over the family's rising self-weights (Thm 5.2.10 (2)) and its
    blind sets (Theorem 4) (module docstring)."""
    bounds = [
        b
        for a, offset, factor in family.rising_diagonal()
        if (b := _self_weight_bound(A, C[a], a, offset, factor))
    ]
    bounds += _blind_set_bounds(A, C, family)
    return min(bounds, key=lambda b: b.value.interval[0], default=None)


def default_agents(A: np.ndarray, C: list[np.ndarray], W: Matrix) -> list[int]:
    """The agents (0-based) with the least finite exact self-weight bound, varied together; agent
    0 (or the first with ``w_aa < 1``) when no agent has one."""
    free = [a for a in range(len(W)) if W[a][a] < 1]
    if not free:
        raise CaseError("dkf.W", "some agent with w_aa < 1 to vary", "every w_aa = 1")
    bounds = {
        a: b.value.value
        for a in free
        if (b := _self_weight_bound(A, C[a], a, Fraction(0), Fraction(1)))
    }
    if not bounds:
        return free[:1]
    least = min(bounds.values())
    return [a for a, u in bounds.items() if math.isclose(u, least, rel_tol=1e-12)]


def _digits(width: Fraction) -> int:
    """The fewest decimals ``d`` with ``10^-d ≤ width``."""
    d = 0
    while Fraction(1, 10**d) > width:
        d += 1
    return d


def _decimal_below(x: Fraction, d: int) -> Fraction:
    """The largest ``d``-decimal strictly below ``x``."""
    return Fraction(math.ceil(x * 10**d) - 1, 10**d)


def _decimal_at_or_above(x: Fraction, d: int) -> Fraction:
    """The smallest ``d``-decimal ``≥ x``."""
    return Fraction(math.ceil(x * 10**d), 10**d)


class _Decider:
    """Exact decisions along one family, the LMI built once per support (issue 28 item 4)."""

    def __init__(
        self, A: np.ndarray, C: list[np.ndarray], family: Family, case: str, solver: str,
        problems: LmiCache | None = None,
    ) -> None:  # fmt: skip
        self.A, self.C, self.family, self.case, self.solver = A, C, family, case, solver
        self.problems = problems if problems is not None else LmiCache(support=family.support())
        self.probes: list[Probe] = []

    def decide(self, w: Fraction) -> Probe:
        """S-detectability of ``W(w)``, by exact certificates only."""
        result = decide_s_detectability(
            self.A, self.C, self.family.at(w), solver=self.solver, case=self.case,
            problems=self.problems,
        )  # fmt: skip
        probe = Probe(w, result.verdict, result.certificate, result.reason)
        self.probes.append(probe)
        return probe

    def refute(self, w: Fraction) -> Probe | None:
        """An ``s-detectability-infeasible`` certificate at ``w`` from a rational blind set."""
        try:
            cert = infeasibility_certificate(self.A, self.C, self.family.at(w), case=self.case)
        except RationalizationError:
            return None
        probe = Probe(w, False, cert, "infeasibility certificate (blind set)")
        self.probes.append(probe)
        return probe

    def violated(self, bound: _Bound, w: Fraction) -> Probe | None:
        """A ``self-weight-necessary-violated`` certificate (every ``w' ≥ u``, Thm 5.2.10 (2)),
        recorded at the rational ``w ≥ u``."""
        if bound.threshold is None:
            return None
        W0, slope = self.family.affine()
        cert = bound.threshold.certificate(self.A, self.C, W0, slope, self.case)
        if cert is None:
            return None
        probe = Probe(w, False, cert, bound.condition)
        self.probes.append(probe)
        return probe


def self_weight_design(
    case: Case,
    *,
    agents: Sequence[int] | None = None,
    links: Sequence[str] = (),
    width: float | Fraction = WEIGHT_TOL,
    solver: str = "CLARABEL",
    problems: LmiCache | None = None,
) -> SelfWeightDesign:
    """The supremum of the S-detectable ``w`` of a weight family, exact when a necessary
    condition decided exactly is tight, else a bracket of ``width`` (module docstring).

    ``agents`` (0-based; default :func:`default_agents`) vary their self-weights with their rows
    rescaled, unless ``links`` (``"W.i.j=EXPR"`` in ``w``) give the family; ``problems`` the
    built LMIs to re-solve (its support must hold the family's; default: one for the family).
    """
    width = Fraction(width) if not isinstance(width, float) else Fraction(repr(width))
    if width <= 0:
        raise CaseError("--width", "a number > 0", str(width), file=COMMAND_LINE)
    A, C, W = exact_system(case)
    if links and agents is not None:
        raise CaseError("--link", "either --link or --agent", "both", file=COMMAND_LINE)
    if links:
        family, ids = link_family(W, links), ()
    else:
        chosen = list(agents) if agents is not None else default_agents(A, C, W)
        if any(not 0 <= a < len(W) for a in chosen):
            raise CaseError(
                "--agent", f"agents 1…{len(W)}", [a + 1 for a in chosen], file=COMMAND_LINE
            )
        family, ids = self_weight_family_exact(W, chosen), tuple(a + 1 for a in chosen)
    decider = _Decider(A, C, family, case.name, solver, problems)
    return _search(decider, _exact_bound(A, C, family), width, ids)


def _search(
    decider: _Decider, bound: _Bound | None, width: Fraction, ids: tuple[int, ...]
) -> SelfWeightDesign:
    """The exact route at ``bound`` when it lies in the family, else the bisection."""
    family = decider.family

    def answer(status: str, sup: Supremum | None, low: Probe | None, high: Probe | None,
               condition: str, note: str) -> SelfWeightDesign:  # fmt: skip
        return SelfWeightDesign(
            decider.case, ids, family.description, status, sup, low, high, width, condition,
            note, tuple(decider.probes),
        )  # fmt: skip

    first = decider.decide(family.lo)
    if first.verdict is not True:
        status = "never" if first.verdict is False else "inconclusive"
        return answer(status, None, None, first if first.verdict is False else None, "",
                      f"at the family's smallest w = {family.lo}: {first.reason}")  # fmt: skip
    d = _digits(width)
    if _refuted_from(bound) and family.lo < bound.value.interval[1] <= family.hi:
        low_end, high_end = bound.value.interval
        below = _decimal_below(low_end, d)
        if below >= family.lo:
            above = (
                high_end if bound.value.rational is not None else _decimal_at_or_above(high_end, d)
            )
            near = decider.decide(below)
            condition = bound.condition
            if near.verdict is True:
                refuted = decider.violated(bound, above) or decider.refute(above)
                note = (
                    "exact: S-detectable (certificate) at a w within the width below the "
                    "supremum; no w at or above it is (the exact necessary condition)"
                    + ("" if refuted else "; no certificate above (no rational blind set)")
                )
                return answer("exact", bound.value, near, refuted, condition, note)
            high = decider.violated(bound, above) or Probe(above, False, None, condition)
            return _bisect(decider, first, high, width, answer, condition)
    last = decider.decide(family.hi)
    if last.verdict is True:
        hi = family.hi
        sup = Supremum(True, float(hi), (hi, hi), rational=hi)
        return answer("always", sup, last, None, "", "S-detectable at the family's largest w")
    if last.verdict is None:
        return answer("inconclusive", None, first, None, "", last.reason)
    return _bisect(decider, first, last, width, answer, "")


def _refuted_from(bound: _Bound | None) -> bool:
    """Whether the bound's condition fails exactly at its isolating interval's upper end: a
    re-check independent of how the root was chosen."""
    return bound is not None and bound.fails(bound.value.interval[1])


def _bisect(decider: _Decider, low: Probe, high: Probe, width: Fraction, answer: Any,
            condition: str) -> SelfWeightDesign:  # fmt: skip
    """Bisection between a certified ``low`` and a refuted ``high``, each probe exact."""
    while high.w - low.w > width:
        probe = decider.decide((low.w + high.w) / 2)
        if probe.verdict is None:
            sup = Supremum(False, float((low.w + high.w) / 2), (low.w, high.w))
            return answer("inconclusive", sup, low, high, condition,
                          f"a probe was inconclusive: {probe.reason}")  # fmt: skip
        low, high = (probe, high) if probe.verdict else (low, probe)
    sup = Supremum(False, float((low.w + high.w) / 2), (low.w, high.w))
    note = (
        "bracket: no necessary condition decided exactly bounds this family tightly, so the "
        "supremum is bisected between certified ends (one threshold presumed)"
    )
    return answer("bracket", sup, low, high, condition, note)
