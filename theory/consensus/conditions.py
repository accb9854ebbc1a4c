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
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import control
import networkx as nx
import numpy as np

from theory.consensus.exact_radius import nonnegative_radius_below
from theory.consensus.exact_self_weight import detectable_exact, self_weight_ok_exact
from theory.consensus.infeasibility import blind_flats
from theory.consensus.operators import spectral_radius
from theory.core.exact import (
    fractions_of,
    identity,
    rational_eigenvalues,
    rational_matrix,
    to_fmpq,
)
from theory.core.observability import RANK_TOL, numeric_rank, observability_matrix
from theory.core.tolerances import EIGEN_TOL, VALUE_TOL

__all__ = [
    "VALUE_TOL",
    "BlindSet",
    "KalmanSplit",
    "NecessaryConditions",
    "SelfWeightBound",
    "SourceComponent",
    "blind_sets",
    "necessary_conditions",
    "o_matrix",
    "self_weight_bounds",
    "source_components",
    "unobservable_partition",
    "w_detectability",
]


@dataclass(frozen=True)
class KalmanSplit:
    """Orthogonal Kalman decomposition of ``(A, C)`` into observable and unobservable parts.

    Attributes
    ----------
    A_u : ndarray, shape (n_u, n_u)
        ``V_u' A V_u``, the unobservable partition (``A V_u = V_u A_u``).
    V_u, V_o : ndarray
        Orthonormal bases of the unobservable subspace and its complement.
    rank : int
        Rank of the observability matrix.
    rank_margin : float
        How many times the rank decision clears ``rank_tol``.
    control_rank : int
        The same rank from ``control.obsv`` (python-control), as a cross-check.
    invariance_residual : float
        ``‖A V_u − V_u A_u‖ / ‖A‖`` (small iff the subspace is A-invariant, as it must be).
    """

    A_u: np.ndarray
    V_u: np.ndarray
    V_o: np.ndarray
    rank: int
    rank_margin: float
    control_rank: int
    invariance_residual: float


def unobservable_partition(
    A: np.ndarray, C: np.ndarray, *, rank_tol: float = RANK_TOL
) -> KalmanSplit:
    """Kalman decomposition of ``(A, C)``; ``A_u`` is the paper's ``A_iᵘ`` (Thm 5.2.10 proof).

    Parameters
    ----------
    A : ndarray, shape (n, n)
        System matrix.
    C : ndarray, shape (p, n)
        Measurement matrix (``p = 0`` allowed: everything is unobservable).
    rank_tol : float
        Relative rank tolerance on the observability matrix's singular values.

    Returns
    -------
    KalmanSplit

    References
    ----------
    seed 000, proof of Thm 5.2.10 (the similarity ``T_i``).
    """
    n = A.shape[0]
    C = np.asarray(C, dtype=float).reshape(-1, n)
    O = observability_matrix(A, C)
    if C.shape[0] == 0 or not np.any(O):
        rank, margin, control_rank = 0, float("inf"), 0
        V = np.eye(n)
    else:
        result = numeric_rank(O, rank_tol=rank_tol)
        rank, margin = result.rank, result.margin
        control_rank = numeric_rank(np.asarray(control.obsv(A, C)), rank_tol=rank_tol).rank
        V = np.linalg.svd(O)[2].T
    V_o, V_u = V[:, :rank], V[:, rank:]
    A_u = V_u.T @ A @ V_u
    scale = max(float(np.linalg.norm(A, 2)), 1e-300)
    residual = float(np.linalg.norm(A @ V_u - V_u @ A_u, 2)) / scale if V_u.size else 0.0
    return KalmanSplit(A_u, V_u, V_o, rank, float(margin), control_rank, residual)


