"""Registered claims of seed 003 (cooperative pursuit, ISS analysis): ids ``seed003.*``.

Model claims (run once, case ``-``) check the paper's algebra symbolically and hold the explicit
counterexamples; case claims (``kind: pursuit``) evaluate Theorem 1, Lemmas 3–4 and Theorem 2 with
the case's gains, path and graph, stating the corrected constants.

References
----------
seed 003, eqs. (4), (21), (22), (65)–(78), Remark 6, Lemmas 1–4, Theorems 1–2.
"""

from __future__ import annotations

from typing import Any

from theory.core.claims import ClaimResult, applicable_results, get_claim, register
from theory.core.tolerances import MARGIN_TOL, VIOLATION_TOL
from theory.pursuit.iss import (
    coordination_iss,
    iss_bound,
    iss_conditions,
    pursuit_iss,
)
from theory.pursuit.iss_counterexamples import (
    eq71_strict_inequality,
    eq72_case_search,
    eq72_printed_region,
    eq74_missing_connectivity,
    eq75_missing_norm,
    xi_not_orthogonal_to_ones,
)
from theory.pursuit.iss_symbolic import (
    delta_check,
    error_dynamics_check,
    lyapunov_derivative_check,
    rotation_rate_check,
)

__all__ = ["run_case_claims", "run_model_claims"]

CASE_CLAIMS = ("seed003.thm1", "seed003.lem4", "seed003.lem3", "seed003.thm2")
MODEL_CLAIMS = (
    "seed003.eq4",
    "seed003.eq21",
    "seed003.eq22.delta-bar",
    "seed003.lem2",
    "seed003.eq70",
    "seed003.eq71",
    "seed003.eq72",
    "seed003.eq74",
    "seed003.eq75",
)


def _model(claim: str, status: str, evidence: dict[str, Any], message: str) -> list[ClaimResult]:
    return [ClaimResult(claim, "-", "symbolic", status, evidence, message=message)]


@register(
    "seed003.eq4",
    source="seed 003 eq. (4), (3), (22)",
    statement="S(ω) = [[0, −r, p], [r, 0, −q], [−p, q, 0]] satisfies Ṙ = RS(ω) and gives Δ of (22)",
)
def check_eq4(case: object = None) -> list[ClaimResult]:
    """Printed S(ω) of (4) against Ṙ = RS(ω) (Z-Y-X Euler angles) and Δ of (22)."""
    printed = rotation_rate_check(3, printed=True)
    standard = rotation_rate_check(3)
    delta = delta_check(3)
    evidence = {
        "standard_skew": "S(ω) = [[0, −r, q], [r, 0, −p], [−q, p, 0]] = [ω]ₓ",
        "rdot_equals_R_S_standard": standard.holds,
        "rdot_minus_R_S_printed_at_point": str(printed.residual),
        "point": "φ = π/6, θ = π/4, ψ = π/3, (p, q, r) = (1, 0, 0)",
        "delta22_equals_delta_from_standard_S": delta.standard_consistent,
        "delta22_equals_delta_from_printed_S": delta.printed_consistent,
        "delta_from_printed_S": str(delta.from_printed_skew.tolist()),
        "two_d": "2D (Remark 2) is consistent: S = [[0, −r], [r, 0]], Δ = [[1, ε₂], [0, −ε₁]]",
    }
    ok = standard.holds and delta.standard_consistent and not printed.holds
    status = "corrected" if ok and not delta.printed_consistent else "inconclusive"
    return _model("seed003.eq4", status, evidence, "eq. (4) swaps p and q; S(ω) = [ω]ₓ is right")


@register(
    "seed003.eq21",
    source="seed 003 eqs. (2)–(5), (19), (21)",
    statement="ė_p = −S(ω)e_p + Δu − Rᵀ(r′(γ)γ̇ + v), in 2D and 3D",
)
def check_eq21(case: object = None) -> list[ClaimResult]:
    """Eq. (21) derived from the kinematics, in 2D and 3D (Cayley rotation, exact)."""
    checks = {dim: error_dynamics_check(dim) for dim in (2, 3)}
    rates = {dim: rotation_rate_check(dim).holds for dim in (2, 3)}
    evidence = {f"{d}D": {"residual": str(c.residual), "holds": c.holds} for d, c in checks.items()}
    evidence["rdot_equals_R_S"] = {f"{d}D": h for d, h in rates.items()}
    ok = all(c.holds for c in checks.values()) and all(rates.values())
    return _model("seed003.eq21", "verified" if ok else "refuted", evidence, "eq. (21) holds")


