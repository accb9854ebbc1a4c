"""Falsifiable wordings of seed 003's claims for ``trackcert falsify``: the ISS inequalities
(71), (72), (74), (75), Theorem 1's dissipation bound, Theorem 2 against the simulator, and the
conditions swept toward their thresholds.

Pursuit loop (Appendix B): ‖Φ‖² < μ‖x̃‖² (71) only holds with ≤ (checked exactly, in rational
arithmetic, on 2D paths and rotations with rational sines and cosines); the region of (72),
‖e‖ ≥ c‖x̃‖/θ, lacks the factor 1/λ_min(K) that (78) has; V̇ ≤ −λ_min(K)‖e‖² + c‖e‖‖x̃‖ holds with
the paper's c = √μ + ‖K‖ and with the sharper c♯ (Theorem 1). V̇ is evaluated from the kinematics
(:meth:`theory.pursuit.strategies.TrackerState.rates`).

Coordination loop (Appendix C): with ξ = (I − 1rᵀ)γ, V_c = ξᵀRξ/2 (eq. (73)) and
γ̇ = ω̄1 − k_c Lγ + e_γ (eqs. (45)–(47)), the paper prints V̇_c ≤ −k_c r_min‖ξ‖² + ‖ξ‖‖RW‖‖e_γ‖
(eq. (74)); what the proof supports is V̇_c ≤ −k_c a(L) ξᵀRξ + ‖ξ‖_R b ‖e_γ‖ with a(L) of
Definition 1 and b = √λ_max(WᵀRW) (``docs/theory/pursuit-iss.md``).

Theorem 2 against the simulator: on random certified cases
(:func:`theory.pursuit.strategies.simulated_pursuit_blocks`), a short seeded run stays within
the certified estimate β(‖μ(0)‖, t) + γ(sup‖x̃‖) with the run's own x̃
(:func:`theory.pursuit.simulation.simulation_agreement`).

Never wrong near a threshold (issue 17): the exact verdicts on ``λ_min(K) ≥ 1`` (whether the
printed region (72) follows), ``K ≻ 0`` and the certificate (it exists iff ``ε₁ ≠ 0``) on Table I
with three trackers (``cases/pursuit-table1-n3.yaml``), swept toward each threshold; "correct" is
computed from the decimals as written, independently of :mod:`theory.pursuit.iss`.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, replace
from fractions import Fraction
from functools import cache
from typing import Any, Literal

import mpmath
import numpy as np
import sympy as sp
import yaml
from hypothesis import strategies as st

import proofs_check
from theory.core.case_file import Case, bundled_cases
from theory.core.claims import FixedInstance, Property
from theory.core.errors import InconclusiveError, PropertyFails
from theory.core.observability import RankResult, numeric_rank
from theory.core.tolerances import INEQUALITY_RTOL, KINEMATICS_RTOL, RANK_TOL
from theory.pursuit.case import PURSUIT, PursuitSpec
from theory.pursuit.certificates import iss_certificate
from theory.pursuit.derivations import (
    delta_matrix,
    error_dynamics_check,
    lyapunov_derivative_check,
    rotation_rate_check,
)
from theory.pursuit.iss import (
    ConditionStatus,
    generalized_algebraic_connectivity,
    iss_conditions,
    pursuit_iss,
    r_perp_connectivity_positive,
)
from theory.pursuit.model import left_eigenvector
from theory.pursuit.observability import helix_fim_rank, o_matrix, range_jacobian
from theory.pursuit.strategies import (
    TrackerState,
    digraph_laplacians,
    pursuit_cases,
    simulated_pursuit_blocks,
    tracker_states,
)
from theory.strategy_helpers import boundary_values, example_record

__all__ = [
    "AGREEMENT_RECORDS",
    "FIXED_INSTANCES",
    "IDENTITIES",
    "MODEL_PROPERTIES",
    "PROPERTIES",
    "AgreementExample",
    "CertificatePoint",
    "CoordinationExample",
    "IdentityPoint",
    "PhiExample",
    "PursuitExample",
    "RegionPoint",
    "StackedPursuit",
    "TrackerPair",
    "agreement_case",
    "agreement_examples",
    "agreement_verdict",
    "certificate_sound",
    "coordination_case",
    "coordination_examples",
    "coordination_iss_holds",
    "coordination_terms",
    "epsilons",
    "gram_determinant",
    "identity_residual",
    "pair_ranks",
    "phi_case",
    "phi_examples",
    "phi_terms",
    "pursuit_example_case",
    "pursuit_examples",
    "pursuit_terms",
    "region_case",
    "region_sound",
    "stacked_dissipation",
    "tracker_pairs",
]

TABLE_I = {"omega_bar": 0.05, "epsilon": [-0.5, 0], "K_p": [0.4, 0.2], "k_gamma": 500}
"""Seed 003 Table I gains, used for case fields an example does not determine."""

Wording = Literal["paper", "corrected"]
"""A property's wording: the statement as printed, or as corrected."""


# ---------------------------------------------------------------------------------------------
# (71): ‖Φ‖² < μ‖x̃‖², exactly


@dataclass(frozen=True)
class PhiExample:
    """A 2D path (semi-axes of (15)), a path angle, an attitude and estimation errors q̃, ṽ.

    The path angle φ = γ + γ₀ and the attitude angle ψ are given by t = tan(φ/2) and
    s = tan(ψ/2), so that cos and sin are rational: cos φ = (1 − t²)/(1 + t²),
    sin φ = 2t/(1 + t²).
    """

    r_x: int
    r_y: int
    t: Fraction
    s: Fraction
    q_err: tuple[Fraction | int, Fraction | int]
    v_err: tuple[Fraction | int, Fraction | int]


def _cos_sin(t: Fraction) -> tuple[Fraction, Fraction]:
    return (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)


def _r_prime(r_x: int, r_y: int, t: Fraction) -> tuple[Fraction, Fraction]:
    """r′(γ) = (−r_x sin φ, r_y cos φ) of path (15), φ = γ + γ₀ = 2 atan t."""
    cos_phi, sin_phi = _cos_sin(t)
    return -r_x * sin_phi, r_y * cos_phi


