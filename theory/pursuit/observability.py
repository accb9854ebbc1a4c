"""Range-only observability of seed 003's tracker paths: the helix (15) and Result 2's (13).

Both claims are about a constant-velocity target ``q(t) = q₀ + t v`` (seed 003 §III-B, Result 1;
eqs. (7)–(8)) measured by range ``‖p − q‖`` (eqs. (9)–(10)). The local test is the Fisher
information of the state ``x = (q₀, v)`` at ``t₀ = 0``: with ``u_k`` the unit vector from the
target to the tracker at ``t_k``, the range's gradient is ``−h_k``, ``h_k = [u_kᵀ, t_k u_kᵀ]``,
and ``FIM = Σ_k h_kᵀ h_k / σ² = HᵀH / σ²``. Ranks are decided on the stacked ``H`` (same rank as
the FIM, square root of its condition number) with :func:`theory.core.observability.numeric_rank`.

- ``seed003.eq15.helix``: (15) excludes c ∈ {0, 1}; c = −1 is just as degenerate. For c = ±1
  every coordinate of r(γ) is a combination of cos γ and sin γ, so the orbit lies in a plane
  through the target (the Wronskian of the coordinates is r_x r_y r_z (1 − 1/c²) sin(γ/c + γ₀),
  proved with sympy), the FIM has rank 4 of 6, and a target off that plane has a mirror twin
  with identical ranges. Status ``corrected``: c ∉ {0, 1, −1}, i.e. |ω₁| ≠ |ω₂| in Result 1.
- ``seed003.result2``: the linear independence of the columns of O(t) in (13) is sufficient for
  two trackers to observe the target, not necessary: with p² = p¹ + (1, 0) the columns are
  dependent, yet p¹ circling alone observes the target (full-rank FIM, and a full-rank
  squared-range regressor, which makes the state unique). Status ``corrected``.

Both are claims about the model alone (run once); their evidence states the parameters (seed 003
§III-B, §IV-A, eqs. (7)–(10), (13), (15)–(18), §VI, Tables I–II).
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from theory.core.claims import ClaimResult, ClaimSet, Context
from theory.core.observability import RANK_TOL, RankResult, numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR, MIRROR_TOL
from theory.pursuit.model import path as path_numeric
from theory.pursuit.model import path_harmonics

__all__ = [
    "CIRCLE_RADIUS",
    "CIRCLE_RATE",
    "ESTIMATED_VELOCITY",
    "HELIX_C_VALUES",
    "MIRROR_OFFSET",
    "OFFSET",
    "SAMPLING_PERIOD",
    "STEPS",
    "TABLE_II_PATH",
    "TABLE_I_PATH",
    "TABLE_SIGMA",
    "check_helix",
    "check_result2",
    "claims",
    "fisher_information",
    "helix_fim_rank",
    "helix_planarity",
    "helix_samples",
    "helix_wronskian",
    "mirror_range_gap",
    "o_matrix",
    "range_jacobian",
    "rank_evidence",
    "sampled_aliases",
    "squared_range_regressor",
    "sufficiency_identity",
]

TABLE_II_PATH = {"r_x": 80.0, "r_y": 80.0, "r_z": 50.0, "omega_bar": 0.1}
"""S-T curve of seed 003 Table II (3-D): r_x = r_y = 80 m, r_z = 50 m, ω̄ = 0.1 rad/s."""

TABLE_I_PATH = {"r_x": 30.0, "r_y": 30.0, "omega_bar": 0.05}
"""S-T curve of seed 003 Table I (2-D): r_x = r_y = 30 m, ω̄ = 0.05 rad/s."""

TABLE_SIGMA = 0.5
"""Range noise σ = 0.5 m of Tables I–II, read as a standard deviation (docs/errata.md)."""

SAMPLING_PERIOD = 2.0
"""T_s = 2 s: "the sampling interval for range measurements is 2 seconds" (§VI, Table I)."""

STEPS = 400
"""Range samples per window (t = 0, 2, …, 798 s). The paper gives no horizon; 400 samples cover
about 12.7 turns at ω̄ = 0.1 and 6.4 at ω̄ = 0.05."""

HELIX_C_VALUES = tuple(Fraction(c) for c in (1, -1, 2, -2, Fraction(1, 2), Fraction(-1, 2)))
"""Values of c in (15) the claim checks: the excluded 1, the finding −1, and four others."""


CIRCLE_RADIUS = 20.0
"""Radius (m) of tracker 1's circle in Result 2's counterexample, p¹ = 20 (sin 0.05t, cos 0.05t)."""

CIRCLE_RATE = 0.05
"""Angular rate (rad/s) of tracker 1's circle in Result 2's counterexample."""

OFFSET = (1.0, 0.0)
"""Constant offset p² − p¹ (m) in Result 2's counterexample."""

