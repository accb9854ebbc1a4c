"""Thm 4.2.3 on the networked pair (seed 000 §4.2.2, App. B.1; seed 001 Theorem 1): the four
minimal connections of agent 1 in Fig. 4.3, symbolically, and the theorem's claims.

App. B.1 gives each undirected edge ``e = (i, j)``, ``i < j``, a free vector ``λ_e``: agent ``i``
has the row ``[λ_e 0]`` and agent ``j`` the row ``[−λ_e 0]`` (the TDOA rows ``u_i − u_j`` and
``u_j − u_i``). :func:`agent_rank_witness` proves ``rank O_i = 6`` for almost all ``λ, T`` by a
``6 × 6`` minor of ``O_i`` equal to ``c · T³ · det(Λ)²`` (``Λ`` the three edge vectors, ``c`` a
non-zero rational from the powers of ``W``); :func:`fig43_analysis` adds the whole ``O`` at an
exact random point, where the paper's ``rank O = Σ rank O_i`` fails for the stars (a) and (b).

The claims ``seed000.thm4.2.3`` and ``seed000.eq4.36.rank-sum`` are decided on Fig. 4.3 (the
model) and at every step of every ``tdoa`` case (:func:`evaluate_tdoa_step`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

import networkx as nx
import numpy as np
import sympy as sp

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, Status, status_of
from theory.core.errors import CaseError
from theory.core.network import adjacency_from_edges, components, exact_weights
from theory.tdoa.case import rank_tolerances
from theory.tdoa.geometry.directions import DirectionGeometry, analyze_geometry
from theory.tdoa.geometry.exact import exact_direction_rank
from theory.tdoa.model import cv_discrete, tdoa_jacobian
from theory.tdoa.observability.network import (
    NetworkObservability,
    Parametrization,
    analyze_network,
    network_generic_rank,
)
from theory.tdoa.observability.single_agent import GenericReport

__all__ = [
    "FIG43_EDGES",
    "TdoaStep",
    "agent_rank_witness",
    "claims",
    "evaluate_tdoa_step",
    "fig43_analysis",
    "fig43_report",
    "rank_sum_claim",
    "shared_lambda_jacobians",
    "theorem_claim",
]

claims = ClaimSet()

FIG43_EDGES: dict[str, tuple[tuple[int, int], ...]] = {
    "a": ((0, 1), (0, 2), (0, 3)),
    "b": ((0, 1), (1, 2), (1, 3)),
    "c": ((0, 1), (0, 2), (2, 3)),
    "d": ((0, 1), (1, 2), (2, 3)),
}
"""Edges (0-based) of Fig. 4.3 (a)–(d): agent 1 has 3, 1, 2, 1 neighbours."""


def shared_lambda_jacobians(
    edges: Sequence[tuple[int, int]], n_agents: int, dim: int = 3
) -> tuple[list[sp.Matrix], sp.Matrix]:
    """Per-agent ``H_i(λ)`` (rows in edge order) with App. B.1's shared-``λ`` sign structure, and
    the edge vectors ``Λ`` as rows (edge ``t`` in sorted order gets ``λ_{dt+1}, …, λ_{dt+d}``)."""
    ordered = sorted((min(e), max(e)) for e in edges)
    symbols = sp.symbols(f"lambda1:{dim * len(ordered) + 1}")
    Lambda = sp.Matrix(len(ordered), dim, symbols)
    rows: list[list[sp.Matrix]] = [[] for _ in range(n_agents)]
    for t, (i, j) in enumerate(ordered):
        rows[i].append(Lambda.row(t))
        rows[j].append(-Lambda.row(t))
    H = [
        sp.Matrix.vstack(*r).row_join(sp.zeros(len(r), dim)) if r else sp.zeros(0, 2 * dim)
        for r in rows
    ]
    return H, Lambda


def agent_rank_witness(
    edges: Sequence[tuple[int, int]], W: Sequence[Sequence[Fraction]], agent: int, dim: int = 3
) -> dict:
    """A ``2d × 2d`` minor of ``O_agent`` equal to ``c · T^d · det(Λ)²`` with ``c ≠ 0`` rational
    (seed 000 eq. (4.37), Lemma 4.2.2, App. B.1); needs exactly ``dim`` edges (a spanning tree).

    For each edge vector ``λ_e`` the rows ``[W^l]_{m,agent} [±λ_e, lTλ_e]`` of an agent ``m``
    holding it are taken at the two smallest powers ``l`` with ``[W^l]_{m,agent} ≠ 0``. These rows
    are ``S · (I_2 ⊗ Λ)`` with ``S`` free of ``λ``, so the minor is ``det(S) · det(Λ)²`` exactly;
    ``det S`` is computed by sympy and divided by ``T^d``."""
    if len(edges) != dim:
        raise ValueError(f"need exactly {dim} edges (a spanning tree of {dim + 1} agents)")
    T = sp.Symbol("T")
    Wq = sp.Matrix([[sp.Rational(x.numerator, x.denominator) for x in r] for r in W])
    powers = [sp.eye(len(W))]
    for _ in range(2 * dim * len(W)):
        powers.append(powers[-1] * Wq)
    selector, chosen = _witness_rows(powers, sorted((min(e), max(e)) for e in edges), agent, T)
    # The chosen rows are S·(I_2 ⊗ Λ) with S = [E, T·L·E] free of λ, so the minor factors as
    # det(S)·det(Λ)² exactly (block-diagonal I_2 ⊗ Λ).
    c_T = sp.factor(sp.Matrix.vstack(*selector).det())
    ratio = sp.cancel(c_T / T**dim)
    constant = ratio.is_Rational and ratio != 0
    return {
        "rows": chosen,
        "c": str(ratio),
        "minor": f"({c_T})*det(Lambda)**2",
        "rank": 2 * dim if constant else None,
    }


def _witness_rows(
    powers: list[sp.Matrix], ordered: list[tuple[int, int]], agent: int, T: sp.Symbol
) -> tuple[list[sp.Matrix], list[tuple[int, int, int]]]:
    """For each tree edge, the two lowest powers ``W^l`` reaching ``agent`` from its nearer
    end ``m``: the selector rows ``[e_t, l·T·e_t]·[W^l]_{m,agent}`` and their ``(l, m, t)``."""
    selector, chosen = [], []
    for t, (i, j) in enumerate(ordered):
        m = min((i, j), key=lambda k: _distance(ordered, agent, k))
        sign = 1 if m == i else -1
        for l in [l for l in range(len(powers)) if powers[l][m, agent] != 0][:2]:
            unit = sp.zeros(1, len(ordered))
            unit[t] = powers[l][m, agent] * sign
            selector.append(unit.row_join(l * T * unit))
            chosen.append((l, m + 1, t + 1))
    return selector, chosen


def _distance(edges: Sequence[tuple[int, int]], source: int, target: int) -> int:
    try:
        return nx.shortest_path_length(nx.Graph(list(edges)), source, target)
    except (nx.NetworkXNoPath, nx.NodeNotFound):
        return 10**9


def fig43_analysis(case: str, *, rule: str = "metropolis", seed: int = 0) -> dict:
    """Fig. 4.3 case ``a``–``d``: symbolic ``rank O_i``, exact whole ``O`` at a random point,
    detectability at a random numeric instance (seed 000 Fig. 4.3, Thm 4.2.3, App. B.1)."""
    edges = FIG43_EDGES[case]
    adjacency = adjacency_from_edges(4, np.array(edges))
    W = exact_weights(adjacency, rule)
    witnesses = [agent_rank_witness(edges, W, agent) for agent in range(4)]
    exact = network_generic_rank(adjacency, W, parametrization=Parametrization.EDGES, seed=seed)
    rng = np.random.default_rng(seed)
    lam = {e: rng.normal(size=3) for e in edges}
    H = [
        np.array([np.r_[lam[e] if e[0] == i else -lam[e], np.zeros(3)] for e in edges if i in e])
        for i in range(4)
    ]
    W_float = np.array([[float(x) for x in r] for r in W])
    numeric = analyze_network(cv_discrete(1.0, 3)[0], W_float, H)
    return {
        "case": case,
        "rule": rule,
        "witnesses": witnesses,
        "exact": dict(exact.__dict__),
        "agree": [w["rank"] for w in witnesses] == exact.agent_ranks,
        "rank_sum_claim_holds": exact.rank_sum_claim_holds,
        "network_observable": exact.network_rank == exact.n_states,
        "detectable": numeric.detectable,
        "numeric_conclusive": numeric.conclusive,
        "unobservable_eigenvalues": [complex(z) for z in numeric.unobservable_eigenvalues],
    }


WEIGHT_RULES = ("metropolis", "uniform")


def fig43_report(case: str, *, weights: str = "metropolis", seed: int = 0) -> GenericReport:
    """``trackcert generic --fig43``: it holds when the symbolic and exact ranks of every ``O_i``
    agree and the pair is detectable (``CaseError`` for an unknown letter or weight rule)."""
    if case not in FIG43_EDGES:
        raise CaseError("--fig43", f"one of {sorted(FIG43_EDGES)}", case, file="<command line>")
    if weights not in WEIGHT_RULES:
        raise CaseError("--weights", " or ".join(WEIGHT_RULES), weights, file="<command line>")
    result = fig43_analysis(case, rule=weights, seed=seed)
    return GenericReport(result, bool(result["agree"] and result["detectable"]))


@dataclass(frozen=True)
class TdoaStep:
    """One time step of a ``kind: tdoa`` case: the networked pair's verdicts, the weakly
    connected components (0-based), their direction geometry and exact ``dim aff{u_i}``."""

    network: NetworkObservability
    components: list[list[int]]
    geometry: list[DirectionGeometry]
    exact_ranks: list[int]


def evaluate_tdoa_step(case: Case, step: int) -> TdoaStep:
    """Analyse 0-based step ``step`` of a ``kind: tdoa`` case (its tolerances, else defaults)."""
    spec = case.spec
    rank_tol, factor = rank_tolerances(case).values()
    agents, target, hears = spec.agents[step], spec.target[step], spec.hears[step]
    H = [
        tdoa_jacobian(target, agents, i, list(np.flatnonzero(hears[i])))
        for i in range(spec.n_agents)
    ]
    network = analyze_network(
        cv_discrete(spec.T, spec.dim)[0],
        spec.weights[step],
        H,
        rank_tol=rank_tol,
        inconclusive_factor=factor,
    )
    parts = components(hears)
    geometry = [
        analyze_geometry(target, agents[c], rank_tol=rank_tol, inconclusive_factor=factor)
        for c in parts
    ]
    exact = [exact_direction_rank(target.tolist(), agents[c].tolist()) for c in parts]
    return TdoaStep(network, parts, geometry, exact)


def _steps(case: Case) -> list[TdoaStep]:
    return [evaluate_tdoa_step(case, k) for k in range(case.spec.steps)]


@claims.register(
    "seed000.thm4.2.3",
    source="seed 000, Thm 4.2.3, Fig. 4.3 and App. B.1; seed 001, Theorem 1",
    statement="The networked system is observable iff every agent is part of a (sub)network of "
    "at least 4 connected, non-coplanar agents.",
    kinds=("tdoa",),
)
def theorem_claim(case: Case | None, ctx: Context) -> list[ClaimResult]:
    """The theorem on Fig. 4.3 (model) or at every step of a case: observable per the paper's
    condition, or (corrected) detectable iff every component's Jacobian has full rank."""
    if case is None:
        return [_theorem_model()]
    return [_theorem_step(case, k, step) for k, step in enumerate(_steps(case))]