@st.composite
def phi_examples(draw: st.DrawFn) -> PhiExample:
    """Semi-axes in 1–30 (r_y = r_x, a circle as in Tables I–II, half of the time), t and s in
    {a/b : |a| ≤ 3, 1 ≤ b ≤ 3}, ṽ with entries in −5…5 (or 0), q̃ with entries in −5…5 or a
    multiple −3…3 of r′(γ) (the direction where Cauchy–Schwarz in (71) is tight)."""
    halves = st.builds(Fraction, st.integers(-3, 3), st.integers(1, 3))
    pair = st.tuples(st.integers(-5, 5), st.integers(-5, 5))
    r_x = draw(st.integers(1, 30))
    r_y = draw(st.one_of(st.just(r_x), st.integers(1, 30)))
    t = draw(halves)
    along = st.integers(-3, 3).map(lambda m: tuple(m * x for x in _r_prime(r_x, r_y, t)))
    q_err = draw(st.one_of(pair, along))
    v_err = draw(st.one_of(st.just((0, 0)), pair))
    return PhiExample(r_x, r_y, t, draw(halves), q_err, v_err)


def phi_terms(example: PhiExample) -> dict[str, Fraction]:
    """‖Φ‖², μ‖x̃‖² and ‖x̃‖² of (71) for ``example``, exactly.

    Φ = col(Rᵀṽ, −q̃ᵀr′(γ)), r′(γ) = (−r_x sin φ, r_y cos φ) (eq. (15)) and μ = max(1, r_x², r_y²)
    (the supremum of ‖r′‖², :func:`theory.pursuit.iss.path_mu`).
    """
    r_prime = _r_prime(example.r_x, example.r_y, example.t)
    cos_psi, sin_psi = _cos_sin(example.s)
    v1, v2 = example.v_err
    rotated = (cos_psi * v1 + sin_psi * v2, -sin_psi * v1 + cos_psi * v2)
    q_dot_r = sum(q * r for q, r in zip(example.q_err, r_prime, strict=True))
    x_sq = Fraction(sum(q * q for q in example.q_err) + v1 * v1 + v2 * v2)
    mu = max(Fraction(1), max(example.r_x, example.r_y) ** 2)
    return {
        "phi_sq": rotated[0] ** 2 + rotated[1] ** 2 + q_dot_r**2,
        "mu_x_sq": mu * x_sq,
        "x_sq": x_sq,
    }


def phi_case(example: PhiExample) -> dict[str, Any]:
    """A ``kind: pursuit`` case with the example's path (γ₀ = φ, so the state is at γ = 0);
    the attitude and the estimation errors go into ``description`` (Table I gains)."""
    terms = phi_terms(example)
    return {
        "name": "falsify-eq71-phi-bound",
        "source": "trackcert falsify (shrunk counterexample to seed 003 eq. (71))",
        "description": f"State of the counterexample: gamma = 0, gamma0 = 2 atan({example.t}), "
        f"attitude psi = 2 atan({example.s}), q_tilde = {[str(q) for q in example.q_err]}, "
        f"v_tilde = {list(example.v_err)}; exactly ‖Φ‖² = {terms['phi_sq']} and "
        f"μ‖x̃‖² = {terms['mu_x_sq']}.",
        "kind": "pursuit",
        "pursuit": {
            "dim": 2,
            "controller": "II",
            **TABLE_I,
            "trackers": [
                {"r_x": example.r_x, "r_y": example.r_y, "gamma0": 2 * math.atan(example.t)}
            ],
        },
    }


def _phi_paper(example: PhiExample) -> bool:
    terms = phi_terms(example)
    return terms["x_sq"] == 0 or terms["phi_sq"] < terms["mu_x_sq"]


def _phi_corrected(example: PhiExample) -> bool:
    terms = phi_terms(example)
    return terms["phi_sq"] <= terms["mu_x_sq"]


# ---------------------------------------------------------------------------------------------
# (72) and Theorem 1: V̇ along the kinematics


@dataclass(frozen=True, eq=False)
class PursuitExample:
    """A one-tracker pursuit case, a state of its tracker and θ ∈ (0, 1) of eqs. (72)/(78)."""

    case: Case
    state: TrackerState
    theta: float


def _norms(spec: PursuitSpec, state: TrackerState) -> tuple[float, float]:
    e_sq = float(state.e_p @ state.e_p) + (state.e_gamma**2 if spec.controller == "II" else 0.0)
    x_sq = float(state.q_err @ state.q_err + state.v_err @ state.v_err)
    return math.sqrt(e_sq), math.sqrt(x_sq)


@st.composite
def pursuit_examples(draw: st.DrawFn, *, region: Wording | None = None) -> PursuitExample:
    """Cases from :func:`~theory.pursuit.strategies.pursuit_cases` (half of them with small gains
    and paths, where λ_min(K) < 1), states from :func:`~theory.pursuit.strategies.tracker_states`
    (in half of them q̃ = 0 and ṽ = Re_p, the direction that maximises the cross term of (70)),
    and θ ∈ {0.1, …, 0.9}.

    With ``region`` = ``paper`` or ``corrected`` the estimation error x̃ = (q̃, ṽ) is rescaled to a
    drawn fraction (0.1 to 1) of the edge of that region: ‖x̃‖ ≤ θ‖e‖/c (72) or
    ‖x̃‖ ≤ θλ_min(K)‖e‖/c (78), c = √μ + ‖K‖.
    """
    cases = st.one_of(pursuit_cases(), pursuit_cases(gains=(0.05, 0.5), path_sizes=(0.5, 2.0)))
    case = draw(cases)
    state = draw(tracker_states(spec=case.spec))
    theta = draw(st.integers(1, 9)) / 10
    if draw(st.booleans()):  # the worst direction of ṽ for the cross term e_pᵀRᵀṽ of (70)
        state = replace(state, q_err=0 * state.q_err, v_err=state.rotation @ state.e_p)
    if region is not None:
        pursuit = pursuit_iss(case.spec)
        e_norm, x_norm = _norms(case.spec, state)
        edge = theta * e_norm / pursuit.cross_gain
        edge *= pursuit.lambda_min if region == "corrected" else 1.0
        fraction = draw(st.integers(1, 10)) / 10
        if x_norm > 0:
            factor = fraction * edge / x_norm
            state = replace(state, q_err=state.q_err * factor, v_err=state.v_err * factor)
    return PursuitExample(case, state, theta)


def pursuit_terms(example: PursuitExample) -> dict[str, float]:
    """V̇ (from the kinematics), ‖e‖, ‖x̃‖, λ_min(K), the paper's c and c♯, and the scale of
    the terms, for ``example``."""
    spec, state = example.case.spec, example.state
    rates = state.rates(spec)
    pursuit = pursuit_iss(spec)
    e_sq = float(rates.e_p @ rates.e_p) + (rates.e_gamma**2 if spec.controller == "II" else 0.0)
    e_norm, x_norm = math.sqrt(e_sq), _norms(spec, state)[1]
    c, c_sharp = pursuit.cross_gain, pursuit.sharp_cross_gain
    return {
        "v_dot": float(rates.v_dot),
        "e_norm": e_norm,
        "x_norm": x_norm,
        "lambda_min": pursuit.lambda_min,
        "c": c,
        "c_sharp": c_sharp,
        "scale": pursuit.norm_K * e_sq + max(c, c_sharp) * e_norm * x_norm + 1.0,
    }


