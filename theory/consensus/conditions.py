"""Necessary conditions for S-detectability: seed 000 Thm 5.2.10 and a sharper blind-set condition.

* Source components (Def. 5.2.8) and their detectability (Def. 5.2.9, Thm 5.2.10 item 1);
* W-detectability through the pairs ``(A, O_i)`` of eqs. (5.19)–(5.20) (Lemma 5.2.7);
* per agent, the unobservable part ``A_iᵘ`` of ``A`` for ``C_i`` (Kalman decomposition) and the
  self-weight bound ``w_ii < 1 / r_σ(A_iᵘ)²`` (Thm 5.2.10 item 2);
* the **blind-set condition** (ours, proven in ``docs/theory/s-detectability.md``): for every
  eigenvalue λ of A and every set S of agents such that some eigenvector v (A v = λ v) has
  ``C_i v = 0`` for all i ∈ S, S-detectability requires ``|λ|² r_σ(W_SS) < 1``. With S = {i} it
  is item 2; with S an undetectable source component (``W_SS`` stochastic) it is item 1; it also
  catches cycles of agents blind to the same unstable mode.

Every verdict is True / False / None (inconclusive: the deciding quantity lies within
``value_tol`` of its threshold, or a rank decision is not ``inconclusive_factor``-safe).

**Exact self-weight bound and detectability** (python-flint), so that boundary cases such as
Example 1's ``W_c`` (``w_ii = 0.25``, ``r_σ = 2``: exactly on the bound) get a verdict:

1. the data are read as the decimals written (:func:`theory.core.exact.exact_decimal`: 0.24 is
   6/25);
2. the unobservable subspace ``N = null O`` (observability matrix, eq. (4.18)) gets a rational
   basis ``V`` from the reduced row echelon form; ``A_u = (V'V)⁻¹ V' A V`` (exact: ``N`` is
   A-invariant, so ``A V = V A_u``);
3. with ``p(x) = det(x I − A_u)`` of degree k, ``s(z) = (−1)^k p(√z) p(−√z)`` has the roots
   ``λ²``, and ``t(z) = w^k s(z / w)`` the roots ``w λ²``;
4. ``w r_σ(A_u)² < 1`` iff ``t`` is Schur stable, decided by the Schur–Cohn reduction: with
   ``|t_0| < |t_k|``, ``t`` is Schur stable iff ``(t_k t(z) − t_0 t*(z)) / z`` is, where ``t*`` is
   ``t`` with reversed coefficients; ``|t_0| ≥ |t_k|`` means the product of the roots has modulus
   ≥ 1, so some root is outside the open disk. Detectability is ``A_u`` Schur stable.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import networkx as nx
import numpy as np
from flint import fmpq_mat
from scipy.linalg import null_space

from theory.consensus.infeasibility import blind_flats
from theory.consensus.operators import nonnegative_radius_below, spectral_radius
from theory.core.exact import (
    exact_decimal,
    fractions_of,
    identity,
    null_basis,
    rational_eigenvalues,
    rational_matrix,
    to_fmpq,
)
from theory.core.observability import RANK_TOL, distinct_values, numeric_rank, observability_matrix
from theory.core.tolerances import EIGEN_TOL, VALUE_TOL
from theory.core.verdicts import all_hold

__all__ = [
    "VALUE_TOL",
    "BlindSet",
    "KalmanSplit",
    "NecessaryConditions",
    "SelfWeightBound",
    "SourceComponent",
    "blind_sets",
    "detectable_exact",
    "exact_unobservable_basis",
    "exact_unobservable_part",
    "necessary_conditions",
    "schur_stable",
    "self_weight_bounds",
    "self_weight_ok_exact",
    "source_components",
    "squared_unobservable_polynomial",
    "unobservable_partition",
    "w_detectability",
]


@dataclass(frozen=True)
class KalmanSplit:
    """Orthogonal Kalman decomposition of ``(A, C)``: ``A_u = V_u' A V_u`` on the unobservable
    subspace, the observability rank (its margin over ``rank_tol``; python-control's rank is the
    cross-check in tests/consensus) and ``‖A V_u − V_u A_u‖ / ‖A‖`` (small iff the subspace is
    A-invariant)."""

    A_u: np.ndarray
    V_u: np.ndarray
    V_o: np.ndarray
    rank: int
    rank_margin: float
    invariance_residual: float


def unobservable_partition(
    A: np.ndarray, C: np.ndarray, *, rank_tol: float = RANK_TOL
) -> KalmanSplit:
    """Kalman decomposition of ``(A, C)``; ``A_u`` is the paper's ``A_iᵘ`` (the similarity
    ``T_i`` of seed 000's proof of Thm 5.2.10; ``p = 0`` leaves everything unobservable)."""
    n = A.shape[0]
    C = np.asarray(C, dtype=float).reshape(-1, n)
    O = observability_matrix(A, C)
    if C.shape[0] == 0 or not np.any(O):
        rank, margin = 0, float("inf")
        V = np.eye(n)
    else:
        result = numeric_rank(O, rank_tol=rank_tol)
        rank, margin = result.rank, result.margin
        V = np.linalg.svd(O)[2].T
    V_o, V_u = V[:, :rank], V[:, rank:]
    A_u = V_u.T @ A @ V_u
    scale = max(float(np.linalg.norm(A, 2)), 1e-300)
    residual = float(np.linalg.norm(A @ V_u - V_u @ A_u, 2)) / scale if V_u.size else 0.0
    return KalmanSplit(A_u, V_u, V_o, rank, float(margin), residual)


