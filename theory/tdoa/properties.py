"""Falsifiable wordings of the TDOA domain's claims about the model (seed 000 ch. 4, App. A; seed
003 Result 3), and the domain's claims about one fixed instance.

Each strategy draws from the class the paper's statement quantifies over:

* **Lemma A.1.1** (App. A, "Let ζ_k be a stochastic process and V_k … with (A.9)–(A.10)"):
  linear processes ``ζ_{k+1} = a ζ_k ± s`` (exact laws, :func:`rademacher_law`) with
  ``V = c ζ²`` and any rational constants ``v̲, v̄, μ > 0``, ``0 < α ≤ 1``; the hypotheses (A.9)
  and (A.10) are checked exactly at every atom, and an example that fails them says nothing.
* **Lemma 4.2.2** ("for a stochastic W with w_ii > 0"): any row-stochastic ``W`` with positive
  diagonal on any directed support (:func:`~theory.tdoa.strategies.stochastic_weights`).
* **Lemma A.1.2** (App. A, the averaged EKF (A.1)–(A.3) of §4.2.2): any undirected network,
  connected or not, with any row-stochastic ``W`` positive exactly on its links and diagonal
  (§4.2.2, the paragraph before eq. (4.26); not only Metropolis weights). The paper wording is
  false; the corrected one weights the norm by the stationary vector of ``W`` (docs/errata.md).
* **Metropolis weights** (§4.2.2): any undirected network, connected or not.
* **Optimal formations** (§4.3.1 after eq. (4.43); seed 003 Result 3, "N ≥ 3 trackers"): every
  formation of ``N ≥ 3`` directions (:func:`~theory.tdoa.strategies.formations`), in general
  position, uniform, unions of uniform ones, and degenerate (collinear, coplanar, repeated).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import numpy as np
from hypothesis import strategies as st
from scipy.linalg import expm

from theory.core.claims import FixedInstance, Property, Wording
from theory.core.network import exact_metropolis_weights
from theory.core.observability import RankResult, numeric_rank
from theory.core.tolerances import BOUND_RTOL, RANK_TOL
from theory.kinds import parse_case
from theory.strategy_helpers import example_record
from theory.tdoa.estimation.scenario import run_tdoa_scenario
from theory.tdoa.estimation.stability import (
    corrected_bound,
    lemma_a12_along,
    printed_bound,
    rademacher_law,
)
from theory.tdoa.geometry.crb import (
    crb_trace,
    optimal_crb_trace,
    platonic_solids,
    range_crb_trace,
)
from theory.tdoa.model import cv_continuous, cv_discrete
from theory.tdoa.observability.weights import path_lemma_failures
from theory.tdoa.observability.window import PERIOD, PINGS, window_observability
from theory.tdoa.strategies import formations, networks, stochastic_weights

__all__ = [
    "FIXED_INSTANCES",
    "PROPERTIES",
    "LinearProcess",
    "frame_deviation",
    "is_platonic",
    "is_uniform_array",
    "lemma_a11_holds",
    "linear_processes",
    "metropolis_conditions",
]

STEPS = 6
"""Steps ``k = 0 … STEPS`` of a process at which (A.11) is checked (``2^k`` atoms at most)."""


@dataclass(frozen=True)
class LinearProcess:
    """``ζ_{k+1} = a ζ_k ± s`` (probability ½ each) from ``ζ_0 = z0``, ``V(ζ) = c ζ²``, and the
    constants ``v̲, v̄, μ, α`` of seed 000 (A.9)–(A.11), all exact."""

    a: Fraction
    s: Fraction
    z0: Fraction
    c: Fraction
    v_min: Fraction
    v_max: Fraction
    mu: Fraction
    alpha: Fraction


def _fractions(low: int, high: int, denominator: int = 4) -> st.SearchStrategy[Fraction]:
    return st.integers(low, high).map(lambda n: Fraction(n, denominator))


def linear_processes() -> st.SearchStrategy[LinearProcess]:
    """Linear processes and constants of Lemma A.1.1 (module docstring); ``α`` and ``μ`` near
    the values (A.10) needs, ``α = 1 − a²`` and ``μ = c s²``, on either side."""

    def build(a: Fraction, s: Fraction, z0: Fraction, c: Fraction, k: tuple) -> LinearProcess:
        low, high, extra_mu, alpha_cut = k
        alpha = min(Fraction(1), max(Fraction(1, 8), (1 - a * a) * alpha_cut))
        return LinearProcess(a, s, z0, c, c * low, c * high, c * s * s + extra_mu, alpha)

    return st.builds(
        build,
        _fractions(-3, 3),
        _fractions(1, 8),
        _fractions(-8, 8),
        _fractions(1, 8),
        st.tuples(_fractions(1, 4), _fractions(4, 8), _fractions(0, 4), _fractions(2, 5)),
    )


def _mean_squares(process: LinearProcess) -> list[tuple[Fraction, dict[Fraction, Fraction]]]:
    laws = [rademacher_law(process.a, process.s, process.z0, k) for k in range(STEPS + 1)]
    return [(sum((p * z * z for z, p in law.items()), Fraction(0)), law) for law in laws]


def _a10_holds(process: LinearProcess, laws: list[dict[Fraction, Fraction]]) -> bool:
    """(A.10) at every atom the process reaches: ``E{V(aζ ± s)} − V(ζ) ≤ μ − α V(ζ)``."""
    a, s, c = process.a, process.s, process.c
    return all(
        c * ((a * z + s) ** 2 + (a * z - s) ** 2) / 2 - c * z * z
        <= process.mu - process.alpha * c * z * z
        for law in laws
        for z in law
    )


def lemma_a11_holds(process: LinearProcess, bound: Callable[..., Fraction]) -> bool:
    """Whether ``E‖ζ_k‖² ≤ bound(k)`` for ``k ≤ STEPS`` when (A.9)–(A.10) hold (vacuously true
    otherwise); seed 000 Lemma A.1.1, eqs. (A.9)–(A.11)."""
    p = process
    if not (0 < p.v_min <= p.c <= p.v_max and p.mu > 0 and 0 < p.alpha <= 1):
        return True  # (A.9) fails for V = c ζ², or the constants are outside the lemma
    moments = _mean_squares(p)
    if not _a10_holds(p, [law for _, law in moments[:-1]]):
        return True
    constants = {"v_min": p.v_min, "v_max": p.v_max, "mu": p.mu, "alpha": p.alpha}
    m0 = moments[0][0]
    return all(m <= bound(k, mean_square_0=m0, **constants) for k, (m, _) in enumerate(moments))


def _process_record(process: LinearProcess) -> dict[str, Any]:
    fields = ("a", "s", "z0", "c", "v_min", "v_max", "mu", "alpha")
    example = {f: str(getattr(process, f)) for f in fields}
    example["process"] = "zeta_{k+1} = a zeta_k ± s (prob. 1/2), V = c zeta^2"
    return example_record("seed000.lemA.1.1", example)


@st.composite
def stochastic_networks(draw: st.DrawFn) -> np.ndarray:
    """Any row-stochastic ``W`` with positive diagonal on a directed or undirected network of
    1–6 agents, connected or not (seed 000 Lemma 4.2.2)."""
    directed = draw(st.booleans())
    hears = draw(networks(min_agents=1, max_agents=6, connected=None, directed=directed))
    return draw(stochastic_weights(hears))


def metropolis_conditions(hears: np.ndarray) -> bool:
    """Whether the exact Metropolis weights of ``hears`` are stochastic and symmetric, with
    ``w_ii > 0`` and ``w_ij > 0`` exactly on the links (seed 000 §4.2.2, before eq. (4.26))."""
    W = exact_metropolis_weights(hears)
    n = len(W)
    pairs = [(i, j) for i in range(n) for j in range(n)]
    return (
        all(sum(row) == 1 for row in W)
        and all(W[i][j] == W[j][i] and W[i][j] >= 0 for i, j in pairs)
        and all(W[i][i] > 0 for i in range(n))
        and all((W[i][j] > 0) == bool(hears[i, j]) for i, j in pairs if i != j)
    )


def _weights_record(claim: str, W: np.ndarray) -> dict[str, Any]:
    return example_record(claim, {"W": np.asarray(W, float).tolist()})


# ------------------------------------------------------------------------- optimal formations
FRAME_TOL = 1e-9
"""Deviation (relative to ``N``) below which a formation is a balanced tight frame; the draws
that reach the bound are exact frames up to rounding, ~1e-15."""


def frame_deviation(directions: np.ndarray, *, tdoa: bool = True) -> float:
    """How far ``directions`` are from reaching the CRB bound, over ``N``: TDOA (eq. (4.43))
    ``max(‖Σ g_i‖, ‖Σ g_ig_iᵀ − (N/d) I‖)``; range (seed 003 Result 3) ``|Σ e^{2iθ_k}|``."""
    n, d = directions.shape
    if not tdoa:
        return float(abs(np.sum(np.exp(2j * np.arctan2(directions[:, 1], directions[:, 0]))))) / n
    frame = np.linalg.norm(directions.T @ directions - n / d * np.eye(d), 2)
    return float(max(np.linalg.norm(directions.sum(axis=0)), frame)) / n


def is_uniform_array(directions: np.ndarray) -> bool:
    """Whether 2-D ``directions`` are a uniform angular array (adjacent angle ``2π/N``)."""
    bearings = np.sort(np.arctan2(directions[:, 1], directions[:, 0]) % (2 * np.pi))
    gaps = np.diff([*bearings, bearings[0] + 2 * np.pi])
    return bool(np.allclose(gaps, 2 * np.pi / len(bearings), atol=1e-9))


def _signature(points: np.ndarray) -> np.ndarray:
    """The sorted inner products of the points: invariant under rotations and relabelling."""
    return np.sort((points @ points.T).ravel())


def is_platonic(directions: np.ndarray) -> bool:
    """Whether 3-D ``directions`` are the vertices of a Platonic solid (equal inner-product
    signature to one of the five, which determines the solid up to rotation)."""
    return any(
        len(v) == len(directions) and np.allclose(_signature(v), _signature(directions), atol=1e-9)
        for v in platonic_solids().values()
    )


def _ratio(directions: np.ndarray, tdoa: bool) -> float:
    n, d = directions.shape
    if tdoa:
        return crb_trace(np.zeros(d), directions) / optimal_crb_trace(n, dim=d)
    return range_crb_trace(directions) / (4 / n)


def _optimal_iff(named: Callable[[np.ndarray], bool], tdoa: bool) -> Callable[[np.ndarray], bool]:
    def holds(directions: np.ndarray) -> bool:
        """The paper's wording: a formation is optimal iff it is the named one."""
        return (abs(_ratio(directions, tdoa) - 1) <= BOUND_RTOL) == named(directions)

    return holds