def _vector(values: np.ndarray) -> list[float]:
    return [float(v) for v in np.ravel(values)]


def _pursuit_block(spec: PursuitSpec) -> dict[str, Any]:
    trackers = []
    for path in spec.trackers:
        entry = {"r_x": path.r_x, "r_y": path.r_y, "gamma0": path.gamma0}
        if spec.dim == 3:
            entry |= {"r_z": path.r_z, "c": path.c}
        trackers.append(entry)
    block = {
        "dim": spec.dim,
        "controller": spec.controller.value,
        "omega_bar": spec.omega_bar,
        "epsilon": _vector(spec.epsilon),
        "K_p": [_vector(row) for row in spec.K_p],
        "trackers": trackers,
    }
    if spec.k_gamma is not None:
        block["k_gamma"] = spec.k_gamma
    return block


def pursuit_example_case(example: PursuitExample) -> dict[str, Any]:
    """A ``kind: pursuit`` case with the example's gains and path; the state (not a case field)
    goes into ``description``."""
    state = example.state
    fields = ("e_p", "e_gamma", "rotation", "gamma", "q_err", "v_err", "omega_d", "omega_d_dot")
    described = ", ".join(
        f"{name} = {np.asarray(getattr(state, name)).tolist()}"
        for name in (*fields, "target", "target_v")
    )
    return {
        "name": f"falsify-pursuit-{example.case.spec.dim}d-type-{example.case.spec.controller}",
        "source": "trackcert falsify (shrunk counterexample to seed 003 Appendix B)",
        "description": f"State of the counterexample (tracker 1): {described}, "
        f"theta = {example.theta}.",
        "kind": "pursuit",
        "pursuit": _pursuit_block(example.case.spec),
    }


def _region_holds(wording: Wording):
    def holds(example: PursuitExample) -> bool:
        terms = pursuit_terms(example)
        lam, theta = terms["lambda_min"], example.theta
        edge = terms["c"] * terms["x_norm"] / theta / (lam if wording == "corrected" else 1.0)
        if terms["e_norm"] < edge:
            return True
        bound = -(1 - theta) * lam * terms["e_norm"] ** 2
        return terms["v_dot"] <= bound + KINEMATICS_RTOL * terms["scale"]

    return holds


def _dissipation_holds(gain: str):
    def holds(example: PursuitExample) -> bool:
        terms = pursuit_terms(example)
        e_norm = terms["e_norm"]
        bound = -terms["lambda_min"] * e_norm**2 + terms[gain] * e_norm * terms["x_norm"]
        return terms["v_dot"] <= bound + KINEMATICS_RTOL * terms["scale"]

    return holds


# ---------------------------------------------------------------------------------------------
# (74), (75): coordination


@dataclass(frozen=True, eq=False)
class CoordinationExample:
    """A strongly connected digraph's Laplacian, k_c (45), path parameters γ, their errors e_γ
    entering γ̇ (47) (the pursuit error with e_p = 0, in (75)), θ of (75) and ω̄ (46)."""

    laplacian: np.ndarray
    k_c: float
    gamma: np.ndarray
    e_gamma: np.ndarray
    theta: float = 0.5
    omega_bar: float = 0.05


@st.composite
def coordination_examples(
    draw: st.DrawFn, *, inside_region: bool = False, weighted: bool | None = None
) -> CoordinationExample:
    """Every strongly connected digraph of 2–8 trackers (:func:`digraph_laplacians`, by ears:
    non-Hamiltonian ones included), with a_ij = 1 (seed 003 §II-B, the class of (74)/(75)) or,
    with ``weighted`` (``None``: either), decimal weights a_ij over three decades (the weighted
    digraphs of Lemma 1's reference [28]); small integer γ and e_γ (e_γ = 0 in half the draws),
    k_c ∈ {1/5, …, 2} and θ ∈ {0.1, …, 0.9}.

    With ``inside_region`` e_γ is rescaled to a drawn fraction (0.1 to 1) of the edge of the
    corrected region of (75), ‖e_γ‖ ≤ θk_c a(L)‖ξ‖_R / b.
    """
    weighted = draw(st.booleans()) if weighted is None else weighted
    laplacian = draw(digraph_laplacians(min_agents=2, max_agents=8, weighted=weighted))
    n = laplacian.shape[0]
    integers = st.lists(st.integers(-5, 5), min_size=n, max_size=n).map(np.array)
    k_c = draw(st.integers(1, 10)) / 5
    gamma = draw(integers).astype(float)
    e_gamma = draw(st.one_of(st.just(np.zeros(n)), integers)).astype(float)
    theta = draw(st.integers(1, 9)) / 10
    example = CoordinationExample(laplacian, k_c, gamma, e_gamma, theta)
    e_norm = float(np.linalg.norm(e_gamma))
    if inside_region and e_norm > 0:
        terms = coordination_terms(example)
        edge = theta * k_c * terms["a"] * terms["xi_r"] / terms["b"]
        fraction = draw(st.integers(1, 10)) / 10
        example = replace(example, e_gamma=e_gamma * (fraction * edge / e_norm))
    return example


def coordination_terms(example: CoordinationExample) -> dict[str, float]:
    """V̇_c and the right-hand sides of (74) and (75), printed and corrected, for ``example``
    (with a(L), b, ‖ξ‖_R and the scale of the terms)."""
    L = example.laplacian.astype(float)
    n = L.shape[0]
    r = np.array([float(x) for x in left_eigenvector(example.laplacian)])
    W = np.eye(n) - np.outer(np.ones(n), r)
    R = np.diag(r)
    xi = W @ example.gamma
    gamma_dot = example.omega_bar * np.ones(n) - example.k_c * L @ example.gamma + example.e_gamma
    v_dot = float(xi @ R @ (W @ gamma_dot))
    xi_norm, e_norm = float(np.linalg.norm(xi)), float(np.linalg.norm(example.e_gamma))
    xi_r = math.sqrt(float(xi @ R @ xi))
    a = generalized_algebraic_connectivity(L, r)
    b = math.sqrt(float(np.linalg.eigvalsh(W.T @ R @ W)[-1]))
    decay = -example.k_c * r.min() * xi_norm**2
    norm_rw = float(np.linalg.norm(R @ W, 2))
    return {
        "v_dot": v_dot,
        "paper": float(decay + xi_norm * norm_rw * e_norm),
        "corrected": -example.k_c * a * xi_r**2 + xi_r * b * e_norm,
        "paper75": float(decay + norm_rw * e_norm),
        "corrected75": -(1 - example.theta) * example.k_c * a * xi_r**2,
        "a": a,
        "b": b,
        "xi_r": xi_r,
        "e_norm": e_norm,
        "scale": example.k_c * float(np.abs(L).max()) * xi_norm**2 + xi_norm * e_norm + 1.0,
    }