MIRROR_OFFSET = (10.0, 0.05)
"""(a, b): the mirror pair's targets are q̂(t) ± (a + b t) n (a in m, b in m/s)."""

ESTIMATED_VELOCITY = (0.0, 0.1, -0.5)
"""Velocity (m/s) of the target estimate the tracker follows in the mirror pair (the drift of
Table II's target trajectory)."""

claims = ClaimSet()


def path(gamma: sp.Symbol, r_x, r_y, gamma0, r_z=None, c=None) -> sp.Matrix:
    """r(γ) of seed 003 eq. (15) (3D, ``r_z`` and ``c`` given) or (16) (2D), as sympy."""
    terms = path_harmonics(r_x, r_y, gamma0, r_z, c, pi=sp.pi)
    return sp.Matrix([a * sp.cos(sp.sympify(f) * gamma + phi) for a, f, phi in terms])


# ---------------------------------------------------------------------------------------------
# range-only information


def range_jacobian(relative: np.ndarray, times: np.ndarray) -> np.ndarray:
    """Rows ``h_k = [u_kᵀ, t_k u_kᵀ]``, ``u_k = relative_k / ‖relative_k‖`` (K × 2d).

    ``−h_k`` is the gradient of the range ``‖p_k − q₀ − t_k v‖`` (seed 003 eq. (9)) in the
    constant-velocity state ``(q₀, v)`` at ``t₀ = 0``, where ``p_k − q(t_k)`` is ``relative_k``;
    ValueError if the shapes disagree or a tracker sits on the target.
    """
    relative = np.atleast_2d(np.asarray(relative, dtype=float))
    times = np.asarray(times, dtype=float).reshape(-1)
    if relative.shape[0] != times.size:
        raise ValueError(
            f"relative has {relative.shape[0]} rows but times has {times.size} entries; "
            "pass one time per sample"
        )
    norms = np.linalg.norm(relative, axis=1, keepdims=True)
    if np.any(norms == 0):
        raise ValueError("a tracker coincides with the target; the range is not differentiable")
    u = relative / norms
    return np.hstack([u, times[:, None] * u])


def fisher_information(
    relative: np.ndarray, times: np.ndarray, *, sigma: float = TABLE_SIGMA
) -> np.ndarray:
    """Range-only Fisher information ``HᵀH / σ²`` of ``(q₀, v)``, seed 003 eqs. (9)–(10).

    Stack several trackers' samples to add their information.
    """
    H = range_jacobian(relative, times)
    return H.T @ H / sigma**2


def rank_evidence(H: np.ndarray, sigma: float, rank_tol: float) -> tuple[RankResult, dict]:
    """The rank decision on a stacked range Jacobian ``H`` and its FIM (HᵀH/σ²) evidence."""
    result = numeric_rank(H, rank_tol=rank_tol)
    sv = np.asarray(result.singular_values)
    evidence = {
        "rank": result.rank,
        "of": H.shape[1],
        "fim_singular_values": [float(s) for s in sv**2 / sigma**2],
        "jacobian_relative_singular_values": [float(s) for s in sv / sv[0]],
        "rank_margin": result.margin,
        "conclusive": result.conclusive(INCONCLUSIVE_FACTOR),
    }
    return result, evidence


# ---------------------------------------------------------------------------------------------
# the helix of eq. (15)


def helix_samples(
    c: float,
    *,
    r_x: float = TABLE_II_PATH["r_x"],
    r_y: float = TABLE_II_PATH["r_y"],
    r_z: float = TABLE_II_PATH["r_z"],
    gamma0: float = 0.0,
    omega_bar: float = TABLE_II_PATH["omega_bar"],
    sampling_period: float = SAMPLING_PERIOD,
    steps: int = STEPS,
) -> tuple[np.ndarray, np.ndarray]:
    """Times ``t_k = k T_s`` and tracker-minus-target ``r(ω̄ t_k)`` on the S-T curve (17).

    Table II's path by default (seed 003 eqs. (15), (17), (18)); ValueError if ``c == 0`` or
    ``steps < 1``.
    """
    if c == 0:
        raise ValueError("c = 0 makes γ/c in eq. (15) undefined; pass a non-zero c")
    if steps < 1:
        raise ValueError(f"steps must be at least 1, got {steps}")
    times = sampling_period * np.arange(steps)
    gamma = omega_bar * times
    relative = path_numeric(gamma, r_x, r_y, gamma0, r_z, float(c))
    return times, relative