@dataclass(frozen=True)
class SelfWeightBound:
    """Thm 5.2.10 item 2 for one agent (1-based): ``w_ii < 1 / r_σ(A_iᵘ)²``, its margin
    ``1 − w_ii r_σ(A_iᵘ)²``, the float verdict (None within ``value_tol``) and the exact one."""

    agent: int
    unobservable_dim: int
    radius: float
    bound: float
    weight: float
    margin: float
    numeric_ok: bool | None
    exact_ok: bool | None = None

    @property
    def ok(self) -> bool | None:
        """The exact verdict when computed, else the numeric one."""
        return self.exact_ok if self.exact_ok is not None else self.numeric_ok


def self_weight_bounds(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    value_tol: float = VALUE_TOL,
    exact: bool = True,
) -> list[SelfWeightBound]:
    """The self-weight bound of Thm 5.2.10 (2) for every agent (Examples 5.3.1: bound 0.25;
    5.3.2: r = 1.7205, bound 0.3378), also decided exactly unless ``exact`` is False."""
    out = []
    for i, Ci in enumerate(C):
        split = unobservable_partition(A, Ci, rank_tol=rank_tol)
        radius = spectral_radius(split.A_u)
        bound = 1.0 / radius**2 if radius > 0 else float("inf")
        margin = 1.0 - W[i, i] * radius**2
        exact_ok = self_weight_ok_exact(A, Ci, float(W[i, i])) if exact else None
        out.append(
            SelfWeightBound(
                i + 1, split.A_u.shape[0], radius, bound, float(W[i, i]), margin,
                _sign(margin, value_tol), exact_ok,
            )
        )  # fmt: skip
    return out


@dataclass(frozen=True)
class SourceComponent:
    """A source component (Def. 5.2.8, 1-based agents), whether ``(A, C_S)`` is detectable
    (decided exactly, Def. 5.2.9) and its float unobservable eigenvalues with ``|λ| ≥ 1 − tol``."""

    agents: tuple[int, ...]
    detectable: bool | None
    unstable_unobservable: tuple[complex, ...]


def source_components(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    value_tol: float = VALUE_TOL,
) -> list[SourceComponent]:
    """Source components and their detectability, sorted by first agent (Thm 5.2.10 (1)).

    A source component is a strongly connected set of agents (paths along ``w_ij > 0``, agent i
    receiving from j) that receives nothing from outside; with ``w_ii > 0`` the common exponent
    ``l`` of Def. 5.2.8 exists.
    """
    graph = nx.DiGraph()
    graph.add_nodes_from(range(W.shape[0]))
    graph.add_edges_from((j, i) for i, j in zip(*np.nonzero(W), strict=True) if i != j)
    condensed = nx.condensation(graph)
    out = []
    for node in condensed.nodes:
        if condensed.in_degree(node) == 0:
            members = sorted(int(m) for m in condensed.nodes[node]["members"])
            C_S = np.vstack(
                [np.asarray(C[i], dtype=float).reshape(-1, A.shape[0]) for i in members]
            )
            verdict, bad = _detectable(A, C_S, rank_tol=rank_tol, value_tol=value_tol)
            out.append(SourceComponent(tuple(i + 1 for i in members), verdict, tuple(bad)))
    return sorted(out, key=lambda s: s.agents[0])


def w_detectability(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    value_tol: float = VALUE_TOL,
) -> list[bool | None]:
    """Whether ``(A, O_i)`` is detectable, per agent, decided exactly (seed 000 eqs.
    (5.19)–(5.20), Lemma 5.2.7; necessary by Lemma 5.2.6)."""
    return [
        _detectable(A, _o_rows_exact(A, C, W, i), rank_tol=rank_tol, value_tol=value_tol)[0]
        for i in range(W.shape[0])
    ]