@register(
    "seed003.eq22.delta-bar",
    source="seed 003 eq. (22), (26), Remark 6",
    statement="a non-zero ε makes Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ well defined (Remark 6)",
)
def check_delta_bar(case: object = None) -> list[ClaimResult]:
    """det(ΔΔᵀ) as a polynomial in ε, with a non-zero ε making it vanish."""
    evidence = {}
    for dim in (2, 3):
        check = delta_check(dim)
        evidence[f"{dim}D"] = {
            "det_gram": str(check.gram_determinant),
            "nonzero_epsilon_with_singular_gram": check.nonzero_epsilon_singular,
        }
    message = "Δ̄ exists iff ε₁ ≠ 0 (det ΔΔᵀ = ε₁² in 2D, ε₁²‖ε‖² in 3D), not iff ε ≠ 0"
    return _model("seed003.eq22.delta-bar", "corrected", evidence, message)


@register(
    "seed003.lem2",
    source="seed 003 Lemma 2, eqs. (24)–(26), (65)–(66)",
    statement="with the true target, V̇ = −eᵀKe for both controllers (exponential convergence)",
)
def check_lemma2(case: object = None) -> list[ClaimResult]:
    """Exact cancellation V̇ + eᵀKe = 0 in 2D/3D, Type I/II, for any symmetric K_p and any ω."""
    checks = {
        f"{d}D type {c}": lyapunov_derivative_check(d, c, False)
        for d in (2, 3)
        for c in ("I", "II")
    }
    evidence: dict[str, Any] = {k: {"residual": str(v.residual)} for k, v in checks.items()}
    evidence["proof_typos"] = [
        "λ₂(K_p) should read λ_min(K_p)",
        "(65) V₂ = ‖e‖² should read V₂ = ½‖e‖²",
        "(66) K = diag(K_p, k_z) should read diag(K_p, k_γ)",
    ]
    ok = all(c.holds for c in checks.values())
    return _model("seed003.lem2", "verified" if ok else "refuted", evidence, "V̇ = −eᵀKe exactly")


@register(
    "seed003.eq70",
    source="seed 003 eq. (70)",
    statement="V̇₂ = −eᵀKe + e_pᵀRᵀṽ + e_pᵀK_pRᵀq̃ − e_γq̃ᵀr′(γ) with estimated target",
)
def check_eq70(case: object = None) -> list[ClaimResult]:
    """Eq. (70) as an exact identity (uses RRᵀ = I via a Cayley rotation)."""
    checks = {
        f"{d}D type {c}": lyapunov_derivative_check(d, c, True) for d in (2, 3) for c in ("I", "II")
    }
    evidence = {k: {"residual": str(v.residual)} for k, v in checks.items()}
    ok = all(c.holds for c in checks.values())
    return _model("seed003.eq70", "verified" if ok else "refuted", evidence, "eq. (70) holds")


@register(
    "seed003.eq71",
    source="seed 003 eq. (71)",
    statement="‖Φ‖² < μ‖x̃‖², μ = max_γ{1, ‖r′(γ)‖²}",
)
def check_eq71(case: object = None) -> list[ClaimResult]:
    """The strict inequality fails (equality attained); ≤ holds."""
    evidence = eq71_strict_inequality()
    status = "corrected" if not evidence["printed_strict_holds"] else "verified"
    return [
        ClaimResult("seed003.eq71", "-", "exact", status, evidence, message="only ‖Φ‖² ≤ μ‖x̃‖²")
    ]


@register(
    "seed003.eq72",
    source="seed 003 eq. (72) (vs. (78))",
    statement="V̇₂ ≤ −(1−θ)λ_min(K)‖e‖² for all ‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/θ",
)
def check_eq72(case: object = None) -> list[ClaimResult]:
    """Counterexample (closed-loop V̇ from the kinematics) to the region printed in (72)."""
    evidence = eq72_printed_region()
    evidence["corrected"] = "‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/(θ λ_min(K)), as printed in (78)"
    status = "corrected" if evidence["violation"] > VIOLATION_TOL else "inconclusive"
    return [
        ClaimResult(
            "seed003.eq72", "-", "numeric", status, evidence, margin=evidence["violation"],
            tolerance={"violation_tol": VIOLATION_TOL}, message="(72) lacks the factor 1/λ_min(K)",
        )
    ]  # fmt: skip


@register(
    "seed003.eq74",
    source="seed 003 eq. (74) and the sentence before it",
    statement="ξ ⊥ 1, so by Definition 1 V̇_c ≤ −k_c r_min‖ξ‖² + ‖ξ‖‖RW‖‖e_γ‖",
)
def check_eq74(case: object = None) -> list[ClaimResult]:
    """ξ ⊥ r (not 1), and the factor a(L) is missing: exact counterexamples."""
    evidence = {
        "missing_a_L": eq74_missing_connectivity(),
        "orthogonality": xi_not_orthogonal_to_ones(),
    }
    evidence["corrected"] = "V̇_c ≤ −k_c a(L) ξᵀRξ + ‖R^{1/2}ξ‖‖R^{1/2}W‖‖e_γ‖, ξ ⊥ r"
    failed = not evidence["missing_a_L"]["printed_holds"]
    status = (
        "corrected" if failed and evidence["missing_a_L"]["corrected_holds"] else "inconclusive"
    )
    return [ClaimResult("seed003.eq74", "-", "exact", status, evidence, message="a(L) dropped")]