def helix_fim_rank(c: float, *, rank_tol: float = RANK_TOL, **path: Any) -> RankResult:
    """Rank (of 6) of the stacked range Jacobian, i.e. of the FIM, of a tracker on the helix.

    ``**path``: the keywords of :func:`helix_samples` (seed 003 eqs. (9), (15), (17), Result 1).
    """
    times, relative = helix_samples(c, **path)
    return numeric_rank(range_jacobian(relative, times), rank_tol=rank_tol)


def helix_wronskian() -> tuple[sp.Expr, bool]:
    """The Wronskian W(γ) of the coordinates of r(γ) in seed 003 eq. (15), all constants symbolic.

    Returns W factored and whether W = r_x r_y r_z (1 − 1/c²) sin(γ/c + γ₀): then W vanishes
    identically iff c² = 1; for c² ≠ 1 the coordinates are linearly independent functions, so no
    plane through the target contains the orbit.
    """
    gamma, gamma0, c = sp.symbols("gamma gamma0 c", real=True)
    r_x, r_y, r_z = sp.symbols("r_x r_y r_z", positive=True)
    r = path(gamma, r_x, r_y, gamma0, r_z, c)
    wronskian = sp.factor(sp.simplify(sp.wronskian(list(r), gamma)))
    expected = r_x * r_y * r_z * (1 - 1 / c**2) * sp.sin(gamma / c + gamma0)
    return wronskian, sp.simplify(wronskian - expected) == 0


_WITNESS_ANGLES = tuple(sp.pi * k / 4 for k in range(8))


def helix_planarity(c: Fraction | int) -> dict[str, Any]:
    """Whether the orbit r(γ) of (15) lies in a plane through the target, decided exactly.

    For c = ±1, ``r(γ) = M [cos γ, sin γ]ᵀ`` with a 3×2 matrix ``M`` of rank 2, and
    ``det[r(γ₁), r(γ₂), r(γ₃)]`` vanishes identically in γ₁, γ₂, γ₃, γ₀ and the radii; the plane's
    normal is ``M[:, 0] × M[:, 1]``. For other c the evidence is three angles (γ₀ = 0) at which
    the determinant is a non-zero polynomial in the radii (``planar`` None when no multiple of
    π/4 is one). ValueError if ``c == 0``.
    """
    if c == 0:
        raise ValueError("c = 0 makes γ/c in eq. (15) undefined; pass a non-zero c")
    c_exact = sp.Rational(Fraction(c).numerator, Fraction(c).denominator)
    gamma, gamma0 = sp.symbols("gamma gamma0", real=True)
    r_x, r_y, r_z = sp.symbols("r_x r_y r_z", positive=True)
    if abs(c_exact) == 1:
        gammas = sp.symbols("gamma1:4", real=True)
        columns = [path(g, r_x, r_y, gamma0, r_z, c_exact) for g in gammas]
        det = sp.simplify(sp.expand_trig(sp.Matrix.hstack(*columns).det()))
        expanded = sp.expand(sp.expand_trig(path(gamma, r_x, r_y, gamma0, r_z, c_exact)))
        M = sp.Matrix([[e.coeff(sp.cos(gamma)), e.coeff(sp.sin(gamma))] for e in expanded])
        basis = sp.Matrix([sp.cos(gamma), sp.sin(gamma)])
        exact_in_basis = sp.simplify(expanded - M * basis).is_zero_matrix
        normal = sp.simplify(M[:, 0].cross(M[:, 1]))
        along = sp.simplify(normal.dot(path(gamma, r_x, r_y, gamma0, r_z, c_exact)))
        return {
            "planar": bool(det == 0 and exact_in_basis and along == 0 and M.rank() == 2),
            "det_three_points": str(det),
            "coefficients": str(M.tolist()),
            "r_equals_M_cos_sin": bool(exact_in_basis),
            "normal": str(list(normal)),
            "normal_dot_r": str(along),
        }
    for triple in itertools.combinations(_WITNESS_ANGLES, 3):
        columns = [path(g, r_x, r_y, 0, r_z, c_exact) for g in triple]
        det = sp.factor(sp.simplify(sp.Matrix.hstack(*columns).det()))
        if det != 0:
            return {
                "planar": False,
                "det_three_points": str(det),
                "witness_gammas": [str(g) for g in triple],
                "witness_gamma0": "0",
            }
    return {"planar": None, "det_three_points": "0 at every witness triple (undecided)"}


