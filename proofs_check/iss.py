"""The ``iss`` kind: ISS of the corrected seed 003 pursuit and coordination loops.

Checks E1–E5 (pursuit error ``e``) and C1–C6 (coordination error ``ξ``, ``N > 1``) of
``docs/theory/pursuit-iss.md`` §7: square roots through squares, ``K`` formed from ``K_p`` and
``k_γ``, and every derived constant the witness states recomputed.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from proofs_check import parse as p
from proofs_check.kinds import Check, _bits, _items, _refuse_costly, definite, show
from proofs_check.linalg import identity, matmul, scale, sub, transpose

__all__ = ["iss"]


def _same(name: str, stated: Fraction, actual: Fraction) -> Check:
    return Check(name, stated == actual, f"stated {show(stated)}, recomputed {show(actual)}")


def iss(cert: dict[str, Any]) -> list[Check]:
    """The ISS estimate of seed 003 Theorem 2 (corrected) with the witness's constants."""
    p.fields(cert["claim"], "claim", ("statement",))
    need = ("dim", "controller", "epsilon", "K_p", "paths")
    data = p.fields(cert["data"], "data", need, ("k_gamma", "laplacian", "k_c"))
    dim = p.index(data["dim"], "data.dim", 2, 3)
    two_stage = p.text(data["controller"], "data.controller", ("I", "II")) == "II"
    paths = [_path(x, dim) for x in _items(data["paths"], "data.paths", None)]
    n = len(paths)
    if (two_stage, n > 1, n > 1) != ("k_gamma" in data, "laplacian" in data, "k_c" in data):
        raise p.MalformedError("data: k_gamma iff controller II; laplacian and k_c iff N > 1")
    keys = ("lambda", "kp_bar", "mu_r", "s", "g_e", "gain")
    keys += ("a", "b", "rho", "kappa", "alpha", "g_xi") if n > 1 else ()
    raw = p.fields(cert["witness"], "witness", keys + ("r",) * (n > 1))
    w = {k: p.rational(raw[k], f"witness.{k}") for k in keys}
    eps = p.matrix([data["epsilon"]], "data.epsilon", 1, dim)[0]
    K_p = p.matrix(data["K_p"], "data.K_p", dim, dim)
    K = [[*row, Fraction(0)] for row in K_p] + [[Fraction(0)] * dim] if two_stage else K_p
    if two_stage:
        K[dim].append(p.rational(data["k_gamma"], "data.k_gamma"))
    lam, kp_bar, s = w["lambda"], w["kp_bar"], w["s"]
    mu_r = max(max(r_x, r_y) ** 2 + vertical for r_x, r_y, vertical in paths)
    bound = f"k̄_p² + 1{' + μ_r' if two_stage else ''}"
    room = s * s - kp_bar**2 - 1 - (mu_r if two_stage else 0)
    sharp = f"s = {show(s)}, s² − ({bound}) = {show(room)}"
    checks = [
        Check("E1: ε₁ ≠ 0 (ΔΔᵀ is invertible)", eps[0] != 0, f"ε₁ = {show(eps[0])}"),
        Check("E2: λ > 0", lam > 0, f"λ = {show(lam)}"),
        definite("E2: K − λI ⪰ 0", sub(K, scale(lam, identity(len(K)))), semi=True),
        definite("E3: k̄_p I − K_p ⪰ 0", sub(scale(kp_bar, identity(dim)), K_p), semi=True),
        _same("E4: μ_r = max_i max(r_x, r_y)² (+ (r_z/c)² in 3D)", w["mu_r"], mu_r),
        Check(f"E4: s ≥ 0, s² ≥ {bound}", s >= 0 and room >= 0, sharp),
        _same("E5: g_e = s/λ", w["g_e"], s / lam if lam else Fraction(0)),
    ]
    if n == 1:
        return [*checks, _same("C6: gain = g_e (N = 1)", w["gain"], w["g_e"])]
    k_c = p.rational(data["k_c"], "data.k_c")
    return checks + _coordination(data["laplacian"], raw["r"], n, k_c, w, two_stage)