def coordination_case(example: CoordinationExample) -> dict[str, Any]:
    """A ``kind: pursuit`` case with the example's graph (edges ``[s, r, a_rs]`` when weighted),
    k_c and γ (as ``gamma0``)."""
    L = example.laplacian
    n = L.shape[0]
    weighted = not np.issubdtype(L.dtype, np.integer)
    edges = [
        [int(j) + 1, int(i) + 1, *([float(-L[i, j])] if weighted else [])]
        for i, j in zip(*(L < 0).nonzero(), strict=True)
    ]
    return {
        "name": f"falsify-coordination-{n}-trackers",
        "source": "trackcert falsify (shrunk counterexample to seed 003 eqs. (74)/(75))",
        "description": f"State of the counterexample: gamma = {example.gamma.tolist()}, "
        f"e_gamma = {example.e_gamma.tolist()}, omega_bar = {example.omega_bar}, "
        f"theta = {example.theta}.",
        "kind": "pursuit",
        "pursuit": {
            "dim": 2,
            "controller": "II",
            **TABLE_I,
            "omega_bar": example.omega_bar,
            "k_c": example.k_c,
            "trackers": [{"r_x": 30, "r_y": 30, "gamma0": float(g)} for g in example.gamma],
            "edges": edges,
        },
    }


def _coordination_holds(bound: str):
    def holds(example: CoordinationExample) -> bool:
        terms = coordination_terms(example)
        return terms["v_dot"] <= terms[bound] + INEQUALITY_RTOL * terms["scale"]

    return holds


def _eq75_corrected(example: CoordinationExample) -> bool:
    terms = coordination_terms(example)
    edge = terms["b"] * terms["e_norm"] / (example.theta * example.k_c * terms["a"])
    if terms["xi_r"] < edge * (1 + INEQUALITY_RTOL):
        return True
    return terms["v_dot"] <= terms["corrected75"] + INEQUALITY_RTOL * terms["scale"]


# ---------------------------------------------------------------------------------------------
# Theorem 2 against the simulator

AGREEMENT_RECORDS = 60
"""Records of 0.1 s per example (6 s: the initial transient, where the held-input scheme
diverged within 3 s; a few DEKF samples)."""


@dataclass(frozen=True, eq=False)
class AgreementExample:
    """A simulatable ``pursuit:`` block (from
    :func:`~theory.pursuit.strategies.simulated_pursuit_blocks`) and its run's noise seed."""

    block: dict[str, Any]
    seed: int


@st.composite
def agreement_examples(draw: st.DrawFn) -> AgreementExample:
    """Blocks of :func:`~theory.pursuit.strategies.simulated_pursuit_blocks` and seeds 0–1000."""
    return AgreementExample(draw(simulated_pursuit_blocks()), draw(st.integers(0, 1000)))


def agreement_case(example: AgreementExample) -> dict[str, Any]:
    """The example as a case file (the seed and the run's length in ``description``)."""
    return {
        "name": "falsify-seed003-sim-agreement",
        "source": "trackcert falsify (shrunk counterexample to seed 003 Theorem 2 vs simulate)",
        "description": f"The run: theory.pursuit.simulation.run_pursuit_case(spec, "
        f"numpy.random.default_rng({example.seed}), steps={AGREEMENT_RECORDS}).",
        "kind": "pursuit",
        "pursuit": example.block,
        "expect": {"iss": True, "simulation_bounded": True},
    }


def agreement_verdict(example: AgreementExample) -> dict[str, Any] | None:
    """:func:`~theory.pursuit.simulation.simulation_agreement` of the example's run, or ``None``
    when a condition of the analysis does not hold (nothing is certified)."""
    from theory.pursuit.simulation import run_pursuit_case, simulation_agreement

    spec = PURSUIT.parse_case(agreement_case(example)).spec
    certified = {ConditionStatus.HOLDS, ConditionStatus.NOT_APPLICABLE}
    if {c.status for c in iss_conditions(spec)} - certified:
        return None
    run = run_pursuit_case(spec, np.random.default_rng(example.seed), steps=AGREEMENT_RECORDS)
    return simulation_agreement(spec, run)


def _agreement_holds(example: AgreementExample) -> bool:
    verdict = agreement_verdict(example)
    return verdict is None or verdict["status"] != "refuted"


# ---------------------------------------------------------------------------------------------
# boundary sweeps: never wrong near a threshold

BASE_CASE = "pursuit-table1-n3"
"""The bundled case the examples vary (2-D, Type II, three trackers, r_x = r_y = 30)."""
SHARP_THRESHOLD = Fraction(951340728979, 981035254257)
"""≈ 0.969731439161695, the root of v(30 + v) = √(v² + 901): with K_p = vI and k_γ = v the
sufficient test c♯ ≤ λ_min(K)·c of (72) holds iff v is at least this root (an irrational
number; the sweep is around this rational approximation, the truth is decided exactly)."""


def _decimal(x: float) -> Fraction:
    return Fraction(repr(float(x)))


@cache
def _base() -> dict[str, Any]:
    data = yaml.safe_load(bundled_cases()[BASE_CASE].read_text(encoding="utf-8"))
    data.pop("expect", None)
    return data


def _case(K_p: Any, k_gamma: float, epsilon_1: float, name: str) -> dict[str, Any]:
    data = copy.deepcopy(_base())
    data["name"] = f"boundary-{name}"
    data["source"] = "trackcert falsify (seed 003 boundary sweep, docs/theory/pursuit-iss.md)"
    block = data["pursuit"]
    block.update({"K_p": K_p, "k_gamma": k_gamma, "epsilon": [epsilon_1, block["epsilon"][1]]})
    return data


