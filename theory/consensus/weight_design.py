"""Consensus weights on a given graph with a small certified ``r_σ(L)`` (seed 000 ch. 5, issue 25
item 1): ``trackcert design weights`` as a library call.

**Search (floats).** Each row of ``W`` is a softmax over the case's support (``w_ij > 0`` and the
diagonal), so every candidate is row-stochastic on exactly that graph. Nelder–Mead (scipy)
minimises the smaller ``r_σ(L)`` of two gain choices: the LMI's candidate gains
(:func:`~theory.consensus.s_detectability.lmi_radius`, one solve of the LMI built once: issue 28
item 4) and the projection gains ``L_i = A C_i⁺`` (fixed, so only ``W`` changes L), from the
case's, uniform and, on a symmetric graph, Metropolis weights.

**Certified (exact).** The best ``W`` is rounded to rationals with denominator ``DENOMINATOR``
on the same support (the diagonal completing each row to exactly 1), and the least ``ρ`` of a
ladder of 4-decimal numbers above its float radius is certified by an ``s-detectability``
certificate claiming ``r_σ(L) < ρ ≤ 1``
(:func:`~theory.consensus.s_detectability.decide_s_detectability`). The case's own, uniform and
Metropolis weights are certified the same way for comparison. Only the certified ``ρ`` are
reported as spectral radii; the float radius is the search's estimate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
from scipy.optimize import minimize

from theory.consensus.certificates import projection_gains
from theory.consensus.design import exact_system
from theory.consensus.operators import L_matrix, closed_loop, spectral_radius
from theory.consensus.s_detectability import LmiCache, decide_s_detectability, lmi_radius
from theory.core.case_file import Case
from theory.core.exact import Matrix
from theory.core.network import exact_metropolis_weights, exact_uniform_weights

__all__ = ["DENOMINATOR", "CertifiedWeights", "WeightDesign", "weight_design"]

DENOMINATOR = 1000
"""Denominator of the designed weights (the rounding of the float optimum)."""

LADDER = (Fraction(1, 1000), Fraction(1, 100), Fraction(1, 10))
"""Relative steps above the float radius at which ``r_σ(L) < ρ`` is tried, then ``ρ = 1``."""


@dataclass(frozen=True)
class CertifiedWeights:
    """Named weights, their float radius estimate, and the least certified ``ρ`` with its
    ``s-detectability`` certificate (None: not certified S-detectable)."""

    name: str
    W: Matrix
    estimate: float
    radius: Fraction | None
    certificate: dict[str, Any] | None

    def to_json(self) -> dict[str, Any]:
        """``{"weights", "W", "spectral_radius", "estimate", "certificate"}``."""
        return {
            "weights": self.name,
            "W": [[str(x) for x in row] for row in self.W],
            "spectral_radius": None if self.radius is None else str(self.radius),
            "spectral_radius_value": None if self.radius is None else float(self.radius),
            "estimate": self.estimate,
            "certificate": self.certificate,
        }


@dataclass(frozen=True)
class WeightDesign:
    """The designed weights and the compared ones; ``verdict`` True when the design is
    certified S-detectable, None when nothing was certified."""

    case: str
    designed: CertifiedWeights
    compared: tuple[CertifiedWeights, ...]
    evaluations: int
    note: str

    @property
    def verdict(self) -> bool | None:
        """True when the designed ``W`` has a certificate."""
        return True if self.designed.certificate is not None else None

    @property
    def certificates(self) -> list[dict[str, Any]]:
        """Every certificate of the answer."""
        every = (self.designed, *self.compared)
        return [c.certificate for c in every if c.certificate is not None]

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert design weights --json`` record."""
        d = self.designed
        return {
            "case": self.case,
            "W": [[str(x) for x in row] for row in d.W],
            "spectral_radius": None if d.radius is None else str(d.radius),
            "spectral_radius_value": None if d.radius is None else float(d.radius),
            "estimate": d.estimate,
            "certificate": d.certificate,
            "compared": [c.to_json() for c in self.compared],
            "evaluations": self.evaluations,
            "verdict": self.verdict,
            "note": self.note,
        }


def _rows(support: np.ndarray) -> list[np.ndarray]:
    """Each row's support columns."""
    return [np.flatnonzero(row) for row in support]


def _weights(theta: np.ndarray, support: np.ndarray) -> np.ndarray:
    """Row-wise softmax over the support; the first support entry of each row has logit 0."""
    W = np.zeros(support.shape)
    at = 0
    for i, cols in enumerate(_rows(support)):
        logits = np.concatenate([[0.0], theta[at : at + len(cols) - 1]])
        at += len(cols) - 1
        e = np.exp(logits - logits.max())
        W[i, cols] = e / e.sum()
    return W