def _theorem_model() -> ClaimResult:
    cases = {c: fig43_analysis(c) for c in "abcd"}
    per_agent = all(r["agree"] and r["exact"]["agent_ranks"] == [6] * 4 for r in cases.values())
    detectable = all(r["detectable"] for r in cases.values())
    observable = {c: r["network_observable"] for c, r in cases.items()}
    only = ", ".join(c for c, o in observable.items() if o)
    evidence = {
        c: {
            "witness_c": [w["c"] for w in r["witnesses"]],
            "agent_ranks": r["exact"]["agent_ranks"],
            "network_rank": r["exact"]["network_rank"],
            "network_observable": r["network_observable"],
            "detectable": r["detectable"],
            "seed": r["exact"]["seed"],
            "error_bound": r["exact"]["error_bound"],
        }
        for c, r in cases.items()
    }
    return ClaimResult(
        Status.CORRECTED if per_agent and detectable else Status.REFUTED,
        Method.EXACT_RANDOM,
        evidence,
        message="Each rank O_i = 6 (symbolic witness minors c·T³·det(Λ)², agreeing with exact "
        f"random evaluation), but the pair is observable only for cases {only}; it is "
        "detectable in all four: the theorem holds for detectability.",
    )


def _theorem_step(case: Case, k: int, step: TdoaStep) -> ClaimResult:
    heuristic_ok = all(g.heuristic_4_noncoplanar for g in step.geometry)
    net = step.network
    geometric = all(
        exact == g.dim for g, exact in zip(step.geometry, step.exact_ranks, strict=True)
    )
    corrected_holds = net.detectable == geometric
    evidence = {
        "step": k + 1,
        "paper_prediction_observable": heuristic_ok,
        "network_rank": net.network_rank,
        "network_observable": net.observable,
        "network_detectable": net.detectable,
        "unobservable_eigenvalues": [[z.real, z.imag] for z in net.unobservable_eigenvalues],
        "agent_ranks": net.agent_ranks,
        "components": [[i + 1 for i in c] for c in step.components],
        "corrected_statement": "detectable iff every component's stacked Jacobian has full rank "
        f"(no cone with apex at the target through its agents): {geometric}; holds: "
        f"{corrected_holds}",
    }
    if not net.conclusive:
        status = Status.INCONCLUSIVE
    elif heuristic_ok == net.observable:
        status = Status.VERIFIED
    else:
        status = Status.CORRECTED if corrected_holds else Status.REFUTED
    return ClaimResult(
        status,
        Method.NUMERIC,
        evidence,
        margin=min(net.margin, net.unit_circle_margin),
        tolerance={**rank_tolerances(case), "unit_circle_tol": net.unit_circle_tol},
        message=f"step {k + 1}: paper predicts observable={heuristic_ok}; the pair is "
        f"observable={net.observable}, detectable={net.detectable}.",
    )


