"""What the report's words and numbers mean: the statuses, each claim's margin (definition, unit,
the safe direction) and the units of common evidence keys.

:data:`MARGINS` is keyed by claim id (``fnmatch`` patterns, the first match wins), each entry a
:class:`Margin` naming its kind, so that a reader of any result with a margin sees what it
measures, in which unit, and which side of its threshold is the safe one.
"""

from __future__ import annotations

from dataclasses import dataclass
from fnmatch import fnmatchcase
from typing import Any

from theory.core.tolerances import TOLERANCES

__all__ = ["MARGINS", "STATUS_LEGEND", "UNITS", "Margin", "margin_of", "margin_table", "unit_of"]

STATUS_LEGEND: dict[str, str] = {
    "verified": "the claim holds on this case, by the method shown (its margin clears the "
    "tolerance)",
    "corrected": "the paper's wording fails here; the corrected statement (in the evidence and "
    "docs/errata.md) holds",
    "refuted": "the claim fails; the evidence holds the counterexample",
    "inconclusive": "the deciding quantity lies within tolerance of its threshold, a solver "
    "failed, or the check ran out of time: no verdict either way",
    "met": "an expectation of the case file agrees with what the claims report",
    "unmet": "an expectation disagrees with what the claims report",
    "unchecked": "no claim reported the expected key (or its check crashed)",
}
"""Status (and expectation verdict) → what it means, shown as the report's legend."""


@dataclass(frozen=True)
class Margin:
    """A margin's ``kind``, ``definition``, ``unit``, and which direction is ``safe``."""

    kind: str
    definition: str
    unit: str
    safe: str


_RANK = Margin(
    "numeric rank",
    "min(σ_r / (rank_tol·σ_max), rank_tol·σ_max / σ_{r+1}): the factor by which the singular "
    "values on either side of the rank decision clear its threshold (seed 000 eq. (4.18))",
    "factor (dimensionless)",
    "larger; below inconclusive_factor (default 1000) the verdict is inconclusive",
)
_RANK_AND_MODES = Margin(
    "rank and unit circle",
    "the smaller of the numeric-rank factor and the factor by which every unobservable mode's "
    "||λ| − 1| clears unit_circle_tol (detectability, Cor. 4.2.4)",
    "factor (dimensionless)",
    "larger; below inconclusive_factor the verdict is inconclusive",
)
_PROBABILITY = Margin(
    "random-evaluation error",
    "bound on the probability that an exact rank at a random rational point understates the "
    "generic rank (Schwartz–Zippel)",
    "probability",
    "smaller",
)
_LMI = Margin(
    "S-detectability LMI",
    "S-detectable: the witness margin m with r_σ(L) ≤ ρ(1 − m) (Def. 5.2.4); not: ε_cert, the "
    "residual of the infeasibility certificate",
    "relative (dimensionless)",
    "S-detectable: larger, at least lmi_margin; not S-detectable: smaller, at most cert_tol",
)
_MARGINS: tuple[tuple[str, Margin], ...] = (
    ("seed000.eq4.16.window", _RANK),
    ("seed000.sec4.2.1.coplanar", _RANK),
    ("seed000.thm4.2.3", _RANK_AND_MODES),
    ("seed000.thm4.2.3.*", _RANK_AND_MODES),
    ("seed000.cor4.2.4", _RANK_AND_MODES),
    ("seed000.eq4.20", _PROBABILITY),
    (
        "seed000.eq4.36.rank-sum",
        Margin(
            "rank factor or counterexample bound",
            "the numeric-rank factor of the networked observability matrix; for a counterexample "
            "found at a random point, the bound on the probability that its exact rank is wrong",
            "factor (dimensionless), or probability",
            "factor: larger (below inconclusive_factor inconclusive); probability: smaller",
        ),
    ),
    (
        "seed000.appC.2",
        Margin(
            "counterexample gap",
            "|printed right side − true difference| of App. C.2's identity on the scalar "
            "counterexample, exact",
            "as the covariance",
            "larger means the printed identity is further off (0: no refutation)",
        ),
    ),
    (
        "seed000.sec4.2.2.metropolis",
        Margin(
            "least self-weight",
            "min_i w_ii of the Metropolis weights over every step, exact (§4.2.2 needs w_ii > 0)",
            "weight (dimensionless)",
            "larger; 0 fails",
        ),
    ),
    ("seed000.def5.2.4*", _LMI),
    (
        "seed000.lem5.2.2",
        Margin(
            "distance of a spectral radius from 1",
            "|1 − r(L)|, r(L) the spectral radius of the covariance operator (eq. (5.13))",
            "dimensionless",
            "larger; within value_tol of 1 the verdict is inconclusive",
        ),
    ),
    (
        "seed000.lemA.2.1",
        Margin(
            "decay ratio slack",
            "1 − the worst ratio of the bound of Lemma A.2.1 along the run",
            "dimensionless",
            "larger (negative: the bound fails)",
        ),
    ),
    (
        "seed000.lemA.1.1",
        Margin(
            "printed bound gap",
            "E[V] − the printed bound of Lemma A.1.1, exact",
            "as V",
            "smaller (positive: the printed bound is exceeded)",
        ),
    ),
    (
        "seed000.lemA.1.2",
        Margin(
            "contraction slack",
            "(1 − α) − the largest contraction factor along the run",
            "dimensionless",
            "larger (negative: no contraction)",
        ),
    ),
    (
        "seed000.lem5.2.3",
        Margin(
            "covariance order gap",
            "min over steps and agents of λ_min(P_i(k) − Σ_i(k)), scaled",
            "relative",
            "larger (negative: the order fails)",
        ),
    ),
    (
        "seed003.result3",
        Margin(
            "CRB agreement",
            "max |CRB / paper's bound − 1| over the formations",
            "relative",
            "smaller",
        ),
    ),
    (
        "seed000.sec4.3.1.*",
        Margin(
            "CRB agreement",
            "max |CRB / paper's formula − 1| over the formations",
            "relative",
            "smaller",
        ),
    ),
    (
        "seed003.thm1",
        Margin(
            "λ_min(K)",
            "least eigenvalue of the gain matrix K (eq. (66)): the decay rate's factor",
            "1/s",
            "larger; ≤ 0 fails",
        ),
    ),
    (
        "seed003.lem4",
        Margin("λ_min(K)", "least eigenvalue of K (eq. (66))", "1/s", "larger; ≤ 0 fails"),
    ),
    (
        "seed003.lem3",
        Margin(
            "a(L)",
            "the coordination rate a(L) of Lemma 1/3 (generalized algebraic connectivity)",
            "dimensionless (per unit k_c)",
            "larger; ≤ 0 fails",
        ),
    ),
    (
        "seed003.thm2",
        Margin(
            "least condition margin",
            "the smallest relative margin of the ISS conditions of Thm 2",
            "relative",
            "larger; below margin_tol inconclusive",
        ),
    ),
    (
        "seed003.thm2.sim-trajectories",
        Margin(
            "estimate slack",
            "(β(‖μ(0)‖, t) + γ‖input‖ − ‖μ(t)‖) / bound at the worst sample",
            "relative",
            "larger (negative: a trajectory leaves the certified estimate)",
        ),
    ),
    (
        "seed003.eq72",
        Margin(
            "violation",
            "how far the printed bound (72) is exceeded",
            "relative",
            "smaller (above violation_tol: the printed bound is corrected)",
        ),
    ),
    (
        "seed002.sec3.convergence",
        Margin(
            "convergence gap",
            "least distance of a node's median tail error from the threshold "
            "its expected verdict needs (converge_tol − median, or median − diverge_tol)",
            "m",
            "larger (negative: a node does not behave as expected)",
        ),
    ),
    (
        "seed002.sec4.pf_vs_ekf",
        Margin(
            "convergence gap",
            "as seed002.sec3.convergence, for the particle filters beside the EKF",
            "m",
            "larger",
        ),
    ),
    (
        "seed002.sec3.consensus",
        Margin(
            "significance",
            "z − improvement_tol: the improvement in standard errors, less the tolerance",
            "standard errors",
            "larger (negative: not significant)",
        ),
    ),
    (
        "seed002.sec3.learning",
        Margin(
            "significance",
            "z − improvement_tol of the learned against the Gaussian model",
            "standard errors",
            "larger",
        ),
    ),
    (
        "seed002.fig3.6",
        Margin(
            "bias significance",
            "tolerance − the largest |z| of a learned parameter's bias",
            "standard errors",
            "larger (negative: a parameter is biased)",
        ),
    ),
    (
        "seed002.eq3.*",
        Margin(
            "goodness of fit",
            "Z_TOL − the worst |z| of the fitted parameters",
            "standard errors",
            "larger",
        ),
    ),
    ("seed002.sec3.measurements", _RANK),
    ("seed003.eq15.helix", _RANK),
    ("seed003.result2", _RANK),
)

