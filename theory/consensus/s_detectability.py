"""Deciding S-detectability (seed 000 Def. 5.2.4) by an LMI, with checked witnesses both ways.

The paper gives only necessary conditions (Thm 5.2.10). Here the question "do gains ``L_i`` exist
with ``r_σ(L) < ρ``" (``ρ = 1``: S-detectability) is decided as a linear matrix inequality.

**The inequality.** For a positive operator, ``r_σ(L) = r_σ(L*) < ρ`` iff some ``Y ∈ ℍⁿ⁺`` has
``ρ Y − L*(Y) ≻ 0``, where ``L*_j(Y) = Σ_i w_ij Γ_i' Y_i Γ_i`` is the adjoint of eq. (5.13),
``Γ_i = A − L_i C_i`` (Lemma 5.2.2 applied to L*). With ``G_i = Y_i L_i`` and
``M_i = Y_i A − G_i C_i = Y_i Γ_i`` the gains enter linearly, and with slack matrices ``Z_i``
(``Z_i ≻ M_i' Y_i⁻¹ M_i = Γ_i' Y_i Γ_i`` by a Schur complement) the condition is the strict,
homogeneous LMI system in ``x = (Y, G, Z)``::

    F1_j(x) = Y_j − Σ_i (w_ij/ρ) Z_i ≻ 0                      j = 1..N
    F2_i(x) = [[Z_i, M_i'], [M_i, Y_i]] ≻ 0                    i = 1..N

We solve ``max μ`` subject to ``F(x) ⪰ μ I`` and ``‖x‖_F ≤ 1`` (always feasible and bounded).

**Candidates (floats).** ``L_i = Y_i⁻¹ G_i`` and ``Y``; re-checked without ``Z``: ``Y_j ≻ 0`` and
``ρ Y_j − Σ_i w_ij (A − L_i C_i)' Y_i (A − L_i C_i) ⪰ m · max_i λ_max(Y_i) · I``. The solver's
dual variables, projected onto the PSD cone, give ``ε_cert = ‖F*(Λ, Ψ)‖_F / (Σ tr Λ_j + Σ tr Ψ_i)``
with ``F*(Λ, Ψ) = 0`` meaning::

    R_Z_i = Ψ_i,11 − Σ_j (w_ij/ρ) Λ_j = 0
    R_G_i = −2 Ψ_i,21 C_i'            = 0
    R_Y_i = Λ_i + Ψ_i,22 + A Ψ_i,21' + Ψ_i,21 A' = 0

(``Ψ_i,21`` is the lower-left ``n × n`` block; Theorem of alternatives: the strict system has no
solution iff such multipliers exist, not all zero). ``ε_cert`` bounds the normalised margin; it
proves nothing (seed 000 Example 1 at ``w = 0.249999999`` has ``ε_cert ≈ 9e-9`` and *is*
S-detectable).

**Verdicts rest on exact certificates only.** True when an ``s-detectability`` certificate
passes :mod:`proofs_check` (:func:`theory.consensus.certificates.primal_certificate`: the witness
rounded when ``m ≥ lmi_margin``, or exact Lyapunov tuples for candidate gains); False when an
``s-detectability-infeasible`` certificate does (:mod:`theory.consensus.infeasibility`: exact
Farkas multipliers); None otherwise, with each route's reason. ``docs/theory/s-detectability.md``
§6 lists every audited decision.

**The largest self-weight** keeping S-detectability (seed 000 Examples 5.3.1–5.3.2): for a set of
agents ``a``, ``W(w)`` sets ``w_aa = w`` and rescales agent a's other weights by
``(1 − w)/(1 − w_aa)``; the supremum over ``[0, 1]`` is bisected to width ``weight_tol`` after
checking that ``W(0)`` is S-detectable. Bisection presumes a single threshold; every probe is
returned, and an inconclusive probe stops the search.
"""

from __future__ import annotations

import threading
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import cvxpy as cp
import numpy as np