def _bound_and_frames(tdoa: bool) -> Callable[[np.ndarray], bool]:
    def holds(directions: np.ndarray) -> bool:
        """The corrected wording: the bound holds, and every balanced tight frame attains it."""
        ratio = _ratio(directions, tdoa)
        attained = abs(ratio - 1) <= BOUND_RTOL
        return ratio >= 1 - BOUND_RTOL and (
            frame_deviation(directions, tdoa=tdoa) > FRAME_TOL or attained
        )

    return holds


def _formations(dim: int) -> st.SearchStrategy[np.ndarray]:
    families = ("general", "uniform", "union", "degenerate")
    return st.sampled_from(families).flatmap(lambda f: formations(dim=dim, family=f))


def _formation_record(claim: str) -> Callable[[np.ndarray], dict[str, Any]]:
    return lambda directions: example_record(claim, {"directions": directions.tolist()})


def _formation_properties(
    claim: str, dim: int, named: str, is_named: Callable[[np.ndarray], bool], tdoa: bool
) -> tuple[Property, Property]:
    bound = "tr J⁻¹ ≥ d²σ²/N² (eq. (4.43))" if tdoa else "tr J⁻¹ ≥ 4σ²/N (range)"
    frame = "Σ g_i = 0 and Σ g_ig_iᵀ = (N/d) I" if tdoa else "Σ e^{2iθ_k} = 0"
    examples, record = _formations(dim), _formation_record(claim)
    return (
        Property(
            f"{claim}/paper", claim, Wording.PAPER,
            f"A formation of N ≥ 3 is optimal ({bound} with equality) iff it is {named}.",
            examples, _optimal_iff(is_named, tdoa), record, expected_to_hold=False,
        ),
        Property(
            f"{claim}/corrected", claim, Wording.CORRECTED,
            f"Every formation of N ≥ 3 has {bound}, and every formation with {frame} attains "
            f"it ({named} among them, but not only).",
            examples, _bound_and_frames(tdoa), record,
        ),
    )  # fmt: skip


