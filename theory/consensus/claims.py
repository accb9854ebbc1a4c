"""Seed 000 ch. 5 claims in the registry, and the one analysis of a ``kind: dkf`` case they share.

:func:`analyze_dkf` runs everything once per case (LMI decision, necessary conditions, radii
with the case's gains or the witness's, self-weight searches); the registered claims and
``trackcert dkf`` (:mod:`theory.consensus.dkf_report`, which also observes the case's ``expect``
keys) read from it.
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass
from typing import Any

import numpy as np

from theory.consensus.case import ORDERS
from theory.consensus.conditions import VALUE_TOL, NecessaryConditions, necessary_conditions
from theory.consensus.exact_radius import gains_stabilize
from theory.consensus.operators import (
    B_matrix,
    J_matrix,
    L_map,
    L_matrix,
    closed_loop,
    spectral_radius,
    unvec_tuple,
    vec_tuple,
)
from theory.consensus.riccati import (
    AveragedBoundCheck,
    RiccatiRun,
    check_averaged_bound,
    check_covariance_bound,
    coupled_riccati,
    riccati_gains,
)
from theory.consensus.s_detectability import (
    CERT_TOL,
    LMI_MARGIN,
    SDetectability,
    decide_s_detectability,
)
from theory.consensus.self_weight import SelfWeightSearch, max_self_weight
from theory.core.case_file import Case, load_case
from theory.core.claims import (
    DOCUMENT_KEY,
    Claim,
    ClaimResult,
    NotApplicable,
    all_claims,
    register,
)
from theory.core.expectations import matches
from theory.core.observability import RANK_TOL
from theory.core.run_cache import RunCache, shared
from theory.core.tolerances import EXACT_DIM, MAP_RTOL, PSD_TOL, RADIUS_TOL

__all__ = ["DkfAnalysis", "analyze_dkf", "case_analysis", "dkf_claim_results", "printed_match"]


@dataclass(frozen=True, eq=False)
class DkfAnalysis:
    """Everything computed about one dkf case.

    Attributes
    ----------
    case : Case
    decision : SDetectability
        LMI decision (seed 000 Def. 5.2.4).
    conditions : NecessaryConditions
        Thm 5.2.10 and the blind-set condition.
    gains : tuple of ndarray or None
        Gains used for the radii: the case's, else the witness's.
    gains_source : str
        ``case``, ``certificate`` (the gains of the exact S-detectability certificate; its route is
        in the decision's evidence), or ``eq5.8_at_identity`` (eq. (5.8) with ``Π_i = I``, used only
        when the case fixes no gains and no witness exists).
    radius_B, radius_L, radius_J : float or None
        Spectral radii with those gains.
    searches : list of (SelfWeightSearch, float) or None
        Per agent with a finite paper bound: the LMI threshold search and the paper's bound.
    riccati : RiccatiRun
        Coupled Riccati iteration from ``P_i(0) = 10 I`` for the case's order.
    tolerances : dict
    """

    case: Case
    decision: SDetectability
    conditions: NecessaryConditions
    gains: tuple[np.ndarray, ...] | None
    gains_source: str
    radius_B: float | None
    radius_L: float | None
    radius_J: float | None
    searches: list[tuple[SelfWeightSearch, float]] | None
    riccati: RiccatiRun
    tolerances: dict[str, float]

    def to_json(self) -> dict[str, Any]:
        """The DESIGN.md ``trackcert dkf --json`` object (plus evidence keys)."""
        cond = self.conditions.evidence()
        return {
            "case": self.case.name,
            "order": self.case.spec.order,
            "spectral_radius_B": self.radius_B,
            "spectral_radius_L": self.radius_L,
            "spectral_radius_J": self.radius_J,
            "gains_source": self.gains_source,
            "s_detectable": self.decision.verdict,
            "s_detectability": self.decision.evidence(),
            "source_components": [
                {"agents": s["agents"], "detectable": s["detectable"]}
                for s in cond["source_components"]
            ],
            "w_detectable": cond["w_detectable"],
            "self_weight_bounds": cond["self_weight_bounds"],
            "self_weight_ok": _all_ok([b["ok"] for b in cond["self_weight_bounds"]]),
            "blind_sets": cond["blind_sets"],
            "blind_set_condition_ok": cond["blind_set_condition"],
            "paper_conditions_ok": cond["paper_conditions"],
            "max_self_weight": None
            if self.searches is None
            else [
                {
                    "agents": list(s.agents),
                    "low": s.low,
                    "high": s.high,
                    "status": s.status,
                    "paper_bound": bound,
                    "equals_paper_bound": s.status == "found" and s.low <= bound <= s.high,
                    "weight_tol": s.weight_tol,
                }
                for s, bound in self.searches
            ],
            "riccati": {
                "status": self.riccati.status,
                "iterations": self.riccati.iterations,
                "stabilizing": self.riccati.stabilizing,
                "radius": self.riccati.radius,
                "final_norm": float(self.riccati.norms[-1]),
                "tolerances": self.riccati.tolerances,
            },
            "tolerances": dict(self.tolerances),
        }


def _all_ok(values: list[bool | None]) -> bool | None:
    if any(v is False for v in values):
        return False
    return None if any(v is None for v in values) else True


def analyze_dkf(
    case: Case, *, search_self_weight: bool = True, solver: str = "CLARABEL"
) -> DkfAnalysis:
    """Run the LMI decision, the necessary conditions and the radii on a dkf case.

    Parameters
    ----------
    case : Case
        A validated ``kind: dkf`` case; its ``tolerances`` override ``rank_tol``,
        ``lmi_margin``, ``cert_tol`` and ``value_tol``.
    search_self_weight : bool
        Whether to bisect the largest self-weight of each agent with a finite paper bound.
    solver : str
        cvxpy SDP solver.

    Returns
    -------
    DkfAnalysis

    References
    ----------
    seed 000 ch. 5 (Def. 5.2.4, Thm 5.2.10, eqs. (5.7)–(5.9)).
    """
    spec = case.spec
    tol = {
        "rank_tol": case.tolerances.get("rank_tol", RANK_TOL),
        "lmi_margin": case.tolerances.get("lmi_margin", LMI_MARGIN),
        "cert_tol": case.tolerances.get("cert_tol", CERT_TOL),
        "value_tol": case.tolerances.get("value_tol", VALUE_TOL),
    }
    riccati = coupled_riccati(
        spec.A, spec.C, spec.W, spec.Q, spec.R, 10 * np.eye(spec.n), order=spec.order
    )
    candidates = [("the case's gains", spec.L)] if spec.L is not None else []
    candidates += [("the Riccati iteration's gains", riccati.gains)] if riccati.gains else []
    decision = decide_s_detectability(
        spec.A, spec.C, spec.W, order=spec.order, solver=solver, lmi_margin=tol["lmi_margin"],
        cert_tol=tol["cert_tol"], candidate_gains=candidates, case=case.name,
    )  # fmt: skip
    conditions = necessary_conditions(
        spec.A, spec.C, spec.W, rank_tol=tol["rank_tol"], value_tol=tol["value_tol"]
    )
    gains, source = (spec.L, "case") if spec.L is not None else (decision.gains, "certificate")
    if gains is None:
        identity = np.broadcast_to(np.eye(spec.n), (spec.n_agents, spec.n, spec.n))
        gains, source = riccati_gains(spec.A, spec.C, spec.R, identity), "eq5.8_at_identity"
    radii: list[float | None] = [None, None, None]
    if gains is not None:
        Gamma = closed_loop(spec.A, spec.C, gains)
        radii = [
            spectral_radius(M)
            for M in (B_matrix(spec.W, Gamma), L_matrix(spec.W, Gamma), J_matrix(spec.W, Gamma))
        ]
    searches = None
    if search_self_weight:
        bounded = [b for b in conditions.self_weights if np.isfinite(b.bound) and b.weight < 1]
        groups = [[b] for b in bounded] + ([bounded] if len(bounded) > 1 else [])
        searches = [
            (
                max_self_weight(
                    spec.A, spec.C, spec.W, [b.agent - 1 for b in group], solver=solver
                ),
                min(b.bound for b in group),
            )
            for group in groups
        ]
    return DkfAnalysis(case, decision, conditions, gains, source, *radii, searches, riccati, tol)


def case_analysis(case: Case, cache: RunCache | None = None) -> DkfAnalysis:
    """:func:`analyze_dkf` of ``case`` without the self-weight search, once per ``cache``.

    The report runs every dkf claim of a case with one :class:`~theory.core.run_cache.RunCache`,
    so the LMI decision, the Riccati iteration and the conditions are computed once per case
    (as :func:`dkf_claim_results` does for ``trackcert dkf``).

    Parameters
    ----------
    case : Case
        A dkf case.
    cache : RunCache, optional
        The case's cache (``None``: compute).

    Returns
    -------
    DkfAnalysis
    """
    return shared(cache, "analyze_dkf", lambda: analyze_dkf(case, search_self_weight=False))


def dkf_claim_results(analysis: DkfAnalysis) -> list[tuple[Claim, ClaimResult]]:
    """Every registered claim about dkf cases, run on ``analysis.case`` with ``analysis`` passed
    to each check that takes it, so the LMI, the Riccati iteration and the conditions are
    computed once (``trackcert dkf``).

    Parameters
    ----------
    analysis : DkfAnalysis
        From :func:`analyze_dkf`.

    Returns
    -------
    list of (Claim, ClaimResult)
        In registry order; a :class:`~theory.core.claims.NotApplicable` check gives no result.
    """
    out = []
    for claim in all_claims():
        if "dkf" not in claim.kinds:
            continue
        params = inspect.signature(claim.run).parameters.values()
        takes = any(p.name == "analysis" or p.kind is p.VAR_KEYWORD for p in params)
        try:
            results = (
                claim.run(analysis.case, analysis=analysis) if takes else claim.run(analysis.case)
            )
        except NotApplicable:
            results = []
        out += [(claim, result) for result in results]
    return out


def printed_match(value: float | None, printed: float) -> bool:
    """Whether ``value`` rounds to ``printed`` at the digits the paper printed.

    The rule of :func:`theory.core.expectations.matches` for an expected float.

    Parameters
    ----------
    value : float or None
        Computed value.
    printed : float
        The paper's number, as printed (its decimals set the tolerance).
    """
    return value is not None and matches(float(printed), value)


def _status(ok: bool | None) -> str:
    return {True: "verified", False: "refuted", None: "inconclusive"}[ok]


def _result(claim: str, case: Case, method: str, ok: bool | None, evidence: dict, **kw: Any):
    return ClaimResult(claim, case.name, method, _status(ok), evidence, **kw)


@register(
    "seed000.def5.2.4",
    source="seed 000 Def. 5.2.4 (decided by LMI, docs/theory/s-detectability.md)",
    statement="(A, C, W) is S-detectable as the case expects (true when it states nothing)",
    kinds=("dkf",),
)
def _claim_s_detectable(
    case: Case, analysis: DkfAnalysis | None = None, *, cache: RunCache | None = None
) -> list[ClaimResult]:
    analysis = analysis or case_analysis(case, cache)
    verdict = analysis.decision.verdict
    expected = case.expect.get("s_detectable", True)
    ok = None if verdict is None else verdict == expected
    margin = analysis.decision.witness_margin if verdict else analysis.decision.cert_epsilon
    evidence = {"expected": expected, **analysis.decision.evidence()}
    if verdict is False:  # the exact infeasibility certificate, re-checked by the report
        evidence[DOCUMENT_KEY] = analysis.decision.certificate
    return [
        _result(
            "seed000.def5.2.4",
            case,
            "lmi",
            ok,
            evidence,
            margin=margin,
            tolerance=analysis.decision.tolerances,
            message=analysis.decision.reason,
        )
    ]


def _necessity(
    analysis: DkfAnalysis, claim: str, holds: bool | None, what: str
) -> list[ClaimResult]:
    case = analysis.case
    verdict = analysis.decision.verdict
    if verdict is True:
        ok = holds
        message = f"S-detectable and {what} {'hold' if holds else 'fail'}"
    elif verdict is False:
        ok = True
        message = f"not S-detectable; {what} {'hold (not sufficient here)' if holds else 'fail'}"
    else:
        ok, message = None, "the LMI decision is inconclusive"
    evidence = {"s_detectable": verdict, **analysis.conditions.evidence()}
    return [
        _result(claim, case, "lmi", ok, evidence, tolerance=analysis.tolerances, message=message)
    ]


@register(
    "seed000.thm5.2.10",
    source="seed 000 Thm 5.2.10",
    statement="S-detectable only if every source component is detectable and "
    "w_ii < 1/r_σ(A_iᵘ)² for every agent",
    kinds=("dkf",),
)
def _claim_thm(
    case: Case, analysis: DkfAnalysis | None = None, *, cache: RunCache | None = None
) -> list[ClaimResult]:
    analysis = analysis or case_analysis(case, cache)
    return _necessity(
        analysis, "seed000.thm5.2.10", analysis.conditions.paper_conditions,
        "Thm 5.2.10's conditions",
    )  # fmt: skip


@register(
    "seed000.thm5.2.10.blindset",
    source="trackcert, docs/theory/s-detectability.md Theorem 2 (sharpens seed 000 Thm 5.2.10)",
    statement="S-detectable only if |λ|² r_σ(W_SS) < 1 for every eigenvalue λ of A and every "
    "set S of agents blind to a common eigenvector",
    kinds=("dkf",),
)
def _claim_blindset(
    case: Case, analysis: DkfAnalysis | None = None, *, cache: RunCache | None = None
) -> list[ClaimResult]:
    analysis = analysis or case_analysis(case, cache)
    return _necessity(
        analysis,
        "seed000.thm5.2.10.blindset",
        analysis.conditions.blind_set_condition,
        "the blind-set conditions",
    )


@register(
    "seed000.lem5.2.2",
    source="seed 000 Lemma 5.2.2, App. C.3",
    statement="r_σ(L) = r_σ(diag[Γ_i ⊗ Γ_i](W ⊗ I_{n²})) = r_σ(J), and r_σ(L) < 1 iff "
    "P − L(P) > 0 for some P > 0",
    kinds=("dkf",),
)
def _claim_lemma_522(
    case: Case, analysis: DkfAnalysis | None = None, *, cache: RunCache | None = None
) -> list[ClaimResult]:
    analysis = analysis or case_analysis(case, cache)
    spec = case.spec
    if analysis.gains is None:
        return [_result("seed000.lem5.2.2", case, "numeric", None, {"gains_source": "none"})]
    Gamma = closed_loop(spec.A, spec.C, analysis.gains)
    rng = np.random.default_rng(0)
    V = rng.normal(size=(spec.n_agents, spec.n, spec.n))
    M = L_matrix(spec.W, Gamma)
    map_error = float(np.linalg.norm(M @ vec_tuple(V) - vec_tuple(L_map(spec.W, Gamma, V))))
    scale = float(np.linalg.norm(M) * np.linalg.norm(V)) + 1.0
    rL, rJ = analysis.radius_L, analysis.radius_J
    lyapunov = gains_stabilize(spec.A, spec.C, spec.W, analysis.gains, order=ORDERS[0])
    identities = map_error <= MAP_RTOL * scale and abs(rL - rJ) <= RADIUS_TOL * max(1.0, rL)
    ok = _lyapunov_agrees(identities, lyapunov, rL)
    evidence = {
        "gains_source": analysis.gains_source,
        "map_vs_kronecker_error": map_error / scale,
        "spectral_radius_L": rL,
        "spectral_radius_J": rJ,
        "lyapunov_characterization": lyapunov,
        "lyapunov_exact": spec.n_agents * spec.n**2 <= EXACT_DIM,
        "vec_convention": "column-stacking vec; tuple = [vec V_1; ...; vec V_N]",
        "seed": 0,
    }
    tolerance = {"map_rtol": MAP_RTOL, "radius_tol": RADIUS_TOL, "exact_dim": EXACT_DIM}
    margin = abs(1 - rL)  # how far the float radius is from the threshold it is compared with
    claim, tol = "seed000.lem5.2.2", tolerance
    return [_result(claim, case, "numeric", ok, evidence, margin=margin, tolerance=tol)]


def _lyapunov_agrees(identities: bool, lyapunov: bool | None, radius: float) -> bool | None:
    """Lemma 5.2.2 on the case: the float identities hold and the float radius lies on the side
    of 1 that the Lyapunov decision says (None when that decision is undecided).

    ``lyapunov`` is :func:`~theory.consensus.exact_radius.gains_stabilize`: whether
    ``X − T(X) = I`` has a positive definite solution, decided exactly (rational solve, LDLᵀ)
    when ``N n² ≤ exact_dim``; by Lemma 1 of ``docs/theory/s-detectability.md`` that is
    ``r_σ(T) < 1``. A float radius within ``radius_tol`` of 1 agrees with either answer.
    """
    if not identities:
        return False
    if lyapunov is None:
        return None
    return radius < 1 + RADIUS_TOL if lyapunov else radius > 1 - RADIUS_TOL


@register(
    "seed000.lem5.2.3",
    source="seed 000 Lemma 5.2.3, App. C.1",
    statement="with fixed gains, the error covariances of (5.5) satisfy Σ(k) ≤ P(k) of (5.15)",
    kinds=("dkf",),
)
def _claim_lemma_523(
    case: Case, analysis: DkfAnalysis | None = None, *, cache: RunCache | None = None
) -> list[ClaimResult]:
    analysis = analysis or case_analysis(case, cache)
    spec = case.spec
    if analysis.gains is None:
        return [_result("seed000.lem5.2.3", case, "simulation", None, {"gains_source": "none"})]
    check = check_covariance_bound(
        spec.A, spec.C, spec.W, spec.Q, spec.R, analysis.gains, 10 * np.eye(spec.n)
    )
    evidence = {
        "gains_source": analysis.gains_source,
        "exact_gap": check.exact_gap,
        "monte_carlo_relative_error": check.mc_error,
        "monte_carlo_violation": check.mc_violation,
        "samples": check.samples,
        "steps": check.steps,
        "seed": check.seed,
    }
    return [
        _result(
            "seed000.lem5.2.3",
            case,
            "simulation",
            check.holds,
            evidence,
            margin=check.exact_gap,
            tolerance={"psd_tol": check.psd_tol},
        )
    ]


@register(
    "seed000.lemA.2.1",
    source="seed 000 Lemma A.2.1, eqs. (A.53)–(A.54)",
    statement="if X^i > f_1^i(M, X) for some X > 0, then f_n(M, P) → 0 and "
    "P_{k+1} = f_1(M, P_k) + U stays below (α + μ/(1 − r)) X",
    kinds=("dkf",),
)
def _claim_lemma_a21(
    case: Case, analysis: DkfAnalysis | None = None, *, cache: RunCache | None = None
) -> list[ClaimResult]:
    analysis = analysis or case_analysis(case, cache)
    if analysis.gains is None:
        raise NotApplicable("no gains: the case fixes none and the LMI found no witness")
    spec = case.spec
    holds = gains_stabilize(spec.A, spec.C, spec.W, analysis.gains, order="filter-then-consensus")
    tol = {"radius_tol": RADIUS_TOL, "exact_dim": EXACT_DIM, "psd_tol": PSD_TOL}
    evidence = {"gains_source": analysis.gains_source, "spectral_radius_J": analysis.radius_J}
    if holds is False:
        raise NotApplicable(
            f"hypothesis r_σ(J) < 1 fails with the {analysis.gains_source} gains (decided "
            f"exactly when N n² ≤ {EXACT_DIM}; float r_σ(J) = {analysis.radius_J:.6g})"
        )
    if holds is None:
        message = f"r_σ(J) = {analysis.radius_J!r} is within radius_tol of 1: hypothesis undecided"
        return [_result(_A21, case, "numeric", None, evidence, tolerance=tol, message=message)]
    check = _averaged_bound(spec, analysis.gains)
    evidence |= {
        "r": check.r, "alpha": check.alpha, "mu": check.mu, "decay_ok": check.decay_ok,
        "bound_ok": check.bound_ok, "worst_ratio": check.worst_ratio, "steps": check.steps,
    }  # fmt: skip
    if not check.r < 1 - RADIUS_TOL:  # r_σ(J) < 1 exactly, but too close to 1 for floats
        message = f"r = {check.r!r} of the float X is within radius_tol of 1: conclusion undecided"
        return [_result(_A21, case, "numeric", None, evidence, tolerance=tol, message=message)]
    ok = check.decay_ok and check.bound_ok
    margin = 1 - check.worst_ratio
    return [_result(_A21, case, "numeric", ok, evidence, margin=margin, tolerance=tol)]


_A21 = "seed000.lemA.2.1"


def _averaged_bound(spec: Any, gains: tuple[np.ndarray, ...]) -> AveragedBoundCheck:
    """Lemma A.2.1's conclusions along the iteration, with ``X`` solving ``X − J(X) = I``
    (``M^j = Γ_j``, ``U_i = Q + L_i R_i L_iᵀ``, ``P_0 = 10 I``; seed 000 eqs. (A.53)–(A.54))."""
    M = closed_loop(spec.A, spec.C, gains)
    n, N = spec.n, spec.n_agents
    identity = vec_tuple(np.broadcast_to(np.eye(n), (N, n, n)))
    X = unvec_tuple(np.linalg.solve(np.eye(N * n * n) - J_matrix(spec.W, M), identity), N, n)
    X = (X + X.transpose(0, 2, 1)) / 2
    U = np.stack([spec.Q + Li @ Ri @ Li.T for Li, Ri in zip(gains, spec.R, strict=True)])
    return check_averaged_bound(spec.W, M, X, np.broadcast_to(10 * np.eye(n), (N, n, n)), U)


@register(
    "seed000.fn5",
    source="seed 000 §5.2 and footnote 5 (from [30])",
    statement="the coupled Riccati equations converge to a stabilizing solution only if "
    "(A, C, W) is S-detectable",
    kinds=("dkf",),
)
def _claim_riccati(
    case: Case, analysis: DkfAnalysis | None = None, *, cache: RunCache | None = None
) -> list[ClaimResult]:
    analysis = analysis or case_analysis(case, cache)
    run, verdict = analysis.riccati, analysis.decision.verdict
    stabilizing = run.status == "converged" and run.stabilizing
    ok = True if not stabilizing else verdict
    evidence = {
        "riccati_status": run.status,
        "iterations": run.iterations,
        "stabilizing": run.stabilizing,
        "radius": run.radius,
        "s_detectable": verdict,
        "expected_converges": case.expect.get("riccati_converges"),
    }
    return [_result("seed000.fn5", case, "numeric", ok, evidence, tolerance=dict(run.tolerances))]


@register(
    "seed000.ex5.1",
    source="seed 000 §5.3.1",
    statement="r_σ(A_1ᵘ) = r_σ(A_2ᵘ) = 2, so w_11, w_22 < 0.25; W_g works, W_c and W_b do not",
)
def _claim_example_1(_: object) -> list[ClaimResult]:
    return _example_claim("seed000.ex5.1", "ch5-example-1", ("wg", "wc", "wb"), {1: 2.0, 2: 2.0})


@register(
    "seed000.ex5.2",
    source="seed 000 §5.3.2",
    statement="r_σ(A_3ᵘ) = 1.7205, so w_33 < 0.3378; W_g works, W_b does not",
)
def _claim_example_2(_: object) -> list[ClaimResult]:
    return _example_claim("seed000.ex5.2", "ch5-example-2", ("wg", "wb"), {3: 1.7205})


def _example_claim(
    claim: str, prefix: str, variants: tuple[str, ...], radii: dict[int, float]
) -> list[ClaimResult]:
    evidence: dict[str, Any] = {}
    ok: bool | None = True
    for variant in variants:
        analysis = analyze_dkf(load_case(f"{prefix}-{variant}"))
        case = analysis.case
        bounds = {b.agent: b for b in analysis.conditions.self_weights}
        printed = {a: printed_match(bounds[a].radius, r) for a, r in radii.items()}
        bound_digits = {
            a: printed_match(bounds[a].bound, round(1 / r**2, 4)) for a, r in radii.items()
        }
        verdict, expected = analysis.decision.verdict, case.expect.get("s_detectable")
        thresholds = {
            str(list(s.agents)): {
                "low": s.low,
                "high": s.high,
                "status": s.status,
                "equals_paper_bound": s.status == "found" and s.low <= b <= s.high,
            }
            for s, b in analysis.searches or []
        }
        evidence[variant] = {
            "radii": {a: bounds[a].radius for a in radii},
            "radii_match_printed": printed,
            "bounds": {a: bounds[a].bound for a in radii},
            "bounds_match_printed": bound_digits,
            "s_detectable": verdict,
            "expected": expected,
            "lmi_thresholds": thresholds,
            "riccati": analysis.riccati.status,
        }
        good = all(printed.values()) and all(bound_digits.values())
        if verdict is None:
            ok = None if ok is True else ok
        elif not good or verdict != expected:
            ok = False
    return [ClaimResult(claim, "-", "lmi", _status(ok), evidence)]


@register(
    "seed000.counterexample5.2",
    source="seed 000 §5.2 after Def. 5.2.4 (W not printed; W = ½·11' found)",
    statement="n=1, N=2, A=C_i=1, L=(0.3, −0.25): r_σ(B) = 0.975 while r_σ(L) = 1.026",
)
def _claim_counterexample(_: object) -> list[ClaimResult]:
    analysis = analyze_dkf(load_case("ch5-counterexample"))
    rB, rL = analysis.radius_B, analysis.radius_L
    ok = printed_match(rB, 0.975) and printed_match(rL, 1.026)
    evidence = {
        "W": analysis.case.spec.W,
        "spectral_radius_B": rB,
        "spectral_radius_L": rL,
        "note": "the paper does not print W; W = [[0.5, 0.5], [0.5, 0.5]] reproduces both "
        "numbers exactly (0.975, 1.02625); r(B)² ≤ r(L) always (docs/theory/s-detectability.md)",
        "system_s_detectable": analysis.decision.verdict,
    }
    return [ClaimResult("seed000.counterexample5.2", "-", "numeric", _status(ok), evidence)]
