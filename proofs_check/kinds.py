"""What each certificate kind claims and the exact checks that establish it.

Every function takes the parsed JSON of one certificate, validates its shape (raising
:class:`~proofs_check.parse.MalformedError`), recomputes every quantity from ``data`` and
``witness`` and returns the list of :class:`Check` results. Nothing a certificate says about
itself is trusted: stated values (the decrease matrices ``ρP_i − T_i(P)``, the minor of
``generic-rank``, the constants of ``iss``) are recomputed and compared exactly, and positivity
is tested on the recomputed matrices. A kind's name is its claim: the number a claim states
about itself (``ρ``, a rate) is read by :func:`proofs_check.claims.claimed`, which refuses it
outside the range in which it implies that claim.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from proofs_check import gain_box
from proofs_check import linalg as la
from proofs_check import parse as p
from proofs_check.checks import Check, definite, show
from proofs_check.claims import claimed
from proofs_check.linalg import Matrix
from proofs_check.observability import loss_tolerance, observability_margin
from proofs_check.operators import OPERATORS, apply_operator
from proofs_check.self_weight import self_weight_necessary_violated

__all__ = ["KINDS", "WORK_LIMIT", "Check"]

WORK_LIMIT = 3_000_000
"""Largest accepted work estimate (rational operations × a number-size factor)."""


def _refuse_costly(work: float, bits: int) -> None:
    cost = work * (1 + bits / 128) ** 2
    if cost > WORK_LIMIT:
        why = f"refused: estimated work {cost:.3g} exceeds the limit {WORK_LIMIT:.3g}"
        raise p.MalformedError(why)


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
    detail = "all w_ij ≥ 0, so the operators are positive"
    if negative:
        i, j = negative[0]
        detail = f"w_{i + 1},{j + 1} = {show(W[i][j])} < 0: the operators need not be positive"
    sums = [(i, sum(row)) for i, row in enumerate(W) if sum(row) != 1]
    rows = f"row {sums[0][0] + 1} sums to {show(sums[0][1])}" if sums else "every row sums to 1"
    return W, [
        Check("data: W ≥ 0 entrywise", not negative, detail),
        Check("data: W row-stochastic (seed 000 eq. (5.3))", not sums, rows),
    ]


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
        actual = la.sub(la.scale(bound, P_i), T_i)
        checks.append(_equal(f"stated {label} = recomputed", R_i, actual))
        checks.append(definite(f"{label} ≻ 0", actual))
    return checks


def _equal(name: str, stated: Matrix, actual: Matrix) -> Check:
    for r, (row_s, row_a) in enumerate(zip(stated, actual, strict=True)):
        for c, (x, y) in enumerate(zip(row_s, row_a, strict=True)):
            if x != y:
                where = f"entry ({r + 1},{c + 1}): stated {show(x)}, recomputed {show(y)}"
                return Check(name, False, f"{where}, off by {show(x - y)}")
    return Check(name, True, "equal entry by entry")


def _lyapunov(operator: str, W: Matrix, gammas: list[Matrix], witness: dict, bound: Fraction):
    """``P_i ≻ 0`` and ``bound · P_i − T_i(P) ≻ 0`` (Lemma 5.2.2's witness)."""
    agents, n = len(W), len(gammas[0])
    P = p.matrix_list(witness["P"], "witness.P", agents, n, n)
    R = p.matrix_list(witness["decrease"], "witness.decrease", agents, n, n)
    checks = [definite(f"P_{i + 1} ≻ 0", P_i) for i, P_i in enumerate(P)]
    name = "P_{i} − " + operator + "_{i}(P)"
    return checks + _decrease(name, operator, W, gammas, P, bound, R)


def _system(cert: dict[str, Any], witness_keys: tuple[str, ...], size_key: str):
    """Claimed ``ρ``, witness, ``n``, ``A``, ``W`` (with its checks) and ``C`` of the four kinds
    about gains ``L_i`` for ``(A, C, W)`` (Lemma 1 of the theory note holds for any ρ > 0)."""
    rho = claimed(cert)
    data = p.fields(cert["data"], "data", ("A", "C", "W"))
    witness = p.fields(cert["witness"], "witness", witness_keys)
    n = _size(witness[size_key], f"witness.{size_key}")
    A = p.matrix(data["A"], "data.A", n, n)
    W, checks = _weights(data["W"])
    C = p.matrix_list(data["C"], "data.C", len(W), None, n)
    return rho, witness, n, A, W, checks, C


def mjls_stability(cert: dict[str, Any]) -> list[Check]:
    """``r_σ(L) < ρ ≤ 1`` for given ``Γ_i`` and ``W`` (seed 000 Lemma 5.2.2)."""
    bound = claimed(cert)
    data = p.fields(cert["data"], "data", ("W", "Gamma"))
    witness = p.fields(cert["witness"], "witness", ("operator", "P", "decrease"))
    operator = p.text(witness["operator"], "witness.operator", OPERATORS)
    n = _size(data["Gamma"], "data.Gamma")
    W, checks = _weights(data["W"])
    gammas = p.matrix_list(data["Gamma"], "data.Gamma", len(W), n, n)
    return checks + _lyapunov(operator, W, gammas, witness, bound)


def s_detectability(cert: dict[str, Any]) -> list[Check]:
    """Gains give ``r_σ(L) < ρ`` with ``Γ_i = A − L_i C_i``; S-detectable if ρ ≤ 1 (Def. 5.2.4)."""
    keys = ("operator", "gains", "P", "decrease")
    bound, witness, n, A, W, checks, C = _system(cert, keys, "P")
    operator = p.text(witness["operator"], "witness.operator", OPERATORS)
    gains = [
        p.matrix(g, f"witness.gains[{i + 1}]", n, len(C[i]))
        for i, g in enumerate(_items(witness["gains"], "witness.gains", len(W)))
    ]
    _refuse_costly(len(W) * n**3, _bits([A, *C, *gains]))
    gammas = [la.sub(A, la.matmul(L_i, C_i)) for L_i, C_i in zip(gains, C, strict=True)]
    return checks + _lyapunov(operator, W, gammas, witness, bound)


def s_detectability_infeasible(cert: dict[str, Any]) -> list[Check]:
    """No gains give ``r_σ(L) < ρ`` (Farkas witness); not S-detectable if ``ρ ≥ 1`` (Def. 5.2.4).

    The witness is multipliers ``Λ_j ⪰ 0`` (n × n) and ``Ψ_i ⪰ 0`` (2n × 2n), not all zero, that
    annihilate the LMI of Theorem 3 in ``docs/theory/s-detectability.md``:
    ``F1_j = Y_j − Σ_i (w_ij/ρ) Z_i``, ``F2_i = [[Z_i, M_iᵀ], [M_i, Y_i]]`` with
    ``M_i = Y_i A − G_i C_i``.
    ``F*(Λ, Ψ) = 0`` reads ``Ψ_i,11 = Σ_j (w_ij/ρ) Λ_j``, ``Ψ_i,21 C_iᵀ = 0`` and
    ``Λ_i + Ψ_i,22 + A Ψ_i,21ᵀ + Ψ_i,21 Aᵀ = 0`` (``Ψ_i,21``: lower-left block). Then no
    ``(Y, G, Z)`` has ``F ≻ 0`` (``0 = ⟨F*(Λ, Ψ), x⟩ = ⟨(Λ, Ψ), F(x)⟩ > 0``), so no gains exist.
    """
    rho, witness, n, A, W, checks, C = _system(cert, ("Lambda", "Psi"), "Lambda")
    agents = len(W)
    Lam = p.matrix_list(witness["Lambda"], "witness.Lambda", agents, n, n)
    Psi = p.matrix_list(witness["Psi"], "witness.Psi", agents, 2 * n, 2 * n)
    _refuse_costly(agents * (agents * n * n + 16 * n**3), _bits([A, W, *C, *Lam, *Psi]))
    checks += [definite(f"Λ_{j + 1} ⪰ 0", L_j, semi=True) for j, L_j in enumerate(Lam)]
    checks += [definite(f"Ψ_{i + 1} ⪰ 0", P_i, semi=True) for i, P_i in enumerate(Psi)]
    total = sum(la.trace(M) for M in (*Lam, *Psi))
    checks.append(Check("not all zero: Σ tr Λ_j + Σ tr Ψ_i > 0", total > 0, f"sum {show(total)}"))
    for i in range(agents):
        checks += _annihilated(i, A, C[i], W, rho, Lam, Psi[i])
    return checks


def _annihilated(
    i: int, A: Matrix, C_i: Matrix, W: Matrix, rho: Fraction, Lam: list[Matrix], Psi_i: Matrix
) -> list[Check]:
    """The three blocks of ``F*(Λ, Ψ)`` belonging to agent ``i`` (0-based), each exactly 0."""
    n, k = len(A), i + 1
    P11 = [row[:n] for row in Psi_i[:n]]
    P21 = [row[:n] for row in Psi_i[n:]]
    P22 = [row[n:] for row in Psi_i[n:]]
    mixed = [[Fraction(0)] * n for _ in range(n)]
    for j, L_j in enumerate(Lam):
        if W[i][j]:
            mixed = la.add(mixed, la.scale(W[i][j] / rho, L_j))
    moved = la.add(la.matmul(A, la.transpose(P21)), la.matmul(P21, la.transpose(A)))
    return [
        _zero(f"F*_Z{k}: Ψ_{k},11 − Σ_j (w_{k}j/ρ) Λ_j = 0", la.sub(P11, mixed)),
        _zero(f"F*_G{k}: Ψ_{k},21 C_{k}ᵀ = 0", la.matmul(P21, la.transpose(C_i))),
        _zero(
            f"F*_Y{k}: Λ_{k} + Ψ_{k},22 + A Ψ_{k},21ᵀ + Ψ_{k},21 Aᵀ = 0",
            la.add(Lam[i], la.add(P22, moved)),
        ),
    ]


def _zero(name: str, matrix: Matrix) -> Check:
    return _equal(name, [[Fraction(0)] * len(row) for row in matrix], matrix)


def covariance_bound(cert: dict[str, Any]) -> list[Check]:
    """``Xⁱ ≻ f₁ⁱ(M, X)`` for every listed mode ``M`` (seed 000 Lemma A.2.1, Cor. A.2.2).

    Modes are given as ``M`` directly or as ``M^j = A (I − K^j H^j)`` from ``A``, ``K``, ``H``.
    """
    rate = claimed(cert)
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
    eye = la.identity(n)
    return [la.matmul(A, la.sub(eye, la.matmul(K_j, H_j))) for K_j, H_j in zip(K, H, strict=True)]


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
    T = p.bounded(data["T"], "data.T", "(0, ∞)", "T is the sampling period of eq. (4.6)")
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
        expected = f"{rank} rows and {rank} columns"
        raise p.MalformedError(f"witness: expected {expected} (claim.rank_at_least)")
    block = range(2 * dim * (agent - 1), 2 * dim * agent) if agent else range(width)
    if any(c not in block for c in cols):
        outside = f"columns outside agent {agent}'s block {block.start + 1}…"
        raise p.MalformedError(f"witness.cols: {outside}")
    max_power = max(r // m for r in rows)
    _refuse_costly(max_power * agents**3 + rank**3, _bits([W, u, [[T]]]))
    support = [[j for j in range(agents) if j != i and W[i][j] != 0] for i in range(agents)]
    mismatch = [i for i in range(agents) if sorted(neighbours[i]) != support[i]]
    detail = "agent i measures against j iff w_ij ≠ 0 (seed 000 eq. (5.3))"
    if mismatch:
        i = mismatch[0]
        ids = [j + 1 for j in neighbours[i]], [j + 1 for j in support[i]]
        detail = f"agent {i + 1}: neighbours {ids[0]}, w_ij ≠ 0 for j in {ids[1]}"
    checks.append(Check("data: neighbours = support of W", not mismatch, detail))
    for a in range(agents):
        norm = sum(x * x for x in u[a])
        checks.append(Check(f"‖u_{a + 1}‖² = 1", norm == 1, f"‖u_{a + 1}‖² = {show(norm)}"))
    powers = [la.identity(agents)]
    for _ in range(max_power):
        powers.append(la.matmul(powers[-1], W))
    sub_matrix = []
    for r in rows:
        k, (a, j) = r // m, owners[r % m]
        g = [x - y for x, y in zip(u[a], u[j], strict=True)]
        row = [powers[k][a][b] * v for b in range(agents) for v in (*g, *(k * T * x for x in g))]
        sub_matrix.append([row[c] for c in cols])
    value = la.determinant(sub_matrix)
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


def _same(name: str, stated: Fraction, actual: Fraction) -> Check:
    return Check(name, stated == actual, f"stated {show(stated)}, recomputed {show(actual)}")


def _loop(data: dict[str, Any]) -> tuple[bool, list[list[Fraction]], Matrix]:
    """Controller Type II?, the paths (15)/(16) and ``K_p`` of an ``iss`` or ``iss-box`` loop."""
    dim = p.index(data["dim"], "data.dim", 2, 3)
    two_stage = p.text(data["controller"], "data.controller", ("I", "II")) == "II"
    names = ("r_x", "r_y", "r_z", "c")[: 2 * dim - 2]  # paths (15) and (16)
    paths = [p.fields(x, "data.paths", names) for x in _items(data["paths"], "data.paths", None)]
    paths = [[p.rational(path[k], f"data.paths: {k}") for k in names] for path in paths]
    if dim == 3 and not all(path[3] for path in paths):
        raise p.MalformedError("data.paths: c must be non-zero")
    return two_stage, paths, p.matrix(data["K_p"], "data.K_p", dim, dim)


def iss(cert: dict[str, Any]) -> list[Check]:
    """The ISS estimate of seed 003 Theorem 2 (corrected) with the witness's constants."""
    p.fields(cert["claim"], "claim", ("statement",))
    need = ("dim", "controller", "epsilon", "K_p", "paths")
    data = p.fields(cert["data"], "data", need, ("k_gamma", "laplacian", "k_c"))
    two_stage, paths, K_p = _loop(data)
    n = len(paths)
    if (two_stage, n > 1, n > 1) != ("k_gamma" in data, "laplacian" in data, "k_c" in data):
        raise p.MalformedError("data: k_gamma iff controller II; laplacian and k_c iff N > 1")
    eps = p.matrix([data["epsilon"]], "data.epsilon", 1, len(K_p))[0]
    k_gamma = p.rational(data["k_gamma"], "data.k_gamma") if two_stage else None
    k_c = p.rational(data["k_c"], "data.k_c") if n > 1 else None
    at = gain_box.point(K_p, k_gamma, k_c, eps[0])
    return _iss_checks(cert["witness"], two_stage, paths, at, data.get("laplacian"))


def iss_box(cert: dict[str, Any]) -> list[Check]:
    """The ``iss`` estimate with the same constants at every point of ``claim.box``."""
    data = p.fields(cert["data"], "data", ("dim", "controller", "K_p", "paths"), ("laplacian",))
    two_stage, paths, K_p = _loop(data)
    if (len(paths) > 1) != ("laplacian" in data):
        raise p.MalformedError("data: laplacian iff N > 1")
    claim = p.fields(cert["claim"], "claim", ("box",), ("statement",))
    box = gain_box.parse_box(claim["box"], two_stage=two_stage, coordinated=len(paths) > 1)
    at = gain_box.corners(K_p, box)
    return _iss_checks(cert["witness"], two_stage, paths, at, data.get("laplacian"))


def _iss_checks(
    raw_witness: Any, two_stage: bool, paths: list, at: gain_box.Corners, raw_L: Any
) -> list[Check]:
    """E1–E5, C1–C6 of ``iss`` with each monotone check at its corner of ``at``."""
    n, dim = len(paths), len(at.K_p_high)
    keys = ("lambda", "kp_bar", "mu_r", "s", "g_e", "gain")
    keys += ("a", "b", "rho", "kappa", "alpha", "g_xi") if n > 1 else ()
    raw = p.fields(raw_witness, "witness", keys + ("r",) * (n > 1))
    w = {k: p.rational(raw[k], f"witness.{k}") for k in keys}
    lam, kp_bar, s = w["lambda"], w["kp_bar"], w["s"]
    mu_r = max(max(v[0] ** 2, v[1] ** 2) + ((v[2] / v[3]) ** 2 if dim == 3 else 0) for v in paths)
    bound = f"k̄_p² + 1{' + μ_r' if two_stage else ''}"
    room = s * s - kp_bar**2 - 1 - (mu_r if two_stage else 0)
    sharp = f"s = {show(s)}, s² − ({bound}) = {show(room)}"
    lo, hi = at.epsilon_1
    e1 = f"ε₁ ∈ [{show(lo)}, {show(hi)}]" if at.box else f"ε₁ = {show(lo)}"
    low, high = (" at the lowest gains", " at the largest K_p scale") if at.box else ("", "")
    K, K_p = at.K_low, at.K_p_high
    checks = [
        Check("E1: ε₁ ≠ 0 (ΔΔᵀ is invertible)", lo > 0 or hi < 0, e1),
        Check("E2: λ > 0", lam > 0, f"λ = {show(lam)}"),
        definite(f"E2: K − λI ⪰ 0{low}", la.sub(K, la.scale(lam, la.identity(len(K)))), semi=True),
        definite(
            f"E3: k̄_p I − K_p ⪰ 0{high}", la.sub(la.scale(kp_bar, la.identity(dim)), K_p), semi=True
        ),
        _same("E4: μ_r = max_i max(r_x², r_y²) (+ (r_z/c)² in 3D)", w["mu_r"], mu_r),
        Check(f"E4: s ≥ 0, s² ≥ {bound}", s >= 0 and room >= 0, sharp),
        _same("E5: g_e = s/λ", w["g_e"], s / lam if lam else Fraction(0)),
    ]
    if n == 1:
        return [*checks, _same("C6: gain = g_e (N = 1)", w["gain"], w["g_e"])]
    return checks + _coordination(raw_L, raw["r"], n, at.k_c_low, w, two_stage)


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
    W = la.sub(la.identity(n), [list(r)] * n)
    alpha = k_c * a
    g_xi = b / (rho * alpha) if two and rho * alpha else Fraction(0)
    spread = kappa**2 * min(r) - max(r)
    room = f"ρ = {show(rho)}, min r_i − ρ² = {show(min(r) - rho**2)}"
    kappa_room = f"κ = {show(kappa)}, κ² min r_i − max r_i = {show(spread)}"
    rows = ", ".join(show(sum(row)) for row in L)
    M1 = ", ".join(show(sum(row)) for row in M)
    stochastic = f"Σr_i = {show(sum(r))}, min r_i = {show(min(r))}"
    WRW = la.matmul(la.transpose(W), la.matmul(R, W))
    checks = [
        Check("C1: L1 = 0", not any(map(sum, L)), f"row sums of L: {rows}"),
        Check("C1: rᵀL = 0", not any(rL), "rᵀL = " + ", ".join(show(x) for x in rL)),
        Check("C1: Σr_i = 1, r_i > 0", sum(r) == 1 and min(r) > 0, stochastic),
        Check("C2: M_ij ≤ 0 (i ≠ j)", not up, up[0] if up else "M = RL + LᵀR"),
        Check("C2: M1 = 0, so M ⪰ 0", not any(map(sum, M)), f"row sums of M: {M1}"),
        Check("C3: a > 0", a > 0, f"a = {show(a)}"),
        Check("C4: b ≥ 0", b >= 0, f"b = {show(b)}"),
        definite("C4: b²I − WᵀRW ⪰ 0", la.sub(la.scale(b * b, la.identity(n)), WRW), semi=True),
        Check("C5: ρ > 0, ρ² ≤ min r_i", 0 < rho and rho**2 <= min(r), room),
        Check("C5: κ > 0, κ² min r_i ≥ max r_i", kappa > 0 and spread >= 0, kappa_room),
        Check("C6: k_c > 0", k_c > 0, f"k_c = {show(k_c)}"),
        _same("C6: α = k_c a", w["alpha"], alpha),
        _same(f"C6: g_ξ = {'b/(ρα)' if two else '0 (Type I)'}", w["g_xi"], g_xi),
        _same("C6: gain = g_e(1 + g_ξ)", w["gain"], w["g_e"] * (1 + g_xi)),
    ]
    if r[-1]:
        B = [*la.identity(n - 1), [-x / r[-1] for x in r[:-1]]]  # columns e_i − (r_i/r_N)e_N
        gap = la.matmul(la.matmul(la.transpose(B), la.sub(M, la.scale(2 * a, R))), B)
        checks.insert(6, definite("C3: Bᵀ(M − 2aR)B ⪰ 0", gap, semi=True))
    return checks


KINDS = {
    "mjls-stability": mjls_stability,
    "s-detectability": s_detectability,
    "gains-radius-below": s_detectability,
    "s-detectability-infeasible": s_detectability_infeasible,
    "gains-radius-below-infeasible": s_detectability_infeasible,
    "covariance-bound": covariance_bound,
    "generic-rank": generic_rank,
    "iss": iss,
    "tdoa-observability-margin": observability_margin,
    "tdoa-loss-tolerance": loss_tolerance,
    "iss-box": iss_box,
    "self-weight-necessary-violated": self_weight_necessary_violated,
}
"""Each kind's checker."""