@claims.register(
    "seed000.eq4.36.rank-sum",
    source="seed 000, §4.2.2 after eq. (4.36); seed 001, after eq. (36)",
    statement="From the structure of D_H, rank O = Σ_i rank O_i.",
    kinds=("tdoa",),
)
def rank_sum_claim(case: Case | None, ctx: Context) -> list[ClaimResult]:
    """``rank O = Σ rank O_i`` on Fig. 4.3 (a) (model: the counterexample) or at every step."""
    if case is None:
        counterexample = fig43_analysis("a")["exact"]
        evidence = {
            "counterexample": "Fig. 4.3 (a), Metropolis weights, shared-λ Jacobians",
            **counterexample,
            "T": None,
        }
        return [
            ClaimResult(
                status_of(counterexample["rank_sum_claim_holds"]),
                Method.EXACT_RANDOM,
                evidence,
                margin=counterexample["error_bound"],
                message=f"rank O = {counterexample['network_rank']} but Σ rank O_i = "
                f"{counterexample['rank_sum']} (only rank O ≤ Σ rank O_i holds).",
            )
        ]
    return [_rank_sum_step(case, k, step.network) for k, step in enumerate(_steps(case))]


def _rank_sum_step(case: Case, k: int, net: NetworkObservability) -> ClaimResult:
    evidence = {
        "step": k + 1,
        "network_rank": net.network_rank,
        "agent_ranks": net.agent_ranks,
        "rank_sum": net.rank_sum,
    }
    return ClaimResult(
        status_of(net.rank_sum_claim_holds if net.conclusive else None),
        Method.NUMERIC,
        evidence,
        margin=net.margin,
        tolerance=rank_tolerances(case),
        message=f"step {k + 1}: rank O = {net.network_rank}, Σ rank O_i = {net.rank_sum}.",
    )
