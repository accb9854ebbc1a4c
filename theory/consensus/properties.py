"""Falsifiable wordings of seed 000 ch. 5's claims (for ``trackcert falsify``).

**Detectability.** Small consensus-filter problems drawn structurally (integer entries, so
hypothesis shrinks them to the smallest counterexample): ``n ≤ 2`` states, ``N ≤ 3`` agents,
``A`` with entries in {−3, …, 3}, each ``C_i`` with 0 or 1 row of entries in {−1, 0, 1}, ``W``
from integer weights 1–4 on a random support with a positive diagonal, normalised by rows.
Verdicts come from the exact decision of :mod:`theory.consensus.s_detectability`; an
inconclusive decision is never a counterexample.

**Never wrong near a threshold** (issue 17). Parameters drawn ever closer to a known threshold,
on both sides and on it (:func:`theory.strategy_helpers.boundary_values`), and the decision must
be **correct or inconclusive**. "Correct" is computed here, independently of the decision
procedure, from the closed-form truths of ``docs/theory/s-detectability.md`` (§8) on the data as
the decimals it prints as, each row of ``W`` projected onto ``Σ_j w_ij = 1`` within its support:

* Example 1 (``A = 2I``, agents 1, 2 with self-weight ``w``): S-detectable iff ``4w < 1``
  (blind-set necessity; the projection gains give ``r_σ(L) = 4w``);
* Example 2 (agent 3 with self-weight ``w``): S-detectable iff ``w (a₁₁ + a₂₁)² < 1`` with
  ``a₁₁ + a₂₁ = 0.8147 + 0.9058 = 1.7205`` the eigenvalue agent 3 is blind to;
* the gains ``[2; 0], [0; 2], 2I`` of Example 1: ``r_σ(L) = r_σ(J) = 4w`` through 1;
* a mode on the unit circle: ``A = diag(λ, 2)``, two agents seeing only the second state,
  ``W = ½·11ᵀ``: S-detectable iff ``|λ| < 1`` (``r_σ(L) = λ²`` with the projection gains).

S-detectability depends on ``(A, C, W)`` only up to a change of state coordinates (``A → TAT⁻¹``,
``C_i → C_iT⁻¹``, ``Q → TQTᵀ``; unimodular integer ``T``, so the transformed data are exact), and
not at all on the noise scale (``Q, R → cQ, cR``), which only changes the Riccati gains offered as
candidates: decided verdicts must agree.

**Riccati agreement** (proofs in ``docs/theory/s-detectability.md``, "Riccati agreement"), for
``Q ≻ 0``, ``R_i ≻ 0`` and either order (operator ``T`` = L or J):

* *S-detectable ⇒ bounded from every P0 ⪰ 0.* For the gains ``L`` of the exact certificate
  (``r_σ(T) < 1``), the Riccati iterates stay below the fixed-gain bound of Lemma 5.2.3,
  ``P(k) ⪯ P^L(k)`` (:func:`~theory.consensus.riccati.bound_iteration`, ``P^L(0) = P(0)``): the
  Riccati map is the minimum over gains of the affine maps and is monotone. ``P^L(k)`` converges
  because ``r_σ(T) < 1``, so ``P(k)`` is bounded; from ``P0 = 0`` it is non-decreasing, hence
  convergent.
* *Not S-detectable ⇒ unbounded from every P0 ⪰ 0.* From ``P0 = 0`` the iterates are
  non-decreasing; were they bounded they would converge to ``P* = Ric(E(P*)) ⪰ Q`` whose gains
  ``L*`` satisfy ``P* − T*(P*) ⪰ Q ≻ 0``, i.e. ``r_σ(T*) < 1`` — a contradiction. So they are
  unbounded, and by monotonicity in ``P0`` so is every other start. Every gain the iteration
  produces has ``r_σ ≥ 1``.

Footnote 5's "S-detectable iff the coupled Riccati iteration converges" is thus right about
boundedness in both directions. The property checks the finite, falsifiable parts on random
problems: domination ``P(k) ⪯ P^L(k)`` over a horizon from a random ``P0 ⪰ 0`` (positive
verdicts), monotonicity from 0 and ``r_σ(T_k) ≥ 1``, decided exactly, for the iteration's own
gains (negative verdicts). Inconclusive verdicts are vacuous.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import networkx as nx
import numpy as np
from hypothesis import strategies as st

from proofs_check import check_certificate
from theory.consensus.case import Order, ch5_examples
from theory.consensus.conditions import exact_unobservable_part, necessary_conditions
from theory.consensus.design import exact_system, self_weight_design, self_weight_family_exact
from theory.consensus.operators import J_matrix, closed_loop, float_lyapunov, gains_stabilize
from theory.consensus.riccati import (
    bound_iteration,
    check_averaged_bound,
    check_covariance_bound,
    coupled_riccati,
    coupled_riccati_step,
)
from theory.consensus.s_detectability import decide_s_detectability
from theory.consensus.self_weight_bound import self_weight_threshold
from theory.consensus.strategies import (
    SELF_WEIGHT_THRESHOLDS,
    DkfProblem,
    dkf_problems,
    self_weight_examples,
)
from theory.consensus.suboptimal_gains import (
    bound_step,
    corrected_gap,
    is_psd,
    optimal_gain,
    printed_gap,
    random_instance,
)
from theory.core.claims import FixedInstance, Property
from theory.core.exact import exact_decimal
from theory.core.observability import unobservable_eigenvalues
from theory.core.tolerances import (
    BLOWUP,
    EXACT_DIM,
    PSD_TOL,
    RADIUS_TOL,
    RICCATI_HORIZON,
    UNIT_CIRCLE_TOL,
)
from theory.kinds import parse_case
from theory.strategy_helpers import boundary_values, example_record

__all__ = [
    "FIXED_INSTANCES",
    "PROPERTIES",
    "RICCATI_EXAMPLES",
    "RiccatiAgreement",
    "ScaledProblem",
    "SelfWeightFamily",
    "SelfWeightPoint",
    "SmallDkf",
    "SuboptimalGainStep",
    "averaged_bound_holds",
    "covariance_bound_holds",
    "dkf_case",
    "jointly_detectable",
    "projected_self_weight",
    "riccati_agreement",
    "scaled_problems",
    "scaling_consistent",
    "self_weight_certified",
    "self_weight_families",
    "self_weight_truth",
    "small_dkf_problems",
    "strongly_connected",
    "suboptimal_gain_step",
    "unit_circle_problem",
]


@dataclass(frozen=True, eq=False)
class SmallDkf:
    """``A`` (integer entries), each agent's ``C_i`` (0 or 1 row) and a row-stochastic ``W`` with
    a positive diagonal."""

    A: np.ndarray
    C: tuple[np.ndarray, ...]
    W: np.ndarray


@st.composite
def small_dkf_problems(draw: st.DrawFn) -> SmallDkf:
    """Small integer consensus-filter problems (module docstring)."""
    n = draw(st.integers(1, 2))
    N = draw(st.integers(1, 3))
    entries = st.integers(-3, 3)
    A = np.array([[draw(entries) for _ in range(n)] for _ in range(n)], dtype=float)
    C = []
    for _ in range(N):
        rows = draw(st.integers(0, 1))
        C.append(np.array([[draw(st.integers(-1, 1)) for _ in range(n)] for _ in range(rows)]))
    raw = np.array(
        [
            [draw(st.integers(1, 4)) if i == j else draw(st.integers(0, 4)) for j in range(N)]
            for i in range(N)
        ],
        dtype=float,
    )
    C = [c.reshape(c.shape[0], n).astype(float) for c in C]
    return SmallDkf(A, tuple(C), raw / raw.sum(axis=1, keepdims=True))


def jointly_detectable(problem: SmallDkf) -> bool:
    """Whether ``(A, col(C_1, …, C_N))`` is detectable (PBH, seed 000 §5.2)."""
    stacked = np.vstack(problem.C) if problem.C else np.zeros((0, problem.A.shape[0]))
    lost = unobservable_eigenvalues(problem.A, stacked)
    return all(abs(lam) < 1 - UNIT_CIRCLE_TOL for lam in lost)


def strongly_connected(problem: SmallDkf) -> bool:
    """Whether the support of ``W`` is a strongly connected digraph."""
    graph = nx.from_numpy_array((problem.W > 0).astype(int), create_using=nx.DiGraph)
    return nx.is_strongly_connected(graph)


def dkf_case(problem: SmallDkf | DkfProblem) -> dict[str, Any]:
    """A ready-to-run ``kind: dkf`` case (``Q = I``, ``R_i = I``) reproducing ``problem``."""
    n = problem.A.shape[0]
    return {
        "name": f"falsify-dkf-n{n}-N{len(problem.C)}",
        "source": "trackcert falsify (shrunk counterexample, seed 000 ch. 5)",
        "kind": "dkf",
        "dkf": {
            "A": problem.A.tolist(),
            "C": [c.tolist() for c in problem.C],
            "W": problem.W.tolist(),
            "Q": np.eye(n).tolist(),
            "R": [np.eye(c.shape[0]).tolist() for c in problem.C],
        },
    }


def _verdict(problem: SmallDkf) -> bool | None:
    return decide_s_detectability(problem.A, list(problem.C), problem.W).verdict


def _detectable_implies_s_detectable(problem: SmallDkf) -> bool:
    if not strongly_connected(problem) or not jointly_detectable(problem):
        return True
    return _verdict(problem) is not False


def _necessary(attribute: str) -> Callable[[SmallDkf], bool]:
    def holds(problem: SmallDkf) -> bool:
        if _verdict(problem) is not True:
            return True
        conditions = necessary_conditions(problem.A, list(problem.C), problem.W)
        return getattr(conditions, attribute) is not False

    return holds


EXAMPLE_1_GAINS = (np.array([[2.0], [0.0]]), np.array([[0.0], [2.0]]), 2 * np.eye(2))
"""The projection gains ``L_i = A C_i⁺`` of Example 1 (``Γ_1 = diag(0, 2)``, ``Γ_2 = diag(2, 0)``,
``Γ_3 = 0``)."""


@dataclass(frozen=True)
class SelfWeightPoint:
    """One swept self-weight ``w`` of seed 000 §5.3 (``example 1`` or ``example 2``,
    :func:`~theory.consensus.strategies.self_weight_examples`)."""

    example: str
    w: float


def projected_self_weight(point: SelfWeightPoint) -> Fraction:
    """The exact self-weight the certificates are about: the row of ``W`` read as decimals and
    projected onto ``Σ_j w_ij = 1`` within its support (each entry moves by the same amount)."""
    w = float(point.w)
    if point.example == "example 1":  # row [w, 1 − w, 0]
        row = [exact_decimal(w), exact_decimal(1 - w)]
    else:  # row [(1 − w)/2, (1 − w)/2, w]
        row = [exact_decimal((1 - w) / 2), exact_decimal((1 - w) / 2), exact_decimal(w)]
    return exact_decimal(w) + (1 - sum(row)) / len(row)


def self_weight_truth(point: SelfWeightPoint) -> bool:
    """Whether ``point`` is S-detectable: ``λ² w < 1`` for the eigenvalue λ the agent is blind to
    (2 in Example 1; ``0.8147 + 0.9058`` in Example 2, read from the printed ``A``)."""
    if point.example == "example 1":
        lam = Fraction(2)
    else:
        A = ch5_examples()["example 2"]["A"]
        lam = exact_decimal(float(A[0][0])) + exact_decimal(float(A[1][0]))
    return lam * lam * projected_self_weight(point) < 1


def _self_weight_points(max_exponent: int = 17) -> st.SearchStrategy[SelfWeightPoint]:
    return st.sampled_from(sorted(SELF_WEIGHT_THRESHOLDS)).flatmap(
        lambda ex: boundary_values(SELF_WEIGHT_THRESHOLDS[ex], max_exponent=max_exponent).map(
            lambda w: SelfWeightPoint(ex, w)
        )
    )


def _self_weight_case(point: SelfWeightPoint) -> dict[str, Any]:
    A, C, W = self_weight_examples(point.example, point.w)
    return dkf_case(SmallDkf(A, tuple(C), W))


def _decision_sound(point: SelfWeightPoint) -> bool:
    A, C, W = self_weight_examples(point.example, point.w)
    return decide_s_detectability(A, C, W).verdict in (self_weight_truth(point), None)


def _radius_sound(point: SelfWeightPoint) -> bool:
    A, C, W = self_weight_examples("example 1", point.w)
    truth = 4 * projected_self_weight(SelfWeightPoint("example 1", point.w)) < 1
    return all(
        gains_stabilize(A, C, W, EXAMPLE_1_GAINS, order=order) in (truth, None) for order in Order
    )


def unit_circle_problem(lam: float) -> SmallDkf:
    """``A = diag(λ, 2)``, ``C_1 = C_2 = [0 1]``, ``W = ½·11ᵀ``: S-detectable iff ``|λ| < 1``."""
    C = np.array([[0.0, 1.0]])
    return SmallDkf(np.diag([lam, 2.0]), (C, C.copy()), np.full((2, 2), 0.5))


def _unit_circle_sound(lam: float) -> bool:
    problem = unit_circle_problem(lam)
    verdict = decide_s_detectability(problem.A, list(problem.C), problem.W).verdict
    return verdict in (abs(exact_decimal(lam)) < 1, None)


@dataclass(frozen=True, eq=False)
class ScaledProblem:
    """An integer problem, a factor ``c > 0`` applied to ``Q`` and every ``R_i``, and a unimodular
    integer ``T`` (so ``TAT⁻¹`` and ``C_iT⁻¹`` are integer)."""

    problem: DkfProblem
    c: float
    T: np.ndarray


@st.composite
def _unimodular(draw: st.DrawFn, n: int) -> np.ndarray:
    T = np.eye(n, dtype=int)
    for _ in range(draw(st.integers(0, 3))):
        i, j = draw(st.integers(0, n - 1)), draw(st.integers(0, n - 1))
        if i != j:
            T[i] += draw(st.integers(-2, 2)) * T[j]  # a shear keeps det T = 1
    signs = np.array([draw(st.sampled_from([-1, 1])) for _ in range(n)])
    return signs[:, None] * T[draw(st.permutations(list(range(n))))]


def scaled_problems() -> st.SearchStrategy[ScaledProblem]:
    """Small integer problems with a noise scale in {10⁻³, ½, 3, 10³} and a unimodular ``T``."""
    problems = dkf_problems(max_states=2, max_agents=3, integer_data=True, a_bound=2.0)
    return problems.flatmap(
        lambda p: st.builds(
            ScaledProblem,
            st.just(p),
            st.sampled_from([1e-3, 0.5, 3.0, 1e3]),
            _unimodular(p.A.shape[0]),
        )
    )


def _riccati_verdict(A: np.ndarray, C: list, W: np.ndarray, Q: np.ndarray, R: list) -> bool | None:
    """The decision with the Riccati gains of ``(Q, R)`` offered as candidates (as a case's)."""
    n = A.shape[0]
    run = coupled_riccati(A, C, W, Q, R, 10 * np.eye(n), max_iter=30, fixed_steps=True)
    candidates = [("the Riccati iteration's gains", run.gains)] if run.gains else []
    return decide_s_detectability(A, C, W, candidate_gains=candidates).verdict


def scaling_consistent(example: ScaledProblem) -> bool:
    """Whether the base, noise-scaled and coordinate-changed problems never get contradicting
    decided verdicts."""
    p, c, T = example.problem, example.c, example.T
    n = p.A.shape[0]
    Ti = np.rint(np.linalg.inv(T)).astype(int)
    if not (T @ Ti == np.eye(n, dtype=int)).all():
        raise ValueError(f"T = {T.tolist()} is not unimodular")
    C = list(p.C)
    R = [np.eye(ci.shape[0]) for ci in C]
    verdicts = [
        _riccati_verdict(p.A, C, p.W, np.eye(n), R),
        _riccati_verdict(p.A, C, p.W, c * np.eye(n), [c * r for r in R]),
        _riccati_verdict(T @ p.A @ Ti, [ci @ Ti for ci in C], p.W, (T @ T.T).astype(float), R),
    ]
    return len({v for v in verdicts if v is not None}) <= 1


@dataclass(frozen=True)
class RiccatiAgreement:
    """The exact verdict and whether every checked inequality holds (vacuously when undecided):
    ``worst`` is ``max_k max_i λ_max(P_i(k) − P_i^L(k)) / max(1, ‖P^L(k)‖)`` for a positive
    verdict, ``λ_max(P_i(k) − P_i(k+1)) / max(1, ‖P(k+1)‖)`` for a negative one (both ≤ PSD_TOL),
    and ``stabilizing_steps`` the checked steps (first, middle, last) of a negative verdict whose
    gains nevertheless have ``r_σ < 1`` (must be empty)."""

    verdict: bool | None
    holds: bool
    worst: float
    stabilizing_steps: tuple[int, ...] = ()


def _riccati(
    problem: DkfProblem, Q: np.ndarray, R: list[np.ndarray], P0: np.ndarray, order: Order
) -> tuple[np.ndarray, list]:
    P, gains = [np.asarray(P0, float)], []
    while len(gains) < RICCATI_HORIZON and np.linalg.norm(P[-1], 2, axis=(1, 2)).max() <= BLOWUP:
        g, nxt = coupled_riccati_step(problem.A, problem.C, problem.W, Q, R, P[-1], order=order)
        P.append(nxt)
        gains.append(g)
    return np.array(P), gains


def _excess(upper: np.ndarray, lower: np.ndarray) -> float:
    """``max_k max_i λ_max(lower_i(k) − upper_i(k)) / max(1, ‖upper(k)‖)``."""
    worst = -np.inf
    for U_k, L_k in zip(upper, lower, strict=True):
        scale = max(1.0, float(np.linalg.norm(U_k, 2, axis=(1, 2)).max()))
        gap = L_k - U_k
        top = float(np.linalg.eigvalsh((gap + gap.transpose(0, 2, 1)) / 2).max())
        worst = max(worst, top / scale)
    return worst


def riccati_agreement(
    problem: DkfProblem, *, order: Order | str = Order.CONSENSUS_THEN_FILTER
) -> RiccatiAgreement:
    """Check the Riccati agreement of the module docstring on ``problem`` (``Q = I``, ``R_i = I``;
    its seed draws ``P0``; seed 000 Def. 5.2.4, Lemma 5.2.3, eqs. (5.7)–(5.9), footnote 5)."""
    order = Order(order)
    n, N = problem.A.shape[0], problem.W.shape[0]
    Q, R = np.eye(n), [np.eye(c.shape[0]) for c in problem.C]
    decision = decide_s_detectability(problem.A, problem.C, problem.W, order=order)
    if decision.verdict is None:
        return RiccatiAgreement(None, True, float("nan"))
    if decision.verdict:
        rng = np.random.default_rng(problem.seed)
        F = rng.standard_normal((N, n, n))
        P0 = F @ F.transpose(0, 2, 1)
        P, _ = _riccati(problem, Q, R, P0, order)
        bound = bound_iteration(
            problem.A, problem.C, problem.W, Q, R, decision.gains, P0, order=order,
            steps=len(P) - 1,
        )  # fmt: skip
        worst = _excess(bound, P)
        return RiccatiAgreement(True, worst <= PSD_TOL, worst)
    P, gains = _riccati(problem, Q, R, np.zeros((N, n, n)), order)
    worst = _excess(P[1:], P[:-1])
    stabilizing = ()
    if N * n * n <= EXACT_DIM:
        checked = sorted({1, (len(gains) + 1) // 2, len(gains)})
        stabilizing = tuple(
            k
            for k in checked
            if gains_stabilize(problem.A, problem.C, problem.W, gains[k - 1], order=order)
        )
    return RiccatiAgreement(False, worst <= PSD_TOL and not stabilizing, worst, stabilizing)


WEIGHT_DECADES = 4
"""Decades over which the properties of Lemmas 5.2.3, A.2.1, footnote 5 and the blind-set
condition draw the raw consensus weights: (5.3) allows any positive w_ij on the links, not only
ratios ≤ 10."""
RICCATI_EXAMPLES = dkf_problems(
    max_states=2, max_agents=3, a_bound=2.0, integer_data=True, weight_decades=WEIGHT_DECADES
)
"""Small integer problems, so that exact verdicts (both ways) are common; weights over
:data:`WEIGHT_DECADES` decades (300 draws: 178 S-detectable, 88 not, 34 inconclusive, against
169, 92, 39 with weights in [0.1, 1])."""


@dataclass(frozen=True)
class SuboptimalGainStep:
    """Sizes and seed of one exact App. C.2 step: agent 1 of ``agents`` with ``n`` states, ``p``
    outputs, ``P_j(k) ⪰ P*_j(k)`` (:func:`~theory.consensus.suboptimal_gains.random_instance`)."""

    n: int
    p: int
    agents: int
    seed: int


def suboptimal_gain_step(step: SuboptimalGainStep) -> dict[str, bool]:
    """On the exact instance: the printed identity of App. C.2, the corrected one, and the
    monotonicity ``P(k+1) ⪰ P*(k+1)`` it yields (seed 000 App. C.2, eqs. (5.15), (C.2)–(C.3))."""
    d = random_instance(np.random.default_rng(step.seed), step.n, step.p, step.agents)
    A, C, R, Q, L, Pi, Ps = (d[k] for k in ("A", "C", "R", "Q", "L", "Pi", "Pi_star"))
    gap = bound_step(A, C, R, Q, L, Pi) - bound_step(A, C, R, Q, optimal_gain(A, C, R, Ps), Ps)
    return {
        "printed": -gap == printed_gap(A, C, R, L, Pi, Ps),
        "corrected": gap == corrected_gap(A, C, R, L, Pi, Ps) and is_psd(gap),
    }


def _gain_step_case(step: SuboptimalGainStep) -> dict[str, Any]:
    return example_record("seed000.appC.2", {"instance": "random_instance", **vars(step)})


SUBOPTIMAL_GAIN_STEPS = st.builds(
    SuboptimalGainStep,
    st.integers(1, 3),
    st.integers(1, 2),
    st.integers(1, 4),
    st.integers(0, 2**32 - 1),
)
"""Exact App. C.2 steps of every size drawn (the identity is about one agent's step)."""


def covariance_bound_holds(problem: DkfProblem) -> bool:
    """Lemma 5.2.3 on ``problem`` with its fixed gains ``L``, ``Q = I``, ``R_i = I`` and a random
    ``P0 ⪰ 0`` from its seed: the exact covariances ``Σ(k) ⪯ P(k)`` of (5.15) (seed 000
    Lemma 5.2.3, App. C.1)."""
    n = problem.A.shape[0]
    F = np.random.default_rng(problem.seed).standard_normal((n, n))
    R = [np.eye(c.shape[0]) for c in problem.C]
    check = check_covariance_bound(
        problem.A, problem.C, problem.W, np.eye(n), R, problem.L, F @ F.T, steps=12, samples=4
    )
    return check.holds


def averaged_bound_holds(problem: DkfProblem) -> bool:
    """Lemma A.2.1 with ``M^j = A − L_jC_j`` and ``X`` solving ``X − f_1(M, X) = I``: when ``X ≻ 0``
    and ``r < 1`` (the hypothesis, outside ``radius_tol``), ``f_k(M, P_0) ⪯ α r^k X`` and
    ``P_k ⪯ (α + μ/(1 − r)) X``; vacuously true otherwise (seed 000 eqs. (A.53)–(A.54))."""
    n, N = problem.A.shape[0], problem.W.shape[0]
    M = closed_loop(problem.A, problem.C, problem.L)
    try:
        X = float_lyapunov(J_matrix(problem.W, M), N, n)
    except np.linalg.LinAlgError:
        return True
    if np.linalg.eigvalsh(X).min() <= 0:
        return True
    F = np.random.default_rng(problem.seed).standard_normal((N, n, n))
    U = np.stack([np.eye(n) + Li @ Li.T for Li in problem.L])
    check = check_averaged_bound(problem.W, M, X, F @ F.transpose(0, 2, 1), U, steps=60)
    return check.r >= 1 - RADIUS_TOL or (check.decay_ok and check.bound_ok)


@dataclass(frozen=True, eq=False)
class SelfWeightFamily:
    """Agent 1's self-weight family (row rescaled) of ``problem``, agent 1 blind to an
    A-invariant subspace; ``t ∈ [0, 1]`` picks the sampled points."""

    problem: SmallDkf
    t: Fraction


@st.composite
def self_weight_families(draw: st.DrawFn) -> SelfWeightFamily:
    """``n ≤ 3`` states, ``A`` entries in {−3, …, 3}, agent 1 with one row in {−1, 0, 1} leaving a
    non-nilpotent unobservable part, agent 2 a random row or the identity, ``W`` 2 × 2 from
    integer weights 1–4."""
    n = draw(st.integers(2, 3))
    A = np.array([[draw(st.integers(-3, 3)) for _ in range(n)] for _ in range(n)], dtype=float)
    C_1 = np.array([[draw(st.integers(-1, 1)) for _ in range(n)]], dtype=float)
    seen = draw(st.booleans())
    C_2 = np.eye(n) if seen else np.array([[draw(st.integers(-1, 1)) for _ in range(n)]], float)
    raw = np.array([[draw(st.integers(1, 4)) for _ in range(2)] for _ in range(2)], dtype=float)
    problem = SmallDkf(A, (C_1, C_2), raw / raw.sum(axis=1, keepdims=True))
    return SelfWeightFamily(problem, draw(st.fractions(0, 1)))


def _blind_and_growing(example: SelfWeightFamily) -> bool:
    A_u = exact_unobservable_part(example.problem.A, example.problem.C[0])
    return A_u.nrows() > 0 and any(A_u.charpoly().coeffs()[:-1])


def self_weight_certified(example: SelfWeightFamily) -> bool:
    """The certified Thm 5.2.10 (2) threshold ``u`` of agent 1's self-weight: its
    ``self-weight-necessary-violated`` certificate is VALID, a rational ``w ≥ u`` of the family is
    never decided S-detectable, and when ``trackcert design self-weight`` reports it as the exact
    supremum, ``t · below.w`` is never decided not S-detectable."""
    case = parse_case(dkf_case(example.problem))
    A, C, W = exact_system(case)
    family = self_weight_family_exact(W, [0])
    (offset, factor) = family.entries[(0, 0)]
    threshold = self_weight_threshold(A, C[0], 0, offset, factor)
    if threshold is None:
        return True
    cert = threshold.certificate(A, C, *family.affine(), case.name)
    if cert is None or not check_certificate(cert).valid:
        return False
    u = threshold.interval[1]
    if u <= 1 and decide_s_detectability(A, C, family.at(u + example.t * (1 - u))).verdict:
        return False
    result = self_weight_design(case, agents=[0], width=Fraction(1, 100))
    if result.status != "exact" or "Thm 5.2.10" not in result.condition:
        return True
    inside = decide_s_detectability(A, C, family.at(example.t * result.below.w))
    return inside.verdict is not False


def _property(
    id_: str, statement: str, examples: st.SearchStrategy, holds: Callable, to_case: Callable,
    *, claim: str | None = None, expected_to_hold: bool = True,
) -> Property:  # fmt: skip
    """The property ``<claim>[.<sweep>]/<wording>`` (``claim``: by default before the ``/``)."""
    prefix, wording = id_.split("/")
    return Property(
        id_, claim or prefix, wording, statement, examples, holds, to_case, expected_to_hold
    )


PROPERTIES = (
    _property(
        "seed000.sec5.2.detectability/paper",
        "On a strongly connected network, if (A, col(C_i)) is detectable, the consensus filter "
        "is S-detectable.",
        small_dkf_problems(),
        _detectable_implies_s_detectable,
        dkf_case,
        expected_to_hold=False,
    ),
    _property(
        "seed000.thm5.2.10/paper",
        "Every S-detectable consensus filter satisfies Thm 5.2.10's conditions (necessity).",
        small_dkf_problems(),
        _necessary("paper_conditions"),
        dkf_case,
    ),
    _property(
        "seed000.thm5.2.10/corrected",
        "Every S-detectable consensus filter satisfies the blind-set condition "
        "|λ|²·r(W_SS) < 1 (docs/theory/s-detectability.md, Theorem 4), which implies Thm 5.2.10's.",
        small_dkf_problems(),
        _necessary("blind_set_condition"),
        dkf_case,
    ),
    _property(
        "seed000.def5.2.4.boundary/corrected",
        "Swept toward the self-weight thresholds of seed 000 Examples 1 and 2 (1/4 and "
        "1/1.7205²) from both sides and onto them, the S-detectability decision is correct or "
        "inconclusive, never wrong.",
        _self_weight_points(),
        _decision_sound,
        _self_weight_case,
        claim="seed000.def5.2.4",
    ),
    _property(
        "seed000.lem5.2.2.boundary/corrected",
        "With Example 1's projection gains r_σ(L) = r_σ(J) = 4w; swept through r_σ = 1, the "
        "decision 'r_σ < 1' is correct or inconclusive for both orders.",
        boundary_values(Fraction(1, 4), max_exponent=16).map(
            lambda w: SelfWeightPoint("example 1", w)
        ),
        _radius_sound,
        _self_weight_case,
        claim="seed000.lem5.2.2",
    ),
    _property(
        "seed000.def5.2.4.unit-circle/corrected",
        "A mode both agents are blind to, swept through the unit circle (λ → ±1): "
        "S-detectable iff |λ| < 1, decided correctly or inconclusive.",
        st.tuples(st.sampled_from([-1, 1]), boundary_values(Fraction(1))).map(
            lambda t: t[0] * t[1]
        ),
        _unit_circle_sound,
        lambda lam: dkf_case(unit_circle_problem(lam)),
        claim="seed000.def5.2.4",
    ),
    _property(
        "seed000.def5.2.4.scaling/corrected",
        "Scaling Q and R by c > 0, or changing state coordinates (A → TAT⁻¹, C_i → C_iT⁻¹, "
        "Q → TQTᵀ), never changes a decided S-detectability verdict.",
        scaled_problems(),
        scaling_consistent,
        lambda example: dkf_case(example.problem),
        claim="seed000.def5.2.4",
    ),
    _property(
        "seed000.fn5/corrected",
        "S-detectable ⇒ the coupled Riccati iterates (both orders) stay below the "
        "fixed-gain bound of Lemma 5.2.3 with the certified gains, hence bounded from every "
        "P0 ⪰ 0; not S-detectable ⇒ from P0 = 0 they are non-decreasing and every gain they "
        "produce has r_σ ≥ 1, hence they are unbounded.",
        RICCATI_EXAMPLES,
        lambda problem: all(riccati_agreement(problem, order=o).holds for o in Order),
        dkf_case,
    ),
    _property(
        "seed000.thm5.2.10.blindset/paper",
        "Every S-detectable consensus filter has |λ|² r_σ(W_SS) < 1 for every eigenvalue λ of A "
        "and every set S of agents blind to a common eigenvector (any row-stochastic W on a "
        "directed support; docs/theory/s-detectability.md Theorem 4).",
        RICCATI_EXAMPLES.map(lambda p: SmallDkf(p.A, p.C, p.W)),
        _necessary("blind_set_condition"),
        dkf_case,
    ),
    _property(
        "seed000.thm5.2.10.self-weight/paper",
        "For agent 1's self-weight w (row rescaled) and u = (1/r_σ(A_1ᵘ)²) of Thm 5.2.10 (2), "
        "exact: the self-weight-necessary-violated certificate is valid, no rational w ≥ u is "
        "S-detectable, and points below the design's certified w are not refuted.",
        self_weight_families().filter(_blind_and_growing),
        self_weight_certified,
        lambda example: dkf_case(example.problem),
        claim="seed000.thm5.2.10",
    ),
    _property(
        "seed000.appC.2/paper",
        "P*_i(k+1) − P_i(k+1) = (A − L*_iC_i)E_i(P*(k) − P(k))(A − L*_iC_i)' − (L_i − L*_i)"
        "(R_i + C_iE_i(P(k))C_i')(L_i − L*_i)' for every step with P(k) ⪰ P*(k) (display before "
        "(C.3)).",
        SUBOPTIMAL_GAIN_STEPS,
        lambda step: suboptimal_gain_step(step)["printed"],
        _gain_step_case,
        expected_to_hold=False,
    ),
    _property(
        "seed000.appC.2/corrected",
        "P(k) ⪰ P*(k) ⇒ P(k+1) − P*(k+1) equals the corrected identity of App. C.2 "
        "(docs/errata.md) and is ⪰ 0.",
        SUBOPTIMAL_GAIN_STEPS,
        lambda step: suboptimal_gain_step(step)["corrected"],
        _gain_step_case,
    ),
    _property(
        "seed000.lem5.2.3/paper",
        "With any fixed gains, any row-stochastic W and any P(0) = Σ(0) ⪰ 0, the error "
        "covariances of (5.5) satisfy Σ_i(k) ⪯ P_i(k) of (5.15).",
        dkf_problems(max_states=3, max_agents=4, gain_bound=1.5, weight_decades=WEIGHT_DECADES),
        covariance_bound_holds,
        dkf_case,
    ),
    _property(
        "seed000.lemA.2.1/paper",
        "If X^i ≻ f_1^i(M, X) for some X ≻ 0, then f_k(M, P_0) ⪯ α r^k X → 0 and "
        "P_{k+1} = f_1(M, P_k) + U stays ⪯ (α + μ/(1 − r)) X.",
        dkf_problems(
            max_states=3, max_agents=4, a_bound=1.2, gain_bound=1.0, weight_decades=WEIGHT_DECADES
        ),
        averaged_bound_holds,
        dkf_case,
    ),
)
"""Every falsifiable wording of the domain (ids ``<claim>/<wording>``)."""

FIXED_INSTANCES = (
    FixedInstance(
        "case.expect.dkf",
        "about the expect block one dkf case file states; S-detectability itself is searched as "
        "seed000.def5.2.4",
    ),
    FixedInstance(
        "seed000.counterexample5.2",
        "one printed example (n = 1, N = 2, L = (0.3, −0.25)), itself a counterexample",
    ),
    FixedInstance(
        "seed000.def5.2.4.certified",
        "a certificate of one case; S-detectability is searched as seed000.def5.2.4",
    ),
    FixedInstance("seed000.ex5.1", "the printed Example 1 of §5.3.1 (its W_g, W_c, W_b)"),
    FixedInstance("seed000.ex5.2", "the printed Example 2 of §5.3.2 (its W_g, W_b)"),
    FixedInstance(
        "seed000.sec5.3.sim-examples",
        "simulations of the printed W_g and W_b of §5.3 (Figs 5.2–5.3)",
    ),
)
"""The domain's claims about one fixed instance, with the reason."""
