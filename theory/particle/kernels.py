"""Seed 002: the online learner's per-node refit as one numba-compiled kernel (the ``"numba"``
engine of :class:`theory.particle.filter.OnlineLearner`).

The same formulas as :mod:`theory.particle.dcrw` (the ``"numpy"`` engine, the reference and the
tests' oracle), written as loops over the ≤ 100 estimates of one node: the movement samples of
eqs. (3.17)–(3.19) (:func:`dcrw.movement_samples`), the wrapped-Cauchy ML fit of eq. (3.1) by
damped Newton steps (:func:`dcrw.fit_wrapped_cauchy`: largest tie, moment start, Newton with the
shifted Hessian and Armijo halving) and the Weibull fit of eq. (3.2) (:func:`dcrw.fit_weibull`:
the profile equation's bracketed Newton root), then the learner's clamp of ``κ`` and the ML scale
for it. NumPy pays a call per operation on these ≤ 100-number arrays (≈ 130 000 calls a run); the
kernel does the arithmetic itself. Sums are loops here and pairwise/BLAS sums in NumPy, so the
two engines agree to rounding (≈ 1e-15 relative per sum), not bit for bit.

The kernel never raises: where the reference falls back to BFGS (Newton did not converge) or
raises (the Weibull root did not converge) it returns :data:`FALLBACK` and the caller runs the
reference on that node. Compiled once per machine (``cache=True``, the conventions of
:mod:`theory.pursuit.kernels`).
"""

from __future__ import annotations

import math

import numpy as np

from theory.core.engines import compiled

__all__ = ["FALLBACK", "FITTED", "TOO_FEW", "fit_track"]

FITTED, TOO_FEW, FALLBACK = 0, 1, 2
"""The statuses of :func:`fit_track`: ``out`` holds the fit; too few samples; run the reference."""

TINY = np.finfo(float).tiny


@compiled
def _wrap(angle):
    """``wrap_angle`` of one angle: ``mod(a + π, 2π) − π`` (NumPy's floor mod), ``−π ↦ π``."""
    wrapped = np.mod(angle + math.pi, 2 * math.pi) - math.pi
    return math.pi if wrapped == -math.pi else wrapped


@compiled
def _movement(track):
    """Turning angles (``K − 2``) and positive steps of a track ``(K, 2)``, eqs. (3.17)–(3.19)."""
    count = track.shape[0] - 1
    headings = np.empty(count)
    steps = np.empty(count)
    kept = 0
    for k in range(count):
        dx, dy = track[k + 1, 0] - track[k, 0], track[k + 1, 1] - track[k, 1]
        headings[k] = math.atan2(dy, dx)
        length = math.sqrt(dx * dx + dy * dy)
        if length > 0:
            steps[kept] = length
            kept += 1
    turns = np.empty(max(count - 1, 0))
    for k in range(count - 1):
        turns[k] = _wrap(headings[k + 1] - headings[k])
    return turns, steps[:kept]


@compiled
def _largest_tie(angles, tol):
    """The most repeated angle (gaps ≤ ``tol``, across ±π) and its count (``dcrw._largest_tie``)."""
    order = np.sort(angles)
    n = order.size
    sizes = np.empty(n, dtype=np.int64)
    firsts = np.empty(n, dtype=np.int64)
    chains, first = 0, 0
    for j in range(1, n + 1):
        if j == n or order[j] - order[j - 1] > tol:
            sizes[chains], firsts[chains] = j - first, first
            chains += 1
            first = j
    if chains > 1 and order[0] + 2 * np.pi - order[n - 1] <= tol:
        sizes[0] += sizes[chains - 1]
        chains -= 1
    best = 0
    for c in range(1, chains):
        if sizes[c] > sizes[best]:
            best = c
    return order[firsts[best]], sizes[best]


@compiled
def _derivatives(zx, zy, x, y):
    """Negative log-likelihood of eq. (3.1) in ``ψ = x + iy``, gradient, Hessian (``dcrw``'s)."""
    n = zx.size
    slack = 1.0 - (x * x + y * y)
    log_sum = sx = sy = inv_sum = wxx = wxy = wyy = 0.0
    for j in range(n):
        ux, uy = zx[j] - x, zy[j] - y
        inv = 1.0 / max(ux * ux + uy * uy, TINY)
        log_sum += math.log(inv)
        sx += ux * inv
        sy += uy * inv
        inv_sum += inv
        wx, wy = ux * inv, uy * inv
        wxx += wx * wx
        wxy += wx * wy
        wyy += wy * wy
    value = -n * math.log(slack) - log_sum
    gx, gy = 2 * n * x / slack - 2 * sx, 2 * n * y / slack - 2 * sy
    diagonal = 2 * n / slack + 2 * inv_sum
    outer = 4 * n / slack**2
    hxx = diagonal + outer * x * x - 4 * wxx
    hxy = outer * x * y - 4 * wxy
    hyy = diagonal + outer * y * y - 4 * wyy
    return value, gx, gy, hxx, hxy, hyy


@compiled
def _direction(gx, gy, a, b, c):
    """``−H⁻¹ g`` with ``H`` shifted to be positive definite (``dcrw._newton_direction``)."""
    half_trace, det = 0.5 * (a + c), a * c - b * b
    smallest = half_trace - math.sqrt(max(half_trace**2 - det, 0.0))
    scale = abs(a) + abs(c) + 1.0
    if smallest <= 1e-12 * scale:
        shift = -smallest + 1e-6 * scale
        a, c, det = a + shift, c + shift, (a + shift) * (c + shift) - b * b
    return -(c * gx - b * gy) / det, -(a * gy - b * gx) / det