@dataclass(frozen=True)
class BlindSet:
    """Agents S (1-based) all blind to one eigenvector of A for λ, and the blind-set condition
    ``value = |λ|² r_σ(W_SS) < 1`` (``ok`` None within ``value_tol``)."""

    eigenvalue: complex
    agents: tuple[int, ...]
    radius: float
    value: float
    ok: bool | None


def blind_sets(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    value_tol: float = VALUE_TOL,
    max_flats: int = 10_000,
) -> list[BlindSet]:
    """Every maximal blind set ``S(λ, v)`` and ``|λ|² r_σ(W_SS) < 1``, by decreasing value
    (``docs/theory/s-detectability.md``, Theorem 2).

    For each distinct eigenvalue λ, the eigenspace ``ker(A − λI)`` is intersected with the
    kernels ``ker C_i`` in every way (a breadth-first search over the lattice of flats, at most
    ``max_flats``); each flat F of dimension ≥ 1 gives ``S(F) = {i : C_i F = 0}``.
    """
    n = A.shape[0]
    Cs = [np.asarray(Ci, dtype=complex).reshape(-1, n) for Ci in C]
    scale = max(float(np.linalg.norm(A, 2)), 1.0)
    found: dict[tuple[complex, tuple[int, ...]], BlindSet] = {}
    for lam in distinct_values(np.linalg.eigvals(A), scale=scale):
        if abs(lam) <= EIGEN_TOL * scale:
            continue
        V = _kernel(A - lam * np.eye(n), EIGEN_TOL * scale)
        queue, seen = [V], set()
        while queue:
            F = queue.pop()
            S = tuple(i for i, Ci in enumerate(Cs) if _annihilates(Ci, F, rank_tol))
            if S in seen:
                continue
            seen.add(S)
            if len(seen) > max_flats:
                raise ArithmeticError(f"more than {max_flats} blind sets: raise max_flats")
            if S:
                radius = spectral_radius(W[np.ix_(S, S)])
                value = abs(lam) ** 2 * radius
                found[(complex(np.round(lam, 12)), S)] = BlindSet(
                    complex(lam), tuple(i + 1 for i in S), radius, value,
                    _sign(1 - value, value_tol),
                )  # fmt: skip
            for i, Ci in enumerate(Cs):
                if i not in S:
                    sub = _kernel(Ci @ F, rank_tol * max(np.linalg.norm(Ci), 1e-300))
                    if sub.shape[1] >= 1:
                        queue.append(F @ sub)
    return sorted(_exact_blind_sets(A, C, W, found, scale), key=lambda b: -b.value)


def _exact_blind_sets(
    A: np.ndarray, C: Sequence[np.ndarray], W: np.ndarray, found: dict, scale: float
) -> list[BlindSet]:
    """The float blind sets, those of rational eigenvalues replaced by exact ones: their flats
    over the rationals (:func:`~theory.consensus.infeasibility.blind_flats`) and ``λ² r_σ(W_SS)
    < 1`` decided exactly (no tolerance); irrational eigenvalues keep the float decision."""
    n = A.shape[0]
    A_q, W_q = rational_matrix(A), rational_matrix(W)
    C_q = [rational_matrix(np.asarray(c, float).reshape(-1, n)) if np.size(c) else [] for c in C]
    out = dict(found)
    for lam in rational_eigenvalues(A_q):
        if lam == 0:
            continue
        out = {k: b for k, b in out.items() if abs(k[0] - float(lam)) > EIGEN_TOL * scale}
        for _, S in blind_flats(A_q, C_q, lam):
            M = [[lam * lam * W_q[i][j] for j in S] for i in S]
            radius = spectral_radius(W[np.ix_(S, S)])
            ok = nonnegative_radius_below(M)
            out[(complex(lam), S)] = BlindSet(
                complex(lam), tuple(i + 1 for i in S), radius, float(lam) ** 2 * radius, ok
            )
    return list(out.values())


