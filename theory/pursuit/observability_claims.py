"""Claims on range-only observability of seed 003's tracker paths (the helix (15), Result 2).

``seed003.eq15.helix`` and ``seed003.result2``, decided with the tools of
:mod:`theory.pursuit.observability` (whose module docstring states the model and both findings).

References
----------
seed 003, §III-B (Results 1 and 2, eq. (13)), eqs. (9)–(10), (15), (17)–(18), Tables I–II.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from theory.core.claims import ClaimResult, register
from theory.core.observability import RANK_TOL, RankResult, numeric_rank
from theory.pursuit.model import path as path_numeric
from theory.pursuit.observability import (
    CIRCLE_RADIUS,
    CIRCLE_RATE,
    HELIX_C_VALUES,
    INCONCLUSIVE_FACTOR,
    MIRROR_TOL,
    OFFSET,
    SAMPLING_PERIOD,
    STEPS,
    TABLE_I_PATH,
    TABLE_II_PATH,
    TABLE_SIGMA,
    helix_fim_rank,
    helix_planarity,
    helix_samples,
    helix_wronskian,
    mirror_range_gap,
    o_matrix,
    range_jacobian,
    rank_evidence,
    sampled_aliases,
    squared_range_regressor,
    sufficiency_identity,
)

__all__ = ["check_helix", "check_result2"]


# ---------------------------------------------------------------------------------------------
# the helix of eq. (15)


@register(
    "seed003.eq15.helix",
    source="seed 003 eq. (15), §III-B Result 1, eqs. (9), (17)–(18)",
    statement="c ∈ ℝ∖{0, 1} in (15) (ω₁ ≠ ω₂ ≠ 0 in Result 1) makes the helix around the target "
    "observe a constant-velocity target from range",
)
def check_helix(case: None = None, *, rank_tol: float = RANK_TOL) -> list[ClaimResult]:
    """Decide, for each c in :data:`HELIX_C_VALUES`, whether the helix (15) is degenerate.

    Symbolically (sympy): the Wronskian of the coordinates (:func:`helix_wronskian`) and the
    planarity of the orbit (:func:`helix_planarity`). Numerically, with Table II's path
    (r_x = r_y = 80 m, r_z = 50 m, ω̄ = 0.1 rad/s, γ₀ = 0), T_s = 2 s, 400 samples and σ = 0.5 m:
    the rank of the range FIM of ``(q₀, v)`` (:func:`helix_fim_rank`) and, for the planar cases,
    a pair of distinct mirror-image states with identical ranges (:func:`mirror_range_gap`).

    Parameters
    ----------
    case : None
        Model claims run on no case.
    rank_tol : float
        Relative rank tolerance of the FIM decisions.

    Returns
    -------
    list of ClaimResult
        One ``symbolic`` result: ``corrected`` when c = −1 is degenerate like c = 1 (planar,
        FIM rank 4) and every other c checked is not (FIM rank 6): the true exclusion set is
        {0, 1, −1}; ``verified`` when c = −1 is not degenerate; ``refuted`` when a c outside
        {0, ±1} is; ``inconclusive`` when a rank decision is within
        :data:`INCONCLUSIVE_FACTOR` of ``rank_tol`` or the symbolic and numeric verdicts
        disagree. The margin is the smallest factor by which a rank decision clears its
        threshold.

    References
    ----------
    seed 003, eq. (15), §III-B Result 1, eqs. (9)–(10), (17)–(18), Table II.
    """
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
            claim="seed003.eq15.helix", case="-", method="symbolic", status=status,
            evidence=evidence, margin=float(min(margins)), tolerance=tolerance, message=message,
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


@register(
    "seed003.result2",
    source="seed 003 §III-B Result 2, eq. (13), eqs. (9)–(10)",
    statement="two trackers observe a constant-velocity target's state at t₀ iff the columns of "
    "O(t) = [(p² − p¹)ᵀ, (t − t₀)(p² − p¹)ᵀ] (13) are linearly independent on [t₀, t]",
)
def check_result2(case: None = None, *, rank_tol: float = RANK_TOL) -> list[ClaimResult]:
    """Check both directions of Result 2 on a counterexample and a symbolic identity.

    "If": :func:`sufficiency_identity` (2-D and 3-D). "Only if": the counterexample
    p¹(t) = 20 (sin 0.05t, cos 0.05t), p² = p¹ + (1, 0) with a target at rest at the origin
    (T_s = 2 s, 400 samples, t₀ = 0, σ = 0.5 m): the columns of (13) are dependent (exactly, as
    functions and sampled), yet tracker 1 alone has a full-rank FIM and a full-rank
    squared-range regressor. Also shown: a moving target for the same trackers, a 3-D analogue
    (tracker 1 on Table II's helix with c = 2, p² = p¹ + (1, 0, 0)), and the paper's own N = 2
    formation (Table I path, γ₀ differing by π/2), where (13) holds and the FIM is full.

    Parameters
    ----------
    case : None
        Model claims run on no case.
    rank_tol : float
        Relative rank tolerance of the numeric rank decisions.

    Returns
    -------
    list of ClaimResult
        One ``symbolic`` result: ``corrected`` when the identity holds and the counterexample
        shows dependent columns with full-rank information (the condition is sufficient, not
        necessary); ``refuted`` if the identity fails; ``inconclusive`` when a rank decision is
        within :data:`INCONCLUSIVE_FACTOR` of ``rank_tol`` or the counterexample does not show.
        The margin is the smallest factor by which a deciding rank clears its threshold.

    References
    ----------
    seed 003, §III-B Results 1–2, eqs. (9)–(10), (13), (15)–(17), Tables I–II.
    """
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
            claim="seed003.result2", case="-", method="symbolic", status=status,
            evidence=evidence, margin=float(min(r.margin for r in ranks)),
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
