"""Seed 000 App. A, Lemma A.1.1 (the stochastic stability lemma of its refs. [49, 50, 56]).

Hypotheses: ``v̲ ‖ζ_k‖² ≤ V_k(ζ_k) ≤ v̄ ‖ζ_k‖²`` (A.9) and
``E{V_{k+1}(ζ_{k+1}) | ζ_k} − V_k(ζ_k) ≤ μ − α V_k(ζ_k)`` (A.10), with ``v̲, v̄, μ > 0`` and
``0 < α ≤ 1``. The lemma prints the bound (A.11)

    ``E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² (1 − α)^k + (μ/v̲) Σ_{l=1}^{k−1} (1 − α)^l``.

The sum must start at ``l = 0``. Taking expectations in (A.10) gives
``E V_{k+1} ≤ (1 − α) E V_k + μ``; since ``1 − α ≥ 0`` the inequality propagates, and induction
gives ``E V_k ≤ (1 − α)^k E V_0 + μ Σ_{l=0}^{k−1} (1 − α)^l``, whence the corrected bound by
(A.9) (:func:`corrected_bound`). For every ``k ≥ 1`` the printed bound is smaller by exactly
``μ/v̲``, and the corrected bound is attained: for ``ζ_{k+1} = a ζ_k + w_k`` with ``|a| < 1``,
``w_k`` independent, zero-mean, ``E‖w_k‖² = q`` and ``V = ‖ζ‖²``, (A.10) holds with equality for
``μ = q``, ``α = 1 − a²``, and ``E‖ζ_k‖² = a^{2k} E‖ζ_0‖² + q Σ_{l=0}^{k−1} a^{2l}``. With
``a = 0``, ``ζ_0 = 0`` (i.i.d. noise) the printed bound says ``E‖ζ_1‖² ≤ 0`` while
``E‖ζ_1‖² = q``.

The closing sentence "the stochastic process is bounded with probability one" does not follow
either: for i.i.d. ``ζ_k ~ N(0, σ² I)`` (``k ≥ 1``), which meets (A.9)–(A.10),
``P(max_{k≤K} ‖ζ_k‖ ≤ M) = F(M)^K → 0`` for every ``M`` (``F(M) = P(‖w‖ ≤ M) < 1``), so
``sup_k ‖ζ_k‖ = ∞`` almost surely. What the hypotheses do give is
``sup_k E‖ζ_k‖² ≤ (v̄/v̲) E‖ζ_0‖² + μ/(v̲ α)``, hence boundedness in probability uniformly in
``k`` (Markov's inequality); almost-sure boundedness needs more (``μ = 0`` with (A.10) given the
whole past, making ``V_k`` a non-negative supermartingale, or bounded noise).

:func:`rademacher_law` gives the exact law of the linear process with ``w_k = ±s``, so
``E V_k`` and the conditional drift at every atom are computed in exact arithmetic,
independently of the closed form.
"""

from __future__ import annotations

from collections import defaultdict
from fractions import Fraction
from typing import Any

import sympy as sp
import sympy.stats as stats

__all__ = [
    "corrected_bound",
    "gaussian_drift",
    "printed_bound",
    "rademacher_law",
    "symbolic_proof",
]


def _check_constants(v_min: Fraction, v_max: Fraction, mu: Fraction, alpha: Fraction) -> None:
    if not (v_min > 0 and v_max >= v_min and mu > 0 and 0 < alpha <= 1):
        raise ValueError(
            f"Lemma A.1.1 needs 0 < v_min ≤ v_max, mu > 0 and 0 < alpha ≤ 1; got v_min={v_min}, "
            f"v_max={v_max}, mu={mu}, alpha={alpha}"
        )


def _bound(
    k: int,
    first: int,
    v_min: Fraction,
    v_max: Fraction,
    mu: Fraction,
    alpha: Fraction,
    mean_square_0: Fraction,
) -> Fraction:
    if k < 0:
        raise ValueError(f"k must be ≥ 0; got {k}")
    _check_constants(v_min, v_max, mu, alpha)
    r = 1 - Fraction(alpha)
    tail = sum((r**l for l in range(first, k)), Fraction(0))
    return Fraction(v_max) / v_min * mean_square_0 * r**k + Fraction(mu) / v_min * tail


def printed_bound(
    k: int,
    *,
    v_min: Fraction,
    v_max: Fraction,
    mu: Fraction,
    alpha: Fraction,
    mean_square_0: Fraction,
) -> Fraction:
    """The right side of (A.11) as printed, ``Σ`` from ``l = 1``, in exact arithmetic.

    Parameters
    ----------
    k : int
        Time step, ``k ≥ 0``.
    v_min : Fraction
        ``v̲`` of (A.9).
    v_max : Fraction
        ``v̄`` of (A.9).
    mu : Fraction
        ``μ`` of (A.10).
    alpha : Fraction
        ``α`` of (A.10), ``0 < α ≤ 1``.
    mean_square_0 : Fraction
        ``E‖ζ_0‖²``.

    Returns
    -------
    Fraction
        ``(v̄/v̲) E‖ζ_0‖² (1 − α)^k + (μ/v̲) Σ_{l=1}^{k−1} (1 − α)^l`` (``0⁰ = 1``).

    Raises
    ------
    ValueError
        If ``k < 0`` or the constants violate the lemma's hypotheses.

    References
    ----------
    seed 000, App. A, eq. (A.11).
    """
    return _bound(k, 1, v_min, v_max, mu, alpha, mean_square_0)