@register(
    "seed003.eq75",
    source="seed 003 eq. (75)",
    statement="V̇_c ≤ −k_c r_min‖ξ‖² + ‖RW‖‖e‖",
)
def check_eq75(case: object = None) -> list[ClaimResult]:
    """The first line of (75) drops ‖ξ‖ from the cross term: exact counterexample."""
    evidence = eq75_missing_norm()
    ok = not evidence["printed_holds"] and evidence["corrected_holds"]
    status = "corrected" if ok else "inconclusive"
    return [ClaimResult("seed003.eq75", "-", "exact", status, evidence, message="‖ξ‖ dropped")]


# ---------------------------------------------------------------------------------------------
# case claims


def _tol(case: Any) -> float:
    return float(case.tolerances.get("margin_tol", MARGIN_TOL))


def _failing(case: Any, status: str = "fails") -> list[str]:
    return [c.name for c in iss_conditions(case.spec, margin_tol=_tol(case)) if c.status == status]


@register(
    "seed003.thm1",
    source="seed 003 Theorem 1, eqs. (67)–(72)",
    statement="controllers (28)/(29) make the tracking error ISS w.r.t. the estimation error",
    kinds=("pursuit",),
)
def check_theorem1(case: Any) -> list[ClaimResult]:
    """Theorem 1 with the case's constants; the printed region (72) is sound iff λ_min(K) ≥ 1."""
    spec = case.spec
    pursuit = pursuit_iss(spec)
    if "delta_full_rank" in _failing(case):
        return [_refuted_delta("seed003.thm1", case)]
    evidence = pursuit.constants() | {
        "decay_rate": pursuit.decay_rate,
        "iss_gain": pursuit.gain,
        "iss_gain_paper_constants": pursuit.paper_gain,
        "beta": "‖e(0)‖·exp(−λ_min(K)·t)",
        "printed_region_argument_sound": pursuit.printed_region_sound,
        "printed_region_statement_holds_by_sharp_bound": pursuit.printed_region_holds,
        "printed_region_counterexample_search": eq72_case_search(spec),
        "corrected_region": "‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/(θ λ_min(K))",
    }
    status = "verified" if pursuit.printed_region_sound else "corrected"
    message = f"ISS with gain {pursuit.gain:.6g} and rate {pursuit.decay_rate:.6g}"
    return [
        ClaimResult(
            "seed003.thm1", case.name, "numeric", status, evidence, margin=pursuit.lambda_min,
            tolerance={"margin_tol": _tol(case)}, message=message,
        )
    ]  # fmt: skip


def _refuted_delta(claim: str, case: Any) -> ClaimResult:
    evidence = {"epsilon": case.spec.epsilon.tolist(), "reason": "ε₁ = 0: Δ̄ does not exist"}
    return ClaimResult(
        claim, case.name, "exact", "refuted", evidence, message="controller (26) undefined"
    )


@register(
    "seed003.lem4",
    source="seed 003 Lemma 4, eqs. (76)–(78)",
    statement="the stacked pursuit error of N trackers is ISS w.r.t. the stacked estimation error",
    kinds=("pursuit",),
)
def check_lemma4(case: Any) -> list[ClaimResult]:
    """Lemma 4: (78) with the case's constants (its region is the correct one)."""
    if "delta_full_rank" in _failing(case):
        return [_refuted_delta("seed003.lem4", case)]
    pursuit = pursuit_iss(case.spec)
    evidence = {
        "n_trackers": case.spec.n_trackers,
        "lyapunov": "V_e = ½ Σ‖e^[i]‖² ((76) with ½ on both terms)",
        "decay_rate": pursuit.decay_rate,
        "iss_gain": pursuit.gain,
        "iss_gain_paper_constants": pursuit.paper_gain,
        "region": "‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/(θ λ_min(K)) (as printed in (78))",
    }
    return [
        ClaimResult(
            "seed003.lem4", case.name, "numeric", "verified", evidence,
            margin=pursuit.lambda_min, tolerance={"margin_tol": _tol(case)},
            message=f"ISS with gain {pursuit.gain:.6g}",
        )
    ]  # fmt: skip