from theory.consensus.case import Order
from theory.consensus.certificates import (
    Route,
    certificate_gains,
    primal_certificate,
    primal_lyapunov,
)
from theory.consensus.infeasibility import infeasibility_certificate
from theory.consensus.operators import (
    B_matrix,
    L_adjoint_map,
    closed_loop,
    covariance_operator_matrix,
    spectral_radius,
)
from theory.core.exact import Matrix, RationalizationError
from theory.core.tolerances import CERT_TOL, LMI_MARGIN, WEIGHT_TOL

__all__ = [
    "CERT_TOL",
    "LMI_MARGIN",
    "SHARED_PROBLEMS",
    "SOLVER_STATUSES",
    "SOLVER_STATUS_TABLE",
    "LmiCache",
    "LmiSolution",
    "SDetectability",
    "SelfWeightSearch",
    "alternative_residual",
    "decide_s_detectability",
    "lmi_radius",
    "max_self_weight",
    "s_detectability_witness",
    "self_weight_family",
    "witness_margin",
]


SOLVER_STATUSES = (
    "optimal",
    "optimal_inaccurate",
    "infeasible",
    "infeasible_inaccurate",
    "unbounded",
    "unbounded_inaccurate",
    "solver_error",
)
"""Closed vocabulary of solver outcomes."""

SOLVER_STATUS_TABLE: dict[str, str] = {
    cp.OPTIMAL: "optimal",
    cp.OPTIMAL_INACCURATE: "optimal_inaccurate",
    cp.INFEASIBLE: "infeasible",
    cp.INFEASIBLE_INACCURATE: "infeasible_inaccurate",
    cp.UNBOUNDED: "unbounded",
    cp.UNBOUNDED_INACCURATE: "unbounded_inaccurate",
    cp.settings.INFEASIBLE_OR_UNBOUNDED: "solver_error",
    cp.USER_LIMIT: "solver_error",
    cp.SOLVER_ERROR: "solver_error",
}
"""The one table translating cvxpy's statuses (which translate each solver's native codes) into
:data:`SOLVER_STATUSES`; anything not listed, and any solver exception, is ``solver_error``."""


@dataclass(frozen=True, eq=False)
class LmiSolution:
    """What the float LMI gave (informative only): the solver's status and margin ``μ``, the
    candidate gains ``Y_i⁻¹ G_i`` with their dual tuple ``Y``, witness margin ``m`` and radii of
    L, J, B, and the multipliers projected onto the PSD cone with ``ε_cert``."""

    solver: str
    solver_status: str
    rho: float
    mu: float | None = None
    witness_margin: float | None = None
    cert_epsilon: float | None = None
    multipliers: dict[str, np.ndarray] | None = None
    gains: tuple[np.ndarray, ...] | None = None
    Y: np.ndarray | None = None
    radius_L: float | None = None
    radius_J: float | None = None
    radius_B: float | None = None

    @property
    def radius_bound(self) -> float | None:
        """``ρ (1 − m)``, a proven upper bound on ``r_σ(L)`` when ``m > 0``."""
        m = self.witness_margin
        return self.rho * (1 - m) if m is not None and m > 0 else None


@dataclass(frozen=True, eq=False)
class SDetectability:
    """The decision and its evidence.

    ``verdict`` is True when an exact ``s-detectability`` certificate checked, False when an
    ``s-detectability-infeasible`` one did, None otherwise; ``certificate`` is that document and
    ``route`` how it was found. On a positive verdict, ``gains`` are the certificate's, ``X`` the
    float primal tuple of the order's operator with them, and on the LMI route ``Y`` and the
    margin ``m`` of the rounded gains with ``radius_bound = ρ (1 − m)``; otherwise the margin is
    the float LMI's.
    """

    verdict: bool | None
    reason: str
    lmi: LmiSolution
    tolerances: dict[str, float]
    order: Order
    certificate: dict[str, Any] | None = None
    route: str = ""
    gains: tuple[np.ndarray, ...] | None = None
    X: np.ndarray | None = None
    Y: np.ndarray | None = None
    witness_margin: float | None = None
    radius_bound: float | None = None

    def evidence(self) -> dict[str, Any]:
        """JSON-ready summary (no matrices)."""
        lmi = self.lmi
        return {
            "verdict": self.verdict,
            "reason": self.reason,
            "solver": lmi.solver,
            "solver_status": lmi.solver_status,
            "rho": lmi.rho,
            "mu": lmi.mu,
            "witness_margin": self.witness_margin,
            "radius_bound": self.radius_bound,
            "cert_epsilon": lmi.cert_epsilon,
            "candidate_radius_L": lmi.radius_L,
            "candidate_radius_J": lmi.radius_J,
            "candidate_radius_B": lmi.radius_B,
            "certificate_kind": None if self.certificate is None else self.certificate["kind"],
            "certificate_route": self.route,
            "tolerances": dict(self.tolerances),
        }