MARGINS: dict[str, Margin] = dict(_MARGINS)
"""Claim-id pattern → its margin's meaning (the first matching pattern applies)."""

UNITS: dict[str, str] = {
    **{name: t.unit for name, t in TOLERANCES.items()},
    "T": "s",
    "tau": "s",
    "radius": "m",
    "upper_bound": "m",
    "size": "m",
    "comm_range": "m",
    "sigma_min": "singular value (unit of the Jacobian)",
    "final_localization_error": "m",
    "mean_localization_error": "m",
    "max_final_error": "m",
    "lambda_min_K": "1/s",
    "decay_rate": "1/s",
    "spectral_radius_B": "dimensionless",
    "spectral_radius_L": "dimensionless",
    "probability_bound": "probability",
    "seconds": "s",
    "cpu_seconds": "s",
}
"""Evidence key → its unit (keys whose unit is not fixed by their name are left out)."""


def margin_of(claim_id: str) -> Margin | None:
    """The margin meaning of ``claim_id``: the first pattern of :data:`MARGINS` that matches."""
    return next((m for p, m in _MARGINS if fnmatchcase(claim_id, p)), None)


def unit_of(key: str) -> str:
    """The unit of evidence key ``key`` (``""`` when the key does not fix one)."""
    return UNITS.get(key, "")


def margin_table() -> list[dict[str, Any]]:
    """The margin kinds as rows (kind, definition, unit, safe direction, claim patterns)."""
    rows: dict[Margin, list[str]] = {}
    for pattern, margin in _MARGINS:
        rows.setdefault(margin, []).append(pattern)
    return [
        {
            "kind": m.kind,
            "definition": m.definition,
            "unit": m.unit,
            "safe": m.safe,
            "claims": patterns,
        }
        for m, patterns in rows.items()
    ]
