"""Seed 003: the per-step work of the DEC loop as numba-compiled kernels (the ``"numba"`` engine).

The same formulas as :mod:`theory.pursuit.closed_loop` (the ``"numpy"`` engine, the reference and
the tests' oracle) and :mod:`theory.pursuit.dekf`, written as loops over a few numbers, which a
compiler turns into the arithmetic itself (NumPy pays a call per operation on 3–27-number arrays):
the vector field (eqs. (2)–(5), (45)–(51)) from :class:`closed_loop._FrameMaps`, the
predictor–corrector step with its error estimate (:func:`closed_loop.heun_step`), the adaptive
steps from record to record (:func:`closed_loop.integrate_until`, :class:`closed_loop.StepControl`)
and Algorithm 2's correction, fusion and prediction (:func:`dekf.dekf_step`, eqs. (41)–(44)).

Compiled once per machine: ``cache=True`` writes the machine code in ``$NUMBA_CACHE_DIR`` if set,
else beside this file (``__pycache__``), else, when that folder is read-only (an installed
package), in numba's per-user cache folder (``~/.cache/numba``); when none can be written the
kernels are compiled in each process instead (:func:`theory.core.engines.compiled`), which costs
the compile time (docs/simulation.md, *Engines*).

``loop`` below is the tuple of :func:`theory.pursuit.compiled_run.loop_arrays`: (state map, state
offset, estimate map, G, g, ε, k_γ, scale) of :class:`closed_loop.DecLoop`.
"""

from __future__ import annotations

import math

import numpy as np

from theory.core.engines import compiled

__all__ = ["dekf_step", "heun_step", "rates", "run"]

FAILED = -1.0
"""The failure time :func:`_advance` returns when it did not fail (times are ≥ 0)."""


@compiled
def _skew_times(R, omega, h, out):
    """out = R + R·S(hω) (2-D: ω = (r,); 3-D: ω = (p, q, r)), seed 003 eq. (3), Euler's step."""
    d = R.shape[0]
    S = np.zeros((d, d))
    if d == 2:
        S[0, 1], S[1, 0] = -h * omega[0], h * omega[0]
    else:
        p, q, r = h * omega[0], h * omega[1], h * omega[2]
        S[0, 1], S[0, 2], S[1, 0], S[1, 2], S[2, 0], S[2, 1] = -r, q, r, -p, -q, p
    for i in range(d):
        for j in range(d):
            total = R[i, j]
            for k in range(d):
                total += R[i, k] * S[k, j]
            out[i, j] = total


@compiled
def _exp_skew(omega):
    """exp(S(ω)) (:func:`model.exp_skew`: the angle in 2-D, Euler–Rodrigues in 3-D)."""
    if omega.size == 1:
        c, s = math.cos(omega[0]), math.sin(omega[0])
        return np.array([[c, -s], [s, c]])
    theta = max(math.sqrt(omega[0] ** 2 + omega[1] ** 2 + omega[2] ** 2), 1e-150)
    w, scale = math.cos(0.5 * theta), math.sin(0.5 * theta) / theta
    v = omega * scale
    E = np.empty((3, 3))
    diagonal = w * w - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    for i in range(3):
        for j in range(3):
            E[i, j] = 2.0 * v[i] * v[j] + (diagonal if i == j else 0.0)
    E[0, 1] -= 2 * w * v[2]
    E[1, 0] += 2 * w * v[2]
    E[0, 2] += 2 * w * v[1]
    E[2, 0] -= 2 * w * v[1]
    E[1, 2] -= 2 * w * v[0]
    E[2, 1] += 2 * w * v[0]
    return E


@compiled
def _affine(vector, matrix, offset):
    """vector·matrix + offset (the maps of :class:`closed_loop._FrameMaps`)."""
    out = offset.copy()
    for i in range(vector.size):
        value = vector[i]
        for j in range(out.size):
            out[j] += value * matrix[i, j]
    return out