def decide_s_detectability(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray | Matrix,
    *,
    rho: float = 1.0,
    order: Order | str = Order.CONSENSUS_THEN_FILTER,
    solver: str = "CLARABEL",
    lmi_margin: float = LMI_MARGIN,
    cert_tol: float = CERT_TOL,
    candidate_gains: Sequence[tuple[str, Sequence[np.ndarray]]] = (),
    case: str | None = None,
    problems: LmiCache | None = None,
) -> SDetectability:
    """Decide whether gains ``L_i`` exist with ``r_σ(L) < rho`` (seed 000 Def. 5.2.4, Lemma
    5.2.2, App. C.3; ``r_σ(J) = r_σ(L)``, so the answer holds for both orders).

    Only exact certificates decide (module docstring), whatever the float margins say; a solver
    failure (``solver``: ``CLARABEL`` or ``SCS``) leaves the exact routes. ``order`` is the
    operator of the witness's primal tuple; ``lmi_margin`` the least witness margin worth
    rounding; ``cert_tol`` the ``ε_cert`` at which the float dual is reported as suggesting
    infeasibility; ``candidate_gains`` further labelled gains (the case's, the Riccati
    iteration's) tried with exact Lyapunov tuples; ``case`` is recorded in the certificate.
    ``W`` given as rows of ``Fraction`` is certified as it is (a float ``W`` is read as the
    decimals it prints as); ``problems`` keeps the built LMI for re-solving (:class:`LmiCache`;
    default: this thread's, :data:`SHARED_PROBLEMS` problems).
    """
    order = Order(order)
    A = np.asarray(A, dtype=float)
    exact_W = W if isinstance(W, list) else np.asarray(W, dtype=float)
    W = np.asarray(W, dtype=float)
    C = [np.asarray(Ci, dtype=float).reshape(-1, A.shape[0]) for Ci in C]
    tolerances = {"lmi_margin": lmi_margin, "cert_tol": cert_tol}
    lmi = _solve_lmi(A, C, W, rho, solver, problems)
    margin = float("-inf") if lmi.witness_margin is None else lmi.witness_margin
    witness = (lmi.gains, lmi.Y) if margin >= lmi_margin else None
    floats = [("LMI candidate gains", lmi.gains)] if lmi.gains else []
    found, reasons = primal_certificate(
        A, C, exact_W, order=order, rho=rho, witness=witness,
        candidates=[*floats, *candidate_gains], case=case,
    )  # fmt: skip
    if found is not None:
        gains = certificate_gains(found.document, C)
        X = primal_lyapunov(A, C, W, gains, order)
        Y = m = bound = None
        if found.route is Route.LMI_WITNESS:  # the margin of the rounded gains
            Y, m = lmi.Y, witness_margin(A, C, W, gains, lmi.Y, rho=rho)
            bound = rho * (1 - m)
        reason = f"certificate verified exactly (proofs_check): {found.description}"
        return SDetectability(
            True, reason, lmi, tolerances, order, found.document, found.description,
            gains, X, Y, m, bound,
        )  # fmt: skip
    margins = {"witness_margin": lmi.witness_margin, "radius_bound": lmi.radius_bound}
    try:
        cert = infeasibility_certificate(A, C, exact_W, rho=rho, case=case)
    except RationalizationError as error:
        reasons.append(str(error))
    else:
        route = "Farkas multipliers from the blind set " + str(cert["produced_by"]["agents"])
        reason = f"infeasibility certificate verified exactly (proofs_check): {route}"
        return SDetectability(False, reason, lmi, tolerances, order, cert, route, **margins)
    reason = _inconclusive_reason(lmi.cert_epsilon, reasons, cert_tol)
    return SDetectability(None, reason, lmi, tolerances, order, **margins)