def corrected_bound(
    k: int,
    *,
    v_min: Fraction,
    v_max: Fraction,
    mu: Fraction,
    alpha: Fraction,
    mean_square_0: Fraction,
) -> Fraction:
    """The corrected (A.11), ``Σ`` from ``l = 0``: what the lemma's hypotheses imply.

    Parameters
    ----------
    k, v_min, v_max, mu, alpha, mean_square_0 :
        As in :func:`printed_bound`.

    Returns
    -------
    Fraction
        ``(v̄/v̲) E‖ζ_0‖² (1 − α)^k + (μ/v̲) Σ_{l=0}^{k−1} (1 − α)^l``
        ``= (v̄/v̲) E‖ζ_0‖² (1 − α)^k + μ (1 − (1 − α)^k)/(v̲ α)`` (``0⁰ = 1``).

    Raises
    ------
    ValueError
        If ``k < 0`` or the constants violate the lemma's hypotheses.

    References
    ----------
    seed 000, App. A, Lemma A.1.1, eq. (A.11) (corrected; module docstring).
    """
    return _bound(k, 0, v_min, v_max, mu, alpha, mean_square_0)


def rademacher_law(a: Fraction, s: Fraction, z0: Fraction, k: int) -> dict[Fraction, Fraction]:
    """Exact law of ``ζ_k`` for ``ζ_{j+1} = a ζ_j + w_j``, ``w_j = ±s`` with probability ½ each.

    Parameters
    ----------
    a : Fraction
        Coefficient of the linear process.
    s : Fraction
        Noise amplitude (``E w_j² = s²``).
    z0 : Fraction
        The deterministic initial state ``ζ_0``.
    k : int
        Time step, ``k ≥ 0``.

    Returns
    -------
    dict of Fraction to Fraction
        Atom ``→`` probability; the probabilities sum to 1.

    Raises
    ------
    ValueError
        If ``k < 0``.
    """
    if k < 0:
        raise ValueError(f"k must be ≥ 0; got {k}")
    law: dict[Fraction, Fraction] = {Fraction(z0): Fraction(1)}
    half = Fraction(1, 2)
    for _ in range(k):
        step: dict[Fraction, Fraction] = defaultdict(Fraction)
        for z, prob in law.items():
            step[a * z + s] += half * prob
            step[a * z - s] += half * prob
        law = dict(step)
    return law


def gaussian_drift(dim: int) -> dict[str, Any]:
    """Prove ``E‖a z + w‖² = a² ‖z‖² + d σ²`` for ``w ~ N(0, σ² I_d)`` (sympy.stats).

    So ``ζ_{k+1} = a ζ_k + w_k`` with Gaussian noise meets (A.10) with equality for
    ``V = ‖ζ‖²``, ``μ = d σ²``, ``α = 1 − a²``.

    Parameters
    ----------
    dim : int
        Dimension ``d``.

    Returns
    -------
    dict
        ``conditional_mean`` (the expectation for fixed ``z``, as a string) and ``equals``
        (whether it simplifies to ``a² ‖z‖² + d σ²``).
    """
    a = sp.Symbol("a", real=True)
    sigma = sp.Symbol("sigma", positive=True)
    z = sp.symbols(f"z0:{dim}", real=True)
    w = [stats.Normal(f"w{i}", 0, sigma) for i in range(dim)]
    mean = sp.expand(stats.E(sum((a * z[i] + w[i]) ** 2 for i in range(dim))))
    target = a**2 * sum(zi**2 for zi in z) + dim * sigma**2
    return {"conditional_mean": str(mean), "equals": sp.simplify(mean - target) == 0}


def symbolic_proof() -> dict[str, Any]:
    """The induction behind the corrected (A.11), and the printed bound's shortfall, in sympy.

    With ``r = 1 − α`` and ``b_k = r^k b_0 + μ Σ_{l=0}^{k−1} r^l``: ``b_{k+1} − (r b_k + μ) = 0``
    identically in ``k`` (so ``m_{k+1} ≤ r m_k + μ``, ``m_k ≤ b_k`` and ``r ≥ 0`` give
    ``m_{k+1} ≤ b_{k+1}``); the closed form ``Σ_{l=0}^{k−1} r^l = (1 − r^k)/α``; and
    ``Σ_{l=0}^{k−1} r^l − Σ_{l=1}^{k−1} r^l = 1`` for ``k ≥ 1`` (the printed bound is smaller by
    ``μ/v̲``).

    Returns
    -------
    dict
        ``recursion_residual``, ``closed_form_residual``, ``corrected_minus_printed`` (strings of
        the simplified expressions; ``"0"``, ``"0"`` and ``"mu/v_min"`` prove the statements).

    References
    ----------
    seed 000, App. A, eqs. (A.9)–(A.11).
    """
    alpha = sp.Symbol("alpha", positive=True)
    mu, v_min, b0 = sp.symbols("mu v_min b_0", positive=True)
    k = sp.Symbol("k", integer=True, positive=True)
    l = sp.Symbol("l", integer=True)
    r = 1 - alpha

    def geometric(first: sp.Expr, last: sp.Expr) -> sp.Expr:
        return sp.Sum(r**l, (l, first, last)).doit()

    def b(j: sp.Expr) -> sp.Expr:
        return r**j * b0 + mu * geometric(0, j - 1)

    recursion = sp.simplify(b(k + 1) - (r * b(k) + mu))
    closed = sp.simplify(geometric(0, k - 1) - (1 - r**k) / alpha)
    shortfall = sp.simplify(mu / v_min * (geometric(0, k - 1) - geometric(1, k - 1)))
    return {
        "recursion_residual": str(recursion),
        "closed_form_residual": str(closed),
        "corrected_minus_printed": str(shortfall),
        "propagation": "m_k ≤ b_k and 1 − α ≥ 0 give m_{k+1} ≤ (1 − α) m_k + μ ≤ b_{k+1}",
    }