# ------------------------------------------------------------------ one agent's TDOA rows (§4.2.1)
@dataclass(frozen=True, eq=False)
class SingleAgentRows:
    """An integer ``k × d`` matrix ``Λ`` of one agent's TDOA rows (eqs. (4.17), (4.19)), possibly
    rank-deficient, an integer period ``T ≥ 1`` and a ``2d``-subset of the rows of ``O``."""

    Lambda: np.ndarray
    T: int
    rows: tuple[int, ...]


def single_agent_matrix(Lambda: np.ndarray, T: int) -> flint.fmpz_mat:
    """``O = [H_λ; H_λA; …; H_λA^{2d−1}]`` with ``H_λ = [Λ 0]``, ``A = [[I, TI], [0, I]]``: the
    rows ``[Λ, jTΛ]``, exactly (seed 000 eqs. (4.6), (4.18))."""
    k, d = Lambda.shape
    rows = [
        [*map(int, row), *(j * T * int(x) for x in row)] for j in range(2 * d) for row in Lambda
    ]
    return flint.fmpz_mat(2 * d * k, 2 * d, [x for row in rows for x in row])


def _minor(Lambda: np.ndarray, T: int, rows: tuple[int, ...]) -> int:
    O = single_agent_matrix(Lambda, T)
    n = O.ncols()
    return int(flint.fmpz_mat(n, n, [O[r, c] for r in rows for c in range(n)]).det())