def _inconclusive_reason(hint: float | None, reasons: list[str], cert_tol: float) -> str:
    """Why no exact certificate decided, with the float dual's hint (which proves nothing)."""
    suggests = (
        f"; the float dual suggests infeasibility (ε_cert = {hint:.3g} ≤ cert_tol) but proves "
        "nothing"
        if hint is not None and hint <= cert_tol
        else ""
    )
    return "no exact certificate either way" + suggests + ": " + "; ".join(reasons)


def _solve_lmi(
    A: np.ndarray,
    C: list[np.ndarray],
    W: np.ndarray,
    rho: float,
    solver: str,
    problems: LmiCache | None = None,
) -> LmiSolution:
    """Solve the normalised LMI: its candidate gains, margins and multipliers (floats only)."""
    problem, parts = (_thread_problems() if problems is None else problems).problem(A, C, W, rho)
    try:
        with warnings.catch_warnings():  # inaccuracy is reported through the status table
            warnings.simplefilter("ignore", UserWarning)
            problem.solve(solver=solver, warm_start=False)  # no state kept between solves
        status = SOLVER_STATUS_TABLE.get(problem.status, "solver_error")
    except (cp.error.SolverError, ArithmeticError, ValueError):
        return LmiSolution(solver, "solver_error", rho)
    if status not in ("optimal", "optimal_inaccurate"):
        return LmiSolution(solver, status, rho)
    Y = np.stack([np.asarray(v.value, dtype=float) for v in parts["Y"]])
    try:
        gains = tuple(
            np.linalg.solve(Y[i], np.asarray(g.value, dtype=float).reshape(A.shape[0], -1))
            if g is not None
            else np.zeros((A.shape[0], 0))
            for i, g in enumerate(parts["G"])
        )
        m = witness_margin(A, C, W, gains, Y, rho=rho)
    except np.linalg.LinAlgError:  # a singular Y_i: no witness (the solution is near x = 0)
        gains = tuple(np.zeros((A.shape[0], Ci.shape[0])) for Ci in C)
        m = float("-inf")
    epsilon, multipliers = _certificate_epsilon(A, C, W, rho, parts)
    Gamma = closed_loop(A, C, gains)
    return LmiSolution(
        solver, status, rho, float(parts["mu"].value), m, epsilon, multipliers, gains, Y,
        spectral_radius(covariance_operator_matrix(W, Gamma, Order.CONSENSUS_THEN_FILTER)),
        spectral_radius(covariance_operator_matrix(W, Gamma, Order.FILTER_THEN_CONSENSUS)),
        spectral_radius(B_matrix(W, Gamma)),
    )  # fmt: skip


SHARED_PROBLEMS = 2
"""Problems kept per thread when no :class:`LmiCache` is given."""

_LOCAL = threading.local()


def _thread_problems() -> LmiCache:
    """This thread's :class:`LmiCache` (made on first use)."""
    if not hasattr(_LOCAL, "problems"):
        _LOCAL.problems = LmiCache(limit=SHARED_PROBLEMS)
    return _LOCAL.problems


def lmi_radius(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    solver: str = "CLARABEL",
    problems: LmiCache | None = None,
) -> float:
    """``r_σ(L)`` (float, informative) with the LMI's candidate gains at ``ρ = 1``; ``inf`` when
    the solver gives none (a search objective, never a verdict)."""
    A = np.asarray(A, dtype=float)
    C = [np.asarray(Ci, dtype=float).reshape(-1, A.shape[0]) for Ci in C]
    lmi = _solve_lmi(A, C, np.asarray(W, dtype=float), 1.0, solver, problems)
    return float("inf") if lmi.radius_L is None else lmi.radius_L