@compiled
def rates(t, z, R, x_hat, t_hat, loop):
    """(ż, ω) of every tracker: :meth:`closed_loop.DecLoop.rates`, seed 003 (2)–(5), (45)–(51)."""
    state_map, state_offset, estimate_map, gain, offset, epsilon, k_gamma, _ = loop
    n, d = R.shape[0], R.shape[1]
    size, a, b = 3 * n * d, n * d, n * (d + 1)
    affine = _affine(z, state_map, state_offset)  # [fγ + φ | A | B | ω_d]
    estimates = _affine(x_hat.ravel(), estimate_map, np.zeros(2 * size))  # [C | D]
    frames = np.empty(size)
    for k in range(size):
        frames[k] = math.cos(affine[k]) * affine[size + k] + affine[2 * size + k] + estimates[k]
        frames[k] += estimates[size + k] * (t - t_hat)
    z_dot, omega = np.empty(b + n), np.empty((n, gain.shape[1] - 1))
    body = np.empty((3, d))
    for i in range(n):
        for row in range(3):  # the rows in the body frame, Rᵀv
            for c in range(d):
                total = 0.0
                for j in range(d):
                    total += frames[(3 * i + row) * d + j] * R[i, j, c]
                body[row, c] = total
        u = offset.copy()  # eq. (51): u = [Rᵀc, Rᵀb] G + g
        for row in range(2):
            for c in range(d):
                u += body[row, c] * gain[row * d + c]
        for c in range(d):
            z_dot[i * d + c] = R[i, c, 0] * u[0]
        z_dot[a + i] = affine[3 * size + i] + z[b + i]
        feedback = 0.0  # ê_pᵀ(Rᵀr′) of (50b), ê_p = Rᵀ(p − r − q̂) − ε of (48)
        if k_gamma != 0.0:
            for c in range(d):
                feedback += (body[1, c] - epsilon[c]) * body[2, c]
        z_dot[b + i] = feedback
        omega[i] = u[1:]
    return z_dot, omega


@compiled
def _etd_weights(k, h):
    """(E, w₁, w₂, g₁, g₂) of :func:`closed_loop._etd_weights` (ETD1/ETD2RK, Cox–Matthews 2002)."""
    z = k * h
    if z < 1e-3:
        return (
            math.exp(-z),
            h * (1 - z / 2 + z * z / 6 - z**3 / 24),
            h * (0.5 - z / 6 + z * z / 24 - z**3 / 120),
            h * h * (0.5 - z / 6 + z * z / 24 - z**3 / 120),
            h * h * (1 / 6 - z / 24 + z * z / 120 - z**3 / 720),
        )
    decay = math.exp(-z)
    w1 = -math.expm1(-z) / k
    return decay, w1, (decay - 1.0 + z) / (k * z), (h - w1) / k, h / (2 * k) - (h - w1) / (k * z)


@compiled
def heun_step(t, h, z, R, z_dot, omega, x_hat, t_hat, loop):
    """(z, R) after one step of ``h`` and the local error: :func:`closed_loop.heun_step`
    (Heun in p, ETD1/ETD2RK in (γ, e_γ), Euler then R exp(½hS(ω₀ + ω₁)) in R)."""
    n, d = R.shape[0], R.shape[1]
    a, b = n * d, n * (d + 1)
    decay, w1, w2, g1, g2 = _etd_weights(loop[6], h)
    z1, z2, R1, R2 = np.empty_like(z), np.empty_like(z), np.empty_like(R), np.empty_like(R)
    free, speed = np.empty(n), np.empty(n)
    for i in range(a):
        z1[i] = z[i] + h * z_dot[i]  # p + hṗ₀
    for i in range(n):  # γ + w₁e_γ + g₁f₀ (+ hω_d), e^{−k_γh}e_γ + w₁f₀
        e, f = z[b + i], z_dot[b + i]
        free[i] = z[a + i] + e * w1 + f * g1
        speed[i] = z_dot[a + i] - e
        z1[a + i] = speed[i] * h + free[i]
        z1[b + i] = e * decay + f * w1
    for i in range(n):
        _skew_times(R[i], omega[i], h, R1[i])
    z_dot1, omega1 = rates(t + h, z1, R1, x_hat, t_hat, loop)
    half = 0.5 * h
    for i in range(a):
        z2[i] = (z_dot[i] + z_dot1[i]) * half + z[i]  # p + ½h(ṗ₀ + ṗ₁)
    for i in range(n):
        slope = z_dot1[b + i] - z_dot[b + i]  # f₁ − f₀
        z2[a + i] = ((z_dot1[a + i] - z1[b + i]) + speed[i]) * half + free[i] + slope * g2
        z2[b + i] = slope * w2 + z1[b + i]
        R2[i] = R[i] @ _exp_skew((omega[i] + omega1[i]) * half)
    return z2, R2, _local_error(z, z1, R1, z2, R2, a, b, loop[7])


