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
passes :mod:`proofs_check` (:mod:`theory.consensus.primal_certificates`: the witness rounded when
``m ≥ lmi_margin``, or exact Lyapunov tuples for candidate gains); False when an
``s-detectability-infeasible`` certificate does (:mod:`theory.consensus.infeasibility`: exact
Farkas multipliers); None otherwise, with each route's reason. ``docs/theory/s-detectability.md``
§6 lists every audited decision.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import cvxpy as cp
import numpy as np

from theory.consensus.infeasibility import infeasibility_certificate
from theory.consensus.operators import (
    B_matrix,
    L_adjoint_map,
    closed_loop,
    covariance_operator_matrix,
    spectral_radius,
)
from theory.consensus.primal_certificates import (
    certificate_gains,
    primal_certificate,
    primal_lyapunov,
)
from theory.core.exact import RationalizationError
from theory.core.tolerances import CERT_TOL, LMI_MARGIN

__all__ = [
    "CERT_TOL",
    "LMI_MARGIN",
    "SOLVER_STATUSES",
    "SOLVER_STATUS_TABLE",
    "WITNESS_CONVENTION",
    "SDetectability",
    "alternative_residual",
    "decide_s_detectability",
    "s_detectability_witness",
    "witness_from_decision",
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
class SDetectability:
    """The decision and its evidence.

    Attributes
    ----------
    verdict : bool or None
        True: S-detectable (an exact ``s-detectability`` certificate checked); False: not (an
        exact ``s-detectability-infeasible`` certificate checked); None: inconclusive.
    reason : str
        One sentence saying what decided it (or why nothing did).
    solver : str
        cvxpy solver name.
    solver_status : str
        One of :data:`SOLVER_STATUSES`.
    rho : float
        The radius asked about (``r_σ(L) < rho``; 1 for S-detectability).
    mu : float or None
        The solver's optimal margin of the normalised LMI.
    witness_margin : float or None
        ``m`` recomputed from ``(L_i, Y_i)`` (see the module docstring); > 0 is a valid witness.
    radius_bound : float or None
        ``ρ (1 − m)``, a proven upper bound on ``r_σ(L)`` when ``m > 0``.
    cert_epsilon : float or None
        ``ε_cert`` recomputed from the projected multipliers.
    gains : tuple of ndarray or None
        ``L_i`` (n × p_i) of the certificate (None unless ``verdict`` is True).
    Y : ndarray or None
        Dual Lyapunov tuple, shape (N, n, n), when the certificate came from the LMI witness.
    X : ndarray or None
        Primal Lyapunov tuple for the filter's operator with the certificate's gains:
        ``X − T(X) = I`` (floats; None unless ``verdict`` is True).
    radius_L, radius_J, radius_B : float or None
        ``r_σ`` of L, J and B (floats) with the candidate gains ``Y_i⁻¹ G_i`` of the solver's
        solution (informative only).
    multipliers : dict or None
        ``{"Lambda": (N, n, n), "Psi": (N, 2n, 2n)}`` projected onto the PSD cone.
    tolerances : dict
        ``lmi_margin`` and ``cert_tol`` used.
    order : str
        Filter order the primal Lyapunov tuple ``X`` refers to.
    certificate : dict or None
        The exact certificate the verdict rests on (``s-detectability`` when True,
        ``s-detectability-infeasible`` when False), already accepted by :mod:`proofs_check`.
    route : str
        How the certificate was obtained.
    """

    verdict: bool | None
    reason: str
    solver: str
    solver_status: str
    rho: float
    mu: float | None = None
    witness_margin: float | None = None
    radius_bound: float | None = None
    cert_epsilon: float | None = None
    gains: tuple[np.ndarray, ...] | None = None
    Y: np.ndarray | None = None
    X: np.ndarray | None = None
    radius_L: float | None = None
    radius_J: float | None = None
    radius_B: float | None = None
    multipliers: dict[str, np.ndarray] | None = None
    tolerances: dict[str, float] = field(default_factory=dict)
    order: str = "consensus-then-filter"
    certificate: dict[str, Any] | None = None
    route: str = ""

    def evidence(self) -> dict[str, Any]:
        """JSON-ready summary (no matrices)."""
        return {
            "verdict": self.verdict,
            "reason": self.reason,
            "solver": self.solver,
            "solver_status": self.solver_status,
            "rho": self.rho,
            "mu": self.mu,
            "witness_margin": self.witness_margin,
            "radius_bound": self.radius_bound,
            "cert_epsilon": self.cert_epsilon,
            "candidate_radius_L": self.radius_L,
            "candidate_radius_J": self.radius_J,
            "candidate_radius_B": self.radius_B,
            "certificate_kind": None if self.certificate is None else self.certificate["kind"],
            "certificate_route": self.route,
            "tolerances": dict(self.tolerances),
        }


def decide_s_detectability(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rho: float = 1.0,
    order: str = "consensus-then-filter",
    solver: str = "CLARABEL",
    lmi_margin: float = LMI_MARGIN,
    cert_tol: float = CERT_TOL,
    candidate_gains: Sequence[tuple[str, Sequence[np.ndarray]]] = (),
    case: str | None = None,
) -> SDetectability:
    """Decide whether gains ``L_i`` exist with ``r_σ(L) < rho`` (S-detectability for rho = 1).

    Only exact certificates decide (module docstring): True when an ``s-detectability``
    certificate passes :mod:`proofs_check`, False when an ``s-detectability-infeasible`` one
    does, None (inconclusive) otherwise — whatever the float margins say.

    Parameters
    ----------
    A : ndarray, shape (n, n)
        System matrix, seed 000 eq. (5.1).
    C : sequence of ndarray, shapes (p_i, n)
        Measurement matrices (zero rows allowed), eq. (5.2).
    W : ndarray, shape (N, N)
        Row-stochastic consensus weights (directed allowed).
    rho : float
        Radius asked about; ``r_σ(J) = r_σ(L)`` so the answer holds for both orders.
    order : str
        Filter order for the primal Lyapunov tuple ``X`` of the witness.
    solver : str
        A cvxpy SDP solver name (``CLARABEL`` or ``SCS``).
    lmi_margin : float
        Least relative witness margin ``m`` worth rounding (see module docstring).
    cert_tol : float
        ``ε_cert`` at or below which the float dual is reported as suggesting infeasibility
        (informative: it decides nothing).
    candidate_gains : sequence of (label, gains)
        Further gains (the case's, the Riccati iteration's) to try with exact Lyapunov tuples.
    case : str, optional
        Case name recorded in the certificate.

    Returns
    -------
    SDetectability
        Never raises on solver failure: the exact routes are still tried.

    References
    ----------
    seed 000 Def. 5.2.4, Lemma 5.2.2, App. C.3; docs/theory/s-detectability.md.
    """
    A = np.asarray(A, dtype=float)
    W = np.asarray(W, dtype=float)
    C = [np.asarray(Ci, dtype=float).reshape(-1, A.shape[0]) for Ci in C]
    tolerances = {"lmi_margin": lmi_margin, "cert_tol": cert_tol}
    base = _float_evidence(A, C, W, rho, solver) | {"order": order, "tolerances": tolerances}
    lmi_gains, lmi_Y = base.pop("gains", None), base.pop("Y", None)
    witness = None
    if base.get("witness_margin", float("-inf")) >= lmi_margin:
        witness = (lmi_gains, lmi_Y)
    floats = [("LMI candidate gains", lmi_gains)] if lmi_gains else []
    cert, route, reasons = primal_certificate(
        A, C, W, order=order, rho=rho, witness=witness, candidates=[*floats, *candidate_gains],
        case=case,
    )  # fmt: skip
    if cert is not None:
        found = _certified_gains(A, C, W, cert, route, lmi_Y, rho=rho, order=order)
        reason = f"certificate verified exactly (proofs_check): {route}"
        return SDetectability(True, reason, **(base | found), certificate=cert, route=route)
    try:
        cert = infeasibility_certificate(A, C, W, rho=rho, case=case)
    except RationalizationError as error:
        reasons.append(str(error))
    else:
        route = "Farkas multipliers from the blind set " + str(cert["produced_by"]["agents"])
        reason = f"infeasibility certificate verified exactly (proofs_check): {route}"
        return SDetectability(False, reason, **base, certificate=cert, route=route)
    return SDetectability(None, _inconclusive_reason(base, reasons, cert_tol), **base)


def _certified_gains(
    A: np.ndarray,
    C: list[np.ndarray],
    W: np.ndarray,
    cert: dict[str, Any],
    route: str,
    lmi_Y: np.ndarray | None,
    *,
    rho: float,
    order: str,
) -> dict[str, Any]:
    """The gains of a checked ``s-detectability`` certificate, their primal tuple ``X`` and, on
    the LMI route, the margin of the rounded gains (not of the float ones)."""
    gains = certificate_gains(cert, C)
    found = {"gains": gains, "X": primal_lyapunov(A, C, W, gains, order), "Y": None}
    found |= {"witness_margin": None, "radius_bound": None}
    if route.startswith("LMI witness"):
        m = witness_margin(A, C, W, gains, lmi_Y, rho=rho)
        found |= {"Y": lmi_Y, "witness_margin": m, "radius_bound": rho * (1 - m)}
    return found


def _inconclusive_reason(base: dict[str, Any], reasons: list[str], cert_tol: float) -> str:
    """Why no exact certificate decided, with the float dual's hint (which proves nothing)."""
    hint = base.get("cert_epsilon")
    suggests = (
        f"; the float dual suggests infeasibility (ε_cert = {hint:.3g} ≤ cert_tol) but proves "
        "nothing"
        if hint is not None and hint <= cert_tol
        else ""
    )
    return "no exact certificate either way" + suggests + ": " + "; ".join(reasons)


def _float_evidence(
    A: np.ndarray, C: list[np.ndarray], W: np.ndarray, rho: float, solver: str
) -> dict[str, Any]:
    """Solve the normalised LMI; its candidate gains, margins and multipliers (floats only)."""
    problem, parts = _build_lmi(A, C, W, rho)
    common: dict[str, Any] = {"solver": solver, "rho": rho}
    try:
        with warnings.catch_warnings():  # inaccuracy is reported through the status table
            warnings.simplefilter("ignore", UserWarning)
            problem.solve(solver=solver)
        status = SOLVER_STATUS_TABLE.get(problem.status, "solver_error")
    except (cp.error.SolverError, ArithmeticError, ValueError):
        return common | {"solver_status": "solver_error"}
    if status not in ("optimal", "optimal_inaccurate"):
        return common | {"solver_status": status}
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
    eps = _certificate_epsilon(A, C, W, rho, parts)
    return common | {
        "solver_status": status,
        "mu": float(parts["mu"].value),
        "witness_margin": m,
        "radius_bound": rho * (1 - m) if m > 0 else None,
        "cert_epsilon": eps["epsilon"],
        "multipliers": eps["multipliers"],
        "gains": gains,
        "Y": Y,
        **_radii(A, C, W, gains),
    }


def s_detectability_witness(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    order: str = "consensus-then-filter",
    solver: str = "CLARABEL",
    lmi_margin: float = LMI_MARGIN,
) -> dict[str, Any] | None:
    """Plain-numpy witness of S-detectability for the certificate builder, or None.

    Parameters
    ----------
    A, C, W : ndarray
        As in :func:`decide_s_detectability`.
    order : str
        ``consensus-then-filter`` (operator L) or ``filter-then-consensus`` (operator J).
    solver : str
        cvxpy solver.
    lmi_margin : float
        Least relative witness margin accepted.

    Returns
    -------
    dict or None
        None unless a witness was found and verified. Otherwise the keys ``gains`` (list of
        n × p_i arrays ``L_i``), ``Y`` (N × n × n, the dual Lyapunov tuple), ``X`` (N × n × n, the
        primal Lyapunov tuple of the order's operator), ``order``, ``convention`` (a string
        stating the inequalities, below), ``margin`` and ``radius_bound``. The inequalities, with
        ``Γ_i = A − L_i C_i``:

        * dual (both orders): ``Y_j ≻ 0`` and ``Y_j − Σ_i w_ij Γ_i' Y_i Γ_i ≻ 0`` for all j
          (proves ``r_σ(L) = r_σ(J) < 1``);
        * primal, ``consensus-then-filter``: ``X_i ≻ 0`` and
          ``X_i − Γ_i (Σ_j w_ij X_j) Γ_i' ≻ 0``;
        * primal, ``filter-then-consensus``: ``X_i ≻ 0`` and ``X_i − Σ_j w_ij Γ_j X_j Γ_j' ≻ 0``.

    References
    ----------
    docs/theory/s-detectability.md, section "Witness format".
    """
    result = decide_s_detectability(A, C, W, order=order, solver=solver, lmi_margin=lmi_margin)
    return witness_from_decision(result, order)


def witness_from_decision(result: SDetectability, order: str) -> dict[str, Any] | None:
    """The witness of :func:`s_detectability_witness` from a decision already made.

    Parameters
    ----------
    result : SDetectability
        From :func:`decide_s_detectability` with the same ``order``.
    order : str
        ``consensus-then-filter`` or ``filter-then-consensus``.

    Returns
    -------
    dict or None
        As :func:`s_detectability_witness`: None unless ``result.verdict`` is True.
    """
    if result.verdict is not True:
        return None
    return {
        "gains": [np.array(g) for g in result.gains],
        "Y": np.array(result.Y),
        "X": np.array(result.X),
        "order": order,
        "convention": WITNESS_CONVENTION[order],
        "margin": result.witness_margin,
        "radius_bound": result.radius_bound,
    }


WITNESS_CONVENTION = {
    "consensus-then-filter": (
        "Gamma_i = A - L_i C_i; Y_j > 0 and Y_j - sum_i w_ij Gamma_i' Y_i Gamma_i > 0 for all j; "
        "X_i > 0 and X_i - Gamma_i (sum_j w_ij X_j) Gamma_i' > 0 for all i (operator L, eq. 5.13)"
    ),
    "filter-then-consensus": (
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

    Parameters
    ----------
    A, C, W : ndarray
        The system and network.
    gains : sequence of ndarray
        ``L_i``.
    Y : ndarray, shape (N, n, n)
        Candidate dual Lyapunov tuple.
    rho : float
        Radius.

    Returns
    -------
    float
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
    A: np.ndarray, C: list[np.ndarray], W: np.ndarray, rho: float
) -> tuple[cp.Problem, dict[str, Any]]:
    N, n = W.shape[0], A.shape[0]
    Ys = [cp.Variable((n, n), symmetric=True) for _ in range(N)]
    Zs = [cp.Variable((n, n), symmetric=True) for _ in range(N)]
    Gs = [cp.Variable((n, Ci.shape[0])) if Ci.shape[0] else None for Ci in C]
    mu = cp.Variable()
    eye = np.eye(n)
    f1, f2 = [], []
    for j in range(N):
        coupling = sum((W[i, j] / rho) * Zs[i] for i in range(N) if W[i, j] != 0)
        f1.append(Ys[j] - coupling - mu * eye >> 0)
    for i in range(N):
        M = Ys[i] @ A - (Gs[i] @ C[i] if Gs[i] is not None else 0)
        block = cp.bmat([[Zs[i], M.T], [M, Ys[i]]])
        f2.append((block + block.T) / 2 - mu * np.eye(2 * n) >> 0)
    flat = [cp.vec(v, order="F") for v in (*Ys, *Zs, *(g for g in Gs if g is not None))]
    norm = cp.norm(cp.hstack(flat), 2) <= 1
    problem = cp.Problem(cp.Maximize(mu), [*f1, *f2, norm])
    return problem, {"Y": Ys, "G": Gs, "Z": Zs, "mu": mu, "f1": f1, "f2": f2}


def _psd_part(M: np.ndarray) -> np.ndarray:
    S = (M + M.T) / 2
    w, V = np.linalg.eigh(S)
    return (V * np.clip(w, 0, None)) @ V.T


def _certificate_epsilon(
    A: np.ndarray, C: list[np.ndarray], W: np.ndarray, rho: float, parts: dict[str, Any]
) -> dict[str, Any]:
    N, n = W.shape[0], A.shape[0]
    Lam = np.stack([_psd_part(np.asarray(c.dual_value, dtype=float)) for c in parts["f1"]])
    Psi = np.stack([_psd_part(np.asarray(c.dual_value, dtype=float)) for c in parts["f2"]])
    residual = alternative_residual(A, C, W, Lam, Psi, rho=rho)
    total = float(sum(np.trace(x) for x in Lam) + sum(np.trace(x) for x in Psi))
    norm = float(np.sqrt(sum(np.sum(r**2) for r in residual.values())))
    epsilon = norm / total if total > 0 else float("inf")
    return {"epsilon": epsilon, "multipliers": {"Lambda": Lam, "Psi": Psi}, "N": N, "n": n}


def alternative_residual(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Lam: np.ndarray,
    Psi: np.ndarray,
    *,
    rho: float = 1.0,
) -> dict[str, np.ndarray]:
    """``F*(Λ, Ψ)``: the adjoint of the LMI map at the multipliers (zero for a certificate).

    Parameters
    ----------
    A, C, W : ndarray
        The system and network.
    Lam : ndarray, shape (N, n, n)
        Multipliers ``Λ_j`` of the blocks ``F1_j``.
    Psi : ndarray, shape (N, 2n, 2n)
        Multipliers ``Ψ_i`` of the blocks ``F2_i``.
    rho : float
        Radius.

    Returns
    -------
    dict
        ``{"Y": (N, n, n), "Z": (N, n, n), "G": flat concatenation of the n × p_i blocks}``.
    """
    n = A.shape[0]
    P11, P21, P22 = Psi[:, :n, :n], Psi[:, n:, :n], Psi[:, n:, n:]
    RZ = P11 - np.einsum("ij,jab->iab", W / rho, Lam)
    RY = Lam + P22 + A @ P21.transpose(0, 2, 1) + P21 @ A.T
    RG = [(-2 * P21[i] @ Ci.T).ravel() for i, Ci in enumerate(C)]
    return {"Y": RY, "Z": RZ, "G": np.concatenate(RG) if RG else np.zeros(0)}


def _radii(
    A: np.ndarray, C: list[np.ndarray], W: np.ndarray, gains: Sequence[np.ndarray]
) -> dict[str, float]:
    Gamma = closed_loop(A, C, gains)
    return {
        "radius_L": spectral_radius(covariance_operator_matrix(W, Gamma, "consensus-then-filter")),
        "radius_J": spectral_radius(covariance_operator_matrix(W, Gamma, "filter-then-consensus")),
        "radius_B": spectral_radius(B_matrix(W, Gamma)),
    }