def s_detectability_witness(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    order: Order | str = Order.CONSENSUS_THEN_FILTER,
    solver: str = "CLARABEL",
    lmi_margin: float = LMI_MARGIN,
) -> dict[str, Any] | None:
    """Plain-numpy witness of S-detectability, or None unless one was found and verified
    (``docs/theory/s-detectability.md``, "Witness format").

    Keys ``gains`` (``L_i``), ``Y`` (dual tuple), ``X`` (primal tuple of the order's operator),
    ``order``, ``convention`` (the inequalities, in words), ``margin`` and ``radius_bound``.
    With ``Γ_i = A − L_i C_i``: dual (both orders) ``Y_j ≻ 0`` and ``Y_j − Σ_i w_ij Γ_i' Y_i Γ_i
    ≻ 0``; primal ``X_i ≻ 0`` and ``X_i − Γ_i (Σ_j w_ij X_j) Γ_i' ≻ 0`` (consensus first) or
    ``X_i − Σ_j w_ij Γ_j X_j Γ_j' ≻ 0`` (filter first).
    """
    order = Order(order)
    result = decide_s_detectability(A, C, W, order=order, solver=solver, lmi_margin=lmi_margin)
    if result.verdict is not True:
        return None
    return {
        "gains": [np.array(g) for g in result.gains],
        "Y": np.array(result.Y),
        "X": np.array(result.X),
        "order": order,
        "convention": _CONVENTION[order],
        "margin": result.witness_margin,
        "radius_bound": result.radius_bound,
    }


_CONVENTION = {
    Order.CONSENSUS_THEN_FILTER: (
        "Gamma_i = A - L_i C_i; Y_j > 0 and Y_j - sum_i w_ij Gamma_i' Y_i Gamma_i > 0 for all j; "
        "X_i > 0 and X_i - Gamma_i (sum_j w_ij X_j) Gamma_i' > 0 for all i (operator L, eq. 5.13)"
    ),
    Order.FILTER_THEN_CONSENSUS: (
        "Gamma_i = A - L_i C_i; Y_j > 0 and Y_j - sum_i w_ij Gamma_i' Y_i Gamma_i > 0 for all j; "
        "X_i > 0 and X_i - sum_j w_ij Gamma_j X_j Gamma_j' > 0 for all i (operator J, App. C.3)"
    ),
}


def witness_margin(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    gains: Sequence[np.ndarray],
    Y: np.ndarray,
    *,
    rho: float = 1.0,
) -> float:
    """``m = min_j λ_min(ρ Y_j − L*_j(Y)) / (ρ max_i λ_max(Y_i))``, or ``-inf`` if some ``Y_i ⊁ 0``.

    ``m > 0`` proves ``r_σ(L) ≤ ρ (1 − m)``: ``L*(Y) ⪯ ρ Y − m ρ λ_max I ⪯ ρ (1 − m) Y``.
    """
    Ysym = (Y + Y.transpose(0, 2, 1)) / 2
    low = min(float(np.linalg.eigvalsh(Yi)[0]) for Yi in Ysym)
    if not low > 0:
        return float("-inf")
    top = max(float(np.linalg.eigvalsh(Yi)[-1]) for Yi in Ysym)
    D = rho * Ysym - L_adjoint_map(W, closed_loop(A, C, gains), Ysym)
    D = (D + D.transpose(0, 2, 1)) / 2
    return min(float(np.linalg.eigvalsh(Dj)[0]) for Dj in D) / (rho * top)