def _logits(W: np.ndarray, support: np.ndarray) -> np.ndarray:
    """The ``theta`` of :func:`_weights` giving ``W`` (entries on the support, > 0)."""
    out = []
    for i, cols in enumerate(_rows(support)):
        logs = np.log(W[i, cols])
        out.extend(logs[1:] - logs[0])
    return np.array(out)


def _rational(W: np.ndarray, support: np.ndarray) -> Matrix:
    """``W`` rounded to ``1/DENOMINATOR`` on its support, at least one step each, the diagonal
    completing each row to exactly 1."""
    out = []
    for i, row in enumerate(W):
        exact = [Fraction(0)] * len(row)
        for j in np.flatnonzero(support[i]):
            if j != i:
                exact[j] = Fraction(max(1, round(row[j] * DENOMINATOR)), DENOMINATOR)
        exact[i] = 1 - sum(exact)
        if exact[i] <= 0:  # keep w_ii > 0: scale the others down
            others = sum(exact) - exact[i]
            exact = [x * Fraction(DENOMINATOR - 1, DENOMINATOR) / others for x in exact]
            exact[i] = Fraction(1, DENOMINATOR)
        out.append(exact)
    return out


def _radius(A, C, W: np.ndarray, projection: np.ndarray, problems: LmiCache) -> float:
    """The smaller float ``r_σ(L)`` of the LMI's candidate gains and the projection gains
    (seed 000 eq. (5.13); informative, a search objective)."""
    fixed = spectral_radius(L_matrix(W, projection))
    return min(lmi_radius(A, C, W, problems=problems), fixed)


def _certify(name: str, A, C, W: Matrix, projection: np.ndarray, problems: LmiCache,
             case: str) -> CertifiedWeights:  # fmt: skip
    """The least ``ρ`` of the ladder above the float radius certified for ``W``."""
    estimate = _radius(A, C, np.asarray(W, dtype=float), projection, problems)
    tries = [Fraction(1)]
    if math.isfinite(estimate) and estimate < 1:
        up = [Fraction(max(1, math.ceil(estimate * (1 + step) * 10**4)), 10**4) for step in LADDER]
        tries = sorted({r for r in up if r < 1}) + tries
    for rho in tries:
        result = decide_s_detectability(A, C, W, rho=float(rho), case=case, problems=problems)
        if result.verdict is True:
            return CertifiedWeights(name, W, estimate, rho, result.certificate)
    return CertifiedWeights(name, W, estimate, None, None)


def weight_design(case: Case, *, max_evaluations: int = 300) -> WeightDesign:
    """Row-stochastic rational ``W`` on the case's graph, certified S-detectable with the least
    ``r_σ(L)`` the search finds, against the case's, uniform and Metropolis weights (module
    docstring)."""
    A, C, W_case = exact_system(case)
    support = np.array([[x != 0 for x in row] for row in W_case]) | np.eye(len(W_case), dtype=bool)
    adjacency = support & ~np.eye(len(W_case), dtype=bool)
    named = {"case": W_case, "uniform": exact_uniform_weights(adjacency)}
    if np.array_equal(adjacency, adjacency.T):
        named["metropolis"] = exact_metropolis_weights(adjacency)
    problems = LmiCache()
    gains = [np.array(g, dtype=float).reshape(A.shape[0], -1) for g in projection_gains(A, C)]
    projection = closed_loop(A, C, gains)
    evaluations = 0

    def objective(theta: np.ndarray) -> float:
        nonlocal evaluations
        evaluations += 1
        return _radius(A, C, _weights(theta, support), projection, problems)

    best: tuple[float, np.ndarray] | None = None
    for start in named.values():
        theta0 = _logits(np.asarray(start, dtype=float), support)
        if theta0.size == 0:
            best = (objective(theta0), theta0)
            break
        found = minimize(
            objective, theta0, method="Nelder-Mead",
            options={"maxfev": max_evaluations // len(named), "xatol": 1e-3, "fatol": 1e-5},
        )  # fmt: skip
        if best is None or found.fun < best[0]:
            best = (float(found.fun), found.x)
    assert best is not None
    designed = _certify("designed", A, C, _rational(_weights(best[1], support), support),
                        projection, problems, case.name)  # fmt: skip
    compared = tuple(
        _certify(n, A, C, W, projection, problems, case.name) for n, W in named.items()
    )
    note = (
        "spectral radii are certified bounds r_σ(L) < ρ (s-detectability certificates); the "
        "search is local (Nelder–Mead), so a smaller radius may exist"
    )
    return WeightDesign(case.name, designed, compared, evaluations, note)