@dataclass(frozen=True)
class NecessaryConditions:
    """All necessary conditions for one ``(A, C, W)``: ``paper_conditions`` is Thm 5.2.10 items 1
    and 2 together, ``blind_set_condition`` ours (which implies the paper's)."""

    source_components: list[SourceComponent]
    w_detectable: list[bool | None]
    self_weights: list[SelfWeightBound]
    blind_sets: list[BlindSet]
    paper_conditions: bool | None
    blind_set_condition: bool | None
    tolerances: dict[str, float] = field(default_factory=dict)

    def evidence(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "source_components": [
                {
                    "agents": list(s.agents),
                    "detectable": s.detectable,
                    "unstable_unobservable": [complex(x) for x in s.unstable_unobservable],
                }
                for s in self.source_components
            ],
            "w_detectable": list(self.w_detectable),
            "self_weight_bounds": [
                {
                    "agent": b.agent,
                    "w_ii": b.weight,
                    "r_unobservable": b.radius,
                    "bound": b.bound,
                    "margin": b.margin,
                    "numeric_ok": b.numeric_ok,
                    "exact_ok": b.exact_ok,
                    "ok": b.ok,
                }
                for b in self.self_weights
            ],
            "blind_sets": [
                {
                    "eigenvalue": b.eigenvalue,
                    "agents": list(b.agents),
                    "r_W_SS": b.radius,
                    "value": b.value,
                    "ok": b.ok,
                }
                for b in self.blind_sets
            ],
            "paper_conditions": self.paper_conditions,
            "blind_set_condition": self.blind_set_condition,
            "tolerances": dict(self.tolerances),
        }


def necessary_conditions(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    value_tol: float = VALUE_TOL,
) -> NecessaryConditions:
    """Thm 5.2.10's conditions, W-detectability and the blind-set condition (seed 000 Thm 5.2.10;
    ``docs/theory/s-detectability.md``)."""
    kw = {"rank_tol": rank_tol, "value_tol": value_tol}
    sources = source_components(A, C, W, **kw)
    bounds = self_weight_bounds(A, C, W, **kw)
    blind = blind_sets(A, C, W, **kw)
    paper = all_hold([s.detectable for s in sources] + [b.ok for b in bounds])
    ours = all_hold([b.ok for b in blind])
    return NecessaryConditions(
        sources, w_detectability(A, C, W, **kw), bounds, blind, paper, ours, dict(kw)
    )


def _sign(margin: float, tol: float) -> bool | None:
    if margin > tol:
        return True
    return False if margin < -tol else None


def _detectable(
    A: np.ndarray, C: np.ndarray | list, *, rank_tol: float, value_tol: float
) -> tuple[bool, list[complex]]:
    """Detectability decided exactly, with the float unobservable eigenvalues ``|λ| ≥ 1 −
    value_tol`` beside it (informative)."""
    rows = C if isinstance(C, list) else np.asarray(C, dtype=float)
    floats = np.array([[float(x) for x in r] for r in rows]) if isinstance(C, list) else rows
    split = unobservable_partition(A, floats.reshape(-1, A.shape[0]), rank_tol=rank_tol)
    eigs = np.linalg.eigvals(split.A_u) if split.A_u.size else np.zeros(0)
    bad = [complex(x) for x in eigs if abs(x) >= 1 - value_tol]
    return detectable_exact(A, C), bad


def _o_rows_exact(A: np.ndarray, C: Sequence[np.ndarray], W: np.ndarray, agent: int) -> list:
    """Exact rows ``C_j A^k`` with ``w_ij^{(k)} > 0`` spanning the row space of ``O_i``.

    ``O_i(k) = Σ_j w_ij^{(k)} A'^k C_j' C_j A^k`` (proof of Thm 5.2.10), so the null space of
    ``O_i`` is that of these rows. With ``w_ii > 0`` the reachable sets grow with k and settle by
    ``k = N − 1``, so by Cayley–Hamilton ``k < min(n² N, N + n − 1)`` spans the same space as the
    paper's ``k < n² N``.
    """
    n, N = A.shape[0], W.shape[0]
    A_q = to_fmpq(rational_matrix(A))
    reach = np.zeros(N, dtype=bool)
    reach[agent] = True
    power = to_fmpq(identity(n))
    rows: list = []
    for _ in range(min(n * n * N, N + n - 1)):
        for j in np.flatnonzero(reach):
            if np.size(C[j]):
                C_q = to_fmpq(rational_matrix(np.asarray(C[j], dtype=float).reshape(-1, n)))
                rows += fractions_of(C_q * power)
        reach = (reach.astype(int) @ (W > 0).astype(int)) > 0
        power = power * A_q
    return rows


def _kernel(M: np.ndarray, tol: float) -> np.ndarray:
    """An orthonormal basis of the right null space of ``M``: singular values ``≤ tol`` vanish."""
    return null_space(M, rcond=tol / max(float(np.linalg.norm(M, 2)), 1e-300))