@register(
    "seed003.lem3",
    source="seed 003 Lemma 3, Lemma 1, Definition 1, eqs. (55)–(58), (73)–(75)",
    statement="for a strongly connected digraph the coordination error ξ is ISS w.r.t. e",
    kinds=("pursuit",),
)
def check_lemma3(case: Any) -> list[ClaimResult]:
    """Lemma 3 with the case's graph: corrected rate k_c·a(L), or the failure of its hypothesis."""
    spec = case.spec
    coordination = coordination_iss(spec)
    if spec.n_trackers == 1:
        evidence = {"reason": "one tracker: ξ = (1 − 1·1)γ ≡ 0"}
        message = "trivial for one tracker (ξ ≡ 0)"
        return [
            ClaimResult("seed003.lem3", case.name, "exact", "verified", evidence, message=message)
        ]
    evidence: dict[str, Any] = {
        "strongly_connected": coordination.strongly_connected,
        "zero_eigenvalue_simple": coordination.zero_eigenvalue_simple,
        "r": [str(x) for x in coordination.r] if coordination.r else None,
        "spectral_rate": coordination.spectral_rate,
    }
    if not coordination.zero_eigenvalue_simple:
        evidence["reason"] = "L has a repeated zero eigenvalue: ξ̇ = −k_cLξ does not decay"
        message = "no spanning tree: the coordination error does not converge"
        return [
            ClaimResult("seed003.lem3", case.name, "exact", "refuted", evidence, message=message)
        ]
    if coordination.a_L is None:
        evidence["reason"] = (
            "not strongly connected but the zero eigenvalue is simple: ξ still decays at the "
            "spectral rate, though r has zero entries and V_c = ½ξᵀRξ is not a Lyapunov function"
        )
        message = "hypothesis stronger than needed: a spanning tree suffices"
        return [
            ClaimResult(
                "seed003.lem3", case.name, "numeric", "corrected", evidence, message=message
            )
        ]
    evidence.update(_lemma3_constants(coordination))
    return [
        ClaimResult(
            "seed003.lem3", case.name, "numeric", "corrected", evidence, margin=coordination.a_L,
            tolerance={"margin_tol": _tol(case)},
            message=f"decay k_c a(L) = {coordination.decay_rate:.6g} (paper: k_c r_min)",
        )
    ]  # fmt: skip


def _lemma3_constants(coordination: Any) -> dict[str, Any]:
    """The corrected constants of Lemma 3 beside the printed ones (rates, gains, κ)."""
    return {
        "a_L": coordination.a_L,
        "r_min": coordination.r_min,
        "decay_rate_R_norm": coordination.decay_rate,
        "printed_decay_coefficient": coordination.printed_decay_coefficient,
        "corrected_decay_coefficient": coordination.decay_rate * coordination.r_min,
        "input_gain": coordination.gain,
        "printed_input_gain": coordination.printed_input_gain,
        "kappa": coordination.kappa,
    }


@register(
    "seed003.thm2",
    source="seed 003 Theorem 2 (cascade of Lemmas 3 and 4)",
    statement="the complete DEC error μ = (ξ, e) is ISS w.r.t. the stacked estimation error",
    kinds=("pursuit",),
)
def check_theorem2(case: Any) -> list[ClaimResult]:
    """The cascade gain from the corrected lemmas, or the failing condition."""
    failing = _failing(case)
    if failing:
        evidence = {"failing_conditions": failing}
        message = f"conditions {failing} fail: no ISS estimate for the cascade"
        return [
            ClaimResult("seed003.thm2", case.name, "numeric", "refuted", evidence, message=message)
        ]
    undecided = _failing(case, "inconclusive")
    if undecided:
        evidence = {"inconclusive_conditions": undecided}
        message = f"conditions {undecided} are inconclusive (margin below margin_tol)"
        return [
            ClaimResult(
                "seed003.thm2", case.name, "numeric", "inconclusive", evidence,
                tolerance={"margin_tol": _tol(case)}, message=message,
            )
        ]  # fmt: skip
    bound = iss_bound(case.spec)
    conditions = iss_conditions(case.spec, margin_tol=_tol(case))
    margins = [c.margin for c in conditions if c.margin is not None]
    evidence = {
        "gain": bound.gain,
        "constants": bound.constants,
        "beta": "r·[κe^{−αt} + (b/√r_min)ψ(t) + e^{−λt}]",
        "beta_at_0": bound.beta(1.0, 0.0),
    }
    return [
        ClaimResult(
            "seed003.thm2", case.name, "numeric", "verified", evidence,
            margin=min(margins, default=None), tolerance={"margin_tol": _tol(case)},
            message=f"ISS gain {bound.gain:.6g}",
        )
    ]  # fmt: skip


def run_model_claims() -> list[ClaimResult]:
    """Run every model-level seed 003 claim."""
    return [r for claim in MODEL_CLAIMS for r in applicable_results(get_claim(claim), None)]


def run_case_claims(case: Any) -> list[ClaimResult]:
    """Run every case-level seed 003 claim on ``case``."""
    return [r for claim in CASE_CLAIMS for r in applicable_results(get_claim(claim), case)]