def mirror_range_gap(c: float, **path: Any) -> dict[str, Any]:
    """Ranges from the helix to two mirror-image constant-velocity targets.

    The tracker follows p_k = q̂(t_k) + r(γ_k) (eq. (17) with a target estimate
    q̂(t) = t · :data:`ESTIMATED_VELOCITY`). The two candidate targets are
    q±(t) = q̂(t) ± (a + b t) n, (a, b) = :data:`MIRROR_OFFSET`, with ``n`` the unit normal of the
    best-fitting plane through q̂ (the last right singular vector of the sampled r(γ_k)). Both are
    constant-velocity states, distinct since (a, b) ≠ 0. When the orbit is planar, n ⊥ r(γ_k)
    and ``‖r(γ_k) ∓ (a + b t_k) n‖² = ‖r(γ_k)‖² + (a + b t_k)²`` for both: identical ranges, so
    range cannot tell a target off the tracker's plane from its mirror image. (A target exactly
    on the plane, q = q̂, is still unique, but only to second order: every other state gives
    larger ranges, yet the FIM has rank 4 and the Cramér–Rao bound along ±n is infinite.)
    ``relative_gap`` is max_k |Δ range| / max_k range; ``**path`` as in :func:`helix_samples`.
    """
    times, relative = helix_samples(c, **path)
    normal = np.linalg.svd(relative)[2][-1]
    a, b = MIRROR_OFFSET
    shift = (a + b * times)[:, None] * normal
    plus = np.linalg.norm(relative - shift, axis=1)
    minus = np.linalg.norm(relative + shift, axis=1)
    gap = float(np.max(np.abs(plus - minus)))
    v_hat = np.asarray(ESTIMATED_VELOCITY)
    return {
        "relative_gap": gap / float(max(plus.max(), minus.max())),
        "max_gap_m": gap,
        "normal": [float(x) for x in normal],
        "state_plus": {"q0": list(a * normal), "v": list(v_hat + b * normal)},
        "state_minus": {"q0": list(-a * normal), "v": list(v_hat - b * normal)},
    }


def sampled_aliases(
    *, omega_bar: float = TABLE_II_PATH["omega_bar"], sampling_period: float = SAMPLING_PERIOD
) -> list[float]:
    """The first values of c ≠ ±1 at which the *sampled* orbit is planar (aliasing).

    With θ = ω̄ T_s, ``sin(θk/c + γ₀) = sin(±θk + γ₀)`` for every integer k when
    θ/c = ±θ + 2πm, so the sampled z-coordinate is a combination of cos θk and sin θk and the
    samples lie in a plane through the target. m = 0 gives c = ±1; this returns m = 1, in the
    order θ/(θ + 2π), θ/(2π − θ), and their negatives (m = −1).
    """
    theta = omega_bar * sampling_period
    first = [theta / (theta + 2 * np.pi), theta / (2 * np.pi - theta)]
    return [*first, *(-c for c in first)]


# ---------------------------------------------------------------------------------------------
# Result 2, eq. (13)


def o_matrix(difference: np.ndarray, times: np.ndarray, t0: float = 0.0) -> np.ndarray:
    """Seed 003 eq. (13) sampled: rows ``[(p² − p¹)(t_k)ᵀ, (t_k − t₀)(p² − p¹)(t_k)ᵀ]``.

    Its columns are linearly independent on ``[t₀, t]`` (as functions) when this matrix, at
    enough samples, has full column rank ``2d``; dependent columns as functions give a
    rank-deficient matrix at every sampling.
    """
    difference = np.atleast_2d(np.asarray(difference, dtype=float))
    times = np.asarray(times, dtype=float).reshape(-1)
    return np.hstack([difference, (times - t0)[:, None] * difference])