def _annihilates(Ci: np.ndarray, F: np.ndarray, rank_tol: float) -> bool:
    if Ci.shape[0] == 0:
        return True
    return float(np.linalg.norm(Ci @ F, 2)) <= rank_tol * max(float(np.linalg.norm(Ci, 2)), 1e-300)


def exact_unobservable_part(A: np.ndarray, C: np.ndarray | list) -> fmpq_mat:
    """``A_u`` of the Kalman decomposition of ``(A, C)``, exact over the rationals (``0 × 0`` if
    observable; exact rows of ``C`` are used as they are)."""
    return exact_unobservable_basis(A, C)[1]


def exact_unobservable_basis(A: np.ndarray, C: np.ndarray | list) -> tuple[list, fmpq_mat]:
    """``(V, A_u)``: a rational basis ``V`` (``n × k`` rows of Fractions) of the unobservable
    subspace ``null O`` (eq. (4.18)) and ``A_u`` with ``A V = V A_u`` exactly (``([], 0 × 0)`` if
    observable)."""
    n = len(A) if isinstance(A, list) else A.shape[0]
    Aq = to_fmpq(rational_matrix(A))
    rows: list[list[Fraction]] = []
    if isinstance(C, list):
        block = C
    else:
        block = rational_matrix(np.asarray(C, dtype=float).reshape(-1, n)) if np.size(C) else []
    power = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    for _ in range(n):
        if block:
            rows.extend(fractions_of(to_fmpq(block) * to_fmpq(power)))
        power = fractions_of(to_fmpq(power) * Aq)
    V = null_basis(rows, n)
    if not V:
        return [], fmpq_mat(0, 0)
    columns = [[V[c][r] for c in range(len(V))] for r in range(n)]
    Vq = to_fmpq(columns)
    Vt = Vq.transpose()
    return columns, (Vt * Vq).solve(Vt * Aq * Vq)


def schur_stable(coefficients: list[Fraction]) -> bool:
    """Whether every root of ``Σ c_j z^j`` (``c_k ≠ 0``) lies in the open unit disk (Schur–Cohn)."""
    c = list(coefficients)
    while len(c) > 1:
        if abs(c[0]) >= abs(c[-1]):
            return False
        lead, const = c[-1], c[0]
        reduced = [lead * a - const * b for a, b in zip(c, reversed(c), strict=True)]
        c = reduced[1:]
    return True


def _charpoly(M: fmpq_mat) -> list[Fraction]:
    return [Fraction(int(x.p), int(x.q)) for x in M.charpoly().coeffs()]  # c_0 … c_k


def squared_unobservable_polynomial(A: np.ndarray, C: np.ndarray | list) -> list[Fraction]:
    """Coefficients ``s_0 … s_k`` of ``s(z) = (−1)^k p(√z) p(−√z)``, whose roots are the squares
    ``λ²`` of the eigenvalues of ``A_u`` (``p`` its characteristic polynomial; ``[1]`` when
    ``(A, C)`` is observable), exact (step 3 of the module docstring)."""
    A_u = exact_unobservable_part(A, C)
    k = A_u.nrows()
    if k == 0:
        return [Fraction(1)]
    p = _charpoly(A_u)
    p_neg = [c * (-1) ** j for j, c in enumerate(p)]
    product = [Fraction(0)] * (2 * k + 1)
    for i, a in enumerate(p):
        for j, b in enumerate(p_neg):
            product[i + j] += a * b
    return [(-1) ** k * product[2 * j] for j in range(k + 1)]


def self_weight_ok_exact(A: np.ndarray, C: np.ndarray, w: float | Fraction) -> bool:
    """``w r_σ(A_u)² < 1`` decided exactly, ``w`` read as the written decimal (seed 000
    Thm 5.2.10 (2); steps 1–4 of the module docstring)."""
    s = squared_unobservable_polynomial(A, C)
    k = len(s) - 1
    if k == 0:
        return True
    wq = exact_decimal(w)
    if wq == 0:
        return True
    return schur_stable([s[j] * wq ** (k - j) for j in range(k + 1)])


def detectable_exact(A: np.ndarray, C: np.ndarray | list) -> bool:
    """Whether ``(A, C)`` is detectable, decided exactly: ``A_u`` is Schur stable, since every
    unobservable eigenvalue is one of ``A_u`` (seed 000 Def. 5.2.9, Thm 5.2.10 (1))."""
    A_u = exact_unobservable_part(A, C)
    return A_u.nrows() == 0 or schur_stable(_charpoly(A_u))
