"""Every named tolerance of the suite, once: its default, unit, meaning and why (docs/cli.md).

A module that decides something by comparing a float with a threshold imports the threshold from
here (``from theory.core.tolerances import RANK_TOL``) and echoes it, under its name, in the
``tolerance`` of its result; a case may override the ones its kind lists in ``tolerances:``.
:data:`TOLERANCES` is the table (``report.json``'s ``environment.tolerance_table``,
``docs/cli.md``), :func:`table` its plain-data form.

Two values were unified here (see ``docs/cli.md``, *Tolerances*):

* ``unit_circle_tol`` is ``1e-6`` everywhere (it was ``1e-9`` in the consensus properties):
  eigenvalues of a defective matrix — the constant-velocity ``A`` has 2 × 2 Jordan blocks at 1 —
  come out of LAPACK with errors of order ``√(eps·κ)``, up to ``6e-7`` for a mildly conditioned
  similarity of a Jordan block, so a tolerance of ``1e-9`` can read a mode on the unit circle as
  stable and call an undetectable pair detectable.
* The two LMI thresholds differ in purpose and now in name: ``lmi_margin = 1e-8`` is the least
  relative margin of a float witness for the *float* verdict "S-detectable"; a certificate
  builder only needs the float witness strictly feasible enough to round
  (``certificate_margin = 1e-9``), because ``proofs_check`` then decides in exact arithmetic.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import Any

__all__ = [
    "BLOWUP",
    "BOUND_RTOL",
    "CERTIFICATE_MARGIN",
    "CERT_TOL",
    "CLUSTER_TOL",
    "COINCIDENCE_TOL",
    "CONSISTENCY_PROBABILITY",
    "CONSISTENCY_RTOL",
    "CONVERGED_TOL",
    "CONV_TOL",
    "EIGEN_TOL",
    "ERROR_BOUND_SIGMAS",
    "EXACT_DIM",
    "GOSPA_ALPHA",
    "GROWTH",
    "INCONCLUSIVE_FACTOR",
    "INEQUALITY_RTOL",
    "INFORMATION_TOL",
    "ISS_BOUND_RTOL",
    "ISS_DIGITS",
    "ISS_SAFE_STEPS",
    "KERNEL_RTOL",
    "KINEMATICS_RTOL",
    "LMI_MARGIN",
    "MAP_RTOL",
    "MARGIN_TOL",
    "MAX_FLATS",
    "MAX_ITER",
    "MIN_CONDITIONING",
    "MIRROR_TOL",
    "MODE_ZERO_TOL",
    "OSPA_CUTOFF",
    "OSPA_ORDER",
    "PERIOD_TOL",
    "PERRON_BITS",
    "PF_TOLERANCES",
    "PSD_RTOL",
    "PSD_TOL",
    "RADIUS_TOL",
    "RANK_TOL",
    "RICCATI_HORIZON",
    "ROUNDING_BITS",
    "ROUNDING_TOL",
    "RUNAWAY_FACTOR",
    "SNAP_RTOL",
    "TOLERANCES",
    "UNIQUENESS_TOL",
    "UNIT_CIRCLE_FACTOR",
    "UNIT_CIRCLE_TOL",
    "VALUE_TOL",
    "VIOLATION_TOL",
    "WEIGHT_SUM_TOL",
    "WEIGHT_TOL",
    "Z_TOL",
    "Tolerance",
    "bits_ladder",
    "defaults",
    "table",
]


@dataclass(frozen=True)
class Tolerance:
    """One named tolerance: its ``name`` in code, case files and outputs, ``default``,
    ``unit``, the comparison it sets (``meaning``) and where the value comes from (``why``)."""

    name: str
    default: float
    unit: str
    meaning: str
    why: str


TOLERANCES: dict[str, Tolerance] = {}
"""Name → :class:`Tolerance`, in the order defined below."""


def _named(name: str, default: float, unit: str, meaning: str, why: str) -> float:
    TOLERANCES[name] = Tolerance(name, default, unit, meaning, why)
    return default


RANK_TOL = _named(
    "rank_tol",
    1e-9,
    "relative to the largest singular value",
    "a singular value below rank_tol · σ_max counts as zero (numeric rank, seed 000 eq. (4.18))",
    "relative, so scale-aware; far above SVD rounding (~1e-16 · dimension), and every "
    "bundled topology verdict clears it by more than inconclusive_factor",
)
INCONCLUSIVE_FACTOR = _named(
    "inconclusive_factor",
    1e3,
    "factor",
    "a rank decision whose deciding singular value lies within this factor of its threshold "
    "rank_tol · σ_max (either side) is inconclusive",
    "three decades between a conclusive decision and its threshold",
)
UNIT_CIRCLE_TOL = _named(
    "unit_circle_tol",
    1e-6,
    "absolute, on |λ|",
    "a mode with |λ| ≥ 1 − unit_circle_tol counts as on or outside the unit circle (not stable)",
    "above the √(eps·κ) error of defective eigenvalues (the CV model's Jordan blocks at 1)",
)
UNIT_CIRCLE_FACTOR = _named(
    "unit_circle_factor",
    10.0,
    "factor",
    "a mode whose ||λ| − 1| lies within this factor of unit_circle_tol (either side) makes the "
    "detectability verdict inconclusive",
    "one decade around the threshold",
)
LMI_MARGIN = _named(
    "lmi_margin",
    1e-8,
    "relative (λ_min(ρY − L*(Y)) / (ρ λ_max(Y)))",
    "least margin m of the LMI witness for the float verdict S-detectable "
    "(r_σ(L) ≤ ρ(1 − m), seed 000 Def. 5.2.4)",
    "of the order of the SDP solvers' accuracy (feasibility tolerances ~1e-8), so a margin at "
    "solver noise is not read as a proof",
)
CERTIFICATE_MARGIN = _named(
    "certificate_margin",
    1e-9,
    "relative (λ_min / max ‖P_i‖)",
    "least float margin a witness must show before it is rounded to rationals for proofs_check",
    "only a gate against futile rounding: the exact check in proofs_check decides",
)
CERT_TOL = _named(
    "cert_tol",
    1e-7,
    "relative",
    "largest ε_cert accepted as a float infeasibility certificate of the S-detectability LMI",
    "a decade above lmi_margin: the residual of an optimal solve is of the solver's accuracy",
)
VALUE_TOL = _named(
    "value_tol",
    1e-9,
    "relative",
    "band around a threshold of seed 000 Thm 5.2.10 (e.g. |1 − w_ii r²| ≤ value_tol) within "
    "which a condition is undecided",
    "far below the decimals the papers print, far above float error",
)
EIGEN_TOL = _named(
    "eigen_tol",
    1e-7,
    "relative to ‖A‖",
    "eigenvalues of A closer than this are one cluster; kernels ker(A − λI) are taken with it",
    "above the √eps error of repeated eigenvalues",
)
WEIGHT_TOL = _named(
    "weight_tol",
    1e-4,
    "absolute, on a weight",
    "bracket width at which the bisection for the largest self-weight stops (seed 000 §5.3)",
    "the paper prints self-weight bounds to 4 decimals",
)
WEIGHT_SUM_TOL = _named(
    "weight_sum_tol",
    1e-9,
    "absolute, on a row sum",
    "an explicit consensus matrix is row-stochastic when |Σ_j w_ij − 1| ≤ weight_sum_tol",
    "a hand-written matrix with 9 decimals is accepted; a typo is not",
)
BOUND_RTOL = _named(
    "bound_rtol",
    1e-9,
    "relative",
    "a formation whose CRB trace is within this relative distance of the bound attains it "
    "(seed 000 eq. (4.43), seed 003 Result 3)",
    "far above the float error of traces of small well-conditioned matrices",
)
CONVERGED_TOL = _named(
    "converged_tol",
    1e-3,
    "relative change",
    "covariances are bounded when ‖P_i(K)‖ / ‖P_i(K/2)‖ is within converged_tol of 1",
    "a bounded covariance changes by less than 0.1 % between K/2 and K",
)
GROWTH = _named(
    "growth",
    2.0,
    "factor",
    "covariances are unbounded when ‖P_i(K)‖ / ‖P_i(K/2)‖ exceeds this factor",
    "the norm of an unbounded covariance at least doubles between K/2 and K",
)
MIRROR_TOL = _named(
    "mirror_tol",
    1e-9,
    "relative to the scene's size",
    "two TDOA (or range) vectors this close are equal (a target and its mirror image; seed 003's "
    "helix mirror pairs)",
    "TDOA differences are differences of distances of order the scene size",
)
UNIQUENESS_TOL = _named(
    "uniqueness_tol",
    1e-7,
    "relative to the scene's size",
    "residual, sign and distinctness tolerance of the spherical-intersection TDOA solutions",
    "absorbs cancellation in the closed-form solution of the quadric",
)
CLUSTER_TOL = _named(
    "cluster_tol",
    1e-8,
    "absolute (W of norm ≤ 1 in the symmetrized basis)",
    "eigenvalues of W closer than this are one cluster (spectral rank, seed 000 eq. (4.36))",
    "far above the ~1e-15 eigenvalue error of a symmetric W",
)
COINCIDENCE_TOL = _named(
    "coincidence_tol",
    1e-9,
    "relative to the scene's size",
    "two agents (or an agent and the target) this close are one point: the case is refused",
    "TDOA Jacobians divide by these distances",
)
PERIOD_TOL = _named(
    "period_tol",
    1e-9,
    "relative",
    "T/τ counts as an integer when within period_tol of one (kind: tdoa-sim)",
    "periods are written with a few decimals",
)
ROUNDING_TOL = _named(
    "rounding_tol",
    8 * sys.float_info.epsilon,
    "absolute, on a weight",
    "largest deviation of the float Metropolis weights from the exact ones",
    "a few ulps: each weight is one division and one subtraction",
)
ERROR_BOUND_SIGMAS = _named(
    "error_bound_sigmas",
    10.0,
    "TDOA noise standard deviations",
    "a tdoa-sim run has bounded_error when every agent's final error is below "
    "error_bound = error_bound_sigmas · √r metres (unless the case sets error_bound)",
    "ten noise standard deviations",
)
CONV_TOL = _named(
    "conv_tol",
    1e-10,
    "relative step",
    "the coupled Riccati iteration has converged when max_i ‖P_i(k+1) − P_i(k)‖ ≤ "
    "conv_tol · max_i ‖P_i(k)‖ (seed 000 eqs. (5.7)–(5.9))",
    "a contraction reaches it long before max_iter; float noise sits near 1e-16",
)
BLOWUP = _named(
    "blowup",
    1e12,
    "factor on the initial norm",
    "the coupled Riccati iteration diverges when its norm exceeds blowup times the initial one",
    "twelve decades above the start",
)
MAX_ITER = _named(
    "max_iter",
    5000.0,
    "iterations",
    "iteration budget of the coupled Riccati iteration (neither converged nor diverged: "
    "status max_iter)",
    "a budget, not a threshold; echoed with the tolerances it bounds",
)
PSD_TOL = _named(
    "psd_tol",
    1e-9,
    "relative to the matrices' norm",
    "a symmetric matrix counts as positive semidefinite when its least eigenvalue is ≥ −psd_tol "
    "(Lemma 5.2.3, Lemma A.2.1 bounds)",
    "far above the float error of the symmetric eigenvalue problem",
)
Z_TOL = _named(
    "z_tol",
    4.0,
    "asymptotic standard errors",
    "a maximum-likelihood estimate is consistent with the true parameter when within z_tol "
    "standard errors (seed 002 eqs. (3.1)–(3.2), (3.17))",
    "a false alarm below 1e-4 per parameter under normality",
)
PSD_RTOL = _named(
    "psd_rtol",
    1e-9,
    "relative to max(‖A‖_F, ‖B‖_F, 1)",
    "A ⪯ B holds when λ_max(A − B) ≤ psd_rtol · max(‖A‖_F, ‖B‖_F, 1) (averaged-filter bounds, "
    "seed 000 App. A)",
    "far above the float error of symmetric eigenvalues, scale-aware through the Frobenius norms",
)
KERNEL_RTOL = _named(
    "kernel_rtol",
    1e-9,
    "relative",
    "along ker G_C the averaged filter's covariance equals the prior's propagation within this "
    "relative tolerance (nothing is learnt there)",
    "the equality is exact in real arithmetic; the tolerance absorbs the recursion's rounding",
)
MIN_CONDITIONING = _named(
    "min_conditioning",
    1e-3,
    "ratio σ_r / σ_1",
    "a component's Jacobian counts for the averaged-filter certificate only when its smallest "
    "non-zero singular value is at least this fraction of the largest",
    "below it the burn-in of the certificate is too short (docs/property-based.md)",
)
MARGIN_TOL = _named(
    "margin_tol",
    1e-9,
    "relative (each condition's margin is scaled, e.g. |ε₁|/‖ε‖, λ_min(K)/λ_max(K))",
    "an ISS condition of seed 003 whose relative margin is below margin_tol is inconclusive",
    "the conditions are exact where they can be (ΔΔᵀ, the Laplacian): the margin guards the "
    "float ones",
)
VIOLATION_TOL = _named(
    "violation_tol",
    1e-6,
    "absolute, on V̇",
    "a printed inequality of seed 003 is violated at a point when it fails by more than this",
    "far above the float error of V̇",
)
INEQUALITY_RTOL = _named(
    "inequality_rtol",
    1e-9,
    "relative to the magnitude of the inequality's terms",
    "a coordination inequality of seed 003 ((74), (75), Lemma 3) holds at a point when it fails "
    "by at most inequality_rtol times its scale (falsify's seed 003 wordings)",
    "the terms are a few products of small matrices: float error is ~1e-15 of the scale",
)
KINEMATICS_RTOL = _named(
    "kinematics_rtol",
    1e-6,
    "relative to the magnitude of the inequality's terms",
    "a pursuit inequality of seed 003 ((72), Theorem 1) holds at a point when V̇, computed from "
    "the kinematics, exceeds its bound by at most kinematics_rtol times the scale",
    "V̇ goes through rotations, path evaluations and the controller: float error grows to ~1e-10",
)
ISS_BOUND_RTOL = _named(
    "iss_bound_rtol",
    1e-3,
    "relative to the certified bound",
    "a simulated pursuit run leaves Theorem 2's estimate when ‖μ(t)‖ > bound·(1 + iss_bound_rtol) "
    "at a record (seed003.thm2.sim-trajectories, trackcert simulate's iss_agreement)",
    "the integrator's local error control is 3e-4 per step (theory.pursuit.closed_loop)",
)
RUNAWAY_FACTOR = _named(
    "runaway_factor",
    5.0,
    "factor, of the largest S-T curve semi-axis",
    "a simulated DEC run stops as a runaway when, at a sampling instant, a tracker's localization "
    "error ‖q̂ − q‖ exceeds runaway_factor times the largest semi-axis of the trackers' S-T curves "
    "(seed 003 (15)–(16); docs/theory/pursuit-iss.md §11)",
    "bounded closed-loop runs of the Table cases (seeds 0–9) stay below 0.7 curve sizes, and the "
    "DEKF fed by a tracker on its curve around the true target wanders to 2.2 and recovers; every "
    "runaway passed 5 within 4–10 s of passing 1 and went on to over 400 (none came back)",
)
RADIUS_TOL = _named(
    "radius_tol",
    1e-6,
    "relative, on the spectral radius",
    "above the exact-arithmetic size limit, a float r_σ(T) decides 'r_σ < ρ' only outside "
    "ρ(1 ± radius_tol) (theory.consensus.operators)",
    "an eigenvalue of a non-normal matrix can move by √ε ≈ 1e-8 (2 × 2 Jordan block)",
)
MAP_RTOL = _named(
    "map_rtol",
    1e-10,
    "relative to ‖mat(T)‖·‖V‖",
    "an operator applied blockwise and its Kronecker matrix agree on a tuple when their "
    "difference is within map_rtol of the scale (seed 000 Lemma 5.2.2's vectorization)",
    "both are a few products of small matrices: float error is ~1e-15 of the scale",
)
# --- budgets of the exact consensus decisions (integers; the exact check decides, they only
# --- bound the work or the precision tried)
EXACT_DIM = int(
    _named(
        "exact_dim",
        200.0,
        "N·n² (size of the operator's matrix)",
        "largest size for which r_σ(T) < ρ is decided by an exact rational Lyapunov solve "
        "(theory.consensus.operators); above it the float radius decides outside radius_tol",
        "a budget: a 200 × 200 rational solve takes about 0.3 s",
    )
)
MAX_FLATS = int(
    _named(
        "max_flats",
        2000.0,
        "flats",
        "most intersections of an eigenspace of A with kernels of the C_i explored when "
        "searching blind sets for an infeasibility certificate (theory.consensus.infeasibility)",
        "a budget: the lattice of flats of the bundled cases has fewer than 20 elements",
    )
)
PERRON_BITS = int(
    _named(
        "perron_bits",
        52.0,
        "bits",
        "finest rounding of a float Perron vector into a Farkas witness; bits_ladder(52) = "
        "13, 26, 52 bits are tried in turn (theory.consensus.infeasibility)",
        "a float Perron vector has no more than 52 correct bits",
    )
)
ROUNDING_BITS = int(
    _named(
        "rounding_bits",
        96.0,
        "significant bits",
        "finest dyadic rounding of float gains and exact Lyapunov tuples into an "
        "s-detectability certificate; bits_ladder(96) = 24, 48, 96 are tried in turn "
        "(theory.consensus.certificates)",
        "an exact tuple has margin I, so 24 bits usually suffice; 96 covers ill-conditioned X",
    )
)
RICCATI_HORIZON = int(
    _named(
        "riccati_horizon",
        40.0,
        "iterations",
        "steps of the Riccati and fixed-gain bound iterations compared by seed000.fn5's "
        "property (fewer if the iterates pass blowup)",
        "a budget: the property's examples converge or double within 40 steps",
    )
)
# --- pursuit certificates
ISS_DIGITS = int(
    _named(
        "iss_digits",
        9.0,
        "significant decimal digits",
        "rounding of the ISS witness constants (λ, k̄_p, s, a, b, ρ, κ) in the safe direction; "
        "a constant whose exact check fails is halved or doubled until it passes",
        "short decimals a reader can check by hand; the exact check in proofs_check decides",
    )
)
ISS_SAFE_STEPS = int(
    _named(
        "iss_safe_steps",
        64.0,
        "halvings or doublings",
        "most moves of a rounded ISS witness constant in its safe direction before the "
        "certificate is reported inconclusive (theory.pursuit.certificates.safe_constant)",
        "2⁻⁶⁴ of a float estimate is far below any rounding error of it",
    )
)


def bits_ladder(top: int) -> tuple[int, int, int]:
    """The precisions tried in turn up to ``top`` bits: a quarter, a half, all of it."""
    return (top // 4, top // 2, top)


# ---------------------------------------------------------------- TDOA localization (theory/tdoa)
INFORMATION_TOL = _named(
    "information_tol",
    1e-12,
    "relative to λ_max of the Fisher information",
    "a TDOA (or range) Fisher information matrix whose least eigenvalue is ≤ information_tol · "
    "λ_max counts as singular: its CRB trace is ∞ (seed 000 eq. (4.43), seed 003 Result 3)",
    "three decades below rank_tol² (J = GᵀG squares the singular values of G): only a rank "
    "deficiency, not an ill-conditioned but full-rank geometry, gives ∞",
)
SNAP_RTOL = _named(
    "snap_rtol",
    1e-4,
    "relative to max(1, |λ|)",
    "an unobservable eigenvalue of the networked pair computed from its (possibly defective) "
    "restriction is replaced by the nearest product λ(W)·λ(A) within snap_rtol; the unit-circle "
    "decision is then made on it with unit_circle_tol and its band",
    "Jordan blocks of size k perturb eigenvalues by ~ε^{1/k} (1e-4 for k = 4); the products "
    "are computed from the well-conditioned factors",
)
MODE_ZERO_TOL = _named(
    "mode_zero_tol",
    1e-12,
    "relative to max(1, ‖W‖_max ‖A‖_max)",
    "a candidate mode λ(W)·λ(A) this small is exactly 0 (a singular W)",
    "far above the eigenvalue error of a well-conditioned W, far below any weight written",
)

PF_TOLERANCES = {
    "converge_tol": _named(
        "converge_tol",
        5.0,
        "metres of median tail error",
        "a particle-filter node converges when its median tail error is below converge_tol",
        "seed 002 §3.3: converged errors stay within a few metres",
    ),
    "diverge_tol": _named(
        "diverge_tol",
        10.0,
        "metres of median tail error",
        "a particle-filter node does not converge when its median tail error exceeds diverge_tol",
        "seed 002 §3.3, Figs. 3.2–3.5",
    ),
    "improvement_tol": _named(
        "improvement_tol",
        3.0,
        "standard errors",
        "a variant is better when its mean error is lower by improvement_tol standard errors",
        "three standard errors of the Monte Carlo mean",
    ),
}
"""The ``kind: pf`` tolerances (their case keys), by name."""

# ------------------------------ filter consistency and OSPA (theory.core.consistency)
CONSISTENCY_PROBABILITY = _named(
    "consistency_probability",
    0.95,
    "probability",
    "the two-sided χ² acceptance band of NEES/ANEES and NIS holds the statistic of a consistent "
    "filter with this probability ((1 − p)/2 in each tail)",
    "Bar-Shalom, Li, Kirubarajan (2001) §5.4: the customary 95 % two-sided region",
)
CONSISTENCY_RTOL = _named(
    "consistency_rtol",
    0.05,
    "widths of the χ² band",
    "a NEES/NIS average within consistency_rtol band widths of either edge is inconclusive",
    "the band is only as exact as the Gaussian, linear and independence assumptions behind it",
)
OSPA_CUTOFF = _named(
    "ospa_cutoff",
    10.0,
    "metres",
    "OSPA/GOSPA cutoff c: a position error counts as min(c, ‖e‖), a missing or extra estimate as c",
    "diverge_tol of the particle filter: beyond 10 m an estimate has lost the target",
)
OSPA_ORDER = _named(
    "ospa_order",
    2.0,
    "exponent p",
    "OSPA/GOSPA order p (p = 2: root-mean-square localization)",
    "Schuhmacher, Vo, Vo (2008) and García-Fernández, Svensson (2017) use p = 2 for tracking",
)
GOSPA_ALPHA = _named(
    "gospa_alpha",
    2.0,
    "factor",
    "GOSPA α: a missed or false estimate costs c^p/α (α = 2: the sum of localization, missed "
    "and false target costs)",
    "α = 2 is the only value with the assignment decomposition (García-Fernández, Svensson 2017)",
)


def defaults(*names: str) -> dict[str, float]:
    """The default values of ``names``, e.g. ``defaults("rank_tol", "inconclusive_factor")``."""
    unknown = [n for n in names if n not in TOLERANCES]
    if unknown:
        raise KeyError(f"unknown tolerances {unknown}; known: {sorted(TOLERANCES)}")
    return {n: TOLERANCES[n].default for n in names}


def table() -> list[dict[str, Any]]:
    """The table as plain data (``name``, ``default``, ``unit``, ``meaning``, ``why``)."""
    return [vars(t).copy() for t in TOLERANCES.values()]