def squared_range_regressor(tracker: np.ndarray, times: np.ndarray) -> np.ndarray:
    """Regressor of the squared range, linear in θ = (q₀, v, ‖q₀‖², q₀ᵀv, ‖v‖²).

    ``‖p_k − q₀ − t_k v‖² − ‖p_k‖² = [−2p_kᵀ, −2t_k p_kᵀ, 1, 2t_k, t_k²] θ``. When this matrix has
    full column rank, two constant-velocity states with the same noise-free ranges have the same
    θ, hence the same (q₀, v): the samples determine the state uniquely (global observability).
    Columns are scaled to unit norm (which does not change the rank).
    """
    tracker = np.atleast_2d(np.asarray(tracker, dtype=float))
    t = np.asarray(times, dtype=float).reshape(-1)[:, None]
    columns = np.hstack([-2 * tracker, -2 * t * tracker, np.ones_like(t), 2 * t, t**2])
    norms = np.linalg.norm(columns, axis=0)
    return columns / np.where(norms > 0, norms, 1.0)


def sufficiency_identity(dim: int) -> bool:
    """Prove ‖p¹ − q‖² − ‖p² − q‖² = ‖p¹‖² − ‖p²‖² + 2 O(t) [q(t₀); v] symbolically.

    With q(t) = q(t₀) + (t − t₀) v and arbitrary functions p¹(t), p²(t): the right-hand side's
    first term is known, so when the columns of O(t) are linearly independent on [t₀, t] the
    state [q(t₀); v] is the unique solution of a linear equation in the two trackers' ranges.
    This is why (13) is *sufficient* (seed 003 eqs. (9), (13)).
    """
    t, t0 = sp.symbols("t t0", real=True)
    p1 = sp.Matrix([sp.Function(f"p1_{i}")(t) for i in range(dim)])
    p2 = sp.Matrix([sp.Function(f"p2_{i}")(t) for i in range(dim)])
    q0 = sp.Matrix(sp.symbols(f"q0_0:{dim}", real=True))
    v = sp.Matrix(sp.symbols(f"v_0:{dim}", real=True))
    q = q0 + (t - t0) * v
    O = sp.Matrix.hstack((p2 - p1).T, (t - t0) * (p2 - p1).T)
    lhs = (p1 - q).dot(p1 - q) - (p2 - q).dot(p2 - q)
    rhs = p1.dot(p1) - p2.dot(p2) + 2 * (O * sp.Matrix.vstack(q0, v))[0]
    return sp.expand(lhs - rhs) == 0


# ---------------------------------------------------------------------------------------------
# the helix of eq. (15)


@claims.register(
    "seed003.eq15.helix",
    source="seed 003 eq. (15), §III-B Result 1, eqs. (9), (17)–(18)",
    statement="c ∈ ℝ∖{0, 1} in (15) (ω₁ ≠ ω₂ ≠ 0 in Result 1) makes the helix around the target "
    "observe a constant-velocity target from range",
)
def check_helix(case: None, ctx: Context) -> list[ClaimResult]:
    """Whether the helix (15) is degenerate for each c of :data:`HELIX_C_VALUES` (seed 003).

    Symbolically: the Wronskian (:func:`helix_wronskian`) and planarity (:func:`helix_planarity`);
    numerically, on Table II's path with T_s = 2 s, 400 samples, σ = 0.5 m: the FIM rank of
    ``(q₀, v)`` and, for planar orbits, mirror-image states with identical ranges. ``corrected``
    when c = −1 is as degenerate as c = 1 and every other c is not (exclude {0, 1, −1});
    ``verified`` when c = −1 is not degenerate; ``refuted`` when a c outside {0, ±1} is;
    ``inconclusive`` when a rank lies in the tolerance band or the two verdicts disagree.
    """
    rank_tol = RANK_TOL
    wronskian, wronskian_ok = helix_wronskian()
    per_c, margins, decided, degenerate = _helix_per_c(rank_tol)
    mirrors_ok = all(
        per_c[str(c)]["mirror_pair"]["relative_gap"] <= MIRROR_TOL
        for c in HELIX_C_VALUES
        if degenerate[c]
    )
    evidence = _helix_evidence(per_c, wronskian, wronskian_ok, rank_tol)
    tolerance = {
        "rank_tol": rank_tol,
        "inconclusive_factor": INCONCLUSIVE_FACTOR,
        "mirror_tol": MIRROR_TOL,
    }
    others = [c for c in HELIX_C_VALUES if abs(c) != 1]
    status, message = _helix_verdict(degenerate, decided and wronskian_ok, mirrors_ok, others)
    return [
        ClaimResult(
            status, "symbolic", evidence, margin=float(min(margins)), tolerance=tolerance,
            message=message,
        )
    ]  # fmt: skip


