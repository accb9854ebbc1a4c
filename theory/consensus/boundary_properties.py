"""Never wrong near a threshold (issue 17): seed 000 ch. 5's verdicts swept toward each boundary.

Each property draws parameters ever closer to a known threshold, on both sides and on it
(:func:`theory.strategy_helpers.boundary_values`: ``t(1 ± 10^{-k})``, ``k = 1 … 17``, and
``t``), and asserts that the decision is **correct or inconclusive**. "Correct" is computed here,
independently of the decision procedure, from the closed-form truths of
``docs/theory/s-detectability.md`` (§8) on the data as the decimals it prints as
(``Fraction(repr(x))``), each row of ``W`` projected onto ``Σ_j w_ij = 1`` within its support:

* Example 1 (``A = 2I``, agents 1, 2 with self-weight ``w``): S-detectable iff ``4w < 1``
  (blind-set necessity; the projection gains give ``r_σ(L) = 4w``);
* Example 2 (agent 3 with self-weight ``w``): S-detectable iff ``w (a₁₁ + a₂₁)² < 1`` with
  ``a₁₁ + a₂₁ = 0.8147 + 0.9058 = 1.7205`` the eigenvalue agent 3 is blind to;
* the gains ``[2; 0], [0; 2], 2I`` of Example 1: ``r_σ(L) = r_σ(J) = 4w`` through 1;
* a mode on the unit circle: ``A = diag(λ, 2)``, two agents seeing only the second state,
  ``W = ½·11ᵀ``: S-detectable iff ``|λ| < 1`` (``r_σ(L) = λ²`` with the projection gains).

The scaling property: S-detectability depends on ``(A, C, W)`` only up to a change of state
coordinates (``A → TAT⁻¹``, ``C_i → C_iT⁻¹``, ``Q → TQTᵀ``; unimodular integer ``T``, so the
transformed data are exact), and not at all on the noise scale (``Q, R → cQ, cR``), which only
changes the Riccati gains offered as candidates: decided verdicts must agree.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
from hypothesis import strategies as st

from theory.consensus.exact_radius import gains_stabilize
from theory.consensus.kalman_filter import ch5_examples
from theory.consensus.properties import SmallDkf, dkf_case
from theory.consensus.riccati import coupled_riccati
from theory.consensus.s_detectability import decide_s_detectability
from theory.consensus.strategies import (
    SELF_WEIGHT_THRESHOLDS,
    DkfProblem,
    dkf_problems,
    self_weight_examples,
)
from theory.falsify import Property, register_property
from theory.strategy_helpers import boundary_values

__all__ = [
    "ScaledProblem",
    "SelfWeightPoint",
    "projected_self_weight",
    "scaled_problems",
    "scaling_consistent",
    "self_weight_truth",
    "unit_circle_problem",
]

EXAMPLE_1_GAINS = (np.array([[2.0], [0.0]]), np.array([[0.0], [2.0]]), 2 * np.eye(2))
"""The projection gains ``L_i = A C_i⁺`` of Example 1 (``Γ_1 = diag(0, 2)``, ``Γ_2 = diag(2, 0)``,
``Γ_3 = 0``)."""


@dataclass(frozen=True)
class SelfWeightPoint:
    """One swept self-weight of seed 000 §5.3.

    Attributes
    ----------
    example : str
        ``example 1`` or ``example 2``.
    w : float
        The self-weight written into ``W``
        (:func:`~theory.consensus.strategies.self_weight_examples`).
    """

    example: str
    w: float


def _decimal(x: float) -> Fraction:
    """The decimal a float prints as (its shortest round-trip representation)."""
    return Fraction(repr(float(x)))


def projected_self_weight(point: SelfWeightPoint) -> Fraction:
    """The exact self-weight the certificates are about: the row of ``W`` read as decimals and
    projected onto ``Σ_j w_ij = 1`` within its support (each entry moves by the same amount).

    Parameters
    ----------
    point : SelfWeightPoint

    Returns
    -------
    Fraction
    """
    w = float(point.w)
    if point.example == "example 1":  # row [w, 1 − w, 0]
        row = [_decimal(w), _decimal(1 - w)]
    else:  # row [(1 − w)/2, (1 − w)/2, w]
        row = [_decimal((1 - w) / 2), _decimal((1 - w) / 2), _decimal(w)]
    return _decimal(w) + (1 - sum(row)) / len(row)


def self_weight_truth(point: SelfWeightPoint) -> bool:
    """Whether the swept ``point`` is S-detectable: ``λ² w < 1`` for the eigenvalue λ the agent
    is blind to (2 in Example 1; ``0.8147 + 0.9058`` in Example 2, read from the printed ``A``)."""
    if point.example == "example 1":
        lam = Fraction(2)
    else:
        A = ch5_examples()["example 2"]["A"]
        lam = _decimal(A[0][0]) + _decimal(A[1][0])
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
        gains_stabilize(A, C, W, EXAMPLE_1_GAINS, order=order) in (truth, None)
        for order in ("consensus-then-filter", "filter-then-consensus")
    )


def unit_circle_problem(lam: float) -> SmallDkf:
    """``A = diag(λ, 2)``, ``C_1 = C_2 = [0 1]``, ``W = ½·11ᵀ``: S-detectable iff ``|λ| < 1``.

    Parameters
    ----------
    lam : float
        The mode both agents are blind to.
    """
    C = np.array([[0.0, 1.0]])
    return SmallDkf(np.diag([lam, 2.0]), (C, C.copy()), np.full((2, 2), 0.5))


def _unit_circle_sound(lam: float) -> bool:
    problem = unit_circle_problem(lam)
    verdict = decide_s_detectability(problem.A, list(problem.C), problem.W).verdict
    return verdict in (abs(_decimal(lam)) < 1, None)


@dataclass(frozen=True, eq=False)
class ScaledProblem:
    """A problem, a noise scale and a change of state coordinates.

    Attributes
    ----------
    problem : DkfProblem
        Integer data (:func:`~theory.consensus.strategies.dkf_problems` with ``integer_data``).
    c : float
        Positive factor applied to ``Q`` and every ``R_i``.
    T : ndarray of int, shape (n, n)
        Unimodular (``det T = ±1``), so ``TAT⁻¹`` and ``C_iT⁻¹`` are integer.
    """

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


def _verdict(A: np.ndarray, C: list, W: np.ndarray, Q: np.ndarray, R: list) -> bool | None:
    """The decision with the Riccati gains of ``(Q, R)`` offered as candidates (as a case's)."""
    n = A.shape[0]
    run = coupled_riccati(A, C, W, Q, R, 10 * np.eye(n), max_iter=30, fixed_steps=True)
    candidates = [("the Riccati iteration's gains", run.gains)] if run.gains else []
    return decide_s_detectability(A, C, W, candidate_gains=candidates).verdict


def scaling_consistent(example: ScaledProblem) -> bool:
    """Whether the base, noise-scaled and coordinate-changed problems never get contradicting
    decided verdicts.

    Parameters
    ----------
    example : ScaledProblem

    Returns
    -------
    bool
    """
    p, c, T = example.problem, example.c, example.T
    n = p.A.shape[0]
    Ti = np.rint(np.linalg.inv(T)).astype(int)
    if not (T @ Ti == np.eye(n, dtype=int)).all():
        raise ValueError(f"T = {T.tolist()} is not unimodular")
    C = list(p.C)
    R = [np.eye(ci.shape[0]) for ci in C]
    verdicts = [
        _verdict(p.A, C, p.W, np.eye(n), R),
        _verdict(p.A, C, p.W, c * np.eye(n), [c * r for r in R]),
        _verdict(T @ p.A @ Ti, [ci @ Ti for ci in C], p.W, (T @ T.T).astype(float), R),
    ]
    return len({v for v in verdicts if v is not None}) <= 1


_ROWS = (
    (
        "seed000.def5.2.4.boundary/corrected",
        "seed000.def5.2.4",
        "Swept toward the self-weight thresholds of seed 000 Examples 1 and 2 (1/4 and "
        "1/1.7205²) from both sides and onto them, the S-detectability decision is correct or "
        "inconclusive, never wrong.",
        _self_weight_points(),
        _decision_sound,
        _self_weight_case,
    ),
    (
        "seed000.lem5.2.2.boundary/corrected",
        "seed000.lem5.2.2",
        "With Example 1's projection gains r_σ(L) = r_σ(J) = 4w; swept through r_σ = 1, the "
        "decision 'r_σ < 1' is correct or inconclusive for both orders.",
        boundary_values(Fraction(1, 4), max_exponent=16).map(
            lambda w: SelfWeightPoint("example 1", w)
        ),
        _radius_sound,
        _self_weight_case,
    ),
    (
        "seed000.def5.2.4.unit-circle/corrected",
        "seed000.def5.2.4",
        "A mode both agents are blind to, swept through the unit circle (λ → ±1): "
        "S-detectable iff |λ| < 1, decided correctly or inconclusive.",
        st.tuples(st.sampled_from([-1, 1]), boundary_values(Fraction(1))).map(
            lambda t: t[0] * t[1]
        ),
        _unit_circle_sound,
        lambda lam: dkf_case(unit_circle_problem(lam)),
    ),
    (
        "seed000.def5.2.4.scaling/corrected",
        "seed000.def5.2.4",
        "Scaling Q and R by c > 0, or changing state coordinates (A → TAT⁻¹, C_i → C_iT⁻¹, "
        "Q → TQTᵀ), never changes a decided S-detectability verdict.",
        scaled_problems(),
        scaling_consistent,
        lambda example: dkf_case(example.problem),
    ),
)

PROPERTIES = tuple(
    Property(id=i, claim=c, wording="corrected", statement=s, examples=e, holds=h, to_case=t)
    for i, c, s, e, h, t in _ROWS
)
"""The registered properties (corrected wordings, expected to hold)."""

for _prop in PROPERTIES:
    register_property(_prop)