@dataclass(frozen=True)
class RegionPoint:
    """``K_p`` with its least eigenvalue swept through 1 by ``value`` = v.

    ``form``: ``diagonal`` (``K_p = diag(v, 2)``), ``coupled`` (``[[2, v], [v, 2]]``, eigenvalues
    ``2 ± v``), ``rotated`` (``Q diag(v, 2) Qᵀ`` with the 3-4-5 rotation ``Q``, entries computed in
    floats: a matrix whose float eigenvalues land on 1 while its decimals do not), all with
    ``k_γ = 5``; or ``equal`` (``K_p = vI``, ``k_γ = v``, swept through the threshold
    ``v(30 + v) = √(v² + 901)`` of the sufficient test of (72), :data:`SHARP_THRESHOLD`).
    """

    form: Literal["diagonal", "coupled", "rotated", "equal"]
    value: float


def _gains(point: RegionPoint) -> list[list[float]]:
    v = float(point.value)
    if point.form == "equal":
        return [[v, 0.0], [0.0, v]]
    if point.form == "diagonal":
        return [[v, 0.0], [0.0, 2.0]]
    if point.form == "coupled":
        return [[2.0, v], [v, 2.0]]
    return [[0.36 * v + 1.28, 0.48 * v - 0.96], [0.48 * v - 0.96, 0.64 * v + 0.72]]


def _k_gamma(point: RegionPoint) -> float:
    return float(point.value) if point.form == "equal" else 5.0


def region_case(point: RegionPoint) -> dict[str, Any]:
    """The pursuit case of ``point`` (``ε = (−0.5, 0)``)."""
    return _case(_gains(point), _k_gamma(point), -0.5, f"region-{point.form}")


def _region_truth(point: RegionPoint) -> tuple[bool, bool | None]:
    """(λ_min(K) ≥ 1, c♯ ≤ λ_min(K)·c) in exact rationals; the second is None for the rotated
    form, whose eigenvalues are irrational.

    For ``K_p = [[a, c], [c, d]]``, λ_min(K) ≥ 1 iff ``a ≥ 1``, ``d ≥ 1``, ``k_γ ≥ 1`` and
    ``(a − 1)(d − 1) ≥ c²`` (K_p − I ⪰ 0); the sufficient test of (72) with ``√μ = 30`` and
    ``c♯² = ‖K_p‖² + 1 + 900`` is decided by squaring.
    """
    (a, c), (_, d) = ((_decimal(x) for x in row) for row in _gains(point))
    k_gamma = _decimal(_k_gamma(point))
    sound = k_gamma >= 1 and a >= 1 and d >= 1 and (a - 1) * (d - 1) >= c * c
    if point.form == "rotated":
        return sound, None
    kp = [2 - abs(c), 2 + abs(c)] if point.form == "coupled" else [a, d]
    lam, top = min(*kp, k_gamma), max(*kp, k_gamma)
    shown = lam > 0 and max(kp) ** 2 + 1 + 900 <= (lam * (30 + top)) ** 2
    return sound, shown


def region_sound(point: RegionPoint) -> bool:
    """The exact verdict on ``λ_min(K) ≥ 1`` is right, ``K ≻ 0`` holds, and the sufficient test
    of (72) is claimed only when it is true."""
    spec = PURSUIT.parse_case(region_case(point)).spec
    pursuit = pursuit_iss(spec)
    sound, shown = _region_truth(point)
    status = {c.name: c.status for c in iss_conditions(spec)}
    return (
        pursuit.printed_region_sound == sound
        and (shown is not False or not pursuit.printed_region_holds)
        and status["K_positive_definite"] == ConditionStatus.HOLDS
    )


def _region_points() -> st.SearchStrategy[RegionPoint]:
    at_one = st.builds(
        RegionPoint,
        st.sampled_from(["diagonal", "coupled", "rotated"]),
        boundary_values(Fraction(1)),
    )
    at_sharp = boundary_values(SHARP_THRESHOLD).map(lambda v: RegionPoint("equal", v))
    return st.one_of(at_one, at_sharp)


@dataclass(frozen=True)
class CertificatePoint:
    """Gains swept toward 0 (``K_p = diag(k_min, 0.2)``, ``k_γ``) and the surge offset ``ε₁``
    toward 0 (where Δ̄ is undefined)."""

    k_min: float
    k_gamma: float
    epsilon_1: float


def _certificate_case(point: CertificatePoint) -> dict[str, Any]:
    return _case([point.k_min, 0.2], point.k_gamma, point.epsilon_1, "certificate")


def certificate_sound(point: CertificatePoint) -> bool:
    """A certificate is issued and accepted by ``proofs_check`` (or reported inconclusive)
    exactly when ``ε₁ ≠ 0``; it is refused only when ``ε₁ = 0``."""
    spec = PURSUIT.parse_case(_certificate_case(point)).spec
    exists = _decimal(point.epsilon_1) != 0
    try:
        cert = iss_certificate(spec)
    except InconclusiveError:
        return exists
    except PropertyFails:
        return not exists
    return exists and proofs_check.check_certificate(cert).valid


def _small() -> st.SearchStrategy[float]:
    return st.integers(0, 11).map(lambda k: 10.0**-k)


def _offsets() -> st.SearchStrategy[float]:
    tiny = st.tuples(st.sampled_from([-1, 1]), st.integers(1, 17)).map(
        lambda t: t[0] * 10.0 ** -t[1]
    )
    return st.one_of(st.just(0.0), st.just(-0.5), tiny)


# ---------------------------------------------------------------------------------------------
# the properties

