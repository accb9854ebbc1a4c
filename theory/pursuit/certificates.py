"""Exact ``iss`` certificates of pursuit cases (seed 003 Theorem 2, corrected).

:func:`iss_certificate_data` states the case's matrices and constants as exact rationals (a case
number denotes its shortest decimal, :func:`theory.core.exact.exact_decimal`) and the witness's
constants, rounded in the safe direction at ``iss_digits`` significant digits (λ below λ_min(K),
k̄ above ‖K_p‖, s above √μ, a below a(L), b above ‖R^{1/2}W‖, ρ below √r_min, κ above
√(r_max/r_min)) and moved further that way until their exact checks pass. Every inequality of
:data:`CERTIFICATE_INEQUALITIES` is re-verified exactly by :func:`verify_certificate` before the
data is returned; :func:`iss_certificate` writes the JSON certificate and has the independent
checker :mod:`proofs_check` (which re-implements the same list) accept it. A case whose
conditions fail (ε₁ = 0, a graph not strongly connected) gets no certificate.

:func:`iss_box_certificate` states the same estimate, with the same constants, for every gain of a
box (kind ``iss-box``): the case's box-independent constants are bracketed once
(:func:`loop_bounds`), and each cell's witness (:func:`box_witness`) takes every monotone bound at
the corner where it is weakest (docs/design.md, *Gain regions*).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import numpy as np

import proofs_check
from proofs_check.linalg import positive_definite
from theory.core.case_file import Case
from theory.core.certificate_format import certificate_results
from theory.core.claims import ClaimResult, ClaimSet, Context
from theory.core.errors import InconclusiveError, PropertyFails
from theory.core.exact import Matrix, exact_decimal, fractions_of, to_fmpq
from theory.core.tolerances import ISS_DIGITS, ISS_SAFE_STEPS
from theory.pursuit.case import Controller, PursuitSpec
from theory.pursuit.iss import (
    ConditionStatus,
    CoordinationIss,
    PursuitIss,
    coordination_iss,
    exact_gain_matrix,
    iss_conditions,
    orthogonal_basis,
    pursuit_iss,
    r_perp_gram,
)
from theory.pursuit.model import exact_laplacian

__all__ = [
    "BOX_STATEMENT",
    "CERTIFICATE_INEQUALITIES",
    "STATEMENT",
    "LoopBounds",
    "box_gain_below",
    "box_witness",
    "bracket",
    "claims",
    "iss_box_certificate",
    "iss_certificate",
    "iss_certificate_data",
    "loop_bounds",
    "pursuit_certificates",
    "safe_constant",
    "verify_certificate",
]

STATEMENT = (
    "seed 003 Theorem 2 (corrected): ‖ξ(t)‖ + ‖e(t)‖ ≤ β(‖μ(0)‖, t) + gain·sup‖x̃‖ with "
    "‖e(t)‖ ≤ e^(−λt)‖e(0)‖ + g_e sup‖x̃‖ and ‖ξ(t)‖ ≤ κe^(−αt)‖ξ(0)‖ + (b/ρ)∫e^(−α(t−s))‖e_γ‖ds, "
    "for the witness's λ, g_e, κ, α, b, ρ and gain"
)
"""The claim of every ``iss`` certificate (docs/theory/pursuit-iss.md §5, §7)."""

CERTIFICATE_INEQUALITIES = (
    "E1  epsilon_1 != 0 (then det(Delta Delta^T) = eps1^2*|eps|^2 > 0 in 3D, eps1^2 in 2D)",
    "E2  K = diag(K_p, k_gamma) (K_p for Type I) symmetric; K - lambda*I PSD; lambda > 0",
    "E3  kp_bar*I - K_p is positive semidefinite (kp_bar >= ||K_p||)",
    "E4  mu_r = max_i [max(r_x,r_y)^2 (+ (r_z/c)^2 in 3D)]; s >= 0 and "
    "s^2 >= kp_bar^2 + 1 + mu_r (Type II) or kp_bar^2 + 1 (Type I)",
    "E5  g_e = s / lambda  (then ||e(t)|| <= exp(-lambda t)||e(0)|| + g_e sup||x~||)",
    "C1  L = D_in - A from the edges; r^T L = 0, sum(r) = 1, r_i > 0",
    "C2  M = R L + L^T R symmetric, M_ij <= 0 (i != j), row sums 0  (hence M >= 0)",
    "C3  B^T (M - 2 a R) B positive semidefinite for B = [e_i - (r_i/r_N) e_N]_{i<N}, a > 0",
    "C4  b^2 I - W^T R W positive semidefinite, W = I - 1 r^T",
    "C5  rho > 0, rho^2 <= min_i r_i;  kappa^2 * min_i r_i >= max_i r_i",
    "C6  k_c > 0; alpha = k_c a; g_xi = b / (rho alpha) (Type II; 0 for Type I); "
    "gain = g_e (1 + g_xi)",
)
"""The exact list a checker verifies (E: pursuit subsystem, C: coordination, N > 1 only)."""

claims = ClaimSet()

# ---------------------------------------------------------------------------------------------
# rational constants, rounded in the safe direction


def _grid(x: float, digits: int) -> int:
    """Decimal exponent k so that 10^-k is about 10^-digits relative to |x|."""
    return digits - math.floor(math.log10(abs(x))) if x != 0 else digits


def _rational_above(x: float, *, digits: int = ISS_DIGITS) -> Fraction:
    """A short decimal rational ≥ x (rounded up at ``digits`` significant digits)."""
    k = _grid(x, digits)
    return Fraction(math.ceil(x * 10**k), 10**k) + Fraction(1, 10**k)


def _rational_below(x: float, *, digits: int = ISS_DIGITS) -> Fraction:
    """A short decimal rational ≤ x (rounded down at ``digits`` significant digits)."""
    k = _grid(x, digits)
    return Fraction(math.floor(x * 10**k), 10**k) - Fraction(1, 10**k)


def _sqrt_above(value: Fraction) -> Fraction:
    """A short decimal rational s ≥ √value (checked exactly)."""
    s = _rational_above(math.sqrt(float(value)))
    while s * s < value:
        s += Fraction(1, 10 ** _grid(float(s), ISS_DIGITS))
    return s


def _sqrt_below(value: Fraction) -> Fraction:
    """A short decimal rational t ≥ 0 with t² ≤ value (checked exactly)."""
    if value <= 0:
        return Fraction(0)
    t = max(_rational_below(math.sqrt(float(value))), Fraction(0))
    while t * t > value:
        t -= Fraction(1, 10 ** _grid(float(t), ISS_DIGITS))
    return max(t, Fraction(0))


def bracket(estimate: float, at_most: Callable[[Fraction], bool]) -> tuple[Fraction, Fraction]:
    """Rationals lo ≤ v < hi around a number v known exactly only through ``at_most``.

    ``at_most(x)`` decides x ≤ v exactly (e.g. K_p − xI ⪰ 0 for v = λ_min(K_p)); the float
    ``estimate`` of v is rounded at ``iss_digits`` and moved out, by doubling steps, until both
    ends pass; InconclusiveError after ``iss_safe_steps`` steps.
    """
    step = Fraction(10) ** -_grid(estimate, ISS_DIGITS)
    lo, hi = _rational_below(estimate), _rational_above(estimate)
    for _ in range(ISS_SAFE_STEPS):
        low_ok, high_ok = at_most(lo), not at_most(hi)
        if low_ok and high_ok:
            return lo, hi
        lo, hi = (lo if low_ok else lo - step), (hi if high_ok else hi + step)
        step *= 2
    raise InconclusiveError(f"no rational bracket of {estimate!r} passes its exact checks")


def safe_constant(
    estimate: Fraction, holds: Callable[[Fraction], bool], *, towards_zero: bool
) -> Fraction | None:
    """The first of ``estimate``, then halved (``towards_zero``) or doubled, that ``holds``.

    ``holds`` is the constant's exact check, monotone in the safe direction (halve a lower bound
    such as λ, double an upper bound such as b); ``None`` after ``iss_safe_steps`` moves.
    """
    value = estimate
    for _ in range(ISS_SAFE_STEPS):
        if holds(value):
            return value
        value = value / 2 if towards_zero else value * 2
    return None


# ---------------------------------------------------------------------------------------------
# the exact checks E1–E5, C1–C6


def _psd(matrix: Matrix) -> bool:
    """Exact positive semidefiniteness of a rational matrix (``False`` if it is not symmetric)."""
    n = len(matrix)
    symmetric = all(matrix[i][j] == matrix[j][i] for i in range(n) for j in range(i))
    return symmetric and positive_definite(matrix, semi=True).positive


def _shifted(matrix: Matrix, shift: Fraction) -> Matrix:
    """matrix − shift·I."""
    n = len(matrix)
    return [[matrix[i][j] - (shift if i == j else 0) for j in range(n)] for i in range(n)]


def _e2_holds(K: Matrix, lam: Fraction) -> bool:
    """E2: λ > 0 and K − λI ⪰ 0 (K symmetric)."""
    return lam > 0 and _psd(_shifted(K, lam))


def _e3_holds(K_p: Matrix, kp_bar: Fraction) -> bool:
    """E3: k̄_p I − K_p ⪰ 0."""
    return _psd([[-x for x in row] for row in _shifted(K_p, kp_bar)])


def _c3_holds(L: Matrix, r: list[Fraction], a: Fraction) -> bool:
    """C3: a > 0 and Bᵀ(M − 2aR)B ⪰ 0, M = RL + LᵀR, B the rational basis of r⊥."""
    return a > 0 and _psd(r_perp_gram(L, r, a))


def _c4_holds(r: list[Fraction], b: Fraction) -> bool:
    """C4: b ≥ 0 and b²I − WᵀRW ⪰ 0, W = I − 1rᵀ."""
    n = len(r)
    W = to_fmpq([[Fraction(int(i == j)) - r[j] for j in range(n)] for i in range(n)])
    R = to_fmpq([[r[i] if i == j else Fraction(0) for j in range(n)] for i in range(n)])
    gap = _shifted(fractions_of(W.transpose() * R * W), b * b)  # WᵀRW − b²I, must be ⪯ 0
    return b >= 0 and _psd([[-x for x in row] for row in gap])


def _rho_holds(r: list[Fraction], rho: Fraction) -> bool:
    """C5, first half: ρ > 0 and ρ² ≤ min r_i."""
    return rho > 0 and rho * rho <= min(r)


def _kappa_holds(r: list[Fraction], kappa: Fraction) -> bool:
    """C5, second half: κ² min r_i ≥ max r_i."""
    return kappa * kappa * min(r) >= max(r)


def verify_certificate(data: dict[str, Any], witness: dict[str, Any]) -> list[tuple[str, bool]]:
    """Each inequality of :data:`CERTIFICATE_INEQUALITIES` and whether it holds, exactly.

    Trackcert's own check before a certificate is emitted; ``proofs_check`` re-implements the
    same list without importing this module.
    """
    K, K_p, eps = data["K"], data["K_p"], data["epsilon"]
    lam, kp_bar, s = witness["lambda"], witness["kp_bar"], witness["s"]
    mu_paths = [
        max(p["r_x"], p["r_y"]) ** 2 + ((p["r_z"] / p["c"]) ** 2 if "r_z" in p else 0)
        for p in data["paths"]
    ]
    mu_r = max(mu_paths)
    needed = kp_bar * kp_bar + 1 + (mu_r if data["controller"] == Controller.II else 0)
    results = [
        ("E1", eps[0] != 0),
        ("E2", _e2_holds(K, lam)),
        ("E3", _e3_holds(K_p, kp_bar)),
        ("E4", witness["mu_r"] == mu_r and s >= 0 and s * s >= needed),
        ("E5", witness["g_e"] == s / lam),
    ]
    if data["n_trackers"] == 1:
        return [*results, ("C6", witness["gain"] == witness["g_e"])]
    return results + _verify_coordination(data, witness)


def _verify_coordination(data: dict[str, Any], witness: dict[str, Any]) -> list[tuple[str, bool]]:
    L = [[Fraction(x) for x in row] for row in data["laplacian"]]
    r, a, b, rho, kappa = (witness[k] for k in ("r", "a", "b", "rho", "kappa"))
    n = len(r)
    left = all(sum((r[i] * L[i][j] for i in range(n)), Fraction(0)) == 0 for j in range(n))
    c1 = left and sum(r) == 1 and all(x > 0 for x in r)
    M = [[r[i] * L[i][j] + L[j][i] * r[j] for j in range(n)] for i in range(n)]
    c2 = all(M[i][j] == M[j][i] and (i == j or M[i][j] <= 0) for i in range(n) for j in range(n))
    c2 = c2 and all(sum(row) == 0 for row in M)
    c5 = _rho_holds(r, rho) and _kappa_holds(r, kappa)
    alpha = data["k_c"] * a
    g_xi = b / (rho * alpha) if data["controller"] == Controller.II else Fraction(0)
    c6 = data["k_c"] > 0 and witness["alpha"] == alpha and witness["g_xi"] == g_xi
    c6 = c6 and witness["gain"] == witness["g_e"] * (1 + g_xi)
    checks = [("C1", c1), ("C2", c2), ("C3", _c3_holds(L, r, a)), ("C4", _c4_holds(r, b))]
    return [*checks, ("C5", c5), ("C6", c6)]


# ---------------------------------------------------------------------------------------------
# the certificate


def iss_certificate_data(spec: PursuitSpec) -> dict[str, Any]:
    """``{"data", "witness", "inequalities", "numeric"}`` of an exact ISS certificate (seed 003).

    ``data`` and ``witness`` hold Fractions (module docstring), ``numeric`` repeats the matrices
    as numpy arrays. PropertyFails if a condition of the analysis fails (the corrected Theorem 2
    does not apply), InconclusiveError if one lies inside its tolerance.
    """
    conditions = iss_conditions(spec)
    failing = [c.name for c in conditions if c.status == ConditionStatus.FAILS]
    if failing:
        raise PropertyFails(
            f"no ISS certificate: conditions {failing} do not hold (see trackcert iss)"
        )
    undecided = [c.name for c in conditions if c.status == ConditionStatus.INCONCLUSIVE]
    if undecided:
        raise InconclusiveError(f"no ISS certificate: conditions {undecided} are inconclusive")
    pursuit = pursuit_iss(spec)
    data = _pursuit_data(spec, pursuit)
    witness = _pursuit_witness(spec, pursuit)
    numeric: dict[str, Any] = {"K": pursuit.K, "lambda_min": pursuit.lambda_min}
    if spec.n_trackers > 1:
        _coordination_certificate(spec, data, witness, numeric)
    failed = [name for name, ok in verify_certificate(data, witness) if not ok]
    if failed:
        raise ValueError(f"certificate generation failed its own exact checks: {failed}")
    return {
        "data": data,
        "witness": witness,
        "inequalities": list(CERTIFICATE_INEQUALITIES),
        "numeric": numeric,
    }


def _pursuit_data(spec: PursuitSpec, pursuit: PursuitIss) -> dict[str, Any]:
    """The pursuit part of a certificate's ``data``: the case's numbers as exact rationals."""
    size = len(pursuit.K)
    return {
        "dim": spec.dim,
        "controller": spec.controller,
        "n_trackers": spec.n_trackers,
        "epsilon": [exact_decimal(x) for x in spec.epsilon],
        "K": [[exact_decimal(x) for x in row] for row in pursuit.K],
        "K_p": [[exact_decimal(x) for x in row] for row in spec.K_p],
        "P_e": [[Fraction(int(i == j), 2) for j in range(size)] for i in range(size)],
        "paths": [
            {"r_x": exact_decimal(p.r_x), "r_y": exact_decimal(p.r_y)}
            | ({} if p.r_z is None else {"r_z": exact_decimal(p.r_z), "c": exact_decimal(p.c)})
            for p in spec.trackers
        ],
    }


def _pursuit_witness(spec: PursuitSpec, pursuit: PursuitIss) -> dict[str, Any]:
    """λ below λ_min(K), k̄ above ‖K_p‖, μ_r, s ≥ √(k̄² + 1 (+ μ_r)) and g_e = s/λ (E1–E5)."""
    K = exact_gain_matrix(pursuit.K)
    K_p = exact_gain_matrix(spec.K_p)
    lam = safe_constant(
        _rational_below(pursuit.lambda_min), lambda x: _e2_holds(K, x), towards_zero=True
    )
    kp_bar = safe_constant(
        _rational_above(pursuit.norm_K_p), lambda x: _e3_holds(K_p, x), towards_zero=False
    )
    if lam is None or kp_bar is None:
        raise InconclusiveError("no rational λ or k̄_p passes its exact check (E2, E3)")
    needed = kp_bar * kp_bar + 1 + (pursuit.mu_r if spec.controller == Controller.II else 0)
    witness: dict[str, Any] = {"lambda": lam, "kp_bar": kp_bar, "mu_r": pursuit.mu_r}
    witness["s"] = _sqrt_above(needed)
    witness["g_e"] = witness["s"] / witness["lambda"]
    witness["gain"] = witness["g_e"]
    return witness


def _coordination_certificate(
    spec: PursuitSpec, data: dict[str, Any], witness: dict[str, Any], numeric: dict[str, Any]
) -> None:
    coordination = coordination_iss(spec)
    r = list(coordination.r)
    n = len(r)
    k_c = exact_decimal(spec.k_c)
    data.update({"laplacian": exact_laplacian(spec.laplacian), "k_c": k_c})
    witness.update({"r": r, **_coordination_constants(data["laplacian"], r, coordination)})
    witness["alpha"] = k_c * witness["a"]
    two_stage = spec.controller == Controller.II
    witness["g_xi"] = (
        witness["b"] / (witness["rho"] * witness["alpha"]) if two_stage else Fraction(0)
    )
    witness["gain"] = witness["g_e"] * (1 + witness["g_xi"])
    r_float = np.array([float(x) for x in r])
    numeric.update(
        {
            "R": np.diag(r_float),
            "W": np.eye(n) - np.outer(np.ones(n), r_float),
            "a_L": coordination.a_L,
            "basis_r_perp": orthogonal_basis(r_float),
        }
    )


def _coordination_constants(
    laplacian: list[list[Fraction]], r: list[Fraction], coordination: CoordinationIss
) -> dict[str, Fraction]:
    """a, b, ρ, κ rounded in the safe direction and moved until C3, C4, C5 pass exactly."""
    L = [[Fraction(x) for x in row] for row in laplacian]
    estimates = {
        "a": (_rational_below(coordination.a_L), lambda x: _c3_holds(L, r, x), True),
        "b": (_rational_above(coordination.b), lambda x: _c4_holds(r, x), False),
        "rho": (_rational_below(math.sqrt(coordination.r_min)), lambda x: _rho_holds(r, x), True),
        "kappa": (_rational_above(coordination.kappa), lambda x: _kappa_holds(r, x), False),
    }
    out = {}
    for name, (estimate, holds, towards_zero) in estimates.items():
        value = safe_constant(estimate, holds, towards_zero=towards_zero)
        if value is None:
            raise InconclusiveError(f"no rational {name} passes its exact check (C3–C5)")
        out[name] = value
    return out


def _text(value: Any) -> Any:
    """Every rational as its exact string, recursively (integers of the Laplacian included)."""
    if isinstance(value, dict):
        return {key: _text(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_text(item) for item in value]
    return str(Fraction(value))


def iss_certificate(spec: PursuitSpec, *, case: str | None = None) -> dict[str, Any]:
    """The exact ``iss`` certificate of a pursuit case, accepted by ``proofs_check``.

    PropertyFails / InconclusiveError as :func:`iss_certificate_data`; RuntimeError if
    ``proofs_check`` rejects it (a bug: trackcert's own check accepted it).
    """
    exact = iss_certificate_data(spec)
    source = exact["data"]
    data: dict[str, Any] = {
        "dim": spec.dim,
        "controller": spec.controller,
        "epsilon": _text(source["epsilon"]),
        "K_p": _text(source["K_p"]),
        "paths": _text(source["paths"]),
    }
    if spec.controller == Controller.II:
        data["k_gamma"] = _text(source["K"][spec.dim][spec.dim])
    if spec.n_trackers > 1:
        data |= {"laplacian": _text(source["laplacian"]), "k_c": _text(source["k_c"])}
    cert: dict[str, Any] = {
        "format": proofs_check.FORMAT,
        "kind": "iss",
        "source": "seed 003, Lemmas 1–4 and Theorems 1–2 (corrected)",
        **({"case": case} if case is not None else {}),
        "claim": {"statement": STATEMENT},
        "data": data,
        "witness": _text(exact["witness"]),
        "produced_by": {
            "module": "theory.pursuit.certificates",
            "rounding": f"{ISS_DIGITS} significant digits, then moved in the safe direction "
            "until each exact check passes",
        },
    }
    verdict = proofs_check.check_certificate(cert)
    if not verdict.valid:
        failed = [c.name for c in verdict.checks if not c.valid]
        raise RuntimeError(f"the iss certificate failed proofs_check (a bug): {failed}")
    return cert


# ---------------------------------------------------------------------------------------------
# the certificate over a box of gains (kind iss-box)

BOX_STATEMENT = (
    "seed 003 Theorem 2 (corrected) for every gain of the box (K_p scaled by any s in K_p_scale, "
    "k_gamma and k_c in their intervals, any epsilon with epsilon_1 in its interval): the "
    "estimate of kind iss holds with the witness's lambda, g_e, kappa, alpha, b, rho and gain"
)
"""The claim of every ``iss-box`` certificate (docs/certificates.md)."""


@dataclass(frozen=True)
class LoopBounds:
    """The case's constants no box parameter changes, as exact brackets lo ≤ v ≤ hi.

    ``lambda_p`` ∋ λ_min(K_p) and ``norm_p`` ∋ ‖K_p‖ (K_p as written, before scaling), ``mu_r``
    the exact path bound; for N > 1 the exact ``r`` and brackets of a(L), b = ‖R^{1/2}W‖ and
    √r_min, and κ ≥ √(r_max/r_min). ``data`` is the certificate's ``data`` (canonical strings).
    """

    data: dict[str, Any]
    controller: Controller
    mu_r: Fraction
    lambda_p: tuple[Fraction, Fraction]
    norm_p: tuple[Fraction, Fraction]
    r: tuple[Fraction, ...] | None = None
    a: tuple[Fraction, Fraction] | None = None
    b: tuple[Fraction, Fraction] | None = None
    rho: tuple[Fraction, Fraction] | None = None
    kappa: Fraction | None = None


def loop_bounds(spec: PursuitSpec) -> LoopBounds:
    """:class:`LoopBounds` of ``spec``, whose box-independent conditions must hold.

    InconclusiveError if a bracket does not pass its exact checks.
    """
    K_p = exact_gain_matrix(spec.K_p)
    eigenvalues = np.linalg.eigvalsh(spec.K_p)
    data: dict[str, Any] = {
        "dim": spec.dim,
        "controller": spec.controller,
        "K_p": _text(K_p),
        "paths": _text(_pursuit_data(spec, pursuit_iss(spec))["paths"]),
    }
    bounds = LoopBounds(
        data,
        spec.controller,
        pursuit_iss(spec).mu_r,
        bracket(float(eigenvalues[0]), lambda x: _psd(_shifted(K_p, x))),
        bracket(float(eigenvalues[-1]), lambda x: not _e3_holds(K_p, x)),
    )
    if spec.n_trackers == 1:
        return bounds
    coordination = coordination_iss(spec)
    r = list(coordination.r)
    L = exact_laplacian(spec.laplacian)
    data["laplacian"] = _text(L)
    return replace(
        bounds,
        r=tuple(r),
        a=bracket(coordination.a_L, lambda x: x <= 0 or _c3_holds(L, r, x)),
        b=bracket(coordination.b, lambda x: not _c4_holds(r, x)),
        rho=bracket(math.sqrt(coordination.r_min), lambda x: x <= 0 or _rho_holds(r, x)),
        kappa=bracket(coordination.kappa, lambda x: x <= 0 or not _kappa_holds(r, x))[1],
    )


Box = Mapping[str, tuple[Fraction, Fraction]]
"""A box in the names of kind ``iss-box``: ``K_p_scale``, ``epsilon_1``, ``k_gamma``, ``k_c``."""


def box_witness(bounds: LoopBounds, box: Box, *, rate: Fraction | None = None) -> dict[str, Any]:
    """The ``iss-box`` witness of ``box``: each bound at the corner where it is weakest.

    λ = min(s_lo·λ̲_p, k_γ,lo) ≤ λ_min(K), k̄_p = s_hi·k̄, α = k_c,lo·a. ``rate``, when the caller
    has decided exactly that λ_min(K) ≥ rate and k_c a(L) ≥ rate at the lowest gains, replaces
    λ and α where it is larger, so that the certificate shows the rate.
    """
    s_lo, s_hi = box["K_p_scale"]
    two_stage = bounds.controller == Controller.II
    lam = s_lo * bounds.lambda_p[0]
    if two_stage:
        lam = min(lam, box["k_gamma"][0])
    lam = max(lam, rate or 0)
    kp_bar = s_hi * bounds.norm_p[1]
    s = _sqrt_above(kp_bar * kp_bar + 1 + (bounds.mu_r if two_stage else 0))
    witness: dict[str, Any] = {"lambda": lam, "kp_bar": kp_bar, "mu_r": bounds.mu_r, "s": s}
    witness["g_e"] = witness["gain"] = s / lam
    if bounds.r is None:
        return witness
    k_c = box["k_c"][0]
    a = max(bounds.a[0], (rate or 0) / k_c)
    b, rho = bounds.b[1], bounds.rho[0]
    g_xi = b / (rho * k_c * a) if two_stage else Fraction(0)
    witness |= {"r": list(bounds.r), "a": a, "b": b, "rho": rho, "kappa": bounds.kappa}
    witness |= {"alpha": k_c * a, "g_xi": g_xi, "gain": witness["g_e"] * (1 + g_xi)}
    return witness


def box_gain_below(bounds: LoopBounds, box: Box) -> Fraction:
    """An exact lower bound of the analysis gain g_e(1 + g_ξ) (seed 003 §5) over ``box``.

    g_e = c♯/min(sλ_min(K_p), k_γ) with c♯ = √(s²‖K_p‖² + C) is at least c♯/(sλ_min(K_p)), which
    decreases in s (its value at s_hi), and at least c♯/k_γ (at s_lo, k_γ,hi); g_ξ = b/(√r_min
    k_c a(L)) is at least its value at k_c,hi. Bracket ends are taken on the side that keeps
    each bound valid.
    """
    s_lo, s_hi = box["K_p_scale"]
    two_stage = bounds.controller == Controller.II
    constant = 1 + (bounds.mu_r if two_stage else 0)
    norm = max(bounds.norm_p[0], Fraction(0))
    g_e = _sqrt_below(s_hi * s_hi * norm * norm + constant) / (s_hi * bounds.lambda_p[1])
    if two_stage:
        g_e = max(g_e, _sqrt_below(s_lo * s_lo * norm * norm + constant) / box["k_gamma"][1])
    if bounds.r is None or not two_stage:
        return g_e
    alpha = box["k_c"][1] * bounds.a[1]
    return g_e * (1 + max(bounds.b[0], Fraction(0)) / (bounds.rho[1] * alpha))


def iss_box_certificate(
    bounds: LoopBounds, box: Box, witness: dict[str, Any], *, case: str | None = None
) -> dict[str, Any]:
    """The ``iss-box`` certificate of ``box`` with ``witness``, accepted by ``proofs_check``.

    RuntimeError if ``proofs_check`` rejects it (a bug: the witness is built to pass).
    """
    cert: dict[str, Any] = {
        "format": proofs_check.FORMAT,
        "kind": "iss-box",
        "source": "seed 003, Lemmas 1–4 and Theorems 1–2 (corrected), over a box of gains",
        **({"case": case} if case is not None else {}),
        "claim": {"statement": BOX_STATEMENT, "box": _text(dict(box))},
        "data": bounds.data,
        "witness": _text(witness),
        "produced_by": {
            "module": "theory.pursuit.certificates",
            "rounding": f"{ISS_DIGITS} significant digits, each bound at its weakest corner",
        },
    }
    verdict = proofs_check.check_certificate(cert)
    if not verdict.valid:
        failed = [c.name for c in verdict.checks if not c.valid]
        raise RuntimeError(f"the iss-box certificate failed proofs_check (a bug): {failed}")
    return cert


def pursuit_certificates(case: Case, seed: int) -> tuple[list[dict[str, Any]], list[str]]:
    """The ``pursuit`` kind's certifier: the ``iss`` certificate, or why there is none.

    ``seed`` is unused (no random choice). PropertyFails if a condition of the analysis fails.
    """
    del seed
    try:
        return [iss_certificate(case.spec, case=case.name)], []
    except InconclusiveError as error:
        return [], [str(error)]


def _certified_constants(cert: dict[str, Any]) -> dict[str, Any]:
    """The witness's rates and gains, exact and approximate."""
    witness = cert["witness"]
    keys = [k for k in ("lambda", "alpha", "kappa", "g_e", "g_xi", "gain") if k in witness]
    approx = {f"{k}_approx": float(Fraction(witness[k])) for k in keys}
    return {k: witness[k] for k in keys} | approx


@claims.register(
    "seed003.thm2.certified",
    source="seed 003, Theorem 2 and Lemmas 1–4 (corrected, docs/theory/pursuit-iss.md §5, §7)",
    statement="the corrected ISS estimate of the pursuit and coordination errors is certified by "
    "exact inequalities E1–E5, C1–C6 re-derived by proofs_check (kind iss)",
    kinds=("pursuit",),
)
def check_certified(case: Case, ctx: Context) -> list[ClaimResult]:
    """The case's ``iss`` certificate, or inconclusive; not applicable when a condition fails."""
    return certificate_results(
        case, lambda: ([iss_certificate(case.spec, case=case.name)], []), _certified_constants
    )
