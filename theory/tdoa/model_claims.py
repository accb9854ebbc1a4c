"""Claims about the target model and the consensus weights that no checker module covers.

- ``seed000.eq4.6``: the discrete model (4.5)–(4.6) is the exact discretization of (4.1),
  proved symbolically with sympy for every sampling period ``T`` in 2D and 3D.
- ``seed000.sec4.2.2.metropolis``: on every ``tdoa`` case with Metropolis weights, the matrix the
  suite uses meets §4.2.2's conditions on ``W`` and is symmetric, hence doubly stochastic,
  checked in exact rational arithmetic at every time step.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, register
from theory.core.exact import exact_float
from theory.core.network import exact_metropolis_weights
from theory.core.tolerances import ROUNDING_TOL
from theory.tdoa.model import cv_continuous, cv_discrete, cv_discrete_symbolic

__all__ = ["check_discretization", "check_metropolis_weights"]

DYADIC_PERIODS = (Fraction(1, 4), Fraction(1), Fraction(3))
"""Sampling periods at which the floating model must equal the exact one bit for bit (their
powers and halves are exact in binary floating point)."""

STEPS_SHOWN = 20
"""Time steps whose exact weights the evidence lists (all steps are checked)."""


@register(
    "seed000.eq4.6",
    source="seed 000 eqs. (4.1), (4.5)–(4.6)",
    statement="A and B of (4.6) are the exact discretization of (4.1) with w held constant over "
    "each period: A = exp(F T), B = ∫₀ᵀ exp(F s) G ds, for every T > 0 (2D and 3D)",
)
def check_discretization(case: None = None) -> list[ClaimResult]:
    """Prove eq. (4.6) symbolically and check the library's floating model against it.

    Parameters
    ----------
    case : None
        Model claims run on no case.

    Returns
    -------
    list of ClaimResult
        One ``symbolic`` result: ``verified`` when, in 2D and 3D, ``exp(F T)`` and
        ``∫₀ᵀ exp(F s) G ds`` equal the printed ``A`` and ``B`` identically in ``T`` and
        ``cv_discrete`` reproduces them exactly at :data:`DYADIC_PERIODS`; ``refuted`` otherwise.

    References
    ----------
    seed 000, eqs. (4.1), (4.5)–(4.6).
    """
    per_dim = {f"{dim}d": _discretization_evidence(dim) for dim in (2, 3)}
    holds = all(e["A_exact"] and e["B_exact"] and e["library_exact"] for e in per_dim.values())
    message = (
        "exp(F T) = I + F T (F² = 0) and ∫₀ᵀ exp(F s) G ds = [T²/2 I; T I] identically in T, "
        "as printed in (4.6); the library's floating model matches exactly"
        if holds
        else "the printed A or B (or the library's model) differs from the exact discretization"
    )
    return [
        ClaimResult(
            claim="seed000.eq4.6",
            case="-",
            method="symbolic",
            status="verified" if holds else "refuted",
            evidence=per_dim,
            message=message,
        )
    ]


def _discretization_evidence(dim: int) -> dict[str, Any]:
    T, s = sp.symbols("T s", positive=True)
    F_num, G_num = cv_continuous(dim)
    F, G = sp.Matrix(F_num.astype(int)), sp.Matrix(G_num.astype(int))
    exact_A = (F * T).exp()
    exact_B = ((F * s).exp() * G).integrate((s, 0, T))
    printed_A = cv_discrete_symbolic(T, dim)
    printed_B = sp.Matrix.vstack(T**2 / 2 * sp.eye(dim), T * sp.eye(dim))
    noise = ((F * s).exp() * G * G.T * (F * s).exp().T).integrate((s, 0, T))
    return {
        "F_squared_is_zero": (F * F).is_zero_matrix,
        "exp_FT": exact_A,
        "integral_exp_Fs_G": exact_B,
        "A_exact": sp.simplify(exact_A - printed_A).is_zero_matrix,
        "B_exact": sp.simplify(exact_B - printed_B).is_zero_matrix,
        "library_exact": all(_library_matches(exact_A, exact_B, T, p, dim) for p in DYADIC_PERIODS),
        "dyadic_periods": [str(p) for p in DYADIC_PERIODS],
        "note": "B is exact for w held constant over each period (eq. 4.5's 'slight abuse of "
        "notation'); continuous white noise of unit intensity would instead give the covariance "
        "integral_white_noise_covariance, not B Bᵀ",
        "integral_white_noise_covariance": sp.simplify(noise),
        "B_Bt": sp.simplify(printed_B * printed_B.T),
    }


def _library_matches(
    exact_A: sp.Matrix, exact_B: sp.Matrix, T: sp.Symbol, period: Fraction, dim: int
) -> bool:
    A, B = cv_discrete(float(period), dim)
    value = sp.Rational(period.numerator, period.denominator)
    want_A = np.array(exact_A.subs(T, value).tolist(), dtype=object)
    want_B = np.array(exact_B.subs(T, value).tolist(), dtype=object)
    as_fraction = np.vectorize(lambda x: Fraction(str(x)) if isinstance(x, sp.Basic) else x)
    return bool(
        np.all(np.vectorize(Fraction)(A) == as_fraction(want_A))
        and np.all(np.vectorize(Fraction)(B) == as_fraction(want_B))
    )


@register(
    "seed000.sec4.2.2.metropolis",
    source="seed 000 §4.2.2 (conditions on W before eq. (4.26)); DESIGN.md Metropolis rule",
    statement="Metropolis weights meet §4.2.2's conditions on W (stochastic, w_ii > 0, w_ij > 0 "
    "exactly on the bidirectional links) and are symmetric, hence doubly stochastic, with every "
    "eigenvalue in (−1, 1]",
    kinds=("tdoa",),
)
def check_metropolis_weights(case: Case) -> list[ClaimResult]:
    """Check the case's Metropolis weights exactly at every step (no result for other weights).

    Parameters
    ----------
    case : Case
        A ``tdoa`` case.

    Returns
    -------
    list of ClaimResult
        Empty when the case does not use Metropolis weights; otherwise one ``exact`` result whose
        margin is the smallest self-weight (the distance from violating ``w_ii > 0``), with the
        per-step exact facts and the largest deviation of the floating weights from the exact
        ones (tolerance ``rounding_tol``).

    References
    ----------
    seed 000, §4.2.2 (the conditions on W stated before eq. (4.26)).
    """
    spec = case.spec
    if spec.weights_rule != "metropolis":
        return []
    steps = [_metropolis_step(spec.hears[k], spec.weights[k]) for k in range(spec.steps)]
    exact_ok = all(
        s["stochastic"] and s["column_sums_one"] and s["symmetric"] and s["support_matches"]
        for s in steps
    )
    positive = all(Fraction(s["min_self_weight"]) > 0 for s in steps)
    library_ok = all(s["max_float_deviation"] <= ROUNDING_TOL for s in steps)
    holds = exact_ok and positive and library_ok
    margin = float(min(Fraction(s["min_self_weight"]) for s in steps))
    return [
        ClaimResult(
            claim="seed000.sec4.2.2.metropolis",
            case=case.name,
            method="exact",
            status="verified" if holds else "refuted",
            margin=margin,
            tolerance={"rounding_tol": ROUNDING_TOL},
            evidence={"steps_shown": steps[:STEPS_SHOWN], "n_steps": len(steps)},
            message=_metropolis_message(holds, exact_ok, positive, margin, len(steps)),
        )
    ]


def _metropolis_step(hears: np.ndarray, used: np.ndarray) -> dict[str, Any]:
    exact = exact_metropolis_weights(hears)
    n = len(exact)
    rows = [sum(row) for row in exact]
    columns = [sum(exact[i][j] for i in range(n)) for j in range(n)]
    self_weights = [exact[i][i] for i in range(n)]
    deviation = max(
        abs(float(exact_float(used[i, j]) - exact[i][j])) for i in range(n) for j in range(n)
    )
    return {
        "W": [[str(w) for w in row] for row in exact],
        "stochastic": all(r == 1 for r in rows) and all(w >= 0 for row in exact for w in row),
        "column_sums_one": all(c == 1 for c in columns),
        "symmetric": all(exact[i][j] == exact[j][i] for i in range(n) for j in range(n)),
        "support_matches": all(
            (exact[i][j] > 0) == bool(hears[i, j]) for i in range(n) for j in range(n) if i != j
        ),
        "min_self_weight": str(min(self_weights)),
        "gershgorin_lower_eigenvalue_bound": str(min(2 * w - 1 for w in self_weights)),
        "max_float_deviation": deviation,
    }


def _metropolis_message(
    holds: bool, exact_ok: bool, positive: bool, margin: float, steps: int
) -> str:
    where = f"at all {steps} steps" if steps > 1 else "for the case's network"
    if holds:
        return (
            f"W is stochastic, symmetric and doubly stochastic {where}; "
            f"min w_ii = {margin:.4g} > 0, so by Gershgorin every eigenvalue lies in "
            "[2 min w_ii − 1, 1] ⊂ (−1, 1]"
        )
    if not (exact_ok and positive):
        return f"the exact Metropolis weights violate §4.2.2's conditions {where}"
    return "the floating weights the suite uses differ from the exact Metropolis weights"