def _helix_per_c(rank_tol: float) -> tuple[dict[str, Any], list[float], bool, dict]:
    """Symbolic planarity, FIM rank (and mirror pair) of the helix (15) for each c checked."""
    per_c: dict[str, dict[str, Any]] = {}
    margins, decided = [], True
    degenerate: dict[Fraction, bool] = {}
    for c in HELIX_C_VALUES:
        planarity = helix_planarity(c)
        times, relative = helix_samples(float(c))
        rank, evidence = rank_evidence(range_jacobian(relative, times), TABLE_SIGMA, rank_tol)
        margins.append(rank.margin)
        decided &= evidence["conclusive"] and planarity["planar"] == (rank.rank < 6)
        degenerate[c] = planarity["planar"] and rank.rank < 6
        entry: dict[str, Any] = {
            "omega1_omega2": f"ω̄, ω̄/c = {TABLE_II_PATH['omega_bar']}, "
            f"{TABLE_II_PATH['omega_bar'] / float(c):.6g} rad/s",
            "symbolic": planarity,
            "fim": evidence,
        }
        if planarity["planar"] or c == 2:
            entry["mirror_pair"] = mirror_range_gap(float(c))
        per_c[str(c)] = entry
    return per_c, margins, decided, degenerate


def _helix_evidence(per_c, wronskian, wronskian_ok: bool, rank_tol: float) -> dict[str, Any]:
    """The evidence of ``seed003.eq15.helix`` (model, parameters, per-c results, aliases)."""
    aliases = {f"{c:.6g}": helix_fim_rank(c, rank_tol=rank_tol).rank for c in sampled_aliases()}
    return {
        "model": "tracker on p_d = q + r(γ) (17), γ = ω̄ t (18), target q(t) = q₀ + t v, range "
        "‖p − q‖ (9); FIM of (q₀, v) at t₀ = 0 with rows h_k = [u_kᵀ, t_k u_kᵀ] / σ",
        "parameters": {
            **TABLE_II_PATH,
            "gamma0": 0.0,
            "sampling_period_s": SAMPLING_PERIOD,
            "steps": STEPS,
            "sigma_m": TABLE_SIGMA,
        },
        "wronskian": str(wronskian),
        "wronskian_is_rxryrz_(1-1/c^2)_sin(gamma/c+gamma0)": wronskian_ok,
        "per_c": per_c,
        "sampled_aliases_fim_rank": aliases,
        "sampled_aliases_note": "with T_s > 0 the samples are also planar at "
        "c = θ/(±θ + 2πm), θ = ω̄T_s (m = 0 is c = ±1); for Table II the first such c have "
        "|c| ≤ 0.033",
        "corrected_statement": "c ∈ ℝ∖{0, 1, −1} in (15); ω₁, ω₂ ≠ 0 and |ω₁| ≠ |ω₂| in "
        "Result 1 (ω₁ = ω̄, ω₂ = ω̄/c)",
    }


def _helix_verdict(
    degenerate: dict[Fraction, bool], decided: bool, mirrors_ok: bool, others: list[Fraction]
) -> tuple[str, str]:
    """Status and message of ``seed003.eq15.helix`` from the per-c degeneracy decisions."""
    if not decided:
        return "inconclusive", (
            "a rank decision is within the tolerance band, or the symbolic and numeric verdicts "
            "disagree; see per_c"
        )
    bad = [str(c) for c in others if degenerate[c]]
    if bad:
        return "refuted", (
            f"c = {', '.join(bad)} (allowed by (15)) gives a planar orbit and FIM rank < 6"
        )
    if not degenerate[Fraction(-1)]:
        return "verified", "c = −1 is not degenerate; every c ≠ 0, 1 checked gives FIM rank 6"
    if not mirrors_ok:
        return (
            "inconclusive",
            "c = −1 is planar but the mirror pair's ranges differ beyond mirror_tol",
        )
    return "corrected", (
        "c = −1 is as degenerate as the excluded c = 1: the orbit lies in a plane through "
        "the target (Wronskian ∝ 1 − 1/c²), the FIM has rank 4 of 6 and mirror-image "
        "states give identical ranges; c = ±2, ±1/2 give rank 6. Exclude c ∈ {0, 1, −1}"
    )


def _offset_o_matrix_symbolic(offset: tuple[float, ...]) -> tuple[str, int, int]:
    """O(t) of (13) for p² = p¹ + offset, its coefficient matrix in (1, t − t₀) and its rank."""
    t, t0 = sp.symbols("t t0", real=True)
    d = sp.Matrix([sp.nsimplify(x) for x in offset])
    O = sp.Matrix.hstack(d.T, (t - t0) * d.T)
    coefficients = sp.Matrix([[e.subs(t, t0) for e in O], [e.diff(t) for e in O]])
    return str(O.tolist()[0]), int(coefficients.rank()), O.shape[1]


