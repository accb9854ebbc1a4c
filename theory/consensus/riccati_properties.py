"""Theory ⇄ simulation for the consensus Kalman filter: S-detectability vs the Riccati iteration.

The true statement (proofs in ``docs/theory/s-detectability.md``, "Riccati agreement"), for
``Q ≻ 0``, ``R_i ≻ 0`` and either filter order (operator ``T`` = L of eq. (5.13) or J of App. C.3):

* **S-detectable ⇒ bounded from every P0 ⪰ 0.** For the gains ``L`` of the exact certificate
  (``r_σ(T) < 1``), the coupled Riccati iterates stay below the fixed-gain bound of Lemma 5.2.3,
  ``P(k) ⪯ P^L(k)`` with ``P^L(k+1) = T(P^L(k)) + U``, ``U_i = Q + L_i R_i L_iᵀ`` (filter then
  consensus: ``E(U)``), ``P^L(0) = P(0)``: the Riccati map is the minimum over gains of the
  affine maps and is monotone. ``P^L(k)`` converges because ``r_σ(T) < 1``, so ``P(k)`` is
  bounded; from ``P0 = 0`` it is non-decreasing, hence convergent.
* **Not S-detectable ⇒ unbounded from every P0 ⪰ 0.** From ``P0 = 0`` the iterates are
  non-decreasing; were they bounded they would converge to ``P* = Ric(E(P*)) ⪰ Q`` whose gains
  ``L*`` satisfy ``P* − T*(P*) ⪰ Q ≻ 0``, i.e. ``r_σ(T*) < 1`` — a contradiction. So they are
  unbounded, and by monotonicity in ``P0`` so is every other start. Every gain the iteration
  produces has ``r_σ ≥ 1``.

The seed's "S-detectable iff the coupled Riccati iteration converges" (footnote 5) is thus right
about boundedness in both directions; convergence is shown from ``P0 = 0``. The property checks
the finite, falsifiable parts on random problems: domination ``P(k) ⪯ P^L(k)`` over a horizon
from a random ``P0 ⪰ 0`` (positive verdicts), monotonicity from 0 and ``r_σ(T_k) ≥ 1``, decided
exactly, for the iteration's own gains (negative verdicts). Inconclusive verdicts are vacuous.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.consensus.case import ORDERS
from theory.consensus.certificates import ORDERS as OPERATOR_OF
from theory.consensus.exact_radius import gains_stabilize
from theory.consensus.operators import E_map, apply_operator, closed_loop
from theory.consensus.properties import dkf_case
from theory.consensus.riccati import coupled_riccati_step
from theory.consensus.s_detectability import decide_s_detectability
from theory.consensus.strategies import DkfProblem, dkf_problems
from theory.core.tolerances import BLOWUP, EXACT_DIM, PSD_TOL, RICCATI_HORIZON
from theory.falsify import Property, register_property

__all__ = [
    "RiccatiAgreement",
    "bound_iteration",
    "riccati_agreement",
]

@dataclass(frozen=True)
class RiccatiAgreement:
    """The outcome of :func:`riccati_agreement` on one problem.

    Attributes
    ----------
    verdict : bool or None
        The exact S-detectability verdict.
    holds : bool
        Whether every checked inequality holds (vacuously True when ``verdict`` is None).
    worst : float
        Positive verdict: ``max_k max_i λ_max(P_i(k) − P_i^L(k)) / max(1, ‖P^L(k)‖)``;
        negative: ``max_k max_i λ_max(P_i(k) − P_i(k+1)) / max(1, ‖P(k+1)‖)`` (both ≤ PSD_TOL).
    stabilizing_steps : tuple of int
        Negative verdict: the checked steps (first, middle, last) whose Riccati gains nevertheless
        have ``r_σ < 1`` (must be empty).
    """

    verdict: bool | None
    holds: bool
    worst: float
    stabilizing_steps: tuple[int, ...] = ()


def bound_iteration(
    A: np.ndarray,
    C: Any,
    W: np.ndarray,
    Q: np.ndarray,
    R: Any,
    gains: Any,
    P0: np.ndarray,
    *,
    order: str,
    steps: int,
) -> np.ndarray:
    """``P^L(k+1) = T(P^L(k)) + U`` with fixed gains (seed 000 Lemma 5.2.3, eq. (5.15)).

    Parameters
    ----------
    A, C, W, Q, R : array_like
        Problem data.
    gains : sequence of ndarray
        Fixed ``L_i``.
    P0 : ndarray, shape (N, n, n)
        ``P^L(0)``.
    order : str
        ``consensus-then-filter`` (``T = L``, ``U_i = Q + L_iR_iL_iᵀ``) or
        ``filter-then-consensus`` (``T = J``, forcing ``E(U)``).
    steps : int
        Horizon.

    Returns
    -------
    ndarray, shape (steps + 1, N, n, n)
    """
    Gamma = closed_loop(A, C, gains)
    U = np.stack([Q + g @ r @ g.T for g, r in zip(gains, R, strict=True)])
    U = U if order == ORDERS[0] else E_map(W, U)
    out = [np.asarray(P0, float)]
    for _ in range(steps):
        out.append(apply_operator(OPERATOR_OF[order], W, Gamma, out[-1]) + U)
    return np.array(out)


def _riccati(problem: DkfProblem, Q, R, P0, order: str) -> tuple[np.ndarray, list]:
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


def riccati_agreement(problem: DkfProblem, *, order: str = ORDERS[0]) -> RiccatiAgreement:
    """Check the module docstring's statement on ``problem`` (``Q = I``, ``R_i = I``).

    Parameters
    ----------
    problem : DkfProblem
        From :func:`theory.consensus.strategies.dkf_problems` (its seed draws ``P0``).
    order : str
        Filter order.

    Returns
    -------
    RiccatiAgreement

    References
    ----------
    seed 000 Def. 5.2.4, Lemma 5.2.3, eqs. (5.7)–(5.9), footnote 5; App. C.3.
    """
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


EXAMPLES = dkf_problems(max_states=2, max_agents=3, a_bound=2.0, integer_data=True)
"""Small integer problems, so that exact verdicts (both ways) are common."""

register_property(
    Property(
        id="seed000.fn5/corrected",
        claim="seed000.fn5",
        wording="corrected",
        statement="S-detectable ⇒ the coupled Riccati iterates (both orders) stay below the "
        "fixed-gain bound of Lemma 5.2.3 with the certified gains, hence bounded from every "
        "P0 ⪰ 0; not S-detectable ⇒ from P0 = 0 they are non-decreasing and every gain they "
        "produce has r_σ ≥ 1, hence they are unbounded.",
        examples=EXAMPLES,
        holds=lambda problem: all(riccati_agreement(problem, order=o).holds for o in ORDERS),
        to_case=dkf_case,
        expected_to_hold=True,
    )
)