WORDINGS = (
    (
        "seed003.eq71/paper",
        "‖Φ‖² < μ‖x̃‖² for x̃ ≠ 0, μ = max_γ{1, ‖r′(γ)‖²} (seed 003 eq. (71) as printed).",
        phi_examples(),
        _phi_paper,
        phi_case,
        False,
    ),
    (
        "seed003.eq71/corrected",
        "‖Φ‖² ≤ μ‖x̃‖² (equality is attained).",
        phi_examples(),
        _phi_corrected,
        phi_case,
        True,
    ),
    (
        "seed003.eq72/paper",
        "V̇ ≤ −(1−θ)λ_min(K)‖e‖² whenever ‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/θ (seed 003 eq. (72) as printed).",
        pursuit_examples(region="paper"),
        _region_holds("paper"),
        pursuit_example_case,
        False,
    ),
    (
        "seed003.eq72/corrected",
        "V̇ ≤ −(1−θ)λ_min(K)‖e‖² whenever ‖e‖ ≥ (√μ + ‖K‖)‖x̃‖/(θλ_min(K)) (the region of (78)).",
        pursuit_examples(region="corrected"),
        _region_holds("corrected"),
        pursuit_example_case,
        True,
    ),
    (
        "seed003.thm1/paper",
        "V̇ ≤ −λ_min(K)‖e‖² + (√μ + ‖K‖)‖e‖‖x̃‖ (first line of (72), behind Theorem 1).",
        pursuit_examples(),
        _dissipation_holds("c"),
        pursuit_example_case,
        True,
    ),
    (
        "seed003.thm1/corrected",
        "V̇ ≤ −λ_min(K)‖e‖² + c♯‖e‖‖x̃‖, c♯ = √(‖K_p‖² + 1 + μ_r) (Type II) or √(‖K_p‖² + 1) "
        "(Type I): the ISS gain c♯/λ_min(K) of Theorem 1, corrected.",
        pursuit_examples(),
        _dissipation_holds("c_sharp"),
        pursuit_example_case,
        True,
    ),
    (
        "seed003.eq74/paper",
        "V̇_c ≤ −k_c r_min‖ξ‖² + ‖ξ‖‖RW‖‖e_γ‖ (seed 003 eq. (74) as printed).",
        coordination_examples(),
        _coordination_holds("paper"),
        coordination_case,
        False,
    ),
    (
        "seed003.eq74/corrected",
        "V̇_c ≤ −k_c a(L) ξᵀRξ + ‖ξ‖_R b‖e_γ‖, a(L) of Definition 1.",
        coordination_examples(),
        _coordination_holds("corrected"),
        coordination_case,
        True,
    ),
    (
        "seed003.eq75/paper",
        "V̇_c ≤ −k_c r_min‖ξ‖² + ‖RW‖‖e‖ (seed 003 eq. (75), first line, with e = e_γ).",
        coordination_examples(),
        _coordination_holds("paper75"),
        coordination_case,
        False,
    ),
    (
        "seed003.eq75/corrected",
        "V̇_c ≤ −(1−θ)k_c a(L) ξᵀRξ whenever ‖ξ‖_R ≥ b‖e_γ‖/(θ k_c a(L)).",
        coordination_examples(inside_region=True),
        _eq75_corrected,
        coordination_case,
        True,
    ),
    (
        "seed003.thm2.sim-trajectories/corrected",
        "ISS certified (every condition holds) ⇒ the simulated ‖μ(t)‖ stays within the certified "
        "estimate β(‖μ(0)‖, t) + γ(sup‖x̃‖) with the run's own estimation error.",
        agreement_examples(),
        _agreement_holds,
        agreement_case,
        True,
    ),
)


BOUNDARY_WORDINGS = (
    (
        "seed003.thm1.boundary/corrected",
        "seed003.thm1",
        "Swept through λ_min(K) = 1 (diagonal, coupled and rotated K_p) and through the "
        "threshold of the sufficient test c♯ ≤ λ_min(K)·c, the verdict 'the printed region (72) "
        "follows from the argument' is exact, K ≻ 0 is decided exactly, and the sufficient test "
        "is never claimed when false.",
        _region_points(),
        region_sound,
        region_case,
    ),
    (
        "seed003.thm2.certificate-boundary/corrected",
        "seed003.thm2",
        "With λ_min(K) and k_γ down to 1e-11 and ε₁ down to 1e-17 (and 0), an iss certificate "
        "accepted by proofs_check (or an inconclusive report) exists iff ε₁ ≠ 0.",
        st.builds(CertificatePoint, _small(), _small(), _offsets()),
        certificate_sound,
        _certificate_case,
    ),
)

PROPERTIES = tuple(
    Property(
        id=name,
        claim=name.split("/")[0],
        wording=name.split("/")[1],
        statement=statement,
        examples=examples,
        holds=holds,
        to_case=to_case,
        expected_to_hold=expected,
    )
    for name, statement, examples, holds, to_case, expected in WORDINGS
) + tuple(
    Property(id=i, claim=c, wording="corrected", statement=s, examples=e, holds=h, to_case=t)
    for i, c, s, e, h, t in BOUNDARY_WORDINGS
)
"""The pursuit domain's falsifiable properties."""

FIXED_INSTANCES = (
    FixedInstance(
        "case.expect.pursuit",
        "about the expect block one pursuit case file states; the ISS claims it observes are "
        "searched as seed003.thm1 and seed003.thm2",
    ),
    FixedInstance(
        "seed003.thm2.certified",
        "a certificate of one case; the corrected Theorem 2 is searched as "
        "seed003.thm2.certificate-boundary and seed003.thm2.sim-trajectories",
    ),
    FixedInstance(
        "seed003.sec6.published-statistics",
        "Monte Carlo statistics of the four published configurations against the authors' runs "
        "(error bands, no runaway); the loop's boundedness is searched as "
        "seed003.thm2.sim-trajectories",
    ),
)
"""The domain's claims about one fixed instance, with the reason."""


# ---------------------------------------------------------------------------------------------
# identities of the model (eqs. (4), (21), (70), Lemma 2), Remark 6, the helix, Lemmas 3–4

IDENTITIES = {
    "eq4-printed-S-3d": lambda: rotation_rate_check(3, printed=True),
    "eq4-2d": lambda: rotation_rate_check(2),
    "eq4-3d": lambda: rotation_rate_check(3),
    "eq21-2d": lambda: error_dynamics_check(2),
    "eq21-3d": lambda: error_dynamics_check(3),
    **{
        f"{name}-{d}d-type-{c}": (
            lambda d=d, c=c, estimated=estimated: lyapunov_derivative_check(d, c, estimated)
        )
        for name, estimated in (("lem2", False), ("eq70", True))
        for d in (2, 3)
        for c in ("I", "II")
    },
}
"""The exact identities of :mod:`theory.pursuit.derivations`, by name (both sides unsimplified)."""

IDENTITY_DIGITS = 50
"""Digits of the evaluation of an identity at a rational point; the residual must be below
``10^(10 − IDENTITY_DIGITS)`` relative to the sides (sin, cos of rational angles are not
rational; everything else is exact)."""


@dataclass(frozen=True)
class IdentityPoint:
    """An identity of :data:`IDENTITIES` and the seed of the rational point (every state,
    rotation, gain and rate a rational in [−5, 5]) where both sides are compared."""

    identity: str
    seed: int


@cache
def _compiled(identity: str) -> tuple[list[sp.Symbol], Any, Any]:
    """The identity's symbols and both sides compiled for mpmath (once per process)."""
    check = IDENTITIES[identity]()
    lhs, rhs = sp.Matrix([check.lhs]), sp.Matrix([check.rhs])
    symbols = sorted(lhs.free_symbols | rhs.free_symbols, key=str)
    return symbols, sp.lambdify(symbols, lhs, "mpmath"), sp.lambdify(symbols, lhs - rhs, "mpmath")