@dataclass(frozen=True)
class SelfWeightBound:
    """Thm 5.2.10 item 2 for one agent: ``w_ii < 1 / r_σ(A_iᵘ)²``.

    Attributes
    ----------
    agent : int
        1-based agent id.
    unobservable_dim : int
        Size of ``A_iᵘ``.
    radius : float
        ``r_σ(A_iᵘ)`` (0 if every mode is observable).
    bound : float
        ``1 / r_σ(A_iᵘ)²`` (``inf`` when the radius is 0).
    weight : float
        ``w_ii``.
    margin : float
        ``1 − w_ii r_σ(A_iᵘ)²``.
    numeric_ok : bool or None
        ``margin > value_tol`` → True; ``< −value_tol`` → False; else None.
    exact_ok : bool or None
        The same inequality decided in exact rational arithmetic on the data as written
        (:mod:`theory.consensus.exact_self_weight`); None when not computed.
    """

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
    """The self-weight bound of Thm 5.2.10 item 2 for every agent.

    Parameters
    ----------
    A, C, W : ndarray
        System, measurement matrices, weights.
    rank_tol : float
        Rank tolerance of the Kalman decomposition.
    value_tol : float
        Tolerance on ``1 − w_ii r²`` below which the numeric verdict is inconclusive.
    exact : bool
        Also decide each bound in exact rational arithmetic (the data read as written decimals).

    Returns
    -------
    list of SelfWeightBound

    References
    ----------
    seed 000 Thm 5.2.10 (2); Examples 5.3.1 (bound 0.25) and 5.3.2 (r = 1.7205, bound 0.3378).
    """
    out = []
    for i, Ci in enumerate(C):
        split = unobservable_partition(A, Ci, rank_tol=rank_tol)
        radius = spectral_radius(split.A_u)
        bound = 1.0 / radius**2 if radius > 0 else float("inf")
        margin = 1.0 - W[i, i] * radius**2
        exact_ok = self_weight_ok_exact(A, Ci, float(W[i, i])) if exact else None
        out.append(
            SelfWeightBound(
                i + 1,
                split.A_u.shape[0],
                radius,
                bound,
                float(W[i, i]),
                margin,
                _sign(margin, value_tol),
                exact_ok,
            )
        )
    return out