@st.composite
def single_agent_rows(draw: st.DrawFn, *, dim: int, rows: tuple[int, ...]) -> SingleAgentRows:
    """``Λ`` with a row count drawn from ``rows``, entries in {−3, …, 3} (any rank, some rows
    repeated or combined to reach the degenerate ones), ``T`` in 1–4, a row subset of ``O``."""
    k = draw(st.sampled_from(rows))
    entries = st.lists(st.integers(-3, 3), min_size=dim, max_size=dim)
    Lambda = np.array([draw(entries) for _ in range(k)], dtype=int)
    if k > 1 and draw(st.booleans()):
        Lambda[-1] = draw(st.integers(-2, 2)) * Lambda[0] + draw(st.integers(-2, 2)) * Lambda[1 % k]
    subset = draw(
        st.lists(st.integers(0, 2 * dim * k - 1), min_size=2 * dim, max_size=2 * dim, unique=True)
    )
    return SingleAgentRows(Lambda, draw(st.integers(1, 4)), tuple(sorted(subset)))


def minor_scales(example: SingleAgentRows) -> bool:
    """Square ``Λ``: the minor of ``O`` on the chosen rows is ``α T^d det(Λ)²`` with ``α`` that
    minor at ``Λ = I``, ``T = 1`` (seed 000 eq. (4.20); §4.2.1 in the plane)."""
    d = example.Lambda.shape[1]
    alpha = _minor(np.eye(d, dtype=int), 1, example.rows)
    exact_det = int(flint.fmpz_mat(d, d, [int(x) for x in example.Lambda.ravel()]).det())
    return _minor(example.Lambda, example.T, example.rows) == alpha * example.T**d * exact_det**2