def _build_lmi(
    A: np.ndarray, C: list[np.ndarray], support: np.ndarray, rho: float
) -> tuple[cp.Problem, dict[str, Any]]:
    """The LMI of the module docstring for every ``W`` with this ``support``: ``W/ρ`` is the
    non-negative cvxpy Parameter ``parts["W"]`` (DPP), so a re-solve needs no rebuild."""
    N, n = support.shape[0], A.shape[0]
    weights = cp.Parameter((N, N), nonneg=True)
    Ys = [cp.Variable((n, n), symmetric=True) for _ in range(N)]
    Zs = [cp.Variable((n, n), symmetric=True) for _ in range(N)]
    Gs = [cp.Variable((n, Ci.shape[0])) if Ci.shape[0] else None for Ci in C]
    mu = cp.Variable()
    eye = np.eye(n)
    f1, f2 = [], []
    for j in range(N):
        coupling = sum(weights[i, j] * Zs[i] for i in range(N) if support[i, j])
        f1.append(Ys[j] - coupling - mu * eye >> 0)
    for i in range(N):
        M = Ys[i] @ A - (Gs[i] @ C[i] if Gs[i] is not None else 0)
        block = cp.bmat([[Zs[i], M.T], [M, Ys[i]]])
        f2.append((block + block.T) / 2 - mu * np.eye(2 * n) >> 0)
    flat = [cp.vec(v, order="F") for v in (*Ys, *Zs, *(g for g in Gs if g is not None))]
    norm = cp.norm(cp.hstack(flat), 2) <= 1
    problem = cp.Problem(cp.Maximize(mu), [*f1, *f2, norm])
    return problem, {"Y": Ys, "G": Gs, "Z": Zs, "mu": mu, "f1": f1, "f2": f2, "W": weights}


class LmiCache:
    """Built LMIs kept for re-solving (issue 28 item 4): one per ``(A, C, support of W, ρ)``,
    with ``W`` set as a parameter, so a bisection or sweep over weights compiles its problem once;
    at most ``limit`` problems, the least recently used dropped first.

    Not shared between threads: a search makes its own, and :func:`decide_s_detectability`
    without one uses a per-thread cache of :data:`SHARED_PROBLEMS` problems (so sweeps, one
    decision per point, reuse too).
    """

    def __init__(self, limit: int | None = None, support: np.ndarray | None = None) -> None:
        """At most ``limit`` problems; with ``support``, every problem is built for it (each
        ``W`` asked for must lie within it; a zero weight inside it only drops its term), so
        weights of different supports — a self-weight search's ``w = 0`` end, the searches of
        every agent of one case — share one problem."""
        self._problems: dict[tuple, tuple[cp.Problem, dict[str, Any]]] = {}
        self._limit = limit
        self._support = None if support is None else np.asarray(support, dtype=bool)

    def __len__(self) -> int:
        """How many problems are built."""
        return len(self._problems)

    def problem(
        self, A: np.ndarray, C: list[np.ndarray], W: np.ndarray, rho: float
    ) -> tuple[cp.Problem, dict[str, Any]]:
        """The LMI of ``(A, C, W, ρ)``, built on first use for this support, ``W`` set."""
        support = W != 0 if self._support is None else self._support
        if np.any((W != 0) & ~support):
            raise ValueError("a weight outside the cache's support")
        key = (A.tobytes(), A.shape, tuple((c.tobytes(), c.shape) for c in C),
               support.tobytes(), support.shape, rho)  # fmt: skip
        built = self._problems.pop(key, None) or _build_lmi(A, C, support, rho)
        self._problems[key] = built  # most recently used last
        if self._limit is not None and len(self._problems) > self._limit:
            del self._problems[next(iter(self._problems))]
        problem, parts = built
        parts["W"].value = W / rho
        return problem, parts


def _psd_part(M: np.ndarray) -> np.ndarray:
    S = (M + M.T) / 2
    w, V = np.linalg.eigh(S)
    return (V * np.clip(w, 0, None)) @ V.T


def _certificate_epsilon(
    A: np.ndarray, C: list[np.ndarray], W: np.ndarray, rho: float, parts: dict[str, Any]
) -> tuple[float, dict[str, np.ndarray]]:
    Lam = np.stack([_psd_part(np.asarray(c.dual_value, dtype=float)) for c in parts["f1"]])
    Psi = np.stack([_psd_part(np.asarray(c.dual_value, dtype=float)) for c in parts["f2"]])
    residual = alternative_residual(A, C, W, Lam, Psi, rho=rho)
    total = float(sum(np.trace(x) for x in Lam) + sum(np.trace(x) for x in Psi))
    norm = float(np.sqrt(sum(np.sum(r**2) for r in residual.values())))
    return (norm / total if total > 0 else float("inf")), {"Lambda": Lam, "Psi": Psi}


