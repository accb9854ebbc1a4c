"""Falsifiable wordings of seed 002's claims (``trackcert falsify``), and its claims about one
fixed instance.

**Maximum likelihood** (eqs. (3.1)–(3.2), (3.17)–(3.19); §3.2.2): for every parameter vector of
the model (:func:`~theory.particle.strategies.dcrw_parameters`) and every seed, the ML fit of
``n = FIT_SAMPLES`` draws lies within ``z_tol`` asymptotic standard errors
(:func:`~theory.particle.dcrw.standard_errors`) of the truth. A statistical statement: under the
claim a deviation beyond ``z_tol = 4`` has probability about 6·10⁻⁵ per parameter, so a found
counterexample is evidence against the estimator, to be rerun with more samples.

**Measurements** (§3.1, citing [35, 36]): "in 2D a node needs two TDOA measurements (three
non-collinear nodes) to localize the target on its own". The rank of the node's constant-velocity
observability matrix is ``2·dim aff{u_j}`` over its nodes' unit directions from the target,
decided exactly (:func:`~theory.tdoa.geometry.exact.exact_direction_rank`). Three non-collinear
nodes do not suffice: with the target on the line through two of them, outside their segment,
both see it in the same direction and the two TDOA rows span one dimension. The corrected
wording: it localizes alone iff its nodes see the target in at least three distinct directions.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from hypothesis import strategies as st

from theory.core.claims import FixedInstance, Property, Wording
from theory.core.tolerances import Z_TOL
from theory.particle.case import DcrwParams
from theory.particle.dcrw import (
    fit_weibull,
    fit_wrapped_cauchy,
    movement_samples,
    sample_dcrw_path,
    sample_weibull,
    sample_wrapped_cauchy,
    standard_errors,
    wrap_angle,
)
from theory.particle.strategies import MeasurementStar, dcrw_parameters, measurement_stars
from theory.strategy_helpers import example_record
from theory.tdoa.geometry.exact import exact_direction_rank

__all__ = [
    "FIT_SAMPLES",
    "FIXED_INSTANCES",
    "PROPERTIES",
    "DcrwDraw",
    "distinct_directions",
    "fit_deviations",
    "local_rank",
]

FIT_SAMPLES = 2000
"""Draws per ML fit."""


@dataclass(frozen=True)
class DcrwDraw:
    """DCRW parameters and the seed of the draws fitted (seed 002 eqs. (3.1)–(3.2))."""

    params: DcrwParams
    seed: int


def _fit(draw: DcrwDraw, which: str) -> dict[str, float]:
    """The ML estimates of eq. (3.1) (``turn``), (3.2) (``step``) or both from a path's
    positions (``path``, eqs. (3.17)–(3.19))."""
    rng, p = np.random.default_rng(draw.seed), draw.params
    if which == "turn":
        mu, gamma = fit_wrapped_cauchy(sample_wrapped_cauchy(rng, p.mu, p.gamma, (FIT_SAMPLES,)))
        return {"mu": mu, "gamma": gamma}
    if which == "step":
        kappa, lam = fit_weibull(sample_weibull(rng, p.kappa, p.lam, (FIT_SAMPLES,)))
        return {"kappa": kappa, "lambda": lam}
    turns, steps = movement_samples(sample_dcrw_path(p, FIT_SAMPLES + 1, rng, start=np.zeros(2)))
    mu, gamma = fit_wrapped_cauchy(turns)
    kappa, lam = fit_weibull(steps)
    return {"mu": mu, "gamma": gamma, "kappa": kappa, "lambda": lam}


def fit_deviations(draw: DcrwDraw, which: str) -> dict[str, float]:
    """Each fitted parameter's distance from the truth in asymptotic standard errors (``μ`` is
    left out when ``γ = 0``: the uniform law has no mean direction); seed 002 §3.2.2."""
    p = draw.params
    truth = {"mu": p.mu, "gamma": p.gamma, "kappa": p.kappa, "lambda": p.lam}
    se = standard_errors(p, FIT_SAMPLES)
    return {
        k: abs(float(wrap_angle(v - truth[k])) if k == "mu" else v - truth[k]) / se[k]
        for k, v in _fit(draw, which).items()
        if np.isfinite(se[k])
    }


def _recovered(which: str) -> Callable[[DcrwDraw], bool]:
    return lambda draw: max(fit_deviations(draw, which).values()) <= Z_TOL


def _dcrw_record(claim: str) -> Callable[[DcrwDraw], dict[str, Any]]:
    def record(draw: DcrwDraw) -> dict[str, Any]:
        p = draw.params
        params = {"mu": p.mu, "gamma": p.gamma, "kappa": p.kappa, "lambda": p.lam}
        return example_record(claim, {"dcrw": params, "seed": draw.seed, "samples": FIT_SAMPLES})

    return record


DCRW_DRAWS = st.builds(DcrwDraw, dcrw_parameters(), st.integers(0, 2**32 - 1))
"""Any DCRW parameters and seed."""


def local_rank(star: MeasurementStar) -> int:
    """Rank of the node's constant-velocity observability matrix from its own TDOA rows:
    ``2·dim aff{u_j}`` (0 without measurements), exact; seed 002 §3.1, seed 000 (4.8)–(4.10)."""
    return 2 * max(exact_direction_rank(list(star.target), [list(n) for n in star.nodes]), 0)


def distinct_directions(star: MeasurementStar) -> int:
    """How many distinct directions the nodes see the target in (exact integer test)."""
    tx, ty = star.target
    seen: list[tuple[int, int]] = []
    for x, y in star.nodes:
        v = (x - tx, y - ty)
        if not any(v[0] * w[1] == v[1] * w[0] and v[0] * w[0] + v[1] * w[1] > 0 for w in seen):
            seen.append(v)
    return len(seen)


def _collinear(points: tuple[tuple[int, int], ...]) -> bool:
    (ax, ay), (bx, by), (cx, cy) = points
    return (bx - ax) * (cy - ay) == (by - ay) * (cx - ax)


def _paper_measurements(star: MeasurementStar) -> bool:
    """Fewer than two measurements: rank < 4; two or more with three non-collinear nodes: 4."""
    rank = local_rank(star)
    if star.measurements < 2:
        return rank < 4
    triples = [
        (star.nodes[0], a, b) for i, a in enumerate(star.nodes[1:]) for b in star.nodes[i + 2 :]
    ]
    return rank == 4 if any(not _collinear(t) for t in triples) else True


def _corrected_measurements(star: MeasurementStar) -> bool:
    """Localizes alone (rank 4) iff the nodes see the target in ≥ 3 distinct directions."""
    return (local_rank(star) == 4) == (distinct_directions(star) >= 3)


def _star_record(star: MeasurementStar) -> dict[str, Any]:
    example = {
        "target": list(star.target),
        "node": list(star.nodes[0]),
        "neighbours": [list(n) for n in star.nodes[1:]],
        "local_observability_rank": local_rank(star),
    }
    return example_record("seed002.sec3.measurements", example)


def _fit_property(claim: str, which: str, what: str) -> Property:
    return Property(
        f"{claim}/paper", claim, Wording.PAPER,
        f"For every DCRW parameter vector, the ML fit of {FIT_SAMPLES} {what} lies within "
        f"{Z_TOL:g} asymptotic standard errors of the truth.",
        DCRW_DRAWS, _recovered(which), _dcrw_record(claim),
    )  # fmt: skip


PROPERTIES = (
    _fit_property("seed002.eq3.1", "turn", "wrapped-Cauchy turning angles (3.1)"),
    _fit_property("seed002.eq3.2", "step", "Weibull step lengths (3.2)"),
    _fit_property(
        "seed002.eq3.17", "path", "turns and steps from a DCRW path's positions (3.17)–(3.19)"
    ),
    Property(
        "seed002.sec3.measurements/paper", "seed002.sec3.measurements", Wording.PAPER,
        "In 2D a node with fewer than two TDOA measurements cannot localize the target on its "
        "own, and two measurements from three non-collinear nodes suffice.",
        measurement_stars(), _paper_measurements, _star_record, expected_to_hold=False,
    ),
    Property(
        "seed002.sec3.measurements/corrected", "seed002.sec3.measurements", Wording.CORRECTED,
        "In 2D a node localizes the target on its own iff its nodes (itself and its TDOA "
        "neighbours) see the target in at least three distinct directions.",
        measurement_stars(), _corrected_measurements, _star_record,
    ),
)  # fmt: skip
"""Every falsifiable wording of the domain (ids ``<claim>/<wording>``)."""

_EXPERIMENT = "a Monte Carlo experiment on the paper's fixed network and DCRW parameters"
FIXED_INSTANCES = (
    FixedInstance("seed002.fig3.6", f"{_EXPERIMENT} (§3.3.2, Fig. 3.6)"),
    FixedInstance("seed002.sec3.consensus", f"{_EXPERIMENT} (topology B, §3.3.1, Fig. 3.4)"),
    FixedInstance(
        "seed002.sec3.convergence", f"{_EXPERIMENT} (topologies A and B, §3.3.1, Figs. 3.2–3.3)"
    ),
    FixedInstance("seed002.sec3.learning", f"{_EXPERIMENT} (§3.3.2, Figs. 3.5–3.6)"),
    FixedInstance(
        "seed002.sec4.pf_vs_ekf", "the field comparison on three-node path graphs (§4.3.3)"
    ),
)
"""The domain's claims about one fixed instance, with the reason."""
