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

References
----------
seed 003, §III-B (Results 1 and 2, eq. (13)), §IV-A (eqs. (15), (17), (18)), eqs. (7)–(10),
§VI and Tables I–II.
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from theory.core.observability import RANK_TOL, RankResult, numeric_rank
from theory.core.tolerances import INCONCLUSIVE_FACTOR, MIRROR_TOL
from theory.pursuit.model import path as path_numeric
from theory.pursuit.model_symbolic import path

__all__ = [
    "CIRCLE_RADIUS",
    "CIRCLE_RATE",
    "ESTIMATED_VELOCITY",
    "HELIX_C_VALUES",
    "INCONCLUSIVE_FACTOR",
    "MIRROR_OFFSET",
    "MIRROR_TOL",
    "OFFSET",
    "SAMPLING_PERIOD",
    "STEPS",
    "TABLE_II_PATH",
    "TABLE_I_PATH",
    "TABLE_SIGMA",
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

HELIX_C_VALUES = (
    Fraction(1),
    Fraction(-1),
    Fraction(2),
    Fraction(-2),
    Fraction(1, 2),
    Fraction(-1, 2),
)
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


# ---------------------------------------------------------------------------------------------
# range-only information


def range_jacobian(relative: np.ndarray, times: np.ndarray) -> np.ndarray:
    """Rows ``h_k = [u_kᵀ, t_k u_kᵀ]``, ``u_k = relative_k / ‖relative_k‖``.

    ``−h_k`` is the gradient of the range ``‖p_k − q₀ − t_k v‖`` (seed 003 eq. (9)) with respect
    to the constant-velocity state ``(q₀, v)`` at ``t₀ = 0``, evaluated where ``p_k − q(t_k)`` is
    ``relative_k``.

    Parameters
    ----------
    relative : ndarray, shape (K, d)
        Tracker position minus target position at each sample.
    times : ndarray, shape (K,)
        Sample times ``t_k`` (measured from ``t₀``).

    Returns
    -------
    ndarray, shape (K, 2d)

    Raises
    ------
    ValueError
        If the shapes disagree or a tracker sits on the target (the range is not differentiable).
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
    """Range-only Fisher information ``HᵀH / σ²`` of the state ``(q₀, v)``.

    Parameters
    ----------
    relative : ndarray, shape (K, d)
        Tracker minus target position at each sample (stack several trackers' samples to add
        their information).
    times : ndarray, shape (K,)
        Sample times.
    sigma : float
        Range noise standard deviation (m).

    Returns
    -------
    ndarray, shape (2d, 2d)

    References
    ----------
    seed 003, eqs. (9)–(10) (range model) and §III-B, Result 1 (FIM as range information).
    """
    H = range_jacobian(relative, times)
    return H.T @ H / sigma**2


def rank_evidence(H: np.ndarray, sigma: float, rank_tol: float) -> tuple[RankResult, dict]:
    """The rank decision on a stacked range Jacobian ``H`` and its FIM evidence (σ: range noise).

    Parameters
    ----------
    H : ndarray
        Stacked range Jacobian (rows h_k).
    sigma : float
        Range noise standard deviation (m); FIM = HᵀH/σ².
    rank_tol : float
        Relative rank tolerance.

    Returns
    -------
    (RankResult, dict)
        The decision and its evidence (rank, FIM singular values, margin, conclusive).
    """
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
    """Sample times and tracker-minus-target positions ``r(ω̄ t_k)`` on the S-T curve (17).

    Parameters
    ----------
    c : float
        The constant of eq. (15); must be non-zero.
    r_x, r_y, r_z : float
        Path radii (m), Table II by default.
    gamma0 : float
        Phase γ₀ (rad).
    omega_bar : float
        γ̇ = ω̄ of eq. (18) (rad/s), Table II by default.
    sampling_period : float
        T_s (s).
    steps : int
        Number of samples; ``t_k = k T_s``, ``k = 0 … steps − 1``.

    Returns
    -------
    times : ndarray, shape (steps,)
    relative : ndarray, shape (steps, 3)
        ``r(γ_k)``, ``γ_k = ω̄ t_k``: the tracker on p_d = q + r(γ) of (17), minus the target.

    Raises
    ------
    ValueError
        If ``c == 0`` or ``steps < 1``.

    References
    ----------
    seed 003, eqs. (15), (17), (18).
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
    """Rank of the stacked range Jacobian (= rank of the FIM) of a tracker on the helix.

    Parameters
    ----------
    c : float
        The constant of eq. (15).
    rank_tol : float
        Relative rank tolerance (σ counts as zero when σ ≤ ``rank_tol`` · σ_max).
    **path
        ``r_x``, ``r_y``, ``r_z``, ``gamma0``, ``omega_bar``, ``sampling_period``, ``steps`` as in
        :func:`helix_samples` (Table II by default).

    Returns
    -------
    RankResult
        Rank of ``H`` (of 6) with its singular values and margin.

    References
    ----------
    seed 003, eqs. (9), (15), (17); §III-B Result 1.
    """
    times, relative = helix_samples(c, **path)
    return numeric_rank(range_jacobian(relative, times), rank_tol=rank_tol)


def helix_wronskian() -> tuple[sp.Expr, bool]:
    """Wronskian of the three coordinates of r(γ) in (15), with c, γ₀ and the radii symbolic.

    Returns
    -------
    wronskian : sympy.Expr
        ``W(γ)`` factored; it equals ``r_x r_y r_z (c − 1)(c + 1) sin(γ/c + γ₀) / c²``.
    matches : bool
        Whether ``W − r_x r_y r_z (1 − 1/c²) sin(γ/c + γ₀)`` simplifies to 0. Then W vanishes
        identically iff c² = 1; for c² ≠ 1 the coordinates are linearly independent functions,
        so no plane through the target contains the orbit.

    References
    ----------
    seed 003, eq. (15).
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
    the determinant is a non-zero polynomial in the radii.

    Parameters
    ----------
    c : Fraction or int
        The constant of eq. (15), non-zero, exact.

    Returns
    -------
    dict
        ``planar`` (bool, or None when no witness angle among multiples of π/4 is found),
        ``det_three_points`` (string), and either ``coefficients`` / ``normal`` /
        ``normal_dot_r`` (planar) or ``witness_gammas`` (not planar).

    Raises
    ------
    ValueError
        If ``c == 0``.

    References
    ----------
    seed 003, eq. (15).
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


def mirror_range_gap(
    c: float,
    *,
    r_x: float = TABLE_II_PATH["r_x"],
    r_y: float = TABLE_II_PATH["r_y"],
    r_z: float = TABLE_II_PATH["r_z"],
    gamma0: float = 0.0,
    omega_bar: float = TABLE_II_PATH["omega_bar"],
    sampling_period: float = SAMPLING_PERIOD,
    steps: int = STEPS,
) -> dict[str, Any]:
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

    Parameters
    ----------
    c : float
        The constant of eq. (15).
    r_x, r_y, r_z, gamma0, omega_bar, sampling_period, steps : float or int
        As in :func:`helix_samples`.

    Returns
    -------
    dict
        ``relative_gap`` (``max_k |Δ range| / max_k range``), ``max_gap_m``, ``normal``, the two
        states ``(q₀, v)``.

    References
    ----------
    seed 003, eqs. (9), (15), (17).
    """
    times, relative = helix_samples(
        c,
        r_x=r_x,
        r_y=r_y,
        r_z=r_z,
        gamma0=gamma0,
        omega_bar=omega_bar,
        sampling_period=sampling_period,
        steps=steps,
    )
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

    Parameters
    ----------
    omega_bar : float
        ω̄ (rad/s).
    sampling_period : float
        T_s (s).

    Returns
    -------
    list of float
    """
    theta = omega_bar * sampling_period
    first = [theta / (theta + 2 * np.pi), theta / (2 * np.pi - theta)]
    return [*first, *(-c for c in first)]


# ---------------------------------------------------------------------------------------------
# Result 2, eq. (13)


def o_matrix(difference: np.ndarray, times: np.ndarray, t0: float = 0.0) -> np.ndarray:
    """Eq. (13) sampled: rows ``O(t_k) = [(p² − p¹)(t_k)ᵀ, (t_k − t₀)(p² − p¹)(t_k)ᵀ]``.

    Its columns are linearly independent on ``[t₀, t]`` (as functions) when this matrix, at
    enough samples, has full column rank ``2d``; dependent columns as functions give a
    rank-deficient matrix at every sampling.

    Parameters
    ----------
    difference : ndarray, shape (K, d)
        ``p²(t_k) − p¹(t_k)``.
    times : ndarray, shape (K,)
        Sample times.
    t0 : float
        The initial time t₀ of (13).

    Returns
    -------
    ndarray, shape (K, 2d)

    References
    ----------
    seed 003, eq. (13).
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

    Parameters
    ----------
    tracker : ndarray, shape (K, d)
        Tracker positions p_k.
    times : ndarray, shape (K,)
        Sample times.

    Returns
    -------
    ndarray, shape (K, 2d + 3)
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
    This is why (13) is *sufficient*.

    Parameters
    ----------
    dim : int
        2 or 3.

    Returns
    -------
    bool
        Whether the difference of the two sides expands to 0.

    References
    ----------
    seed 003, eqs. (9), (13).
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