def identity_residual(point: IdentityPoint) -> float:
    """``max |lhs − rhs| / (1 + max |lhs|)`` at the point, to :data:`IDENTITY_DIGITS` digits
    (seed 003 eqs. (3)–(4), (21), (70), Lemma 2)."""
    symbols, lhs, diff = _compiled(point.identity)
    rng = np.random.default_rng(point.seed)
    with mpmath.workdps(IDENTITY_DIGITS):
        values = [
            mpmath.mpf(int(rng.integers(-50, 51))) / int(rng.integers(1, 11)) for _ in symbols
        ]
        left = max(abs(x) for x in np.asarray(lhs(*values), dtype=object).ravel())
        gap = max(abs(x) for x in np.asarray(diff(*values), dtype=object).ravel())
        return float(gap / (1 + left))


def _identity_examples(names: list[str]) -> st.SearchStrategy[IdentityPoint]:
    return st.builds(IdentityPoint, st.sampled_from(names), st.integers(0, 2**32 - 1))


def _identity_record(claim: str):
    return lambda point: example_record(claim, {"identity": point.identity, "seed": point.seed})


def _identity_holds(point: IdentityPoint) -> bool:
    return identity_residual(point) <= 10.0 ** (10 - IDENTITY_DIGITS)


def _identity(claim: str, wording: str, statement: str, names: list[str], hold: bool) -> Property:
    return Property(
        f"{claim}/{wording}", claim, wording, statement, _identity_examples(names),
        _identity_holds, _identity_record(claim), expected_to_hold=hold,
    )  # fmt: skip


def _of(prefix: str) -> list[str]:
    return [name for name in IDENTITIES if name.startswith(prefix)]


@st.composite
def epsilons(draw: st.DrawFn) -> tuple[int, ...]:
    """Non-zero offsets ε (seed 003 eq. (19)) in 2-D or 3-D, integer entries, often with zeros."""
    dim = draw(st.sampled_from((2, 3)))
    entries = st.one_of(st.just(0), st.integers(-3, 3))
    return tuple(draw(st.lists(entries, min_size=dim, max_size=dim).filter(any)))


def gram_determinant(epsilon: tuple[int, ...]) -> sp.Expr:
    """``det(ΔΔᵀ)`` of eq. (22) at ``ε``, exactly (Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ exists iff it is non-zero)."""
    delta = delta_matrix(sp.Matrix(epsilon))
    return (delta * delta.T).det()


def _delta_record(epsilon: tuple[int, ...]) -> dict[str, Any]:
    det = gram_determinant(epsilon)
    return example_record("seed003.eq22.delta-bar", {"epsilon": list(epsilon), "det": str(det)})


HELIX_C = st.one_of(
    st.integers(-4, 4).filter(lambda c: c not in (0, 1)),
    st.fractions(-4, 4, max_denominator=8).filter(lambda c: c not in (0, 1)),
).map(float)
"""Every constant ``c ∈ ℝ∖{0, 1}`` of eq. (15) (integers, so ±1 and the other degenerate
values are drawn, and rationals)."""


def _helix_observes(c: float, excluded: tuple[float, ...]) -> bool:
    """Whether a tracker on the helix of eq. (15) with ``c`` sees rank 6 (vacuous for the
    excluded ``c`` and for rank decisions inside the inconclusive band)."""
    if c in excluded:
        return True
    result = helix_fim_rank(c)
    return result.rank == 6 or not result.conclusive()


def _helix_record(c: float) -> dict[str, Any]:
    return example_record("seed003.eq15.helix", {"c": c, "path": "Table II (eq. (17))"})


@dataclass(frozen=True, eq=False)
class StackedPursuit:
    """Trackers' pursuit examples stacked as in Lemma 4 (eqs. (76)–(78))."""

    trackers: tuple[PursuitExample, ...]


def stacked_dissipation(example: StackedPursuit) -> bool:
    """Lemma 4: ``Σ_i V̇_i ≤ −λ‖e‖² + c‖e‖‖x̃‖`` with ``λ = min_i λ_min(K_i)``, ``c = max_i c_i``
    and the stacked errors (Cauchy–Schwarz on the per-tracker bounds of (72)); seed 003 (78)."""
    terms = [pursuit_terms(t) for t in example.trackers]
    e = math.sqrt(sum(t["e_norm"] ** 2 for t in terms))
    x = math.sqrt(sum(t["x_norm"] ** 2 for t in terms))
    lam, c = min(t["lambda_min"] for t in terms), max(t["c"] for t in terms)
    v_dot = sum(t["v_dot"] for t in terms)
    return v_dot <= -lam * e * e + c * e * x + KINEMATICS_RTOL * sum(t["scale"] for t in terms)


def _stacked_record(example: StackedPursuit) -> dict[str, Any]:
    return pursuit_example_case(example.trackers[0]) | {
        "description": f"{len(example.trackers)} trackers stacked (Lemma 4); the first is shown"
    }


def coordination_iss_holds(example: CoordinationExample) -> bool:
    """Lemma 3 (corrected constants): for a strongly connected weighted digraph ``a(L) > 0``
    (exact) and ``V̇_c ≤ −k_c a(L)‖ξ‖²_R + ‖ξ‖_R b ‖e_γ‖``; seed 003 Lemmas 1, 3, eq. (74)."""
    r = left_eigenvector(example.laplacian)
    if r is None or not r_perp_connectivity_positive(example.laplacian, r):
        return False
    terms = coordination_terms(example)
    return terms["v_dot"] <= terms["corrected"] + INEQUALITY_RTOL * terms["scale"]