def rank_of_o(example: SingleAgentRows) -> tuple[int, int]:
    """``(rank O, rank Λ)`` exactly."""
    k, d = example.Lambda.shape
    Lambda = flint.fmpz_mat(k, d, [int(x) for x in example.Lambda.ravel()])
    return single_agent_matrix(example.Lambda, example.T).rank(), Lambda.rank()


def _rows_record(claim: str) -> Callable[[SingleAgentRows], dict[str, Any]]:
    def record(example: SingleAgentRows) -> dict[str, Any]:
        rank_o, rank_l = rank_of_o(example)
        data = {"Lambda": example.Lambda.tolist(), "T": example.T, "rows_of_O": list(example.rows)}
        return example_record(claim, data | {"rank_O": rank_o, "rank_Lambda": rank_l})

    return record


def _rows_property(
    claim: str, statement: str, dim: int, rows: tuple[int, ...], holds: Callable[..., bool]
) -> Property:
    examples = single_agent_rows(dim=dim, rows=rows)
    return Property(
        f"{claim}/paper", claim, Wording.PAPER, statement, examples, holds, _rows_record(claim)
    )


def _discretization_matches(example: tuple[float, int]) -> bool:
    """``cv_discrete(T)`` against ``exp(F T)`` and ``∫₀ᵀ exp(F s) G ds`` computed independently
    (Van Loan: the exponential of ``[[F, G], [0, 0]] T``), within ``DISCRETIZATION_RTOL``; seed
    000 eqs. (4.1), (4.5)–(4.6)."""
    T, dim = example
    F, G = cv_continuous(dim)
    n, m = F.shape[0], G.shape[1]
    block = np.zeros((n + m, n + m))
    block[:n, :n], block[:n, n:] = F, G
    exact = expm(block * T)
    A, B = cv_discrete(T, dim)
    scale = 1.0 + T * T
    return bool(
        np.abs(A - exact[:n, :n]).max() <= DISCRETIZATION_RTOL * scale
        and np.abs(B - exact[:n, n:]).max() <= DISCRETIZATION_RTOL * scale
    )


DISCRETIZATION_RTOL = 1e-12
"""Relative agreement of two float evaluations of eq. (4.6) (both are a few roundings off)."""


@dataclass(frozen=True, eq=False)
class FewReceivers:
    """2 or 3 static receivers (1 or 2 TDOA rows, centralized) and a constant-velocity target
    (start, velocity), seed 000 §4.2.1 before Def. 4.2.1."""

    receivers: np.ndarray
    start: np.ndarray
    velocity: np.ndarray


@st.composite
def few_receivers(draw: st.DrawFn) -> FewReceivers:
    """Receivers with integer coordinates in [−20, 20]³ (distinct), target start in [−30, 30]³
    and velocity in [−2, 2]³ (zero allowed: a target at rest)."""
    n = draw(st.integers(2, 3))
    point = st.tuples(*[st.integers(-20, 20)] * 3)
    receivers = np.array(draw(st.lists(point, min_size=n, max_size=n, unique=True)), float)
    start = np.array(draw(st.tuples(*[st.integers(-30, 30)] * 3)), float)
    velocity = np.array(draw(st.tuples(*[st.integers(-2, 2)] * 3)), float)
    return FewReceivers(receivers, start, velocity)


def window_ranks(example: FewReceivers) -> tuple[RankResult, int]:
    """Rank of the window matrix ``𝒪_K`` and the largest frozen-pair rank (seed 000 (4.16))."""
    window, frozen = window_observability(
        lambda t: example.receivers, start=example.start, velocity=example.velocity
    )
    return numeric_rank(window, rank_tol=RANK_TOL), frozen