@compiled
def _local_error(z, z1, R1, z2, R2, a, b, scale):
    """:func:`closed_loop._local_error`: p relative to max(scale, max|p|), γ and R absolute; NaN
    when any difference is NaN."""
    largest = 0.0
    for i in range(a):
        largest = max(largest, abs(z[i]))
    scale = max(scale, largest)
    error = 0.0
    for i in range(b):
        difference = abs(z2[i] - z1[i]) / (scale if i < a else 1.0)
        if math.isnan(difference):
            return math.nan
        error = max(error, difference)
    for difference in np.abs(R2 - R1).ravel():
        if math.isnan(difference):
            return math.nan
        error = max(error, difference)
    return error


@compiled
def _next_step(h, cap, step, error, accepted, reached_end):
    """:meth:`closed_loop.StepControl.update`: the next proposed step."""
    if not math.isfinite(error):
        return 0.2 * step
    factor = 2.0 if error == 0 else 0.9 / math.sqrt(error)
    proposal = step * min(2.0 if accepted else 1.0, max(0.2, factor))
    if accepted and reached_end:
        proposal = max(proposal, h)
    return min(proposal, cap)


@compiled
def _advance(first, last, dt, z, R, x_hat, t_hat, h, settings, loop, z_records, R_records):
    """Integrate from record ``first`` to record ``last`` (:func:`closed_loop.integrate_until`
    per record), writing records ``first + 1 …`` into ``z_records``, ``R_records``.

    ``settings`` = (rtol, min_step). Returns (z, R, h, accepted, rejected, the last record
    reached, the time a step fell below ``min_step`` or :data:`FAILED`).
    """
    rtol, min_step = settings
    accepted = rejected = 0
    z_dot, omega = rates(first * dt, z, R, x_hat, t_hat, loop)
    for m in range(first, last):
        t, t_end = m * dt, (m + 1) * dt
        while t_end - t > 1e-12 * max(1.0, abs(t_end)):
            final = h >= t_end - t
            step = t_end - t if final else h
            z_new, R_new, error = heun_step(t, step, z, R, z_dot, omega, x_hat, t_hat, loop)
            error /= rtol
            ok = error <= 1.0
            if ok:
                t, z, R = (t_end if final else t + step), z_new, R_new
                accepted += 1
                z_dot, omega = rates(t, z, R, x_hat, t_hat, loop)
            else:
                rejected += 1
            h = _next_step(h, dt, step, error, ok, final)
            if h < min_step:
                return z, R, h, accepted, rejected, m, t
        z_records[m + 1] = z
        R_records[m + 1] = R
    return z, R, h, accepted, rejected, last, FAILED


@compiled
def _lost(positions, x_hat, truth, limit):
    """Whether the worst localization error exceeds ``limit`` (:func:`closed_loop.runaway_reason`:
    the first NaN counts as the worst, and a NaN exceeds nothing)."""
    d = positions.shape[1]
    errors = np.empty(x_hat.shape[0])
    for i in range(errors.size):
        errors[i] = math.sqrt(np.sum((x_hat[i, :d] - truth[:d]) ** 2))
    return errors[np.argmax(errors)] > limit


