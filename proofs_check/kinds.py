"""What each certificate kind claims and the exact checks that establish it.

Every function takes the parsed JSON of one certificate, validates its shape (raising
:class:`~proofs_check.parse.MalformedError`), recomputes every quantity from ``data`` and
``witness`` and returns the list of :class:`Check` results. Nothing a certificate says about
itself is trusted: stated values (the decrease matrices ``ρP_i − T_i(P)``, the minor of
``generic-rank``) are recomputed and compared exactly, and positivity is tested on the
recomputed matrices.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from proofs_check import parse as p
from proofs_check.linalg import (
    Matrix,
    determinant,
    first_asymmetry,
    identity,
    matmul,
    positive_definite,
    scale,
    semidefinite,
    sub,
)
from proofs_check.operators import OPERATORS, apply_operator

__all__ = ["KINDS", "WORK_LIMIT", "Check"]

WORK_LIMIT = 3_000_000
"""Largest accepted work estimate (rational operations × a number-size factor)."""


@dataclass(frozen=True)
class Check:
    """One verified inequality or identity: its name, verdict and the numbers behind it."""

    name: str
    valid: bool
    detail: str

    def to_json(self) -> dict[str, Any]:
        """``{"name", "valid", "detail"}``."""
        return {"name": self.name, "valid": self.valid, "detail": self.detail}


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


def _refuse_costly(work: float, bits: int) -> None:
    cost = work * (1 + bits / 128) ** 2
    if cost > WORK_LIMIT:
        raise p.MalformedError(
            f"refused: estimated work {cost:.3g} exceeds the limit {WORK_LIMIT:.3g}"
        )


def _bits(mats: list[Matrix]) -> int:
    return max(
        (x.numerator.bit_length() + x.denominator.bit_length() for m in mats for r in m for x in r),
        default=0,
    )


def _size(raw: Any, where: str) -> int:
    """Rows of the first matrix of a raw list (before parsing); refuses costly shapes early."""
    first = raw[0] if isinstance(raw, list) and raw else None
    if not isinstance(first, list) or not first:
        raise p.MalformedError(f"{where}: expected a non-empty list of non-empty matrices")
    n = len(first)
    _refuse_costly(len(raw) * (len(raw) * n * n + 4 * n**3), 0)
    return n


def _weights(raw: Any) -> tuple[Matrix, list[Check]]:
    W = p.matrix(raw, "data.W")
    if len(W) != len(W[0]):
        raise p.MalformedError(f"data.W: expected a square matrix, got {len(W)} × {len(W[0])}")
    negative = [(i, j) for i, row in enumerate(W) for j, w in enumerate(row) if w < 0]
    detail = (
        "all w_ij ≥ 0, so the operators are positive"
        if not negative
        else f"w_{negative[0][0] + 1},{negative[0][1] + 1} = "
        f"{show(W[negative[0][0]][negative[0][1]])} < 0: the operators need not be positive"
    )
    sums = [(i, sum(row)) for i, row in enumerate(W) if sum(row) != 1]
    rows = f"row {sums[0][0] + 1} sums to {show(sums[0][1])}" if sums else "every row sums to 1"
    return W, [
        Check("data: W ≥ 0 entrywise", not negative, detail),
        Check("data: W row-stochastic (seed 000 eq. (5.3))", not sums, rows),
    ]


def definite(name: str, matrix: Matrix, *, semi: bool = False) -> Check:
    """The exact check "``matrix`` is symmetric positive (semi)definite", with the failing pivot."""
    asym = first_asymmetry(matrix)
    if asym is not None:
        r, c, diff = asym
        detail = (
            f"not symmetric: entries ({r + 1},{c + 1}) and ({c + 1},{r + 1}) differ by {show(diff)}"
        )
        return Check(name, False, detail)
    result = semidefinite(matrix) if semi else positive_definite(matrix)
    if result.positive:
        detail = f"all {len(matrix)} LDLᵀ pivots {'≥' if semi else '>'} 0"
        return Check(name, True, f"{detail}; smallest {show(result.pivot)}")
    if semi:
        why = f"LDLᵀ pivot {result.order} is {show(result.pivot)}"
        return Check(name, False, why + (" < 0" if result.pivot else " with a non-zero row"))
    return Check(
        name,
        False,
        f"leading principal minor of order {result.order} is not positive: "
        f"LDLᵀ pivot {show(result.pivot)} ≤ 0",
    )


def _decrease(
    name: str,
    operator: str,
    W: Matrix,
    gammas: list[Matrix],
    P: list[Matrix],
    bound: Fraction,
    stated: list[Matrix],
) -> list[Check]:
    """``R_i = bound · P_i − T_i(P)`` recomputed: equal to the stated ``R_i`` and ``≻ 0``.

    ``name`` is formatted with the 1-based agent ``i``. The positivity test runs on the
    recomputed matrix, so a wrong stated ``R_i`` fails the equality and cannot hide the truth.
    """
    n, agents = len(P[0]), len(W)
    _refuse_costly(agents * (agents * n * n + 4 * n**3), _bits([W, *gammas, *P, *stated]))
    images = apply_operator(operator, W, gammas, P)
    factor = "" if bound == 1 else f"{bound}·"
    checks = []
    for i, (P_i, T_i, R_i) in enumerate(zip(P, images, stated, strict=True)):
        label = factor + name.format(i=i + 1)
        actual = sub(scale(bound, P_i), T_i)
        checks.append(_equal(f"stated {label} = recomputed", R_i, actual))
        checks.append(definite(f"{label} ≻ 0", actual))
    return checks


def _equal(name: str, stated: Matrix, actual: Matrix) -> Check:
    for r, (row_s, row_a) in enumerate(zip(stated, actual, strict=True)):
        for c, (x, y) in enumerate(zip(row_s, row_a, strict=True)):
            if x != y:
                return Check(
                    name,
                    False,
                    f"entry ({r + 1},{c + 1}): stated {show(x)}, "
                    f"recomputed {show(y)}, off by {show(x - y)}",
                )
    return Check(name, True, "equal entry by entry")


def _lyapunov(operator: str, W: Matrix, gammas: list[Matrix], witness: dict, bound: Fraction):
    """``P_i ≻ 0`` and ``bound · P_i − T_i(P) ≻ 0`` (Lemma 5.2.2's witness)."""
    agents, n = len(W), len(gammas[0])
    P = p.matrix_list(witness["P"], "witness.P", agents, n, n)
    R = p.matrix_list(witness["decrease"], "witness.decrease", agents, n, n)
    checks = [definite(f"P_{i + 1} ≻ 0", P_i) for i, P_i in enumerate(P)]
    name = "P_{i} − " + operator + "_{i}(P)"
    return checks + _decrease(name, operator, W, gammas, P, bound, R)


def _bound(claim: dict[str, Any], key: str) -> Fraction:
    bound = p.rational(claim[key], f"claim.{key}")
    if not 0 < bound <= 1:
        raise p.MalformedError(f"claim.{key}: expected a rational in (0, 1], got {bound}")
    return bound


def mjls_stability(cert: dict[str, Any]) -> list[Check]:
    """``r_σ(L) < ρ`` for given ``Γ_i`` and ``W`` (seed 000 Lemma 5.2.2)."""
    claim = p.fields(cert["claim"], "claim", ("spectral_radius_below",), ("statement",))
    data = p.fields(cert["data"], "data", ("W", "Gamma"))
    witness = p.fields(cert["witness"], "witness", ("operator", "P", "decrease"))
    operator = p.text(witness["operator"], "witness.operator", OPERATORS)
    n = _size(data["Gamma"], "data.Gamma")
    W, checks = _weights(data["W"])
    gammas = p.matrix_list(data["Gamma"], "data.Gamma", len(W), n, n)
    bound = _bound(claim, "spectral_radius_below")
    return checks + _lyapunov(operator, W, gammas, witness, bound)


def s_detectability(cert: dict[str, Any]) -> list[Check]:
    """``(A, C, W)`` is S-detectable: ``r_σ(L) < ρ`` with ``Γ_i = A − L_i C_i`` (Def. 5.2.4)."""
    claim = p.fields(cert["claim"], "claim", ("spectral_radius_below",), ("statement",))
    data = p.fields(cert["data"], "data", ("A", "C", "W"))
    witness = p.fields(cert["witness"], "witness", ("operator", "gains", "P", "decrease"))
    operator = p.text(witness["operator"], "witness.operator", OPERATORS)
    n = _size(witness["P"], "witness.P")
    A = p.matrix(data["A"], "data.A", n, n)
    W, checks = _weights(data["W"])
    C = p.matrix_list(data["C"], "data.C", len(W), None, n)
    gains = [
        p.matrix(g, f"witness.gains[{i + 1}]", n, len(C[i]))
        for i, g in enumerate(_items(witness["gains"], "witness.gains", len(W)))
    ]
    _refuse_costly(len(W) * n**3, _bits([A, *C, *gains]))
    gammas = [sub(A, matmul(L_i, C_i)) for L_i, C_i in zip(gains, C, strict=True)]
    bound = _bound(claim, "spectral_radius_below")
    return checks + _lyapunov(operator, W, gammas, witness, bound)


def covariance_bound(cert: dict[str, Any]) -> list[Check]:
    """``Xⁱ ≻ f₁ⁱ(M, X)`` for every listed mode ``M`` (seed 000 Lemma A.2.1, Cor. A.2.2).

    Modes are given as ``M`` directly or as ``M^j = A (I − K^j H^j)`` from ``A``, ``K``, ``H``.
    """
    claim = p.fields(cert["claim"], "claim", ("rate",), ("statement",))
    data = p.fields(cert["data"], "data", ("W", "modes"), ("A",))
    witness = p.fields(cert["witness"], "witness", ("X", "decrease"))
    n = _size(witness["X"], "witness.X")
    W, checks = _weights(data["W"])
    X = p.matrix_list(witness["X"], "witness.X", len(W), n, n)
    A = p.matrix(data["A"], "data.A", n, n) if "A" in data else None
    modes = [
        _mode(raw, f"data.modes[{k + 1}]", A, len(W), n)
        for k, raw in enumerate(_items(data["modes"], "data.modes", None))
    ]
    stated = [
        p.matrix_list(item, f"witness.decrease[{k + 1}]", len(W), n, n)
        for k, item in enumerate(_items(witness["decrease"], "witness.decrease", len(modes)))
    ]
    rate = _bound(claim, "rate")
    checks += [definite(f"X_{i + 1} ≻ 0", X_i) for i, X_i in enumerate(X)]
    for k, M in enumerate(modes):
        label = f"mode {k + 1}: " if len(modes) > 1 else ""
        checks += _decrease(label + "X_{i} − f₁^{i}(M, X)", "J", W, M, X, rate, stated[k])
    return checks


def _mode(raw: Any, where: str, A: Matrix | None, agents: int, n: int) -> list[Matrix]:
    if isinstance(raw, dict) and "M" in raw:
        return p.matrix_list(p.fields(raw, where, ("M",))["M"], f"{where}.M", agents, n, n)
    entry = p.fields(raw, where, ("K", "H"))
    if A is None:
        raise p.MalformedError(f"{where}: K and H need data.A (M^j = A (I − K^j H^j))")
    H = p.matrix_list(entry["H"], f"{where}.H", agents, None, n)
    K = [
        p.matrix(k, f"{where}.K[{j + 1}]", n, len(H[j]))
        for j, k in enumerate(_items(entry["K"], f"{where}.K", agents))
    ]
    _refuse_costly(agents * 2 * n**3, _bits([A, *K, *H]))
    return [matmul(A, sub(identity(n), matmul(K_j, H_j))) for K_j, H_j in zip(K, H, strict=True)]


def _items(value: Any, where: str, count: int | None) -> list[Any]:
    if not isinstance(value, list) or not value or len(value) > p.MAX_ITEMS:
        raise p.MalformedError(f"{where}: expected a non-empty list of at most {p.MAX_ITEMS} items")
    if count is not None and len(value) != count:
        raise p.MalformedError(f"{where}: expected {count} items, got {len(value)}")
    return value


def generic_rank(cert: dict[str, Any]) -> list[Check]:
    """Generic rank ``≥ r`` of the TDOA network observability matrix, seed 000 eq. (4.36).

    ``O`` stacks ``D_H (W^k ⊗ A^k)``, ``k = 0 … 2dN − 1``, with ``D_H = blkdiag(H_i)`` and the
    rows of ``H_i`` equal to ``[u_i − u_j, 0]`` for each neighbour ``j`` of agent ``i``, ``u_i``
    the unit direction from agent ``i`` to the target (eqs. (4.7)–(4.10)) and ``A`` eq. (4.6).
    Since ``[g, 0] A^k = [g, kT g]``, row ``(k, ρ)`` of agent ``a`` has block ``b`` equal to
    ``(W^k)_ab [g_ρ, kT g_ρ]``. A non-zero ``r × r`` minor at rational unit directions shows the
    minor, a polynomial in ``u``, does not vanish identically on the product of spheres.
    """
    claim = p.fields(cert["claim"], "claim", ("agent", "rank_at_least"), ("statement",))
    data = p.fields(cert["data"], "data", ("model", "dim", "T", "W", "neighbours"))
    witness = p.fields(cert["witness"], "witness", ("directions", "rows", "cols", "minor"))
    p.text(data["model"], "data.model", ("tdoa-network-observability",))
    dim = p.index(data["dim"], "data.dim", 2, 3)
    T = p.rational(data["T"], "data.T")
    W, checks = _weights(data["W"])
    agents = len(W)
    neighbours = _neighbours(data["neighbours"], agents)
    u = p.matrix(witness["directions"], "witness.directions", agents, dim)
    owners = [(a, j) for a in range(agents) for j in neighbours[a]]
    m, width = len(owners), 2 * dim * agents
    rows = _indices(witness["rows"], "witness.rows", m * width)
    cols = _indices(witness["cols"], "witness.cols", width)
    agent = p.index(claim["agent"], "claim.agent", 0, agents)
    rank = p.index(claim["rank_at_least"], "claim.rank_at_least", 1, width)
    stated = p.rational(witness["minor"], "witness.minor")
    if len(rows) != rank or len(cols) != rank:
        raise p.MalformedError(
            f"witness: expected {rank} rows and {rank} columns (claim.rank_at_least)"
        )
    block = range(2 * dim * (agent - 1), 2 * dim * agent) if agent else range(width)
    if any(c not in block for c in cols):
        raise p.MalformedError(
            f"witness.cols: columns outside agent {agent}'s block {block.start + 1}…"
        )
    max_power = max(r // m for r in rows)
    _refuse_costly(max_power * agents**3 + rank**3, _bits([W, u, [[T]]]))
    support = [[j for j in range(agents) if j != i and W[i][j] != 0] for i in range(agents)]
    mismatch = [i for i in range(agents) if sorted(neighbours[i]) != support[i]]
    detail = (
        f"agent {mismatch[0] + 1}: neighbours {[j + 1 for j in neighbours[mismatch[0]]]}, "
        f"w_ij ≠ 0 for j in {[j + 1 for j in support[mismatch[0]]]}"
        if mismatch
        else "agent i measures against j iff w_ij ≠ 0 (seed 000 eq. (5.3))"
    )
    checks.append(Check("data: neighbours = support of W", not mismatch, detail))
    for a in range(agents):
        norm = sum(x * x for x in u[a])
        checks.append(Check(f"‖u_{a + 1}‖² = 1", norm == 1, f"‖u_{a + 1}‖² = {show(norm)}"))
    powers = [identity(agents)]
    for _ in range(max_power):
        powers.append(matmul(powers[-1], W))
    sub_matrix = []
    for r in rows:
        k, (a, j) = r // m, owners[r % m]
        g = [x - y for x, y in zip(u[a], u[j], strict=True)]
        row = [powers[k][a][b] * v for b in range(agents) for v in (*g, *(k * T * x for x in g))]
        sub_matrix.append([row[c] for c in cols])
    value = determinant(sub_matrix)
    where = f"rows {[r + 1 for r in rows]}, columns {[c + 1 for c in cols]}"
    checks.append(Check(f"{rank}×{rank} minor ≠ 0", value != 0, f"{where}: {show(value)}"))
    checks.append(
        Check("stated minor = recomputed minor", value == stated, f"stated {show(stated)}")
    )
    return checks


def _neighbours(raw: Any, agents: int) -> list[list[int]]:
    lists = _items(raw, "data.neighbours", agents)
    out = []
    for i, items in enumerate(lists):
        where = f"data.neighbours[{i + 1}]"
        if not isinstance(items, list) or len(set(map(repr, items))) != len(items):
            raise p.MalformedError(f"{where}: expected a list of distinct 1-based agent ids")
        ids = [p.index(j, where, 1, agents) - 1 for j in items]
        if i in ids:
            raise p.MalformedError(f"{where}: agent {i + 1} cannot be its own neighbour")
        out.append(ids)
    return out


def _indices(raw: Any, where: str, size: int) -> list[int]:
    if not isinstance(raw, list) or not raw or len(raw) > p.MAX_DIM:
        raise p.MalformedError(f"{where}: expected a non-empty list of at most {p.MAX_DIM} indices")
    out = [p.index(x, where, 1, size) - 1 for x in raw]
    if len(set(out)) != len(out):
        raise p.MalformedError(f"{where}: indices must be distinct")
    return out


KINDS = {
    "mjls-stability": mjls_stability,
    "s-detectability": s_detectability,
    "covariance-bound": covariance_bound,
    "generic-rank": generic_rank,
}
"""Each kind's checker."""