def _meets_a_receiver(example: FewReceivers) -> bool:
    """Whether the target sits on a receiver at a ping (a range is not differentiable there)."""
    path = example.start + np.arange(PINGS)[:, None] * PERIOD * example.velocity
    return bool(np.any(np.all(path[:, None, :] == example.receivers[None], axis=2)))


def _window_paper(example: FewReceivers) -> bool:
    """Fewer than 3 TDOA rows: not localizable even centrally (window rank < 6)."""
    if _meets_a_receiver(example):
        return True
    window, _ = window_ranks(example)
    return not window.conclusive() or window.rank < 6


def _window_corrected(example: FewReceivers) -> bool:
    """Every frozen pair ``(A, H(k))`` with fewer than 3 TDOA rows has rank ≤ 4."""
    if _meets_a_receiver(example):
        return True
    return window_ranks(example)[1] <= 4


def _window_record(example: FewReceivers) -> dict[str, Any]:
    window, frozen = window_ranks(example)
    data = {
        "receivers": example.receivers.tolist(),
        "target_start": example.start.tolist(),
        "target_velocity": example.velocity.tolist(),
        "window_rank": window.rank,
        "frozen_pair_rank_max": frozen,
    }
    return example_record("seed000.eq4.16.window", data)


LEMMA_A12_STEPS = 8
"""Pings of a drawn run checked against (A.24) (each costs a generalized eigenproblem)."""


@st.composite
def averaged_filter_cases(draw: st.DrawFn) -> dict[str, Any]:
    """``kind: tdoa-sim`` cases running the averaged EKF with one averaging per ping (τ = T, the
    setting of App. A) with ping period T in {0.5, 1, 2}: 2–6 agents at integer positions (the
    lemma asks nothing of the number of TDOA rows), any undirected network (connected or
    not) with any row-stochastic W positive exactly on its links and diagonal (the filter
    (A.1)–(A.3) is §4.2.2's, whose W is that class: the paragraph before eq. (4.26)), target
    anywhere in [−25, 25]³, noise levels Q, R and prior P0 over three decades each (seed 000
    Lemma A.1.2, (A.18)–(A.23))."""
    n = draw(st.integers(2, 6))
    point = st.lists(st.integers(-10, 10), min_size=3, max_size=3).filter(any)  # x0 = 0: off it
    agents = draw(st.lists(point, min_size=n, max_size=n, unique_by=tuple))
    hears = draw(networks(min_agents=n, max_agents=n, connected=None))
    weights = draw(stochastic_weights(hears))
    edges = [[i + 1, j + 1] for i in range(n) for j in range(i + 1, n) if hears[i, j]]
    decades = st.sampled_from((0.01, 0.1, 1.0, 10.0))
    period = draw(st.sampled_from((0.5, 1.0, 2.0)))
    block = {
        "agents": agents,
        "target": draw(st.lists(st.integers(-25, 25), min_size=3, max_size=3)),
        "Q": draw(decades), "R": draw(decades), "T": period, "tau": period,
        "P0": draw(st.sampled_from((1.0, 10.0, 100.0))), "x0": [0] * 6, "b": 5,
        "edges": edges, "weights": weights.tolist(), "filter": "averaged",
        "steps": LEMMA_A12_STEPS, "formation": "crown",
    }  # fmt: skip
    return {
        "name": f"falsify-lemA.1.2-{n}-agents",
        "source": "trackcert falsify (seed 000 Lemma A.1.2)",
        "kind": "tdoa-sim",
        "tdoa-sim": block,
    }


def lemma_a12_holds(case: dict[str, Any]) -> bool:
    """(A.24) at every ping of the case's run (seed 0) with ``1 − α`` of (A.35); seed 000
    Lemma A.1.2. A run whose Jacobians are undefined somewhere (an estimate on a receiver:
    non-finite factors) fails (A.20) and says nothing."""
    spec = parse_case(case).spec
    with np.errstate(invalid="ignore", divide="ignore"):
        out = lemma_a12_along(spec, run_tdoa_scenario(spec, np.random.default_rng(0)))
    if not np.all(np.isfinite(out["factors"])):
        return True
    return bool(out["holds"].all())


