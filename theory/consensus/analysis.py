"""A ``kind: dkf`` case: its one analysis, the seed 000 ch. 5 claims that read it, its
certificates, and what ``trackcert dkf`` reports.

:func:`analyze_dkf` runs everything once per case (LMI decision, necessary conditions, radii with
the case's gains or the certificate's, the Riccati iteration, self-weight searches); the claims
share it through :meth:`~theory.core.claims.Context.shared` under :data:`ANALYSIS`, and
:func:`dkf_report` (``trackcert dkf``) puts its own analysis there before running them. The kind's
observer :func:`observe_dkf` reads the same analysis, so the ``case.expect.dkf`` claim and the
command agree on every expectation. The property decided (Def. 5.2.4): S-detectability,
True/False, or None when no exact certificate decides.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from theory.consensus.case import DKF, DkfSpec, Order
from theory.consensus.certificates import (
    exact_gain_certificate,
    primal_lyapunov,
    s_detectability_certificate,
)
from theory.consensus.conditions import VALUE_TOL, NecessaryConditions, necessary_conditions
from theory.consensus.operators import (
    B_matrix,
    J_matrix,
    L_map,
    L_matrix,
    closed_loop,
    float_lyapunov,
    gains_stabilize,
    spectral_radius,
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
    LmiCache,
    SDetectability,
    decide_s_detectability,
)
from theory.core.case_file import Case
from theory.core.certificate_format import Certified, certificate_results
from theory.core.claims import (
    DOCUMENT_KEY,
    Claim,
    ClaimResult,
    ClaimSet,
    Context,
    NotApplicable,
    status_of,
)
from theory.core.errors import CaseError, PropertyFails
from theory.core.exact import RationalizationError, rational_matrix
from theory.core.expectations import Expectation, Observed, expectation_claim, judge, matches
from theory.core.observability import RANK_TOL
from theory.core.tolerances import EXACT_DIM, MAP_RTOL, PSD_TOL, RADIUS_TOL
from theory.core.verdicts import all_hold

if TYPE_CHECKING:
    from theory.consensus.design import SelfWeightDesign

__all__ = [
    "ANALYSIS",
    "CERTIFIED_DECISION",
    "DkfAnalysis",
    "DkfReport",
    "analyze_dkf",
    "claims",
    "decision_certificates",
    "dkf_certificates",
    "dkf_report",
    "observe_dkf",
    "riccati_converges",
]

claims = ClaimSet()

ANALYSIS = "analyze_dkf"
"""Key of the case's :class:`DkfAnalysis` in the claims' shared cache."""

CERTIFIED_DECISION = "dkf.certified-decision"
"""Key of the decision whose certificates ``seed000.def5.2.4.certified`` reports (a command that
already decided puts its own)."""

SOLVERS = ("CLARABEL", "SCS")


@dataclass(frozen=True, eq=False)
class DkfAnalysis:
    """Everything computed about one dkf case.

    ``gains`` are those of the radii: the case's (``gains_source`` ``case``), else the exact
    certificate's (``certificate``), else eq. (5.8) at ``Π_i = I`` (``eq5.8_at_identity``);
    ``searches`` pairs each self-weight supremum (exact or bracketed) with the paper's bound;
    ``riccati`` starts from ``P_i(0) = 10 I`` in the case's order.
    """

    case: Case
    decision: SDetectability
    conditions: NecessaryConditions
    gains: tuple[np.ndarray, ...]
    gains_source: str
    radius_B: float
    radius_L: float
    radius_J: float
    searches: list[tuple[SelfWeightDesign, float]] | None
    riccati: RiccatiRun
    tolerances: dict[str, float]

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert dkf --json`` object (plus evidence keys)."""
        cond = self.conditions.evidence()
        return {
            "case": self.case.name,
            "order": self.case.spec.order.value,
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
            "self_weight_ok": all_hold([b["ok"] for b in cond["self_weight_bounds"]]),
            "blind_sets": cond["blind_sets"],
            "blind_set_condition_ok": cond["blind_set_condition"],
            "paper_conditions_ok": cond["paper_conditions"],
            "max_self_weight": None
            if self.searches is None
            else [self_weight_record(s, bound) for s, bound in self.searches],
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


def self_weight_record(design: SelfWeightDesign, paper_bound: float) -> dict[str, Any]:
    """``max_self_weight``'s entry: the supremum of ``trackcert design self-weight`` (exact, or
    its certified bracket ``[low, high]``) beside the paper's bound ``1/r_σ(A_aᵘ)²``."""
    low = 0.0 if design.below is None else float(design.below.w)
    high = 1.0 if design.at_or_above is None else float(design.at_or_above.w)
    supremum = design.supremum
    exact = supremum is not None and supremum.exact
    equal = supremum is not None and (
        abs(supremum.value - paper_bound) <= 1e-12 * max(1.0, paper_bound)
        if exact
        else low <= paper_bound <= high
    )
    return {
        "agents": list(design.agents),
        "low": low,
        "high": high,
        "status": design.status,
        "exact": exact,
        "supremum": None if supremum is None else supremum.to_json(),
        "paper_bound": paper_bound,
        "equals_paper_bound": equal,
        "weight_tol": float(design.width),
    }


def analyze_dkf(
    case: Case, *, search_self_weight: bool = True, solver: str = "CLARABEL"
) -> DkfAnalysis:
    """The LMI decision, the necessary conditions, the radii and the Riccati iteration of a dkf
    case, its ``tolerances`` overriding ``rank_tol``, ``lmi_margin``, ``cert_tol`` and
    ``value_tol``; with ``search_self_weight``, the largest self-weight of each agent with a
    finite paper bound (seed 000 Def. 5.2.4, Thm 5.2.10, eqs. (5.7)–(5.9))."""
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
    Gamma = closed_loop(spec.A, spec.C, gains)
    radii = [
        spectral_radius(M)
        for M in (B_matrix(spec.W, Gamma), L_matrix(spec.W, Gamma), J_matrix(spec.W, Gamma))
    ]
    searches = None
    if search_self_weight:
        from theory.consensus.design import self_weight_design

        bounded = [b for b in conditions.self_weights if np.isfinite(b.bound) and b.weight < 1]
        groups = [[b] for b in bounded] + ([bounded] if len(bounded) > 1 else [])
        problems = LmiCache(support=(spec.W != 0) | np.eye(spec.n_agents, dtype=bool))
        searches = [
            (
                self_weight_design(
                    case, agents=[b.agent - 1 for b in group], solver=solver, problems=problems
                ),
                min(b.bound for b in group),
            )
            for group in groups
        ]
    return DkfAnalysis(case, decision, conditions, gains, source, *radii, searches, riccati, tol)


def _analysis(case: Case, ctx: Context) -> DkfAnalysis:
    """The case's analysis without the self-weight search (no claim reads it), once per case."""
    return ctx.shared(ANALYSIS, lambda: analyze_dkf(case, search_self_weight=False))


def riccati_converges(status: str, s_detectable: bool | None) -> bool | None:
    """Whether the coupled Riccati iteration converges, never read off a float budget alone.

    Footnote 5 holds both ways for boundedness (``docs/theory/s-detectability.md`` §7): not
    S-detectable ⇒ unbounded from every ``P0 ⪰ 0``, so an exact negative verdict answers False
    whatever the iteration did within ``max_iter`` (e.g. Example 1's ``W_c``, ``r_σ = 1``, whose
    iterates grow only linearly); S-detectable ⇒ bounded, and the answer is True when the
    iteration met ``conv_tol``. Anything else — the budget ran out, a float "diverged" against a
    positive certificate, or an inconclusive decision — is None.
    """
    if s_detectable is False:
        return False
    if s_detectable is True and status == "converged":
        return True
    return None


def _observed(analysis: DkfAnalysis) -> Observed:
    """Every dkf expect key read off the ``--json`` record (``None`` values are undecided)."""
    data = analysis.to_json()
    values = {key: data.get(key) for key in DKF.expect_keys}
    values["riccati_converges"] = riccati_converges(data["riccati"]["status"], data["s_detectable"])
    return Observed(values, frozenset(k for k, v in values.items() if v is None))


def observe_dkf(case: Case, ctx: Context) -> Observed:
    """The observer of ``kind: dkf``: the expect keys of the analysis the dkf claims share."""
    return _observed(_analysis(case, ctx))


@dataclass(frozen=True)
class DkfReport:
    """The record ``trackcert dkf`` prints: the analysis, every dkf claim's results (with its
    claim) and the case's ``expect`` block judged against the analysis."""

    analysis: DkfAnalysis
    claims: tuple[tuple[Claim, ClaimResult], ...]
    expectations: tuple[Expectation, ...]

    @property
    def verdict(self) -> bool | None:
        """S-detectable (True/False), or None when no exact certificate decides."""
        return self.analysis.decision.verdict

    def to_json(self) -> dict[str, Any]:
        """The ``--json`` record, with ``expectations`` and ``claims``."""
        return {
            **self.analysis.to_json(),
            "expectations": [e.to_json() for e in self.expectations],
            "claims": [r.to_json(claim.source) for claim, r in self.claims],
        }


def dkf_report(
    case: Case,
    checks: Sequence[Claim],
    *,
    search_self_weight: bool = True,
    solver: str = "CLARABEL",
) -> DkfReport:
    """Analyze ``case`` once, run ``checks`` (every claim about dkf cases, in id order) on that
    analysis and judge its expectations (``trackcert dkf``); :class:`CaseError` for another kind
    or an unknown solver."""
    if case.kind != "dkf":
        raise CaseError("kind", "dkf", case.kind, file=case.file)
    if solver not in SOLVERS:
        raise CaseError("--solver", " or ".join(SOLVERS), solver, file=case.file)
    analysis = analyze_dkf(case, search_self_weight=search_self_weight, solver=solver)
    ctx = Context()
    ctx.cache.put(ANALYSIS, analysis)
    ctx.cache.put(CERTIFIED_DECISION, analysis.decision)
    ran = [(claim, result) for claim in checks for result in claim.results(case, ctx)]
    expectations = judge(case, _observed(analysis), source="trackcert dkf")
    return DkfReport(analysis, tuple(ran), tuple(expectations))


def _printed(value: float | None, printed: float) -> bool:
    """Whether ``value`` rounds to ``printed`` at the digits the paper printed."""
    return value is not None and matches(float(printed), value)


@claims.register(
    "seed000.def5.2.4",
    source="seed 000 Def. 5.2.4 (decided by LMI, docs/theory/s-detectability.md)",
    statement="(A, C, W) is S-detectable as the case expects (true when it states nothing)",
    kinds=("dkf",),
    shares_work=True,
)
def _claim_s_detectable(case: Case, ctx: Context) -> list[ClaimResult]:
    decision = _analysis(case, ctx).decision
    expected = case.expect.get("s_detectable", True)
    ok = None if decision.verdict is None else decision.verdict == expected
    margin = decision.witness_margin if decision.verdict else decision.lmi.cert_epsilon
    evidence = {"expected": expected, **decision.evidence()}
    if decision.verdict is False:  # the exact infeasibility certificate, re-checked by the report
        evidence[DOCUMENT_KEY] = decision.certificate
    return [
        ClaimResult(
            status_of(ok), "lmi", evidence, margin=margin, tolerance=decision.tolerances,
            message=decision.reason,
        )
    ]  # fmt: skip


def _necessity(analysis: DkfAnalysis, holds: bool | None, what: str) -> list[ClaimResult]:
    """A necessary condition agrees with the decision: it holds whenever S-detectable."""
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
    tolerance = analysis.tolerances
    return [ClaimResult(status_of(ok), "lmi", evidence, tolerance=tolerance, message=message)]


@claims.register(
    "seed000.thm5.2.10",
    source="seed 000 Thm 5.2.10",
    statement="S-detectable only if every source component is detectable and "
    "w_ii < 1/r_σ(A_iᵘ)² for every agent",
    kinds=("dkf",),
    shares_work=True,
)
def _claim_thm(case: Case, ctx: Context) -> list[ClaimResult]:
    analysis = _analysis(case, ctx)
    return _necessity(analysis, analysis.conditions.paper_conditions, "Thm 5.2.10's conditions")


@claims.register(
    "seed000.thm5.2.10.blindset",
    source="trackcert, docs/theory/s-detectability.md Theorem 2 (sharpens seed 000 Thm 5.2.10)",
    statement="S-detectable only if |λ|² r_σ(W_SS) < 1 for every eigenvalue λ of A and every "
    "set S of agents blind to a common eigenvector",
    kinds=("dkf",),
    shares_work=True,
)
def _claim_blindset(case: Case, ctx: Context) -> list[ClaimResult]:
    analysis = _analysis(case, ctx)
    holds = analysis.conditions.blind_set_condition
    return _necessity(analysis, holds, "the blind-set conditions")


@claims.register(
    "seed000.lem5.2.2",
    source="seed 000 Lemma 5.2.2, App. C.3",
    statement="r_σ(L) = r_σ(diag[Γ_i ⊗ Γ_i](W ⊗ I_{n²})) = r_σ(J), and r_σ(L) < 1 iff "
    "P − L(P) > 0 for some P > 0",
    kinds=("dkf",),
    shares_work=True,
)
def _claim_lemma_522(case: Case, ctx: Context) -> list[ClaimResult]:
    analysis, spec = _analysis(case, ctx), case.spec
    Gamma = closed_loop(spec.A, spec.C, analysis.gains)
    V = np.random.default_rng(0).normal(size=(spec.n_agents, spec.n, spec.n))
    M = L_matrix(spec.W, Gamma)
    map_error = float(np.linalg.norm(M @ vec_tuple(V) - vec_tuple(L_map(spec.W, Gamma, V))))
    scale = float(np.linalg.norm(M) * np.linalg.norm(V)) + 1.0
    rL, rJ = analysis.radius_L, analysis.radius_J
    lyapunov = gains_stabilize(
        spec.A, spec.C, spec.W, analysis.gains, order=Order.CONSENSUS_THEN_FILTER
    )
    identities = map_error <= MAP_RTOL * scale and abs(rL - rJ) <= RADIUS_TOL * max(1.0, rL)
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
    ok = _lyapunov_agrees(identities, lyapunov, rL)
    margin = abs(1 - rL)  # how far the float radius is from the threshold it is compared with
    return [ClaimResult(status_of(ok), "numeric", evidence, margin=margin, tolerance=tolerance)]


def _lyapunov_agrees(identities: bool, lyapunov: bool | None, radius: float) -> bool | None:
    """Lemma 5.2.2 on the case: the float identities hold and the float radius lies on the side
    of 1 that the exact Lyapunov decision (``X − T(X) = I`` has a positive definite solution iff
    ``r_σ(T) < 1``) says; a float radius within ``radius_tol`` of 1 agrees with either answer."""
    if not identities:
        return False
    if lyapunov is None:
        return None
    return radius < 1 + RADIUS_TOL if lyapunov else radius > 1 - RADIUS_TOL


@claims.register(
    "seed000.lem5.2.3",
    source="seed 000 Lemma 5.2.3, App. C.1",
    statement="with fixed gains, the error covariances of (5.5) satisfy Σ(k) ≤ P(k) of (5.15)",
    kinds=("dkf",),
    shares_work=True,
)
def _claim_lemma_523(case: Case, ctx: Context) -> list[ClaimResult]:
    analysis, spec = _analysis(case, ctx), case.spec
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
        ClaimResult(
            status_of(check.holds), "simulation", evidence, margin=check.exact_gap,
            tolerance={"psd_tol": check.psd_tol},
        )
    ]  # fmt: skip


