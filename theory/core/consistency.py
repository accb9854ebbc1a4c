"""Filter consistency and multi-object distances: NEES, NIS, their χ² acceptance bands, OSPA and
GOSPA (docs/simulation.md, *Filter metrics*).

A filter is consistent when its errors are zero-mean with the covariance it reports. Then the
normalized estimation error squared ``ε = eᵀP⁻¹e`` of an ``n``-dimensional state is ``χ²_n`` and
the normalized innovation squared ``νᵀS⁻¹ν`` of an ``m``-dimensional measurement is ``χ²_m``;
the sum of ``M`` independent runs' statistics at one step is ``χ²_{nM}``, so their average (the
ANEES) lies in ``[χ²_{nM}((1−p)/2), χ²_{nM}((1+p)/2)] / M`` with probability ``p`` (Bar-Shalom,
Li, Kirubarajan 2001, §5.4, eqs. (5.4.1-5)–(5.4.2-7)). Above the band the filter is *optimistic*
(its covariance is too small for its errors: the unsafe side), below it *pessimistic* (safe but
wasteful). The band counts every step as independent, which estimation errors correlated in time
are not, so a verdict outside it is kept only when the spread of independent units agrees
(:func:`spread_interval`: runs, or batch means of contiguous steps, each batch several
correlation times long); otherwise it is inconclusive. Every simulator records the errors,
covariances, innovations and their covariances; this module alone turns them into statistics and
verdicts.

OSPA (Schuhmacher, Vo, Vo 2008) and GOSPA (García-Fernández, Svensson 2017) compare a set of
estimated positions with the set of true ones at cutoff ``c`` and order ``p``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np

from theory.core.tolerances import (
    CONSISTENCY_PROBABILITY,
    CONSISTENCY_RTOL,
    GOSPA_ALPHA,
    OSPA_CUTOFF,
    OSPA_ORDER,
)

__all__ = [
    "AUTOCORRELATION_WINDOW",
    "BATCH_LENGTH",
    "SPREAD_UNITS",
    "Band",
    "Consistency",
    "ConsistencyTest",
    "Spread",
    "agent_columns",
    "chi2_band",
    "consistency_test",
    "correlation_steps",
    "describe",
    "evidence",
    "filter_metrics",
    "gospa",
    "nees",
    "nis",
    "ospa",
    "padded",
    "position_distances",
    "spread_interval",
]

SPREAD_UNITS = 10
"""From this many runs on, :func:`spread_interval` takes the runs as its independent units; with
fewer, it cuts each run into contiguous batches of :data:`BATCH_LENGTH` correlation times (batch
means)."""

BATCH_LENGTH = 10
"""Length of a batch of steps in integrated autocorrelation times, taken one standard error
above their estimate (:func:`correlation_steps`): adjacent batch means of L steps correlate by
about τ/(2L), and τ estimated from a short run comes out low. Measured in
``benchmarks/bench_spread_check.py`` (docs/simulation.md, *The spread check*)."""

AUTOCORRELATION_WINDOW = 5
"""Sokal's automatic window: τ is summed over the first M lags, M the least with M ≥ 5 τ(M)."""


class Consistency(StrEnum):
    """Where a NEES/NIS average lies against its band."""

    CONSISTENT = "consistent"
    OPTIMISTIC = "optimistic"  # above the band: covariance too small for the errors (unsafe)
    PESSIMISTIC = "pessimistic"  # below the band: covariance too large (safe, conservative)
    INCONCLUSIVE = "inconclusive"  # within consistency_rtol of an edge, or nothing to test