@compiled
def _newton(zx, zy, x, y, max_iter=100, step_tol=1e-10):
    """The ML ``ψ`` by damped Newton steps (``dcrw._wrapped_cauchy_newton``); ``ok`` False when
    it does not converge (the reference then runs BFGS)."""
    value, gx, gy, a, b, c = _derivatives(zx, zy, x, y)
    for _ in range(max_iter):
        sx, sy = _direction(gx, gy, a, b, c)
        if math.hypot(sx, sy) <= step_tol * (1.0 - math.hypot(x, y)):
            if math.hypot(x + sx, y + sy) < 1.0:
                return x + sx, y + sy, True
            return x, y, True
        slope = gx * sx + gy * sy
        noise = 1e-13 * (1.0 + abs(value))
        t, accepted = 1.0, False
        tx, ty, trial = x, y, (value, gx, gy, a, b, c)
        while t > 1e-12:
            tx, ty = x + t * sx, y + t * sy
            if math.hypot(tx, ty) < 1.0:
                trial = _derivatives(zx, zy, tx, ty)
                if trial[0] <= value + 1e-4 * t * slope + noise:
                    accepted = True
                    break
            t *= 0.5
        if not accepted:
            return x, y, False
        x, y = tx, ty
        value, gx, gy, a, b, c = trial
    return x, y, False


@compiled
def _profile(kappa, shifted, centred):
    """The Weibull profile equation at ``κ`` and its derivative (``dcrw._weibull_profile``)."""
    n = shifted.size
    weights = np.empty(n)
    total = 0.0
    for j in range(n):
        weights[j] = math.exp(kappa * shifted[j])
        total += weights[j]
    mean = 0.0
    for j in range(n):
        weights[j] /= total
        mean += weights[j] * centred[j]
    variance = 0.0
    for j in range(n):
        variance += weights[j] * (centred[j] - mean) ** 2
    return mean - 1.0 / kappa, variance + 1.0 / kappa**2


@compiled
def _weibull_shape(steps, low, high, tol=1e-12):
    """ML ``κ`` of eq. (3.2) in ``[low, high]`` (``dcrw.fit_weibull``); NaN if no convergence."""
    n = steps.size
    logs = np.log(steps)
    top, mean_log = logs.max(), logs.mean()
    shifted, centred = logs - top, logs - mean_log
    if _profile(low, shifted, centred)[0] >= 0:
        return low
    if _profile(high, shifted, centred)[0] <= 0:
        return high
    spread = math.sqrt(np.sum(centred**2) / n)
    kappa = min(max(math.pi / (math.sqrt(6.0) * max(spread, 1e-300)), low), high)
    for _ in range(200):
        value, slope = _profile(kappa, shifted, centred)
        if value < 0:
            low = kappa
        else:
            high = kappa
        candidate = kappa - value / slope
        if not low < candidate < high:
            candidate = 0.5 * (low + high)
        if abs(candidate - kappa) <= tol * kappa or high - low <= tol * kappa:
            return candidate
        kappa = candidate
    return math.nan


@compiled
def _wrapped_cauchy(turns, gamma_max, tie_tol=1e-9):
    """ML ``(μ, γ)`` of eq. (3.1) (``dcrw.fit_wrapped_cauchy``); ``ok`` False: run the reference."""
    n = turns.size
    zx, zy, angles = np.cos(turns), np.sin(turns), np.empty(n)
    for j in range(n):
        angles[j] = math.atan2(zy[j], zx[j])
    mode, count = _largest_tie(angles, tie_tol)
    if 2 * count >= n:
        return mode, gamma_max, True
    mx, my = zx.sum() / n, zy.sum() / n
    size = math.hypot(mx, my)
    shrink = min(size, 0.99) / max(size, 1e-12)
    x, y, ok = _newton(zx, zy, mx * shrink, my * shrink)
    return math.atan2(y, x), min(math.hypot(x, y), gamma_max), ok


@compiled
def fit_track(track, min_samples, gamma_max, kappa_low, kappa_high, out):
    """The learner's refit of one node from its estimates ``track (K, 2)`` into ``out``
    ``(μ, γ, κ, λ)``: :data:`FITTED`, :data:`TOO_FEW` or :data:`FALLBACK` (module docstring).

    ``κ`` is fitted inside ``(1e-2, 1e3)`` (``dcrw.fit_weibull``'s bounds), then clamped to
    ``[kappa_low, kappa_high]``, and ``λ = (mean δ^κ)^{1/κ}`` for the clamped ``κ``.
    """
    turns, steps = _movement(track)
    if turns.size < min_samples or steps.size == 0:
        return TOO_FEW
    mu, gamma, ok = _wrapped_cauchy(turns, gamma_max)
    kappa = _weibull_shape(steps, 1e-2, 1e3)
    if not ok or math.isnan(kappa):
        return FALLBACK
    kappa = min(max(kappa, kappa_low), kappa_high)
    out[0], out[1], out[2] = mu, gamma, kappa
    out[3] = (np.sum(steps**kappa) / steps.size) ** (1.0 / kappa)
    return FITTED