WEIGHTED_A24_RTOL = 1e-9
"""Rounding allowance on the ``π``-weighted factor of the corrected Lemma A.1.2, which reaches 1
exactly on many draws (the largest float excess over 150 drawn runs was 4e-12)."""


def lemma_a12_weighted_holds(case: dict[str, Any]) -> bool:
    """The corrected Lemma A.1.2 (docs/errata.md): along the case's run (seed 0), with ``π`` the
    stationary vector of ``W``, the ``π``-weighted factor of (A.24) is at most
    ``1 + WEIGHTED_A24_RTOL``. Undefined Jacobians say nothing, as in :func:`lemma_a12_holds`."""
    spec = parse_case(case).spec
    with np.errstate(invalid="ignore", divide="ignore"):
        out = lemma_a12_along(spec, run_tdoa_scenario(spec, np.random.default_rng(0)))
    if not np.all(np.isfinite(out["factors"])):
        return True
    return bool(np.all(out["weighted_factors"] <= 1 + WEIGHTED_A24_RTOL))


PROPERTIES = (
    Property(
        "seed000.lemA.1.1/paper", "seed000.lemA.1.1", Wording.PAPER,
        "(A.9)–(A.10) imply E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² (1 − α)^k + (μ/v̲) Σ_{l=1}^{k−1} (1 − α)^l "
        "for every k ≥ 0 (A.11).",
        linear_processes(), lambda p: lemma_a11_holds(p, printed_bound), _process_record,
        expected_to_hold=False,
    ),
    Property(
        "seed000.lemA.1.1/corrected", "seed000.lemA.1.1", Wording.CORRECTED,
        "(A.9)–(A.10) imply (A.11) with the sum from l = 0: E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² (1 − α)^k "
        "+ (μ/v̲) Σ_{l=0}^{k−1} (1 − α)^l.",
        linear_processes(), lambda p: lemma_a11_holds(p, corrected_bound), _process_record,
    ),
    Property(
        "seed000.lem4.2.2/paper", "seed000.lem4.2.2", Wording.PAPER,
        "For a stochastic W with w_ii > 0, [W^l]_ij > 0 iff a (directed) path of length ≤ l "
        "joins i and j.",
        stochastic_networks(), lambda W: not path_lemma_failures(W, range(len(W) + 1)),
        lambda W: _weights_record("seed000.lem4.2.2", W),
    ),
    Property(
        "seed000.sec4.2.2.metropolis/paper", "seed000.sec4.2.2.metropolis", Wording.PAPER,
        "On every undirected network, Metropolis weights are stochastic and symmetric with "
        "w_ii > 0 and w_ij > 0 exactly on the links.",
        networks(min_agents=1, max_agents=8, connected=None), metropolis_conditions,
        lambda hears: example_record(
            "seed000.sec4.2.2.metropolis", {"hears": np.asarray(hears, int).tolist()}
        ),
    ),
    *_formation_properties("seed003.result3", 2, "the uniform formation", is_uniform_array, False),
    *_formation_properties(
        "seed000.sec4.3.1.uniform-array", 2, "the uniform angular array", is_uniform_array, True
    ),
    *_formation_properties("seed000.sec4.3.1.platonic", 3, "a Platonic solid", is_platonic, True),
    _rows_property(
        "seed000.eq4.20",
        "With 3 TDOA rows every 6×6 minor of O is α·T³·det(Λ)² (α an integer of the minor).",
        3, (3,), minor_scales,
    ),
    _rows_property(
        "seed000.sec4.2.1.planar",
        "In the plane every 4×4 minor of O is 0 with 1 TDOA row and α·T²·det(Λ)² with 2.",
        2, (1, 2),
        lambda e: rank_of_o(e)[0] < 4 if len(e.Lambda) == 1 else minor_scales(e),
    ),
    _rows_property(
        "seed000.sec4.2.1.two-rows",
        "With 1 or 2 TDOA rows every 6×6 minor of O vanishes (rank O < 6), whatever Λ and T.",
        3, (1, 2), lambda e: rank_of_o(e)[0] < 6,
    ),
    _rows_property(
        "seed000.fn2",
        "With more than 3 TDOA rows, rank O = 6 iff rank Λ ≥ 3.",
        3, (4, 5, 6), lambda e: (rank_of_o(e)[0] == 6) == (rank_of_o(e)[1] >= 3),
    ),
    Property(
        "seed000.eq4.16.window/paper", "seed000.eq4.16.window", Wording.PAPER,
        "With fewer than 3 TDOA rows (fewer than 4 receivers) the target cannot be localized "
        "even centrally: the window observability matrix of (4.16) is rank-deficient.",
        few_receivers(), _window_paper, _window_record, expected_to_hold=False,
    ),
    Property(
        "seed000.eq4.16.window/corrected", "seed000.eq4.16.window", Wording.CORRECTED,
        "With fewer than 3 TDOA rows every frozen pair (A, H(k)) is unobservable (rank ≤ 4); "
        "a moving target is localized over a window when the window matrix has rank 6.",
        few_receivers(), _window_corrected, _window_record,
    ),
    Property(
        "seed000.lemA.1.2/paper", "seed000.lemA.1.2", Wording.PAPER,
        "Along the averaged EKF (τ = T), under (A.18)–(A.23), (A.24) holds at every k with α of "
        "(A.35).",
        averaged_filter_cases(), lemma_a12_holds, lambda case: case, expected_to_hold=False,
    ),
    Property(
        "seed000.lemA.1.2/corrected", "seed000.lemA.1.2", Wording.CORRECTED,
        "Along the averaged EKF (τ = T), for every W of §4.2.2's class and π > 0 with πᵀW = πᵀ, "
        "(A.24) holds with 1 − α = 1 in the π-weighted norm Π = diag(π) ⊗ I: (I − K_kH_k)ᵀ"
        "(W⊗A)ᵀ Π P_{k+1}⁻¹ (W⊗A)(I − K_kH_k) ≤ Π P_k⁻¹ (π = 1 when W is doubly stochastic).",
        averaged_filter_cases(), lemma_a12_weighted_holds, lambda case: case,
    ),
    Property(
        "seed000.eq4.6/paper", "seed000.eq4.6", Wording.PAPER,
        "A = exp(F T) and B = ∫₀ᵀ exp(F s) G ds as printed in (4.6), for every T > 0, 2-D and 3-D.",
        st.tuples(st.floats(-3, 3).map(lambda e: float(10.0**e)), st.sampled_from((2, 3))),
        _discretization_matches,
        lambda ex: example_record("seed000.eq4.6", {"T": ex[0], "dim": ex[1]}),
    ),
)  # fmt: skip
"""The domain's new wordings (ids ``<claim>/<wording>``)."""

FIXED_INSTANCES = (
    FixedInstance(
        "case.expect.tdoa",
        "about the expect block one tdoa case file states; the topology claims it observes are "
        "searched as seed000.thm4.2.3",
    ),
    FixedInstance(
        "case.expect.tdoa-sim",
        "about the expect block one tdoa-sim case file states (what trackcert simulate finds)",
    ),
    FixedInstance(
        "seed000.eq4.36.certified",
        "a certificate of one case's generic rank; the rank claim is searched as "
        "seed000.eq4.36.rank-sum",
    ),
    FixedInstance(
        "seed000.sec4.4.b-tradeoff",
        "the trend of Figs 4.9–4.10 on the paper's scenario, a Monte Carlo observation about "
        "that run, not a statement over a class",
    ),
)
"""The domain's claims about one fixed instance, with the reason."""