@dataclass(frozen=True)
class SourceComponent:
    """A source component (Def. 5.2.8) and its detectability (Def. 5.2.9).

    Attributes
    ----------
    agents : tuple of int
        1-based agent ids.
    detectable : bool or None
        Whether ``(A, C_S)`` is detectable, decided exactly (Schur–Cohn on the unobservable part,
        :func:`~theory.consensus.exact_self_weight.detectable_exact`).
    unstable_unobservable : tuple of complex
        Unobservable eigenvalues of ``(A, C_S)`` with ``|λ| ≥ 1 − value_tol``.
    """

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
    """Source components of the network and their detectability (Thm 5.2.10 item 1).

    A source component is a strongly connected set of agents (paths along ``w_ij > 0``, agent i
    receiving from j) that receives nothing from outside; with ``w_ii > 0`` the common exponent
    ``l`` of Def. 5.2.8 exists.

    Parameters
    ----------
    A, C, W : ndarray
        System, measurement matrices, weights.
    rank_tol, value_tol : float
        PBH rank tolerance; tolerance of ``|λ|`` around 1.

    Returns
    -------
    list of SourceComponent
        Sorted by first agent.

    References
    ----------
    seed 000 Def. 5.2.8, Def. 5.2.9, Thm 5.2.10 (1).
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


def o_matrix(A: np.ndarray, C: Sequence[np.ndarray], W: np.ndarray, agent: int) -> np.ndarray:
    """Rows spanning the row space of ``O_i`` (eqs. (5.19)–(5.20)) for 0-based ``agent``.

    ``O_i(k) = Σ_j w_ij^{(k)} A'^k C_j' C_j A^k`` (proof of Thm 5.2.10), so the null space of
    ``O_i`` is that of the rows ``C_j A^k`` with ``w_ij^{(k)} > 0``. Each block is normalised
    (row scaling does not change the null space; it avoids overflow for unstable A). With
    ``w_ii > 0`` the reachable sets grow with k and settle by ``k = N − 1``, so by Cayley–Hamilton
    ``k < min(n² N, N + n − 1)`` spans the same space as the paper's ``k < n² N``.

    Parameters
    ----------
    A, C, W : ndarray
        System, measurement matrices, weights (``w_ii > 0``).
    agent : int
        0-based agent ``i``.

    Returns
    -------
    ndarray, shape (rows, n)
    """
    n, N = A.shape[0], W.shape[0]
    steps = min(n * n * N, N + n - 1)
    reach = np.zeros(N, dtype=bool)
    reach[agent] = True
    power = np.eye(n)
    support = W > 0
    rows = []
    for _ in range(steps):
        for j in np.flatnonzero(reach):
            block = np.asarray(C[j], dtype=float).reshape(-1, n) @ power
            norm = np.linalg.norm(block)
            if norm > 0:
                rows.append(block / norm)
        reach = (reach.astype(int) @ support.astype(int)) > 0
        power = power @ A
        power = power / max(np.linalg.norm(power), 1e-300)
    return np.vstack(rows) if rows else np.zeros((0, n))


def w_detectability(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rank_tol: float = RANK_TOL,
    value_tol: float = VALUE_TOL,
) -> list[bool | None]:
    """Detectability of ``(A, O_i)`` for each agent (Lemma 5.2.7; necessary by Lemma 5.2.6).

    Parameters
    ----------
    A, C, W, rank_tol, value_tol : ndarray, float
        As in :func:`source_components`.

    Returns
    -------
    list of bool or None
        One verdict per agent, decided exactly on the rows ``C_j A^k`` (data as written).

    References
    ----------
    seed 000 eqs. (5.19)–(5.20), Lemmas 5.2.6–5.2.7.
    """
    return [
        _detectable(A, _o_rows_exact(A, C, W, i), rank_tol=rank_tol, value_tol=value_tol)[0]
        for i in range(W.shape[0])
    ]


@dataclass(frozen=True)
class BlindSet:
    """Agents all blind to one eigenvector of A, and the blind-set condition for them.

    Attributes
    ----------
    eigenvalue : complex
        λ.
    agents : tuple of int
        1-based ids of S (every ``C_i`` annihilates a common eigenvector for λ).
    radius : float
        ``r_σ(W_SS)``.
    value : float
        ``|λ|² r_σ(W_SS)`` (must be < 1).
    ok : bool or None
        ``1 − value > value_tol`` → True; ``< −value_tol`` → False; else None.
    """

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
    """Every maximal blind set ``S(λ, v)`` and the condition ``|λ|² r_σ(W_SS) < 1``.

    For each distinct eigenvalue λ, the eigenspace ``V = ker(A − λI)`` is intersected with the
    kernels ``ker C_i`` in every way (a breadth-first search over the lattice of flats); each flat
    F of dimension ≥ 1 gives ``S(F) = {i : C_i F = 0}``.

    Parameters
    ----------
    A, C, W : ndarray
        System, measurement matrices, weights.
    rank_tol : float
        Relative tolerance for null spaces.
    value_tol : float
        Tolerance of ``|λ|² r_σ(W_SS)`` around 1.
    max_flats : int
        Cap on the number of flats explored (raises ``ArithmeticError`` beyond).

    Returns
    -------
    list of BlindSet
        One per distinct (λ, S) with S non-empty, sorted by decreasing value.

    References
    ----------
    docs/theory/s-detectability.md, Theorem 2 (blind-set condition).
    """
    n = A.shape[0]
    Cs = [np.asarray(Ci, dtype=complex).reshape(-1, n) for Ci in C]
    scale = max(float(np.linalg.norm(A, 2)), 1.0)
    found: dict[tuple[complex, tuple[int, ...]], BlindSet] = {}
    for lam in _distinct_eigenvalues(A, scale):
        if abs(lam) <= EIGEN_TOL * scale:
            continue
        V = _null_space(A - lam * np.eye(n), EIGEN_TOL * scale)
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
                key = (complex(np.round(lam, 12)), S)
                radius = spectral_radius(W[np.ix_(S, S)])
                value = abs(lam) ** 2 * radius
                found[key] = BlindSet(
                    complex(lam),
                    tuple(i + 1 for i in S),
                    radius,
                    value,
                    _sign(1 - value, value_tol),
                )
            for i, Ci in enumerate(Cs):
                if i not in S:
                    sub = _null_space(Ci @ F, rank_tol * max(np.linalg.norm(Ci), 1e-300))
                    if sub.shape[1] >= 1:
                        queue.append(F @ sub)
    return sorted(_exact_blind_sets(A, C, W, found, scale), key=lambda b: -b.value)


def _exact_blind_sets(
    A: np.ndarray, C: Sequence[np.ndarray], W: np.ndarray, found: dict, scale: float
) -> list[BlindSet]:
    """The float blind sets, with those of rational eigenvalues replaced by exact ones.

    For a rational eigenvalue λ the flats are computed over the rationals
    (:func:`~theory.consensus.infeasibility.blind_flats`) and ``λ² r_σ(W_SS) < 1`` is decided
    exactly (:func:`~theory.consensus.exact_radius.nonnegative_radius_below`); the verdict then
    has no tolerance. Irrational eigenvalues keep the float decision with ``value_tol``.
    """
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
    """All necessary conditions for one ``(A, C, W)``.

    Attributes
    ----------
    source_components : list of SourceComponent
    w_detectable : list of bool or None
        ``(A, O_i)`` detectable, per agent.
    self_weights : list of SelfWeightBound
    blind_sets : list of BlindSet
    paper_conditions : bool or None
        Thm 5.2.10 items 1 and 2 together.
    blind_set_condition : bool or None
        Our condition (implies the paper's).
    tolerances : dict
    """

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
    """Thm 5.2.10's conditions, W-detectability and the blind-set condition.

    Parameters
    ----------
    A, C, W : ndarray
        System, measurement matrices (zero rows allowed), row-stochastic weights.
    rank_tol : float
        Relative rank tolerance (Kalman decomposition, PBH, null spaces).
    value_tol : float
        Tolerance around each threshold.

    Returns
    -------
    NecessaryConditions

    References
    ----------
    seed 000 Thm 5.2.10; docs/theory/s-detectability.md.
    """
    kw = {"rank_tol": rank_tol, "value_tol": value_tol}
    sources = source_components(A, C, W, **kw)
    bounds = self_weight_bounds(A, C, W, **kw)
    blind = blind_sets(A, C, W, **kw)
    paper = _all([s.detectable for s in sources] + [b.ok for b in bounds])
    ours = _all([b.ok for b in blind])
    return NecessaryConditions(
        sources, w_detectability(A, C, W, **kw), bounds, blind, paper, ours, dict(kw)
    )


def _all(verdicts: list[bool | None]) -> bool | None:
    if any(v is False for v in verdicts):
        return False
    return None if any(v is None for v in verdicts) else True


def _sign(margin: float, tol: float) -> bool | None:
    if margin > tol:
        return True
    return False if margin < -tol else None


def _detectable(
    A: np.ndarray, C: np.ndarray | list, *, rank_tol: float, value_tol: float
) -> tuple[bool, list[complex]]:
    """Detectability decided exactly (:func:`detectable_exact`); the float unobservable
    eigenvalues with ``|λ| ≥ 1 − value_tol`` are reported beside it (informative)."""
    rows = C if isinstance(C, list) else np.asarray(C, dtype=float)
    floats = np.array([[float(x) for x in r] for r in rows]) if isinstance(C, list) else rows
    split = unobservable_partition(A, floats.reshape(-1, A.shape[0]), rank_tol=rank_tol)
    eigs = np.linalg.eigvals(split.A_u) if split.A_u.size else np.zeros(0)
    bad = [complex(x) for x in eigs if abs(x) >= 1 - value_tol]
    return detectable_exact(A, C), bad


def _o_rows_exact(A: np.ndarray, C: Sequence[np.ndarray], W: np.ndarray, agent: int) -> list:
    """Exact rows ``C_j A^k`` with ``w_ij^{(k)} > 0`` spanning ``O_i``'s row space (see
    :func:`o_matrix`; the data read as written decimals)."""
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


def _distinct_eigenvalues(A: np.ndarray, scale: float, rel: float = EIGEN_TOL) -> list[complex]:
    out: list[complex] = []
    for value in np.linalg.eigvals(A):
        if all(abs(value - seen) > rel * scale for seen in out):
            out.append(complex(value))
    return out


def _null_space(M: np.ndarray, tol: float) -> np.ndarray:
    if M.shape[0] == 0:
        return np.eye(M.shape[1], dtype=complex)
    _, s, Vh = np.linalg.svd(M)
    rank = int(np.sum(s > tol))
    return Vh[rank:].conj().T


def _annihilates(Ci: np.ndarray, F: np.ndarray, rank_tol: float) -> bool:
    if Ci.shape[0] == 0:
        return True
    return float(np.linalg.norm(Ci @ F, 2)) <= rank_tol * max(float(np.linalg.norm(Ci, 2)), 1e-300)