def _exact_sampled_rank(offset: tuple[float, ...]) -> int:
    """Rank of the sampled (13) for a constant offset, in exact rationals (t_k = k T_s)."""
    d = [sp.nsimplify(x) for x in offset]
    period = sp.nsimplify(SAMPLING_PERIOD)
    rows = [[*d, *(k * period * x for x in d)] for k in range(STEPS)]
    return int(sp.Matrix(rows).rank())


def _circle_tracker(times: np.ndarray) -> np.ndarray:
    angle = CIRCLE_RATE * times
    return CIRCLE_RADIUS * np.stack([np.sin(angle), np.cos(angle)], axis=1)


def _pair_evidence(
    tracker1: np.ndarray,
    offset: tuple[float, ...],
    times: np.ndarray,
    target: np.ndarray,
    rank_tol: float,
) -> tuple[list[RankResult], dict[str, Any]]:
    """O's rank and the FIM of tracker 1 alone and of both trackers, p² = p¹ + offset."""
    tracker2 = tracker1 + np.asarray(offset)
    o_rank = numeric_rank(o_matrix(tracker2 - tracker1, times), rank_tol=rank_tol)
    rel1, rel2 = tracker1 - target, tracker2 - target
    one, one_ev = rank_evidence(range_jacobian(rel1, times), TABLE_SIGMA, rank_tol)
    both, both_ev = rank_evidence(
        range_jacobian(np.vstack([rel1, rel2]), np.concatenate([times, times])),
        TABLE_SIGMA,
        rank_tol,
    )
    regressor = numeric_rank(squared_range_regressor(tracker1, times), rank_tol=rank_tol)
    symbolic_o, coefficient_rank, columns = _offset_o_matrix_symbolic(offset)
    evidence = {
        "offset_p2_minus_p1": list(offset),
        "O_t_symbolic": symbolic_o,
        "O_coefficient_rank_in_basis_1_t": coefficient_rank,
        "O_columns": columns,
        "O_sampled_rank_exact": _exact_sampled_rank(offset),
        "O_sampled_rank_numeric": o_rank.rank,
        "fim_tracker1": one_ev,
        "fim_both": both_ev,
        "squared_range_regressor_rank": regressor.rank,
        "squared_range_regressor_columns": 2 * tracker1.shape[1] + 3,
        "squared_range_regressor_margin": regressor.margin,
    }
    return [one, both, regressor], evidence


@claims.register(
    "seed003.result2",
    source="seed 003 §III-B Result 2, eq. (13), eqs. (9)–(10)",
    statement="two trackers observe a constant-velocity target's state at t₀ iff the columns of "
    "O(t) = [(p² − p¹)ᵀ, (t − t₀)(p² − p¹)ᵀ] (13) are linearly independent on [t₀, t]",
)
def check_result2(case: None, ctx: Context) -> list[ClaimResult]:
    """Both directions of seed 003 Result 2: a symbolic identity and a counterexample.

    "If": :func:`sufficiency_identity`. "Only if": with p¹(t) = 20 (sin 0.05t, cos 0.05t),
    p² = p¹ + (1, 0) and a target at rest (T_s = 2 s, 400 samples, σ = 0.5 m) the columns of (13)
    are dependent, yet tracker 1 alone has full-rank FIM and squared-range regressor; also a
    moving target, a 3-D analogue on Table II's helix (c = 2) and the paper's N = 2 formation,
    where (13) holds. ``corrected`` (sufficient, not necessary) unless the identity fails
    (``refuted``) or a rank is undecided (``inconclusive``).
    """
    rank_tol = RANK_TOL
    times = SAMPLING_PERIOD * np.arange(STEPS)
    scenarios, ranks, decisive = _result2_scenarios(times, rank_tol)
    identity = {f"{dim}d": sufficiency_identity(dim) for dim in (2, 3)}
    evidence = {
        "model": "ranges ‖p^i − q‖ (9)–(10) of a constant-velocity target q(t) = q(t₀) + "
        "(t − t₀) v; FIM of (q(t₀), v) with t₀ = 0",
        "parameters": {
            "tracker1": "p¹(t) = 20 (sin 0.05t, cos 0.05t) m",
            "sampling_period_s": SAMPLING_PERIOD,
            "steps": STEPS,
            "sigma_m": TABLE_SIGMA,
        },
        "counterexamples": scenarios,
        "result1_says_tracker1_alone_observes": "p¹ is Result 1's cycloid-type trajectory with "
        "r_x = r_y = 20, ω = 0.05, c_x = c_y = 0",
        "sufficiency_identity_holds": identity,
        "paper_formation_N2": _formation_evidence(times, rank_tol),
        "corrected_statement": "if the columns of O(t) are linearly independent on [t₀, t], the "
        "state is observable from the two ranges (sufficient); the converse fails",
    }
    conclusive = all(r.conclusive(INCONCLUSIVE_FACTOR) for r in ranks)
    status, message = _result2_verdict(all(identity.values()), conclusive, decisive, scenarios)
    return [
        ClaimResult(
            status, "symbolic", evidence, margin=float(min(r.margin for r in ranks)),
            tolerance={"rank_tol": rank_tol, "inconclusive_factor": INCONCLUSIVE_FACTOR},
            message=message,
        )
    ]  # fmt: skip