@claims.register(
    "seed000.lemA.2.1",
    source="seed 000 Lemma A.2.1, eqs. (A.53)–(A.54)",
    statement="if X^i > f_1^i(M, X) for some X > 0, then f_n(M, P) → 0 and "
    "P_{k+1} = f_1(M, P_k) + U stays below (α + μ/(1 − r)) X",
    kinds=("dkf",),
    shares_work=True,
)
def _claim_lemma_a21(case: Case, ctx: Context) -> list[ClaimResult]:
    analysis, spec = _analysis(case, ctx), case.spec
    order = Order.FILTER_THEN_CONSENSUS
    holds = gains_stabilize(spec.A, spec.C, spec.W, analysis.gains, order=order)
    tol = {"radius_tol": RADIUS_TOL, "exact_dim": EXACT_DIM, "psd_tol": PSD_TOL}
    evidence = {"gains_source": analysis.gains_source, "spectral_radius_J": analysis.radius_J}
    if holds is False:
        raise NotApplicable(
            f"hypothesis r_σ(J) < 1 fails with the {analysis.gains_source} gains (decided "
            f"exactly when N n² ≤ {EXACT_DIM}; float r_σ(J) = {analysis.radius_J:.6g})"
        )
    if holds is None:
        message = f"r_σ(J) = {analysis.radius_J!r} is within radius_tol of 1: hypothesis undecided"
        return [ClaimResult(status_of(None), "numeric", evidence, tolerance=tol, message=message)]
    check = _averaged_bound(spec, analysis.gains)
    evidence |= {
        "r": check.r, "alpha": check.alpha, "mu": check.mu, "decay_ok": check.decay_ok,
        "bound_ok": check.bound_ok, "worst_ratio": check.worst_ratio, "steps": check.steps,
    }  # fmt: skip
    if not check.r < 1 - RADIUS_TOL:  # r_σ(J) < 1 exactly, but too close to 1 for floats
        message = f"r = {check.r!r} of the float X is within radius_tol of 1: conclusion undecided"
        return [ClaimResult(status_of(None), "numeric", evidence, tolerance=tol, message=message)]
    ok, margin = check.decay_ok and check.bound_ok, 1 - check.worst_ratio
    return [ClaimResult(status_of(ok), "numeric", evidence, margin=margin, tolerance=tol)]