def nees(errors: np.ndarray, covariances: np.ndarray) -> np.ndarray:
    """Normalized estimation error squared ``eᵀP⁻¹e`` over the leading axes.

    Parameters
    ----------
    errors : ndarray, shape (..., n)
        Estimation errors ``e = x − x̂`` (either sign convention gives the same value).
    covariances : ndarray, shape (..., n, n)
        The covariances the filter reports for them (symmetric positive definite).

    Returns
    -------
    ndarray, shape (...)
        ``χ²_n`` distributed for a consistent filter; NaN where an error is NaN (a stopped run);
        ∞ where ``P`` is singular to working precision (a filter claiming no uncertainty).

    References
    ----------
    Bar-Shalom, Li, Kirubarajan (2001), eq. (5.4.1-5).
    """
    e = np.asarray(errors, dtype=float)
    P = np.asarray(covariances, dtype=float)
    singular = _singular(P)
    safe = np.where(singular[..., None, None], np.eye(P.shape[-1]), P)
    solved = np.linalg.solve(safe, np.nan_to_num(e)[..., None])
    value = np.where(singular, np.inf, np.einsum("...i,...i->...", e, solved[..., 0]))
    return np.where(np.isnan(e).any(axis=-1), np.nan, value)


def _singular(P: np.ndarray) -> np.ndarray:
    """Where ``P`` is singular to working precision: ``σ_min ≤ n·eps·σ_max`` (a collapsed cloud)."""
    if P.shape[-1] == 0:
        return np.zeros(P.shape[:-2], dtype=bool)
    s = np.linalg.svd(np.nan_to_num(P), compute_uv=False)
    return s[..., -1] <= P.shape[-1] * np.finfo(float).eps * s[..., 0]


def nis(innovations: np.ndarray, covariances: np.ndarray) -> np.ndarray:
    """Normalized innovation squared ``νᵀS⁻¹ν`` (:func:`nees` of the innovations).

    Parameters
    ----------
    innovations : ndarray, shape (..., m)
        Innovations ``ν = y − ŷ``.
    covariances : ndarray, shape (..., m, m)
        Their covariances ``S = HPHᵀ + R`` as the filter computes them.

    Returns
    -------
    ndarray, shape (...)
        ``χ²_m`` distributed for a consistent filter.

    References
    ----------
    Bar-Shalom, Li, Kirubarajan (2001), eq. (5.4.2-1).
    """
    return nees(innovations, covariances)


@dataclass(frozen=True)
class Band:
    """The two-sided acceptance band ``[lower, upper]`` of the average of ``samples`` statistics
    whose sum is ``χ²_dof`` under consistency, holding it with ``probability``."""

    lower: float
    upper: float
    dof: int
    samples: int
    probability: float

    def to_json(self) -> dict[str, Any]:
        """``lower``, ``upper``, ``dof``, ``samples``, ``probability``."""
        return vars(self).copy()


def chi2_band(dof: int, samples: int, probability: float = CONSISTENCY_PROBABILITY) -> Band:
    """The χ² acceptance band of an average of ``samples`` normalized squares totalling ``dof``
    degrees of freedom.

    Parameters
    ----------
    dof : int
        Degrees of freedom of the sum: dimension × runs (× steps for a time average).
    samples : int
        Number of statistics averaged (runs, or runs × steps).
    probability : float
        Two-sided probability ``p`` of the band (default ``consistency_probability``).

    Returns
    -------
    Band
        ``[χ²_dof((1−p)/2), χ²_dof((1+p)/2)] / samples``.

    Raises
    ------
    ValueError
        If ``dof`` or ``samples`` is below 1 or ``probability`` not in (0, 1).

    References
    ----------
    Bar-Shalom, Li, Kirubarajan (2001), eqs. (5.4.2-6)–(5.4.2-7).
    """
    if dof < 1 or samples < 1:
        raise ValueError(f"dof and samples must be ≥ 1, got dof={dof}, samples={samples}")
    if not 0 < probability < 1:
        raise ValueError(f"probability must be in (0, 1), got {probability}")
    low, high = _chi2_quantile(np.array([(1 - probability) / 2, (1 + probability) / 2]), dof)
    return Band(float(low / samples), float(high / samples), int(dof), int(samples), probability)


@dataclass(frozen=True)
class Spread:
    """The mean over ``units`` independent units of ``Σ values / Σ dims`` (1 for a consistent
    filter) with its two-sided Student-t interval at the band's probability (unbounded with one
    unit); ``method`` is ``"runs"`` or ``"batch means"``: contiguous batches of
    ``batch_steps`` steps, :data:`BATCH_LENGTH` times the statistic's integrated autocorrelation
    time ``correlation_steps`` plus its standard error (both ``None`` for runs)."""

    units: int
    method: str
    mean: float
    lower: float
    upper: float
    batch_steps: int | None = None
    correlation_steps: float | None = None

    def to_json(self) -> dict[str, Any]:
        """``units``, ``method``, ``mean``, ``lower``, ``upper``, ``batch_steps``,
        ``correlation_steps``."""
        return vars(self).copy()