def _result2_scenarios(times: np.ndarray, rank_tol: float):
    """The three counterexample scenarios to "only if", their deciding ranks and whether every
    one shows dependent columns of (13) with full-rank information."""
    tracker1 = _circle_tracker(times)
    moving_q0, moving_v = np.array([5.0, -3.0]), np.array([0.1, 0.05])
    _, helix = helix_samples(2.0)
    setups = {
        "2d_target_at_rest": (tracker1, OFFSET, np.zeros((STEPS, 2))),
        "2d_target_moving": (tracker1, OFFSET, moving_q0 + times[:, None] * moving_v),
        "3d_helix_c2_target_at_rest": (helix, (1.0, 0.0, 0.0), np.zeros((STEPS, 3))),
    }
    scenarios: dict[str, dict[str, Any]] = {}
    ranks: list[RankResult] = []
    decisive = True
    for name, (tracker, offset, target) in setups.items():
        deciding, scenario = _pair_evidence(tracker, offset, times, target, rank_tol)
        ranks += deciding
        full = 2 * (3 if name.startswith("3d") else 2)
        decisive &= (
            scenario["O_coefficient_rank_in_basis_1_t"] < full
            and scenario["O_sampled_rank_exact"] < full
            and scenario["fim_tracker1"]["rank"] == full
            and scenario["fim_both"]["rank"] == full
            and scenario["squared_range_regressor_rank"] == full + 3
        )
        scenarios[name] = scenario
    scenarios["2d_target_moving"]["target"] = {"q0": list(moving_q0), "v": list(moving_v)}
    return scenarios, ranks, decisive


def _result2_verdict(identity: bool, conclusive: bool, decisive: bool, scenarios: dict):
    """Status and message of ``seed003.result2``."""
    if not identity:
        return "refuted", "the squared-range identity behind (13) fails"
    if not conclusive:
        return "inconclusive", "a rank decision is within the tolerance band; see counterexamples"
    if not decisive:
        return "inconclusive", (
            "the counterexample does not show (see counterexamples); 'only if' undecided"
        )
    one = scenarios["2d_target_at_rest"]["fim_tracker1"]["fim_singular_values"]
    return "corrected", (
        "'only if' is false: with p² = p¹ + (1, 0), (13) has rank 2 of 4, yet tracker 1 "
        f"alone has FIM rank 4 (smallest singular value {one[-1]:.3g}); (13) is sufficient, "
        "not necessary"
    )


def _formation_evidence(times: np.ndarray, rank_tol: float) -> dict[str, Any]:
    """Table I's N = 2 formation around a target at rest: γ₀^[1] − γ₀^[2] = π/2 (§V)."""
    radius, rate = TABLE_I_PATH["r_x"], TABLE_I_PATH["omega_bar"]
    p1 = path_numeric(rate * times, radius, radius, np.pi / 2)
    p2 = path_numeric(rate * times, radius, radius, 0.0)
    o_rank = numeric_rank(o_matrix(p2 - p1, times), rank_tol=rank_tol)
    both = numeric_rank(
        range_jacobian(np.vstack([p1, p2]), np.concatenate([times, times])), rank_tol=rank_tol
    )
    return {
        "O_rank": o_rank.rank,
        "O_margin": o_rank.margin,
        "fim_both_rank": both.rank,
        "fim_both_margin": both.margin,
        "note": "(13) holds here (p² − p¹ rotates) and the FIM is full: consistent with "
        "sufficiency",
    }