def _averaged_bound(spec: DkfSpec, gains: tuple[np.ndarray, ...]) -> AveragedBoundCheck:
    """Lemma A.2.1's conclusions along the iteration, with ``X`` solving ``X − J(X) = I``
    (``M^j = Γ_j``, ``U_i = Q + L_i R_i L_iᵀ``, ``P_0 = 10 I``; seed 000 eqs. (A.53)–(A.54))."""
    M = closed_loop(spec.A, spec.C, gains)
    n, N = spec.n, spec.n_agents
    X = float_lyapunov(J_matrix(spec.W, M), N, n)
    U = np.stack([spec.Q + Li @ Ri @ Li.T for Li, Ri in zip(gains, spec.R, strict=True)])
    return check_averaged_bound(spec.W, M, X, np.broadcast_to(10 * np.eye(n), (N, n, n)), U)


@claims.register(
    "seed000.fn5",
    source="seed 000 §5.2 and footnote 5 (from [30])",
    statement="the coupled Riccati equations converge to a stabilizing solution only if "
    "(A, C, W) is S-detectable",
    kinds=("dkf",),
    shares_work=True,
)
def _claim_riccati(case: Case, ctx: Context) -> list[ClaimResult]:
    analysis = _analysis(case, ctx)
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
    return [ClaimResult(status_of(ok), "numeric", evidence, tolerance=dict(run.tolerances))]


