"""Exact certificates that ``(A, C, W)`` **is** S-detectable, and of ``r_σ(L) < ρ`` for given gains.

Kinds ``mjls-stability`` (seed 000 Lemma 5.2.2) and ``s-detectability`` (Def. 5.2.4): rational
gains ``L_i`` and a Lyapunov tuple ``P ≻ 0`` with ``ρP − T(P) ≻ 0`` (format of
``docs/certificates.md``). A float witness is kept only once it is strictly feasible with a
relative margin above ``certificate_margin``, then rounded to rationals with growing precision
until the independent checker :mod:`proofs_check` accepts it
(:func:`theory.core.certificate_format.rounded`); nothing weaker is ever emitted: failure raises
:class:`~theory.core.exact.RationalizationError`. The negative kind is
:mod:`theory.consensus.infeasibility`.

:func:`primal_certificate` tries two routes in turn (:class:`Route`):

1. **the LMI witness**, when its float margin clears ``lmi_margin``: gains and the primal tuple
   ``X`` (``X − T(X) = I``, float) or the dual tuple ``Y``, rounded
   (:func:`s_detectability_certificate`);
2. **exact Lyapunov tuples** for candidate gains (the projection gains ``L_i = A C_i⁺``, which
   make ``Γ_i = A (I − C_i⁺C_i)`` vanish on what agent i sees; the LMI's, the case's and the
   Riccati iteration's, rounded to dyadics): ``X`` solving ``X − T(X)/ρ = I`` exactly
   (:func:`theory.consensus.operators.exact_lyapunov`), then rounded to dyadics well inside its
   exact margin ``I``. This needs no float margin at all, so it settles problems whose best
   margin is far below ``lmi_margin`` (seed 000 Example 1 at ``w = 0.249999999``:
   ``r_σ(L) = 4w``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from fractions import Fraction
from typing import Any

import numpy as np

from proofs_check.linalg import Matrix, matmul, scale, sub
from proofs_check.operators import apply_operator as exact_operator
from theory.consensus.case import Order
from theory.consensus.operators import (
    apply_operator,
    closed_loop,
    covariance_operator_matrix,
    exact_lyapunov,
    float_lyapunov,
)
from theory.core.certificate_format import checked, envelope, rational_bound, rounded, strings
from theory.core.exact import (
    PRECISIONS,
    RationalizationError,
    dyadic_matrix,
    exact_matrix,
    fraction_strings,
    fractions_of,
    rational_matrix,
    stochastic_matrix,
    symmetric_projection,
    to_fmpq,
)
from theory.core.tolerances import CERTIFICATE_MARGIN, EXACT_DIM, ROUNDING_BITS, bits_ladder

__all__ = [
    "SOURCES",
    "PrimalCertificate",
    "Route",
    "certificate_gains",
    "decrease_strings",
    "exact_gain_certificate",
    "exact_s_detectability_certificate",
    "float_margin",
    "mjls_stability_certificate",
    "primal_certificate",
    "primal_lyapunov",
    "projection_gains",
    "s_detectability_certificate",
]

SOURCES = {
    "mjls-stability": "seed 000, Lemma 5.2.2",
    "s-detectability": "seed 000, Definition 5.2.4 and Lemma 5.2.2",
    "gains-radius-below": "seed 000, Lemma 5.2.2; docs/theory/s-detectability.md, Lemma 1",
}


def float_margin(
    operator: str,
    W: np.ndarray,
    gammas: Sequence[np.ndarray],
    P: Sequence[np.ndarray],
    bound: float = 1.0,
) -> float:
    """Relative margin ``min_i min(λ_min(P_i), λ_min(ρP_i − T_i(P))) / max_i ‖P_i‖₂`` of a float
    witness (``T`` named as in :mod:`proofs_check.operators`): positive iff strictly feasible."""
    P = [symmetric_projection(p) for p in P]
    Gamma = np.stack([np.asarray(g, float) for g in gammas])
    images = apply_operator(operator, np.asarray(W, float), Gamma, P)
    top = max(float(np.linalg.norm(p, 2)) for p in P)
    if not np.isfinite(top) or top == 0:
        return float("-inf")
    lows = [np.linalg.eigvalsh(p)[0] for p in P]
    lows += [
        np.linalg.eigvalsh(symmetric_projection(bound * p - t))[0]
        for p, t in zip(P, images, strict=True)
    ]
    return float(min(lows)) / top


def decrease_strings(
    operator: str, W: Matrix, gammas: list[Matrix], P: list[Matrix], bound: Fraction
) -> list:
    """Exact ``bound · P_i − T_i(P)`` as strings (the checker recomputes and compares)."""
    images = exact_operator(operator, W, gammas, P)
    return [fraction_strings(sub(scale(bound, p), t)) for p, t in zip(P, images, strict=True)]


def mjls_stability_certificate(
    gammas: Sequence[np.ndarray],
    W: np.ndarray,
    P: Sequence[np.ndarray],
    *,
    operator: str = "L",
    spectral_radius_below: float | Fraction = 1,
    certificate_margin: float = CERTIFICATE_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Certificate of ``r_σ(L) < ρ`` for given ``Γ_i`` and ``W`` (seed 000 Lemma 5.2.2, eq.
    (5.13)) from a float witness ``P`` for ``operator``, ``ρ`` limited to denominators ≤ 10⁶."""
    bound = rational_bound(spectral_radius_below)
    claim = {"statement": "r_σ(L) < ρ for the given Γ_i and W", "spectral_radius_below": str(bound)}
    W_q, gammas_q = stochastic_matrix(W), [exact_matrix(g) for g in gammas]
    data = {"W": fraction_strings(W_q), "Gamma": strings(gammas_q)}
    margin = float_margin(operator, W, gammas, P, float(bound))

    def build(exact: dict[str, list[Matrix]]) -> dict:
        P_q = exact["P"]
        witness = {
            "operator": operator,
            "P": strings(P_q),
            "decrease": decrease_strings(operator, W_q, gammas_q, P_q, bound),
        }
        return envelope(
            "mjls-stability", claim, data, witness, source=SOURCES["mjls-stability"], case=case
        )

    return rounded(
        build,
        {"P": [symmetric_projection(p) for p in P]},
        margin=margin,
        lmi_margin=certificate_margin,
        precisions=precisions,
        what="mjls-stability",
    )