def _path(raw: Any, dim: int) -> tuple[Fraction, Fraction, Fraction]:
    """``(r_x, r_y, (r_z/c)²)`` of path (15) or (16) (the last is 0 in 2D)."""
    names = ("r_x", "r_y", "r_z", "c")[: 2 * dim - 2]
    v = [p.rational(x, f"data.paths: {k}") for k, x in p.fields(raw, "data.paths", names).items()]
    if dim == 3 and v[3] == 0:
        raise p.MalformedError("data.paths: c must be non-zero")
    return v[0], v[1], (v[2] / v[3]) ** 2 if dim == 3 else Fraction(0)


def _coordination(raw_L: Any, raw_r: Any, n: int, k_c: Fraction, w: dict, two: bool) -> list[Check]:
    """C1–C6: ``V_c = ½ξᵀRξ`` on ``ξ ⊥ r`` for ``ξ̇ = −k_c Lξ + W e_γ`` (seed 003 Lemmas 1, 3)."""
    L = p.matrix(raw_L, "data.laplacian", n, n)
    r = p.matrix([raw_r], "witness.r", 1, n)[0]
    _refuse_costly(6 * n**3, _bits([L, [r]]))
    a, b, rho, kappa = w["a"], w["b"], w["rho"], w["kappa"]
    rL = [sum(r[i] * L[i][j] for i in range(n)) for j in range(n)]
    M = [[r[i] * L[i][j] + L[j][i] * r[j] for j in range(n)] for i in range(n)]
    up = [f"M_{i + 1},{j + 1} > 0" for i in range(n) for j in range(n) if i != j and M[i][j] > 0]
    R = [[r[i] * (i == j) for j in range(n)] for i in range(n)]
    W = sub(identity(n), [list(r)] * n)
    alpha = k_c * a
    g_xi = b / (rho * alpha) if two and rho * alpha else Fraction(0)
    spread = kappa**2 * min(r) - max(r)
    rows = ", ".join(show(sum(row)) for row in L)
    M1 = ", ".join(show(sum(row)) for row in M)
    stochastic = f"Σr_i = {show(sum(r))}, min r_i = {show(min(r))}"
    WRW = matmul(transpose(W), matmul(R, W))
    checks = [
        Check("C1: L1 = 0", not any(map(sum, L)), f"row sums of L: {rows}"),
        Check("C1: rᵀL = 0", not any(rL), "rᵀL = " + ", ".join(show(x) for x in rL)),
        Check("C1: Σr_i = 1, r_i > 0", sum(r) == 1 and min(r) > 0, stochastic),
        Check("C2: M_ij ≤ 0 (i ≠ j)", not up, up[0] if up else "M = RL + LᵀR"),
        Check("C2: M1 = 0, so M ⪰ 0", not any(map(sum, M)), f"row sums of M: {M1}"),
        Check("C3: a > 0", a > 0, f"a = {show(a)}"),
        Check("C3: r_N ≠ 0 (basis B of r⊥)", r[-1] != 0, f"r_N = {show(r[-1])}"),
        Check("C4: b ≥ 0", b >= 0, f"b = {show(b)}"),
        definite("C4: b²I − WᵀRW ⪰ 0", sub(scale(b * b, identity(n)), WRW), semi=True),
        Check("C5: ρ > 0", rho > 0, f"ρ = {show(rho)}"),
        Check("C5: ρ² ≤ min r_i", rho**2 <= min(r), f"min r_i − ρ² = {show(min(r) - rho**2)}"),
        Check("C5: κ² min r_i ≥ max r_i", spread >= 0, f"κ² min r_i − max r_i = {show(spread)}"),
        _same("C6: α = k_c a", w["alpha"], alpha),
        _same(f"C6: g_ξ = {'b/(ρα)' if two else '0 (Type I)'}", w["g_xi"], g_xi),
        _same("C6: gain = g_e(1 + g_ξ)", w["gain"], w["g_e"] * (1 + g_xi)),
    ]
    if r[-1]:
        B = [
            [Fraction(i == j) if i < n - 1 else -r[j] / r[-1] for j in range(n - 1)]
            for i in range(n)
        ]
        gap = matmul(matmul(transpose(B), sub(M, scale(2 * a, R))), B)
        checks.insert(7, definite("C3: Bᵀ(M − 2aR)B ⪰ 0", gap, semi=True))
    return checks