@dataclass(frozen=True)
class TrackerPair:
    """Two trackers and a constant-velocity target sampled at ``times`` (seed 003 Result 2):
    tracker 1 on a circle (radius, rate, phase) around a centre, tracker 2 offset from it by a
    fixed vector or by one rotating at ``offset_rate``; target ``q₀ + t v``."""

    radius: float
    rate: float
    phase: float
    offset: tuple[float, float]
    offset_rate: float
    q0: tuple[float, float]
    v: tuple[float, float]

    times = np.arange(60) * 2.0

    def paths(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Tracker 1, tracker 2 and target positions at :attr:`times`."""
        angle = self.rate * self.times + self.phase
        p1 = self.radius * np.column_stack([np.cos(angle), np.sin(angle)])
        turn = self.offset_rate * self.times
        ox, oy = self.offset
        offset = np.column_stack(
            [ox * np.cos(turn) - oy * np.sin(turn), ox * np.sin(turn) + oy * np.cos(turn)]
        )
        target = np.asarray(self.q0) + self.times[:, None] * np.asarray(self.v)
        return p1, p1 + offset, target


@st.composite
def tracker_pairs(draw: st.DrawFn) -> TrackerPair:
    """Circle radius 5–40 m, rate 0.01–0.2 rad/s, integer offset ≠ 0 fixed (often) or rotating,
    a target at rest (often) or slowly moving."""
    small = st.integers(-3, 3).map(float)
    offset = draw(st.tuples(small, small).filter(any))
    return TrackerPair(
        float(draw(st.integers(5, 40))),
        draw(st.integers(1, 20)) / 100,
        draw(st.integers(0, 6)) / 2,
        offset,
        draw(st.sampled_from((0.0, 0.0, 0.03, -0.07))),
        (draw(small) * 3, draw(small) * 3),
        draw(st.sampled_from(((0.0, 0.0), (0.1, 0.05), (-0.05, 0.02)))),
    )


def pair_ranks(pair: TrackerPair) -> tuple[RankResult, RankResult]:
    """Rank of (13) sampled, and of both trackers' stacked range Jacobian (their FIM), seed 003
    eqs. (9)–(10), (13)."""
    p1, p2, target = pair.paths()
    both = np.vstack([range_jacobian(p - target, pair.times) for p in (p1, p2)])
    o = o_matrix(p2 - p1, pair.times)
    return numeric_rank(o, rank_tol=RANK_TOL), numeric_rank(both, rank_tol=RANK_TOL)


def _result2(paper: bool):
    def holds(pair: TrackerPair) -> bool:
        o, fim = pair_ranks(pair)
        if not (o.conclusive() and fim.conclusive()):
            return True
        independent, observes = o.rank == 4, fim.rank == 4
        return observes == independent if paper else observes or not independent

    return holds


def _pair_record(pair: TrackerPair) -> dict[str, Any]:
    data = {k: list(v) if isinstance(v, tuple) else v for k, v in vars(pair).items()}
    return example_record("seed003.result2", data | {"times": "0, 2, …, 118 s"})


MODEL_PROPERTIES = (
    _identity(
        "seed003.eq4", "paper",
        "Ṙ = R S(ω) with S(ω) as printed in eq. (4), for every Z-Y-X Euler angle and body rate.",
        _of("eq4-printed"), False,
    ),
    _identity(
        "seed003.eq4", "corrected",
        "Ṙ = R [ω]ₓ for every Euler angle and body rate, in 2-D and 3-D.",
        ["eq4-2d", "eq4-3d"], True,
    ),
    _identity(
        "seed003.eq21", "paper",
        "ė_p = −S(ω)e_p + Δu − Rᵀ(r′(γ)γ̇ + v) along (2)–(5) for every state, in 2-D and 3-D.",
        _of("eq21"), True,
    ),
    _identity(
        "seed003.lem2", "paper",
        "With the true target V̇ = −eᵀKe for controllers (24)/(25) and (28)/(29), every "
        "symmetric K_p, every state, in 2-D and 3-D.",
        _of("lem2"), True,
    ),
    _identity(
        "seed003.eq70", "paper",
        "V̇₂ = −eᵀKe + e_pᵀRᵀṽ + e_pᵀK_pRᵀq̃ − e_γq̃ᵀr′(γ) with the estimated target, every "
        "state and gain, in 2-D and 3-D.",
        _of("eq70"), True,
    ),
    Property(
        "seed003.eq22.delta-bar/paper", "seed003.eq22.delta-bar", "paper",
        "Every non-zero ε makes Δ̄ = Δᵀ(ΔΔᵀ)⁻¹ well defined (det ΔΔᵀ ≠ 0), Remark 6.",
        epsilons(), lambda eps: gram_determinant(eps) != 0, _delta_record,
        expected_to_hold=False,
    ),
    Property(
        "seed003.eq22.delta-bar/corrected", "seed003.eq22.delta-bar", "corrected",
        "Δ̄ is well defined iff ε₁ ≠ 0 (det ΔΔᵀ = ε₁² in 2-D, ε₁²‖ε‖² in 3-D).",
        epsilons(), lambda eps: (gram_determinant(eps) != 0) == (eps[0] != 0), _delta_record,
    ),
    Property(
        "seed003.eq15.helix/paper", "seed003.eq15.helix", "paper",
        "Every c ∈ ℝ∖{0, 1} in (15) makes the helix observe a constant-velocity target "
        "(range FIM of rank 6 along Table II's path).",
        HELIX_C, lambda c: _helix_observes(c, ()), _helix_record, expected_to_hold=False,
    ),
    Property(
        "seed003.eq15.helix/corrected", "seed003.eq15.helix", "corrected",
        "Every c ∈ ℝ∖{0, 1, −1} makes the helix observe the target (c = −1 keeps the orbit in "
        "a plane through it).",
        HELIX_C, lambda c: _helix_observes(c, (-1.0,)), _helix_record,
    ),
    Property(
        "seed003.result2/paper", "seed003.result2", "paper",
        "Two trackers observe a constant-velocity target's state iff the columns of O(t) of "
        "(13) are linearly independent on [t₀, t].",
        tracker_pairs(), _result2(True), _pair_record, expected_to_hold=False,
    ),
    Property(
        "seed003.result2/corrected", "seed003.result2", "corrected",
        "If the columns of O(t) of (13) are linearly independent, the two trackers observe "
        "the state (sufficient, not necessary).",
        tracker_pairs(), _result2(False), _pair_record,
    ),
    Property(
        "seed003.lem3/paper", "seed003.lem3", "paper",
        "On every strongly connected digraph (a_ij = 1, and weighted) ξ is ISS w.r.t. e_γ: "
        "a(L) > 0 and V̇_c ≤ −k_c a(L)‖ξ‖²_R + ‖ξ‖_R b‖e_γ‖ (Lemma 3 with the constants of "
        "docs/theory/pursuit-iss.md).",
        coordination_examples(), coordination_iss_holds, coordination_case,
    ),
    Property(
        "seed003.lem4/paper", "seed003.lem4", "paper",
        "For N trackers the stacked pursuit error is ISS w.r.t. the stacked estimation error: "
        "V̇_e ≤ −λ_min(K)‖e‖² + (√μ + ‖K‖)‖e‖‖x̃‖ (eqs. (76)–(78)).",
        st.lists(pursuit_examples(), min_size=1, max_size=4).map(
            lambda t: StackedPursuit(tuple(t))
        ),
        stacked_dissipation, _stacked_record,
    ),
)  # fmt: skip
"""Wordings of seed 003's model claims and of Lemmas 3–4 (ids ``<claim>/<wording>``)."""