@claims.register(
    "seed000.ex5.1",
    source="seed 000 §5.3.1",
    statement="r_σ(A_1ᵘ) = r_σ(A_2ᵘ) = 2, so w_11, w_22 < 0.25; W_g works, W_c and W_b do not",
)
def _claim_example_1(case: None, ctx: Context) -> list[ClaimResult]:
    return _example_claim("ch5-example-1", ("wg", "wc", "wb"), {1: 2.0, 2: 2.0})


@claims.register(
    "seed000.ex5.2",
    source="seed 000 §5.3.2",
    statement="r_σ(A_3ᵘ) = 1.7205, so w_33 < 0.3378; W_g works, W_b does not",
)
def _claim_example_2(case: None, ctx: Context) -> list[ClaimResult]:
    return _example_claim("ch5-example-2", ("wg", "wb"), {3: 1.7205})


def _example_claim(
    prefix: str, variants: tuple[str, ...], radii: dict[int, float]
) -> list[ClaimResult]:
    """The paper's radii and bounds to its printed digits, and each weight's expected verdict."""
    evidence: dict[str, Any] = {}
    verdicts: list[bool | None] = []
    for variant in variants:
        analysis = analyze_dkf(DKF.load_case(f"{prefix}-{variant}"))
        bounds = {b.agent: b for b in analysis.conditions.self_weights}
        printed = {a: _printed(bounds[a].radius, r) for a, r in radii.items()}
        bound_digits = {a: _printed(bounds[a].bound, round(1 / r**2, 4)) for a, r in radii.items()}
        verdict, expected = analysis.decision.verdict, analysis.case.expect.get("s_detectable")
        thresholds = {
            str(list(s.agents)): self_weight_record(s, b) for s, b in analysis.searches or []
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
        verdicts.append(None if verdict is None else good and verdict == expected)
    return [ClaimResult(status_of(all_hold(verdicts)), "lmi", evidence)]


@claims.register(
    "seed000.counterexample5.2",
    source="seed 000 §5.2 after Def. 5.2.4 (W not printed; W = ½·11' found)",
    statement="n=1, N=2, A=C_i=1, L=(0.3, −0.25): r_σ(B) = 0.975 while r_σ(L) = 1.026",
)
def _claim_counterexample(case: None, ctx: Context) -> list[ClaimResult]:
    analysis = analyze_dkf(DKF.load_case("ch5-counterexample"))
    rB, rL = analysis.radius_B, analysis.radius_L
    ok = _printed(rB, 0.975) and _printed(rL, 1.026)
    evidence = {
        "W": analysis.case.spec.W,
        "spectral_radius_B": rB,
        "spectral_radius_L": rL,
        "note": "the paper does not print W; W = [[0.5, 0.5], [0.5, 0.5]] reproduces both "
        "numbers exactly (0.975, 1.02625); r(B)² ≤ r(L) always (docs/theory/s-detectability.md)",
        "system_s_detectable": analysis.decision.verdict,
    }
    return [ClaimResult(status_of(ok), "numeric", evidence)]


def _case_gains_certificate(case: Case) -> Certified:
    """The case's own gains certified: float primal tuple rounded, else the exact tuple."""
    spec = case.spec
    reasons = []
    X = primal_lyapunov(spec.A, spec.C, spec.W, spec.L, spec.order)
    if X is None:
        reasons.append("the case's gains: X − T(X) = I has no positive definite solution")
    else:
        try:
            cert = s_detectability_certificate(
                spec.A, spec.C, spec.W, spec.order, spec.L, list(X), case=case.name
            )
            return [cert], []
        except RationalizationError as error:
            reasons.append(f"the case's gains: {error}")
    exact = [rational_matrix(g) if g.size else [] for g in spec.L]
    try:
        cert = exact_gain_certificate(
            spec.A, spec.C, spec.W, exact, order=spec.order, case=case.name
        )
        return [cert], []
    except RationalizationError as error:
        return [], [*reasons, f"the case's gains (exact tuple): {error}"]


def decision_certificates(case: Case, decision: SDetectability) -> Certified:
    """The ``s-detectability`` certificates of a dkf case given its decision: the decision's own
    and, when the case fixes gains, one for those; :class:`PropertyFails` when the decision is
    "not S-detectable" (nothing to certify)."""
    if decision.verdict is False:
        raise PropertyFails(
            f"{case.name} is not S-detectable ({decision.reason}; seed000.def5.2.4, trackcert "
            "dkf): there is nothing to certify"
        )
    certs, reasons = [], []
    if decision.verdict:
        certs.append(decision.certificate)
    else:
        reasons.append(f"no exact S-detectability certificate: {decision.reason}")
    if case.spec.L is not None:
        found, why = _case_gains_certificate(case)
        certs += found
        reasons += why
    return certs, reasons


def _certified_decision(case: Case) -> SDetectability:
    """The decision ``trackcert certify`` certifies: the case's own gains the only candidates."""
    spec = case.spec
    candidates = [("the case's gains", spec.L)] if spec.L is not None else []
    return decide_s_detectability(
        spec.A, spec.C, spec.W, order=spec.order, candidate_gains=candidates, case=case.name
    )


def dkf_certificates(case: Case, seed: int) -> Certified:
    """The ``s-detectability`` certificates of a dkf case (seed 000 Def. 5.2.4, Lemma 5.2.2):
    :func:`decision_certificates` after deciding it (``seed`` unused: no random point)."""
    del seed
    return decision_certificates(case, _certified_decision(case))


@claims.register(
    "seed000.def5.2.4.certified",
    source="seed 000, Definition 5.2.4 and Lemma 5.2.2",
    statement="S-detectability is certified by rational gains and a Lyapunov tuple whose strict "
    "inequalities are verified in exact arithmetic (proofs_check)",
    kinds=("dkf",),
)
def _claim_certified(case: Case, ctx: Context) -> list[ClaimResult]:
    def make() -> Certified:
        decision = ctx.shared(CERTIFIED_DECISION, lambda: _certified_decision(case))
        return decision_certificates(case, decision)

    return certificate_results(
        case,
        make,
        lambda cert: {
            "operator": cert["witness"]["operator"],
            "gains": cert["witness"]["gains"],
            **{k: v for k, v in cert["produced_by"].items() if k != "tool"},
        },
    )


claims.add(expectation_claim("dkf", command="dkf", observe=observe_dkf))