def alternative_residual(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Lam: np.ndarray,
    Psi: np.ndarray,
    *,
    rho: float = 1.0,
) -> dict[str, np.ndarray]:
    """``F*(Λ, Ψ)`` as ``{"Y", "Z", "G" (the n × p_i blocks flattened)}``: the adjoint of the LMI
    map at the multipliers of ``F1_j`` and ``F2_i`` (zero for a certificate)."""
    n = A.shape[0]
    P11, P21, P22 = Psi[:, :n, :n], Psi[:, n:, :n], Psi[:, n:, n:]
    RZ = P11 - np.einsum("ij,jab->iab", W / rho, Lam)
    RY = Lam + P22 + A @ P21.transpose(0, 2, 1) + P21 @ A.T
    RG = [(-2 * P21[i] @ Ci.T).ravel() for i, Ci in enumerate(C)]
    return {"Y": RY, "Z": RZ, "G": np.concatenate(RG) if RG else np.zeros(0)}


def self_weight_family(W: np.ndarray, agents: Sequence[int], w: float) -> np.ndarray:
    """``W(w)``: self-weight ``w ∈ [0, 1]`` for each 0-based agent, its other weights rescaled
    (``ValueError`` when an agent has ``w_aa = 1``: nothing to rescale)."""
    if not 0.0 <= w <= 1.0:
        raise ValueError(f"self-weight {w!r} outside [0, 1]")
    out = np.array(W, dtype=float)
    for a in agents:
        rest = 1.0 - W[a, a]
        if rest <= 0:
            raise ValueError(f"agent {a + 1} has w_aa = 1: no other weight to rescale")
        out[a] = W[a] * (1.0 - w) / rest
        out[a, a] = w
    return out


@dataclass(frozen=True)
class SelfWeightSearch:
    """The bracket ``[low, high]`` of the largest self-weight of ``agents`` (1-based): ``W(low)``
    certified S-detectable, ``W(high)`` certified not (or ``high = 1``); ``status`` ``found``
    (width ≤ ``weight_tol``), ``always`` (``W(1)`` is), ``never`` (``W(0)`` is not) or
    ``inconclusive`` (a probe was); every ``(w, verdict)`` probed."""

    agents: tuple[int, ...]
    low: float
    high: float
    status: str
    probes: tuple[tuple[float, bool | None], ...]
    weight_tol: float

    @property
    def estimate(self) -> float:
        """Midpoint of the bracket."""
        return (self.low + self.high) / 2


def max_self_weight(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    agents: Sequence[int],
    *,
    weight_tol: float = WEIGHT_TOL,
    solver: str = "CLARABEL",
    reuse: bool = True,
) -> SelfWeightSearch:
    """Supremum of ``w ∈ [0, 1]`` with ``(A, C, W(w))`` S-detectable, the 0-based ``agents``
    varying together (seed 000 Thm 5.2.10 (2); §5.3.1: 0.25, §5.3.2: 0.3378); ``reuse`` solves
    one built LMI per support (:class:`LmiCache`; False rebuilds it per probe, the old path)."""
    probes: list[tuple[float, bool | None]] = []
    ids = tuple(a + 1 for a in agents)
    problems = LmiCache()

    def decide(w: float) -> bool | None:
        family = self_weight_family(W, agents, w)
        cache = problems if reuse else LmiCache()
        verdict = decide_s_detectability(A, C, family, solver=solver, problems=cache).verdict
        probes.append((w, verdict))
        return verdict

    def done(low: float, high: float, status: str) -> SelfWeightSearch:
        return SelfWeightSearch(ids, low, high, status, tuple(probes), weight_tol)

    first = decide(0.0)
    if first is not True:
        return done(0.0, 0.0, "never" if first is False else "inconclusive")
    last = decide(1.0)
    if last is True:
        return done(1.0, 1.0, "always")
    if last is None:
        return done(0.0, 1.0, "inconclusive")
    low, high = 0.0, 1.0
    while high - low > weight_tol:
        mid = (low + high) / 2
        verdict = decide(mid)
        if verdict is None:
            return done(low, high, "inconclusive")
        low, high = (mid, high) if verdict else (low, mid)
    return done(low, high, "found")