def s_detectability_certificate(
    A: np.ndarray,
    Cs: Sequence[np.ndarray],
    W: np.ndarray,
    order: Order | str,
    gains: Sequence[np.ndarray],
    Ps: Sequence[np.ndarray],
    *,
    dual: bool = False,
    rho: float | Fraction = 1,
    certificate_margin: float = CERTIFICATE_MARGIN,
    precisions: Sequence[int] = PRECISIONS,
    case: str | None = None,
) -> dict:
    """Certificate that ``(A, C, W)`` is S-detectable (seed 000 Def. 5.2.4, Lemma 5.2.2, App.
    C.3), from float gains ``L_i`` and a float Lyapunov tuple ``P``.

    ``P ≻ 0`` and ``ρP − T(P) ≻ 0`` for ``Γ_i = A − L_i C_i``, ``T`` the order's operator (L or
    J), or with ``dual`` the adjoint ``L*`` (the LMI's dual tuple, the same for both orders): all
    prove ``r_σ(L) = r_σ(J) < ρ``. An agent without measurements is written as one zero row of
    ``C_i`` with a zero gain column, which leaves ``Γ_i = A`` unchanged.
    """
    order = Order(order)
    operator = "L-adjoint" if dual else order.operator
    bound = rational_bound(rho)
    Cs, gains = _padded(A, Cs, [np.asarray(g, float) for g in gains])
    exact = _exact_data(A, Cs, W)
    A_f = np.asarray(A, float)
    gammas = [A_f - g @ c for g, c in zip(gains, Cs, strict=True)]
    margin = float_margin(operator, W, gammas, Ps, float(bound))

    def build(witness: dict[str, list[Matrix]]) -> dict:
        return _document(exact, operator, witness["gains"], witness["P"], bound, case)

    matrices = {"gains": gains, "P": [symmetric_projection(p) for p in Ps]}
    return rounded(
        build,
        matrices,
        margin=margin,
        lmi_margin=certificate_margin,
        precisions=precisions,
        what="s-detectability",
    )


def exact_s_detectability_certificate(
    A: np.ndarray,
    Cs: Sequence[np.ndarray],
    W: np.ndarray,
    gains: Sequence[Matrix],
    P: Sequence[Matrix],
    *,
    operator: str,
    rho: float | Fraction = 1,
    case: str | None = None,
) -> dict:
    """The ``s-detectability`` certificate of exact gains (one zero column for an agent without
    sensor) and an exact Lyapunov tuple for ``operator``: nothing is rounded, so any positive
    margin is a proof; :class:`RationalizationError` names the check proofs_check fails."""
    n = np.asarray(A).shape[0]
    Cs, _ = _padded(A, Cs, [np.zeros((n, 0))] * len(Cs))
    zero = [[Fraction(0)] for _ in range(n)]
    gains = [g if g and g[0] else zero for g in gains]
    cert = _document(_exact_data(A, Cs, W), operator, gains, list(P), rational_bound(rho), case)
    why = checked(cert)
    if why is not None:
        raise RationalizationError(f"s-detectability: {why}")
    cert["produced_by"] = {"tool": "trackcert", "witness": "exact (no rounding)"}
    return cert