def spread_interval(
    values: np.ndarray, dims: np.ndarray, valid: np.ndarray, probability: float
) -> Spread | None:
    """The mean normalized statistic over independent units with its Student-t interval
    (Bar-Shalom et al. §5.4 sums independent runs; steps of one run are correlated): the runs,
    or batches of each run :data:`BATCH_LENGTH` correlation times long; ``None`` when a unit is
    infinite (a singular covariance: optimistic as it is)."""
    runs = values.shape[0]
    steps = [np.flatnonzero(valid[run]) for run in range(runs)]
    if runs >= SPREAD_UNITS:
        parts, batch, tau = [[s] for s in steps], None, None
    else:
        tau, error = correlation_steps([values[r, s] / dims[r, s] for r, s in enumerate(steps)])
        batch = math.ceil(BATCH_LENGTH * (tau + error))
        parts = [np.array_split(s, max(1, s.size // batch)) for s in steps]
    ratios = np.asarray(
        [values[r, p].sum() / dims[r, p].sum() for r in range(runs) for p in parts[r] if p.size]
    )
    if not np.isfinite(ratios).all():  # ∞: a singular covariance
        return None
    mean, method = float(ratios.mean()), "runs" if batch is None else "batch means"
    if len(ratios) < 2:
        return Spread(len(ratios), method, mean, -math.inf, math.inf, batch, tau)
    half = float(_t_quantile((1 + probability) / 2, len(ratios) - 1) * ratios.std(ddof=1))
    half /= math.sqrt(len(ratios))
    return Spread(len(ratios), method, mean, mean - half, mean + half, batch, tau)


def correlation_steps(series: list[np.ndarray]) -> tuple[float, float]:
    """The integrated autocorrelation time τ = 1 + 2 Σ_{k≥1} ρ_k (in steps, ≥ 1) of runs of one
    statistic and its standard error τ·√(2(2M + 1)/N) (N steps in all).

    Each run is centred on its own mean and the autocovariances are pooled over the runs; τ is
    summed over Sokal's automatic window of M lags (:data:`AUTOCORRELATION_WINDOW`), or over
    every lag of the longest run, with an error of τ, when no window fits (Sokal 1997, "Monte
    Carlo methods in statistical mechanics", §3, eqs. (3.19), (3.21)).
    """
    longest, total = max((x.size for x in series), default=0), sum(x.size for x in series)
    covariances = np.zeros(max(longest, 1))
    for x in series:
        if x.size > 1 and np.isfinite(x).all():
            transform = np.fft.rfft(x - x.mean(), 2 * x.size)
            covariances[: x.size] += np.fft.irfft(transform * transform.conj())[: x.size]
    if covariances[0] <= 0:
        return 1.0, 0.0
    taus = 1 + 2 * np.cumsum(covariances[1:] / covariances[0])
    fits = np.flatnonzero(np.arange(1, longest) >= AUTOCORRELATION_WINDOW * taus)
    if not fits.size:
        return float(longest), float(longest)
    tau = max(float(taus[fits[0]]), 1.0)
    return tau, tau * math.sqrt(2 * (2 * fits[0] + 3) / total)


@dataclass(frozen=True)
class ConsistencyTest:
    """One statistic (``NEES`` or ``NIS``) of a filter against its band.

    ``value`` is the average over every run and step (the band: dimension × runs × steps degrees
    of freedom, exact when the steps are independent, as innovations of an optimal filter are);
    ``expected`` the mean dimension; ``margin`` the distance to the nearer edge in band widths
    (negative outside);
    ``steps_in_band`` the fraction of steps whose average over runs lies in its own band
    (dimension × runs degrees of freedom; about ``probability`` when consistent); ``spread`` the
    check of a verdict outside the band on independent units (:func:`spread_interval`).
    """

    statistic: str
    value: float
    expected: float
    band: Band
    margin: float
    verdict: Consistency
    steps_in_band: float
    rtol: float
    spread: Spread | None = None

    def to_json(self) -> dict[str, Any]:
        """The record: statistic, value, expected, band, margin, verdict, steps in band, the
        safe side and the tolerances."""
        return {
            "statistic": self.statistic,
            "value": self.value,
            "expected": self.expected,
            "band": self.band.to_json(),
            "margin": self.margin,
            "verdict": self.verdict.value,
            "steps_in_band": self.steps_in_band,
            "spread": None if self.spread is None else self.spread.to_json(),
            "safe_side": "below the upper edge (above it the covariance understates the error)",
            "tolerance": {
                "consistency_probability": self.band.probability,
                "consistency_rtol": self.rtol,
            },
        }


def consistency_test(
    statistic: str,
    values: np.ndarray,
    dims: np.ndarray | int,
    *,
    probability: float = CONSISTENCY_PROBABILITY,
    rtol: float = CONSISTENCY_RTOL,
) -> ConsistencyTest:
    """ANEES (or average NIS) of ``values`` against its χ² band, with a verdict.

    Parameters
    ----------
    statistic : str
        ``"NEES"`` or ``"NIS"`` (a label).
    values : ndarray, shape (runs, steps)
        Normalized squares from :func:`nees` or :func:`nis`; NaN entries (no estimate, no
        measurement) are left out.
    dims : ndarray of int, shape (runs, steps), or int
        Dimension of each statistic (state or innovation dimension); 0 entries are left out.
    probability : float
        Two-sided probability of the bands (default ``consistency_probability``).
    rtol : float
        Within ``rtol`` band widths of an edge the verdict is inconclusive (default
        ``consistency_rtol``).

    Returns
    -------
    ConsistencyTest
        Inconclusive with NaN value when nothing is left to test.

    References
    ----------
    Bar-Shalom, Li, Kirubarajan (2001), §5.4.2.
    """
    values = np.atleast_2d(np.asarray(values, dtype=float))
    dims = np.broadcast_to(np.asarray(dims, dtype=int), values.shape)
    valid = ~np.isnan(values) & (dims > 0)
    if not valid.any():
        band = Band(np.nan, np.nan, 0, 0, probability)
        return ConsistencyTest(
            statistic, np.nan, np.nan, band, np.nan, Consistency.INCONCLUSIVE, np.nan, rtol
        )
    count = int(valid.sum())
    band = chi2_band(int(dims[valid].sum()), count, probability)
    value = float(values[valid].sum() / count)
    expected = float(dims[valid].sum() / count)
    margin = min(value - band.lower, band.upper - value) / (band.upper - band.lower)
    spread = spread_interval(values, dims, valid, probability)
    return ConsistencyTest(
        statistic,
        value,
        expected,
        band,
        margin,
        _verdict(value, band, margin, rtol, spread),
        _steps_in_band(values, dims, valid, probability),
        rtol,
        spread,
    )


def _verdict(
    value: float, band: Band, margin: float, rtol: float, spread: Spread | None
) -> Consistency:
    """Inside, above or below the band; inconclusive within ``rtol`` of an edge (§5.4.2), or
    outside it while the independent units' interval still contains 1 (consistency)."""
    if abs(margin) <= rtol:
        return Consistency.INCONCLUSIVE
    if margin > 0:
        return Consistency.CONSISTENT
    if spread is not None and spread.lower <= 1.0 <= spread.upper:
        return Consistency.INCONCLUSIVE
    return Consistency.OPTIMISTIC if value > band.upper else Consistency.PESSIMISTIC


def _steps_in_band(
    values: np.ndarray, dims: np.ndarray, valid: np.ndarray, probability: float
) -> float:
    """Fraction of steps whose average over runs lies in its ``χ²_{dim·runs}`` band (5.4.2-6):
    the sum over runs at a step against ``χ²`` quantiles of that step's degrees of freedom."""
    tested = valid.any(axis=0)
    sums = np.where(valid, values, 0.0).sum(axis=0)[tested]
    dof = np.where(valid, dims, 0).sum(axis=0)[tested]
    low, high = (
        _chi2_quantile((1 - probability) / 2, dof),
        _chi2_quantile((1 + probability) / 2, dof),
    )
    return float(np.mean((low <= sums) & (sums <= high)))


def _t_quantile(q: float, dof: int) -> float:
    """The Student-t quantile at ``q`` with ``dof`` degrees of freedom (scipy.special)."""
    from scipy.special import stdtrit

    return float(stdtrit(dof, q))


def _chi2_quantile(q: Any, dof: Any) -> Any:
    """The ``χ²_dof`` quantile at ``q``: scipy.special's inverse survival function (scipy.stats's
    ``chi2.ppf`` computes the same, for half a second of import)."""
    from scipy.special import chdtri

    return chdtri(dof, 1 - np.asarray(q))


def _cutoff_costs(X: np.ndarray, Y: np.ndarray, cutoff: float, order: float) -> np.ndarray:
    """``min(c, ‖x − y‖)^p`` for every pair (Schuhmacher et al. 2008, eq. (3))."""
    distance = np.linalg.norm(X[:, None, :] - Y[None, :, :], axis=-1)
    return np.minimum(distance, cutoff) ** order


def _points(points: np.ndarray) -> np.ndarray:
    """A set of points as an ``(m, d)`` array (``m`` may be 0)."""
    array = np.asarray(points, dtype=float)
    return array.reshape(0, 1) if array.size == 0 else np.atleast_2d(array)


def ospa(
    X: np.ndarray, Y: np.ndarray, *, cutoff: float = OSPA_CUTOFF, order: float = OSPA_ORDER
) -> float:
    """OSPA distance of order ``p`` and cutoff ``c`` between two finite point sets.

    Parameters
    ----------
    X, Y : ndarray, shape (m, d) and (n, d)
        The sets (e.g. estimated and true positions), possibly empty.
    cutoff : float
        ``c > 0`` (default ``ospa_cutoff``, metres).
    order : float
        ``p ≥ 1`` (default ``ospa_order``).

    Returns
    -------
    float
        ``(min_π Σ_i min(c, ‖x_i − y_π(i)‖)^p + c^p |n − m|)^{1/p} / max(m, n)^{1/p}``, 0 for two
        empty sets; a metric bounded by ``c``.

    References
    ----------
    Schuhmacher, Vo, Vo (2008), IEEE Trans. Signal Process. 56(8), eq. (3).
    """
    X, Y = _points(X), _points(Y)
    m, n = len(X), len(Y)
    if max(m, n) == 0:
        return 0.0
    total = _assigned_cost(X, Y, cutoff, order) + cutoff**order * abs(m - n)
    return float((total / max(m, n)) ** (1 / order))


def gospa(
    X: np.ndarray,
    Y: np.ndarray,
    *,
    cutoff: float = OSPA_CUTOFF,
    order: float = OSPA_ORDER,
    alpha: float = GOSPA_ALPHA,
) -> float:
    """GOSPA distance of order ``p``, cutoff ``c`` and ``α`` between two finite point sets.

    Parameters
    ----------
    X, Y : ndarray, shape (m, d) and (n, d)
        The sets, possibly empty.
    cutoff : float
        ``c > 0`` (default ``ospa_cutoff``, metres).
    order : float
        ``p ≥ 1`` (default ``ospa_order``).
    alpha : float
        ``0 < α ≤ 2`` (default ``gospa_alpha`` = 2: localization plus ``c^p/2`` per missed or
        false estimate).

    Returns
    -------
    float
        ``(min_π Σ_i min(c, ‖x_i − y_π(i)‖)^p + (c^p/α) |n − m|)^{1/p}`` (not normalized).

    References
    ----------
    García-Fernández, Svensson (2017), arXiv:1601.05585, Definition 1 and Proposition 1.
    """
    if not 0 < alpha <= 2:
        raise ValueError(f"GOSPA needs 0 < alpha ≤ 2, got {alpha}")
    X, Y = _points(X), _points(Y)
    total = _assigned_cost(X, Y, cutoff, order) + cutoff**order / alpha * abs(len(X) - len(Y))
    return float(total ** (1 / order))


def _assigned_cost(X: np.ndarray, Y: np.ndarray, cutoff: float, order: float) -> float:
    """``min_π Σ min(c, d)^p`` over the assignments of the smaller set (linear_sum_assignment)."""
    if min(len(X), len(Y)) == 0:
        return 0.0
    from scipy.optimize import linear_sum_assignment  # imported when positions are compared

    costs = _cutoff_costs(X, Y, cutoff, order)
    rows, cols = linear_sum_assignment(costs)
    return float(costs[rows, cols].sum())


def position_distances(
    estimates: np.ndarray,
    truth: np.ndarray,
    *,
    cutoff: float = OSPA_CUTOFF,
    order: float = OSPA_ORDER,
    alpha: float = GOSPA_ALPHA,
) -> dict[str, Any]:
    """Mean OSPA and GOSPA of every agent's estimate of one target, over runs and steps.

    Parameters
    ----------
    estimates : ndarray, shape (runs, steps, agents, d)
        Estimated positions; a NaN row is no estimate (the empty set: cost ``c``, resp.
        ``c/α^{1/p}``).
    truth : ndarray, shape (runs, steps, d)
        The target's true positions.
    cutoff, order, alpha : float
        ``c`` (metres), ``p`` and GOSPA's ``α`` (defaults from the tolerance table).

    Returns
    -------
    dict
        With one estimate and one target per set, :func:`ospa` is ``min(c, ‖x̂ − x‖)`` and ``c``
        without an estimate, :func:`gospa` the same with ``c/α^{1/p}`` for the missed target:
        ``ospa`` and ``gospa`` per agent (lists) and their network means, with the tolerances.
    """
    error = np.linalg.norm(estimates - truth[:, :, None, :], axis=-1)
    missing = np.isnan(error)
    located = np.minimum(np.nan_to_num(error, nan=cutoff), cutoff)
    ospas = np.where(missing, cutoff, located)
    gospas = np.where(missing, cutoff / alpha ** (1 / order), located)
    return {
        "ospa": [float(v) for v in ospas.mean(axis=(0, 1))],
        "gospa": [float(v) for v in gospas.mean(axis=(0, 1))],
        "mean_ospa": float(ospas.mean()),
        "mean_gospa": float(gospas.mean()),
        "tolerance": {"ospa_cutoff": cutoff, "ospa_order": order, "gospa_alpha": alpha},
    }


def filter_metrics(
    nees_values: np.ndarray,
    nees_dims: np.ndarray | int,
    nis_values: np.ndarray,
    nis_dims: np.ndarray | int,
    positions: tuple[np.ndarray, np.ndarray] | None = None,
    *,
    probability: float = CONSISTENCY_PROBABILITY,
) -> dict[str, Any]:
    """The ``metrics`` record of a simulation: NEES and NIS tests per agent, OSPA/GOSPA.

    Parameters
    ----------
    nees_values, nis_values : ndarray, shape (runs, steps, agents)
        :func:`nees` and :func:`nis` of every run, step and agent (NaN: none).
    nees_dims, nis_dims : ndarray of int, shape (runs, steps, agents), or int
        The state and innovation dimensions (0: none).
    positions : (ndarray, ndarray), optional
        Estimated positions ``(runs, steps, agents, d)`` and true ones ``(runs, steps, d)`` for
        :func:`position_distances` (``None``: the filter estimates no position).
    probability : float
        Two-sided probability of the χ² bands.

    Returns
    -------
    dict
        ``nees`` and ``nis``: one :meth:`ConsistencyTest.to_json` per agent; ``positions``:
        :func:`position_distances` or ``None``; ``tolerance``.
    """
    record: dict[str, Any] = {}
    for name, values, dims in (("NEES", nees_values, nees_dims), ("NIS", nis_values, nis_dims)):
        dims = np.broadcast_to(np.asarray(dims, dtype=int), values.shape)
        record[name.lower()] = [
            consistency_test(name, values[..., i], dims[..., i], probability=probability).to_json()
            for i in range(values.shape[-1])
        ]
    record["positions"] = None if positions is None else position_distances(*positions)
    record["tolerance"] = {
        "consistency_probability": probability,
        "consistency_rtol": CONSISTENCY_RTOL,
    }
    return record


def agent_columns(metrics: dict[str, Any], agent: int) -> dict[str, Any]:
    """The summary-table columns of agent ``agent`` (0-based): ``anees``, its verdict, the mean
    NIS and, where positions are estimated, the mean OSPA."""
    columns = {
        "anees": metrics["nees"][agent]["value"],
        "nees_verdict": metrics["nees"][agent]["verdict"],
        "mean_nis": metrics["nis"][agent]["value"],
        "nis_verdict": metrics["nis"][agent]["verdict"],
    }
    if metrics["positions"] is not None:
        columns["mean_ospa"] = metrics["positions"]["ospa"][agent]
    return columns


def padded(innovation: np.ndarray, covariance: np.ndarray, size: int) -> tuple:
    """``ν`` zero-padded to ``size`` and ``S`` to ``blkdiag(S, I)``: the same :func:`nis`, so
    innovations of varying dimension stack (Bar-Shalom et al. 2001, eq. (5.4.2-1))."""
    m = innovation.shape[0]
    full = np.eye(size)
    full[:m, :m] = covariance
    return np.concatenate([innovation, np.zeros(size - m)]), full


def describe(metrics: dict[str, Any]) -> list[str]:
    """One line per agent and statistic of a :func:`filter_metrics` record, and one for OSPA:
    the value, its band and probability, the verdict and the safe side (for printed tables).

    Parameters
    ----------
    metrics : dict
        A ``metrics`` record (from a simulation summary, ``pf.json`` or an API result).

    Returns
    -------
    list of str
    """
    lines = [
        "NEES/NIS against two-sided χ² bands: above the band the covariance understates the error"
    ]
    for name in ("nees", "nis"):
        for agent, test in enumerate(metrics[name], start=1):
            band = test["band"]
            lines.append(
                f"agent {agent} {test['statistic']} {_number(test['value'])} vs "
                f"{band['probability']:.0%} band [{_number(band['lower'])}, "
                f"{_number(band['upper'])}] ({band['dof']} dof): {test['verdict']}"
                f"{_SIDES.get(test['verdict'], '')}"
            )
    positions = metrics["positions"]
    if positions is not None:
        tol = positions["tolerance"]
        lines.append(
            f"mean OSPA {positions['mean_ospa']:.3g} m, GOSPA {positions['mean_gospa']:.3g} "
            f"(c = {tol['ospa_cutoff']:g} m, p = {tol['ospa_order']:g}, "
            f"α = {tol['gospa_alpha']:g}); smaller is better"
        )
    return lines


_SIDES = {"optimistic": " (unsafe side)", "pessimistic": " (safe side)"}
"""What a verdict outside the band means for the user."""


def _number(value: Any) -> str:
    """A float to 4 significant digits (JSON records hold ``"inf"``/``"nan"`` as text)."""
    return f"{value:.4g}" if isinstance(value, float | int) else str(value)


def evidence(metrics: dict[str, Any]) -> dict[str, Any]:
    """A :func:`filter_metrics` record as a claim's evidence: per statistic the values, bands
    and verdicts by agent, the band probability and the safe side; OSPA/GOSPA means.

    Parameters
    ----------
    metrics : dict
        A ``metrics`` record.

    Returns
    -------
    dict
    """
    out: dict[str, Any] = {}
    for name in ("nees", "nis"):
        tests = metrics[name]
        out[name.upper()] = {
            "value": [t["value"] for t in tests],
            "band": [[t["band"]["lower"], t["band"]["upper"]] for t in tests],
            "dof": [t["band"]["dof"] for t in tests],
            "verdict": [t["verdict"] for t in tests],
            "probability": metrics["tolerance"]["consistency_probability"],
            "safe_side": "below the upper edge",
        }
    positions = metrics["positions"]
    if positions is not None:
        out["OSPA"] = {k: positions[k] for k in ("mean_ospa", "mean_gospa", "tolerance")}
    return out