@compiled
def run(target, noise, z, R, filter_arrays, settings, loop, records):
    """The DEC loop of :func:`closed_loop._run`: at each sampling instant the ranges (9)–(10)
    with the given ``noise`` (σ times a standard normal a tracker), one DEKF step
    (:func:`dekf_step`) and the runaway check, then :func:`_advance` to the next instant.

    ``filter_arrays`` = (x̂_{1|0}, Ω_{1|0}, π, F, W); ``settings`` = (dt, every, V, predictions,
    runaway limit (m), rtol, min_step); ``records`` = (z, R, estimates), NaN, filled in place.
    Returns (accepted, rejected, the record of an early stop or −1, 1 runaway or 2 step floor,
    the time of the step failure, x̂ and Ω_{k+1|k} of the last sampling instant).
    """
    x_pred, Omega, fusion, F, W = filter_arrays
    dt, every, V, predictions, limit, rtol, min_step = settings
    z_records, R_records, estimates = records
    steps, n, d = z_records.shape[0] - 1, R.shape[0], R.shape[1]
    h, accepted, rejected, m = dt, 0, 0, 0
    while True:
        positions = z[: n * d].reshape(n, d)
        ranges = np.empty(n)
        for i in range(n):
            ranges[i] = math.sqrt(np.sum((positions[i] - target[m, :d]) ** 2))
            ranges[i] += noise[m // every, i]
        x_hat, _, Omega, x_pred = dekf_step(
            x_pred, Omega, positions, ranges, fusion, F, W, V, predictions
        )
        z_records[m] = z
        R_records[m] = R
        last = min(m + every, steps)
        reached, failed = m, FAILED
        lost = m < steps and _lost(positions, x_hat, target[m], limit)
        if m < steps and not lost:
            z, R, h, ok, refused, reached, failed = _advance(
                m, last, dt, z, R, x_hat, m * dt, h, (rtol, min_step), loop, z_records, R_records
            )
            accepted += ok
            rejected += refused
        for k in range(m, reached + 1):
            estimates[k, :, :-1] = x_hat
            estimates[k, :, -1] = k * dt - m * dt
        if lost:
            return accepted, rejected, m, 1, FAILED, x_hat, Omega
        if failed >= 0:
            return accepted, rejected, reached, 2, failed, x_hat, Omega
        if m == steps or (last == steps and last % every):
            return accepted, rejected, -1, 0, FAILED, x_hat, Omega
        m = last


@compiled
def dekf_step(x_pred, Omega, positions, ranges, fusion, F, W, V, predictions):
    """One sampling instant of Algorithm 2 (:func:`theory.pursuit.dekf.dekf_step`): correction
    (41), one fusion round (43), ``predictions`` predictions (44) with F and W. Returns x̂_{k|k},
    Ω_{k|k}, Ω_{k+1|k}, x̂_{k+1|k}."""
    n, d = positions.shape
    m = 2 * d
    z_tilde, Omega_tilde = np.empty((n, m)), np.empty((n, m, m))
    for i in range(n):
        diff = x_pred[i, :d] - positions[i]
        predicted = math.sqrt(np.sum(diff * diff))
        C = np.zeros(m)
        C[:d] = diff / predicted
        linearized = ranges[i] - predicted + np.sum(C * x_pred[i])
        for r in range(m):
            z_tilde[i, r] = np.sum(Omega[i, r] * x_pred[i]) + C[r] * (V * linearized)
        Omega_tilde[i] = Omega[i] + V * np.outer(C, C)
    x_hat, Omega_post, Omega_next = np.empty((n, m)), np.empty((n, m, m)), np.empty((n, m, m))
    FtWF, WF, FtW = F.T @ W @ F, W @ F, F.T @ W
    for i in range(n):
        fused, fused_z = np.zeros((m, m)), np.zeros(m)
        for j in range(n):
            fused += fusion[i, j] * Omega_tilde[j]
            fused_z += fusion[i, j] * z_tilde[j]
        Omega_post[i] = fused
        x_hat[i] = np.linalg.solve(fused, fused_z)
        for _ in range(predictions):
            fused = W - WF @ np.linalg.inv(fused + FtWF) @ FtW
        Omega_next[i] = fused
    x_next = x_hat.copy()
    for _ in range(predictions):
        x_next = x_next @ F.T
    return x_hat, Omega_post, Omega_next, x_next