def _padded(
    A: np.ndarray, Cs: Sequence[np.ndarray], gains: list[np.ndarray]
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """``C_i`` and ``L_i`` with an agent without sensor as one zero row and one zero column."""
    n = np.asarray(A).shape[0]
    Cs = [np.asarray(c, float).reshape(-1, n) for c in Cs]
    gains = [np.asarray(g, float).reshape(n, -1) for g in gains]
    gains = [g if c.shape[0] else np.zeros((n, 1)) for g, c in zip(gains, Cs, strict=True)]
    return [c if c.shape[0] else np.zeros((1, n)) for c in Cs], gains


def _exact_data(A: np.ndarray, Cs: Sequence[np.ndarray], W: np.ndarray) -> dict[str, list]:
    return {
        "A": exact_matrix(A),
        "C": [exact_matrix(c) for c in Cs],
        "W": stochastic_matrix(W),
    }


def _document(
    exact: dict[str, list],
    operator: str,
    gains: list[Matrix],
    P: list[Matrix],
    bound: Fraction,
    case: str | None,
) -> dict:
    A_q, C_q, W_q = exact["A"], exact["C"], exact["W"]
    gammas = [sub(A_q, matmul(g, c)) for g, c in zip(gains, C_q, strict=True)]
    kind = "s-detectability" if bound <= 1 else "gains-radius-below"  # ρ > 1 proves less
    claim = {
        "statement": ("(A, C, W) is S-detectable: " if bound <= 1 else "")
        + "r_σ(L) < ρ with Γ_i = A − L_i C_i",
        "spectral_radius_below": str(bound),
    }
    data = {"A": fraction_strings(A_q), "C": strings(C_q), "W": fraction_strings(W_q)}
    witness = {
        "operator": operator,
        "gains": strings(gains),
        "P": strings(P),
        "decrease": decrease_strings(operator, W_q, gammas, P, bound),
    }
    return envelope(kind, claim, data, witness, source=SOURCES[kind], case=case)


def primal_lyapunov(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    gains: Sequence[np.ndarray],
    order: Order | str,
) -> np.ndarray | None:
    """The float ``X = Σ_k T^k(I)`` solving ``X − T(X) = I`` for the order's operator, or None
    when ``I − T`` is singular or ``X ⊁ 0`` (seed 000 Lemma 5.2.2, "only if")."""
    T = covariance_operator_matrix(np.asarray(W, float), closed_loop(A, C, gains), order)
    try:
        X = float_lyapunov(T, len(W), np.asarray(A).shape[0])
    except np.linalg.LinAlgError:
        return None
    return X if all(np.linalg.eigvalsh(Xi)[0] > 0 for Xi in X) else None


def projection_gains(A: np.ndarray, C: Sequence[np.ndarray]) -> list[Matrix]:
    """Exact gains ``L_i = A C_i⁺`` (``C_i⁺`` on a maximal set of independent rows, zero else),
    so ``Γ_i = A (I − C_i⁺ C_i)``: agent i removes everything it measures."""
    n = np.asarray(A).shape[0]
    A_q = to_fmpq(rational_matrix(A))
    out = []
    for Ci in C:
        rows = rational_matrix(np.asarray(Ci, float).reshape(-1, n)) if np.size(Ci) else []
        keep: list[int] = []
        for r in range(len(rows)):
            if to_fmpq([rows[k] for k in [*keep, r]]).rank() == len(keep) + 1:
                keep.append(r)
        if not keep:
            out.append([[Fraction(0)] * len(rows) for _ in range(n)] if rows else [])
            continue
        Ck = to_fmpq([rows[k] for k in keep])
        partial = fractions_of(A_q * Ck.transpose() * (Ck * Ck.transpose()).inv())
        gain = [[Fraction(0)] * len(rows) for _ in range(n)]
        for col, k in enumerate(keep):
            for r in range(n):
                gain[r][k] = partial[r][col]
        out.append(gain)
    return out


def _dyadic_exact(M: Matrix, bits: int) -> Matrix:
    """An exact matrix rounded to ``bits`` significant bits of its largest entry (no floats)."""
    top = max((abs(x) for row in M for x in row), default=Fraction(0))
    if top == 0:
        return M
    exponent = top.numerator.bit_length() - top.denominator.bit_length() - bits
    unit = Fraction(2) ** exponent
    return [[round(x / unit) * unit for x in row] for row in M]


def exact_gain_certificate(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    gains: Sequence[Matrix],
    *,
    order: Order | str,
    rho: float | Fraction = 1,
    case: str | None = None,
) -> dict:
    """The certificate of exact ``gains`` with the exact Lyapunov tuple of the order's operator,
    rounded to dyadics inside its margin; :class:`RationalizationError` above ``EXACT_DIM``, when
    ``r_σ(T) ≥ ρ`` for these gains, or when no rounding checks."""
    operator = Order(order).operator
    n, N = np.asarray(A).shape[0], np.asarray(W).shape[0]
    if N * n * n > EXACT_DIM:
        raise RationalizationError(f"N n² = {N * n * n} exceeds EXACT_DIM = {EXACT_DIM}")
    A_q, W_q, bound = rational_matrix(A), stochastic_matrix(W), rational_bound(rho)
    C_q = [rational_matrix(np.asarray(c, float).reshape(-1, n)) if np.size(c) else [] for c in C]
    gammas = [
        A_q if not c else fractions_of(to_fmpq(A_q) - to_fmpq(g) * to_fmpq(c))
        for g, c in zip(gains, C_q, strict=True)
    ]
    X = exact_lyapunov(operator, W_q, gammas, bound)
    if X is None:
        raise RationalizationError("I − T/ρ is singular for these gains: r_σ(T) ≥ ρ")
    reasons = []
    for P in ([_dyadic_exact(x, b) for x in X] for b in bits_ladder(ROUNDING_BITS)):
        try:
            return exact_s_detectability_certificate(
                A, C, W, gains, P, operator=operator, rho=bound, case=case
            )
        except RationalizationError as error:
            reasons.append(str(error))
    raise RationalizationError("; ".join(reasons[-1:]) or "no rounding of X checks")


class Route(StrEnum):
    """How a checked ``s-detectability`` certificate was obtained (module docstring)."""

    LMI_WITNESS = "LMI witness"
    EXACT_TUPLE = "exact Lyapunov tuple"


@dataclass(frozen=True)
class PrimalCertificate:
    """A checked ``s-detectability`` certificate, its route, and which tuple or gains."""

    document: dict[str, Any]
    route: Route
    detail: str

    @property
    def description(self) -> str:
        """E.g. ``LMI witness, dual Y rounded`` or ``the case's gains, exact Lyapunov tuple``."""
        if self.route is Route.LMI_WITNESS:
            return f"{self.route}, {self.detail}"
        return f"{self.detail}, {self.route}"


def _exact_candidates(
    A: np.ndarray, C: Sequence[np.ndarray], candidates: Sequence[tuple[str, Sequence[np.ndarray]]]
) -> list[tuple[str, list[Matrix]]]:
    out = [("projection gains L_i = A C_i⁺", projection_gains(A, C))]
    bits = bits_ladder(ROUNDING_BITS)[0]
    for label, gains in candidates:
        floats = [np.asarray(g, float) for g in gains]
        if len(floats) == len(C) and all(np.all(np.isfinite(g)) for g in floats):
            out.append((label, [dyadic_matrix(g, bits) if g.size else [] for g in floats]))
    return out


def primal_certificate(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    order: Order | str,
    rho: float = 1.0,
    witness: tuple[Sequence[np.ndarray], np.ndarray] | None = None,
    candidates: Sequence[tuple[str, Sequence[np.ndarray]]] = (),
    case: str | None = None,
) -> tuple[PrimalCertificate | None, list[str]]:
    """The first checked ``s-detectability`` certificate of the routes of the module docstring
    (``witness``: the LMI's ``(gains, Y)`` when its margin cleared ``lmi_margin``; ``candidates``:
    labelled float gains), and why each route tried before failed."""
    reasons: list[str] = []
    if witness is not None:
        gains, Y = witness
        X = primal_lyapunov(A, C, W, gains, order)
        for tuple_, dual in ((X, False), (Y, True)):
            if tuple_ is None:
                continue
            try:
                cert = s_detectability_certificate(
                    A, C, W, order, gains, list(tuple_), dual=dual, rho=rho, case=case
                )
                detail = f"{'dual Y' if dual else 'primal X'} rounded"
                return PrimalCertificate(cert, Route.LMI_WITNESS, detail), reasons
            except RationalizationError as error:
                reasons.append(f"LMI witness: {error}")
    for label, gains_q in _exact_candidates(A, C, candidates):
        try:
            cert = exact_gain_certificate(A, C, W, gains_q, order=order, rho=rho, case=case)
            return PrimalCertificate(cert, Route.EXACT_TUPLE, label), reasons
        except RationalizationError as error:
            reasons.append(f"{label}: {error}")
    return None, reasons


def certificate_gains(cert: dict[str, Any], C: Sequence[np.ndarray]) -> tuple[np.ndarray, ...]:
    """A certificate's gains as floats, ``n × p_i`` (``n × 0`` for an agent without sensor)."""
    out = []
    for g, Ci in zip(cert["witness"]["gains"], C, strict=True):
        gain = np.array([[float(Fraction(x)) for x in row] for row in g])
        out.append(gain if np.size(Ci) else gain[:, :0])
    return tuple(out)
