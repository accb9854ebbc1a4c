"""Discrete-time correlated random walk (DCRW): the target model of seed 002 eqs. (3.1)–(3.5).

The turning angle ``φ`` is wrapped Cauchy with mean ``μ`` and clustering ``γ ∈ [0, 1)`` (eq. 3.1);
the step length ``δ`` is Weibull with shape ``κ`` and scale ``λ`` (eq. 3.2). The heading integrates
the turning angles (eq. 3.3) and the position moves by ``δ`` along the heading (eqs. 3.4–3.5).

Maximum-likelihood fits: the wrapped Cauchy by maximising the log-likelihood over the unit disk
(``ψ = γ e^{iμ}``) by damped Newton steps from the method-of-moments start
``E[e^{iφ}] = γ e^{iμ}``; the Weibull by the profile-likelihood equation in ``κ`` (one monotone
root, bracketed Newton steps) with ``λ = (mean δ^κ)^{1/κ}``. Both are cross-checked against
``scipy.stats`` in the tests.

The claims about the model alone draw a long sample with a fixed seed and compare the fit with
the truth in ``z_tol`` asymptotic standard errors, from the Fisher information of each
distribution: wrapped Cauchy ``Var(γ̂) = (1 − γ²)²/(2n)``, ``Var(μ̂) = (1 − γ²)²/(2nγ²)``;
Weibull ``Var(κ̂) = 6κ²/(π² n)``, ``Var(λ̂) = λ²(1 + 6(1 − γ_E)²/π²)/(κ² n)``.
"""

from __future__ import annotations

import numpy as np
from scipy import optimize

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, status_of
from theory.core.errors import SolverError
from theory.core.tolerances import Z_TOL
from theory.particle.case import PARAM_NAMES, DcrwParams

__all__ = [
    "REFERENCE",
    "SAMPLES",
    "SEED",
    "claims",
    "fit_dcrw",
    "fit_weibull",
    "fit_wrapped_cauchy",
    "movement_samples",
    "sample_dcrw_path",
    "sample_weibull",
    "sample_wrapped_cauchy",
    "standard_errors",
    "weibull_logpdf",
    "wrap_angle",
    "wrapped_cauchy_logpdf",
]

claims = ClaimSet()

REFERENCE = DcrwParams(mu=0.4, gamma=0.7, kappa=2.0, lam=3.0)
SAMPLES, SEED = 20_000, 2
EULER_GAMMA = 0.5772156649015329


def wrap_angle(angle: np.ndarray | float) -> np.ndarray:
    """Wrap ``angle`` (rad, any shape) to ``(−π, π]``, the support of eq. (3.1)."""
    wrapped = np.mod(np.asarray(angle, dtype=float) + np.pi, 2 * np.pi) - np.pi
    return np.where(wrapped == -np.pi, np.pi, wrapped)


def wrapped_cauchy_logpdf(phi: np.ndarray, mu: float, gamma: float) -> np.ndarray:
    """Log of eq. (3.1): ``(1 − γ²) / (2π (1 + γ² − 2γ cos(φ − μ)))``."""
    phi = np.asarray(phi, dtype=float)
    return np.log1p(-(gamma**2)) - np.log(2 * np.pi * (1 + gamma**2 - 2 * gamma * np.cos(phi - mu)))


def weibull_logpdf(delta: np.ndarray, kappa: float, lam: float) -> np.ndarray:
    """Log of eq. (3.2): ``(κ/λ)(δ/λ)^{κ−1} exp(−(δ/λ)^κ)``."""
    z = np.asarray(delta, dtype=float) / lam
    return np.log(kappa / lam) + (kappa - 1) * np.log(z) - z**kappa


def sample_wrapped_cauchy(
    rng: np.random.Generator, mu: np.ndarray | float, gamma: np.ndarray | float, size: tuple
) -> np.ndarray:
    """Turning angles of eq. (3.1) (parameters broadcast against ``size``): ``μ + a·tan(π(U − ½))``
    wrapped, with ``γ = e^{−a}``; ``γ = 0`` is uniform."""
    gamma = np.asarray(gamma, dtype=float)
    u = rng.random(size)
    positive = gamma > 0
    scale = -np.log(np.where(positive, gamma, 1.0))
    cauchy = np.asarray(mu) + scale * np.tan(np.pi * (u - 0.5))
    return wrap_angle(np.where(positive, cauchy, 2 * np.pi * u - np.pi))


def sample_weibull(
    rng: np.random.Generator, kappa: np.ndarray | float, lam: np.ndarray | float, size: tuple
) -> np.ndarray:
    """Step lengths of eq. (3.2) by inversion, ``λ(−ln U)^{1/κ}`` (broadcast against ``size``)."""
    return np.asarray(lam) * (-np.log1p(-rng.random(size))) ** (1.0 / np.asarray(kappa))


def sample_dcrw_path(
    params: DcrwParams,
    steps: int,
    rng: np.random.Generator,
    *,
    start: np.ndarray,
    heading: float | None = None,
) -> np.ndarray:
    """A trajectory ``p(0) = start, …, p(steps)``, shape ``(steps + 1, 2)`` (eqs. (3.3)–(3.5));
    ``θ(0)`` uniform on ``(−π, π]`` unless ``heading`` is given."""
    theta0 = rng.uniform(-np.pi, np.pi) if heading is None else heading
    turns = sample_wrapped_cauchy(rng, params.mu, params.gamma, (steps,))
    lengths = sample_weibull(rng, params.kappa, params.lam, (steps,))
    theta = theta0 + np.cumsum(turns)
    moves = lengths[:, None] * np.stack([np.cos(theta), np.sin(theta)], axis=1)
    return np.vstack(
        [np.asarray(start, float)[None], np.asarray(start, float) + np.cumsum(moves, 0)]
    )


def movement_samples(track: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Turning angles and step lengths implied by successive positions ``(K, 2)``
    (eqs. (3.17)–(3.19)).

    ``φ̂(k) = wrap(θ̂(k) − θ̂(k−1))`` with ``θ̂(k) = atan2(Δy, Δx)`` (``K − 2`` values) and
    ``δ̂(k) = ‖χ(k) − χ(k−1)‖`` (``K − 1`` values, zeros dropped: eq. (3.2) has support ``δ > 0``).
    """
    moves = np.diff(np.asarray(track, dtype=float), axis=0)
    headings = np.arctan2(moves[:, 1], moves[:, 0])
    steps = np.linalg.norm(moves, axis=1)
    return wrap_angle(np.diff(headings)), steps[steps > 0]


def fit_wrapped_cauchy(
    phi: np.ndarray, *, gamma_max: float = 1 - 1e-9, tie_tol: float = 1e-9
) -> tuple[float, float]:
    """Maximum-likelihood ``(μ, γ)`` of eq. (3.1) from turning angles (seed 002 §3.2.2).

    The log-likelihood ``n log(1 − |ψ|²) − Σ log|e^{iφ_j} − ψ|²`` (``ψ = γ e^{iμ}``) is maximised
    over the open unit disk by damped Newton steps (exact gradient and Hessian), started from the
    circular moments, falling back to BFGS in the coordinates ``ψ = v / √(1 + |v|²)`` (so
    ``1 − |ψ|² = 1/(1 + |v|²)`` exactly) if Newton does not converge. The maximum is interior
    exactly when no angle (within ``tie_tol``) carries half or more of the sample (Kent & Tyler
    1988); otherwise the supremum is at ``γ = 1`` at the repeated angle, and the result is that
    angle with ``γ = gamma_max``.
    """
    z = np.exp(1j * np.asarray(phi, dtype=float))
    if z.size == 0:
        raise ValueError("fit_wrapped_cauchy needs at least one angle")
    mode, count = _largest_tie(np.angle(z), tie_tol)
    if 2 * count >= z.size:
        return mode, float(gamma_max)
    start = _moment_start(z)
    psi = _wrapped_cauchy_newton(z, start)
    if psi is None:
        psi = _wrapped_cauchy_bfgs(z, start)
    return float(np.angle(psi)), float(min(abs(psi), gamma_max))


def _moment_start(z: np.ndarray) -> complex:
    """The circular moment ``mean e^{iφ}`` (``= γ e^{iμ}`` in expectation), shrunk into
    ``|ψ| ≤ 0.99``: the start of the ML iterations."""
    moment = z.mean()
    return moment * min(abs(moment), 0.99) / max(abs(moment), 1e-12)


def _wrapped_cauchy_bfgs(z: np.ndarray, start: complex) -> complex:
    """The ML ``ψ`` by BFGS in the coordinates ``v`` (fallback of the Newton iteration)."""
    v0 = np.array([start.real, start.imag]) / np.sqrt(1 - abs(start) ** 2)
    result = optimize.minimize(_wrapped_cauchy_objective, v0, args=(z,), method="BFGS", jac=True)
    if not np.isfinite(result.fun):
        raise SolverError(f"wrapped-Cauchy ML fit failed: {result.message}")
    return complex(*result.x) / np.sqrt(1 + result.x @ result.x)


def _wrapped_cauchy_newton(
    z: np.ndarray, start: complex, *, max_iter: int = 100, step_tol: float = 1e-10
) -> complex | None:
    """The ML ``ψ`` by damped Newton steps on the negative log-likelihood over the unit disk.

    ``f(ψ) = −n log(1 − |ψ|²) + Σ log|z_j − ψ|²`` with its exact gradient and Hessian
    (:func:`_wrapped_cauchy_derivatives`); where the Hessian is not positive definite it is
    shifted until it is (:func:`_newton_direction`), and each step is halved until it stays inside
    the disk and decreases ``f`` (Armijo, up to rounding of ``f``). Converged when the full Newton
    step is below ``step_tol · (1 − |ψ|)``; returns ``None`` after ``max_iter`` steps without it.
    """
    psi = start
    value, grad, hess = _wrapped_cauchy_derivatives(z, psi)
    for _ in range(max_iter):
        step = _newton_direction(grad, hess)
        if abs(step) <= step_tol * (1.0 - abs(psi)):
            return psi + step if abs(psi + step) < 1.0 else psi
        slope = grad.real * step.real + grad.imag * step.imag
        noise = 1e-13 * (1.0 + abs(value))
        t = 1.0
        while t > 1e-12:
            trial = psi + t * step
            if abs(trial) < 1.0:
                trial_value, trial_grad, trial_hess = _wrapped_cauchy_derivatives(z, trial)
                if trial_value <= value + 1e-4 * t * slope + noise:
                    break
            t *= 0.5
        else:
            return None
        psi, value, grad, hess = trial, trial_value, trial_grad, trial_hess
    return None


def _newton_direction(grad: complex, hess: tuple[float, float, float]) -> complex:
    """``−H⁻¹ g`` for ``H = [[a, b], [b, c]]``, ``H`` first shifted by a multiple of ``I`` to be
    positive definite (``g`` and the result as complex numbers ``x + iy``)."""
    a, b, c = hess
    half_trace, det = 0.5 * (a + c), a * c - b * b
    smallest = half_trace - np.sqrt(max(half_trace**2 - det, 0.0))
    scale = abs(a) + abs(c) + 1.0
    if smallest <= 1e-12 * scale:
        shift = -smallest + 1e-6 * scale
        a, c, det = a + shift, c + shift, (a + shift) * (c + shift) - b * b
    return complex(-(c * grad.real - b * grad.imag), -(a * grad.imag - b * grad.real)) / det


def _wrapped_cauchy_derivatives(
    z: np.ndarray, psi: complex
) -> tuple[float, complex, tuple[float, float, float]]:
    """Negative log-likelihood of eq. (3.1) in ``ψ = γ e^{iμ}``, its gradient and Hessian.

    With ``p = (Re ψ, Im ψ)``, ``u_j = z_j − p`` and ``d_j = |u_j|``:
    ``∇f = 2n p / (1 − |p|²) − 2 Σ u_j / d_j²`` and
    ``∇²f = 2n I / (1 − |p|²) + 4n p pᵀ / (1 − |p|²)² + Σ (2 I / d_j² − 4 u_j u_jᵀ / d_j⁴)``.
    The gradient is returned as the complex number ``∂f/∂x + i ∂f/∂y``, the Hessian as
    ``(∂²f/∂x², ∂²f/∂x∂y, ∂²f/∂y²)``.
    """
    n = z.size
    x, y = psi.real, psi.imag
    slack = 1.0 - (x * x + y * y)
    gap = z - psi
    ux, uy = gap.real, gap.imag
    inv = 1.0 / np.maximum(ux * ux + uy * uy, np.finfo(float).tiny)
    value = -n * np.log(slack) - float(np.log(inv).sum())
    grad = 2 * n * psi / slack - 2 * complex(ux @ inv, uy @ inv)
    wx, wy = ux * inv, uy * inv
    diagonal = 2 * n / slack + 2 * float(inv.sum())
    outer = 4 * n / slack**2
    return (
        float(value),
        grad,
        (
            diagonal + outer * x * x - 4 * float(wx @ wx),
            outer * x * y - 4 * float(wx @ wy),
            diagonal + outer * y * y - 4 * float(wy @ wy),
        ),
    )


def _largest_tie(angles: np.ndarray, tol: float) -> tuple[float, int]:
    """The most repeated angle (chains of gaps ≤ ``tol``, across ±π too) and its multiplicity."""
    order = np.sort(angles)
    starts = np.flatnonzero(np.diff(order) > tol) + 1
    bounds = np.concatenate([[0], starts, [order.size]])
    sizes = np.diff(bounds)
    if sizes.size > 1 and order[0] + 2 * np.pi - order[-1] <= tol:
        sizes[0] += sizes[-1]
        sizes = sizes[:-1]
    best = int(np.argmax(sizes))
    return float(order[bounds[best]]), int(sizes[best])


def _wrapped_cauchy_objective(v: np.ndarray, z: np.ndarray) -> tuple[float, np.ndarray]:
    """Negative log-likelihood of eq. (3.1) and its gradient in the coordinates ``v``."""
    norm2 = float(v @ v)
    psi = complex(*v) / np.sqrt(1 + norm2)
    gap = z - psi
    dist2 = np.maximum(gap.real**2 + gap.imag**2, np.finfo(float).tiny)
    value = -z.size * np.log1p(norm2) - np.sum(np.log(dist2))
    grad_psi = -2 * z.size * psi * (1 + norm2) + 2 * np.sum(gap / dist2)
    jacobian = (np.eye(2) * (1 + norm2) - np.outer(v, v)) / (1 + norm2) ** 1.5
    return -value, -(jacobian @ np.array([grad_psi.real, grad_psi.imag]))


def fit_weibull(
    delta: np.ndarray, *, kappa_bounds: tuple[float, float] = (1e-2, 1e3)
) -> tuple[float, float]:
    """Maximum-likelihood ``(κ, λ)`` of eq. (3.2) from positive step lengths (seed 002 §3.2.2).

    Solves the profile equation ``Σ δ^κ ln δ / Σ δ^κ − 1/κ − mean(ln δ) = 0`` (increasing in ``κ``)
    by bracketed Newton steps inside ``kappa_bounds``; at a bound the root is clamped to it (e.g.
    all lengths equal: κ → ∞). Then ``λ = (mean δ^κ)^{1/κ}``.
    """
    x = np.asarray(delta, dtype=float)
    if x.size == 0 or np.any(x <= 0):
        raise ValueError("fit_weibull needs at least one step length, all > 0")
    logs = np.log(x)
    shifted = logs - logs.max()
    centred = logs - logs.mean()
    low, high = kappa_bounds
    if _weibull_profile(low, shifted, centred)[0] >= 0:
        kappa = low
    elif _weibull_profile(high, shifted, centred)[0] <= 0:
        kappa = high
    else:
        kappa = _weibull_root(shifted, centred, low, high)
    lam = float(np.exp(logs.max()) * np.mean(np.exp(kappa * shifted)) ** (1.0 / kappa))
    return float(kappa), lam


def _weibull_profile(kappa: float, shifted: np.ndarray, centred: np.ndarray) -> tuple[float, float]:
    """The profile equation of :func:`fit_weibull` at ``κ`` and its derivative in ``κ``.

    With weights ``w_j ∝ δ_j^κ`` (``shifted = ln δ − max ln δ`` keeps them finite) the value is
    ``Σ w_j ℓ_j / Σ w_j − 1/κ`` (``centred`` = ``ℓ = ln δ − mean ln δ``) and the derivative is the
    ``w``-weighted variance of ``ln δ`` plus ``1/κ²`` (> 0: the equation is increasing).
    """
    weights = np.exp(kappa * shifted)
    weights /= weights.sum()
    mean = float(weights @ centred)
    variance = float(weights @ (centred - mean) ** 2)
    return mean - 1.0 / kappa, variance + 1.0 / kappa**2


def _weibull_root(
    shifted: np.ndarray, centred: np.ndarray, low: float, high: float, *, tol: float = 1e-12
) -> float:
    """The root of the profile equation inside ``[low, high]`` (value < 0 at ``low``, > 0 at
    ``high``) by Newton steps kept inside a shrinking bracket (bisection when a step leaves it).

    Started from the moment estimate ``κ ≈ π / (√6 · sd(ln δ))`` (the log of a Weibull variable
    has standard deviation ``π / (κ√6)``); converged when a step is below ``tol · κ``.
    """
    spread = float(np.sqrt(np.mean(centred**2)))
    kappa = float(np.clip(np.pi / (np.sqrt(6.0) * max(spread, 1e-300)), low, high))
    for _ in range(200):
        value, slope = _weibull_profile(kappa, shifted, centred)
        if value < 0:
            low = kappa
        else:
            high = kappa
        step = value / slope
        candidate = kappa - step
        if not low < candidate < high:
            candidate = 0.5 * (low + high)
        if abs(candidate - kappa) <= tol * kappa or high - low <= tol * kappa:
            return candidate
        kappa = candidate
    raise SolverError("Weibull profile-likelihood root did not converge")


def fit_dcrw(turns: np.ndarray, steps: np.ndarray, *, gamma_max: float = 1 - 1e-9) -> DcrwParams:
    """ML fit of all four DCRW parameters (eqs. (3.1)–(3.2)), ``γ`` clamped to ``gamma_max``."""
    mu, gamma = fit_wrapped_cauchy(turns, gamma_max=gamma_max)
    kappa, lam = fit_weibull(steps)
    return DcrwParams(mu, gamma, kappa, lam)


def standard_errors(params: DcrwParams, n: int) -> dict[str, float]:
    """Asymptotic ML standard errors of ``(μ, γ, κ, λ)`` from ``n`` samples (module docstring)."""
    wc = (1 - params.gamma**2) / np.sqrt(2 * n)
    mu = wc / params.gamma if params.gamma > 0 else float("inf")
    kappa = np.sqrt(6 / np.pi**2) * params.kappa / np.sqrt(n)
    lam = (
        params.lam
        * np.sqrt(1 + 6 * (1 - EULER_GAMMA) ** 2 / np.pi**2)
        / (params.kappa * np.sqrt(n))
    )
    return {"mu": float(mu), "gamma": float(wc), "kappa": float(kappa), "lambda": float(lam)}


def _fit_result(fitted: dict[str, float], message: str) -> list[ClaimResult]:
    """Each fitted parameter's distance from :data:`REFERENCE` in standard errors, ≤ ``z_tol``."""
    truth = dict(zip(PARAM_NAMES, REFERENCE.as_array().tolist(), strict=True))
    se = standard_errors(REFERENCE, SAMPLES)
    z = {
        k: abs(float(wrap_angle(v - truth[k])) if k == "mu" else v - truth[k]) / se[k]
        for k, v in fitted.items()
    }
    worst = max(z.values())
    evidence = {
        "true": {k: truth[k] for k in fitted},
        "fitted": fitted,
        "standard_errors": {k: se[k] for k in fitted},
        "z": z,
        "samples": SAMPLES,
        "seed": SEED,
    }
    return [
        ClaimResult(
            status_of(worst <= Z_TOL),
            Method.NUMERIC,
            evidence,
            margin=Z_TOL - worst,
            tolerance={"z_tol": Z_TOL},
            message=f"{message}: largest deviation {worst:.2f} standard errors",
        )
    ]


@claims.register(
    "seed002.eq3.1",
    source="seed 002, eq. (3.1) and §3.2.2",
    statement="The wrapped-Cauchy turning angle's (μ, γ) are recovered by maximum likelihood.",
)
def check_wrapped_cauchy(case: Case | None, ctx: Context) -> list[ClaimResult]:
    """Fit (μ, γ) to ``SAMPLES`` draws of eq. (3.1)."""
    rng = np.random.default_rng(SEED)
    phi = sample_wrapped_cauchy(rng, REFERENCE.mu, REFERENCE.gamma, (SAMPLES,))
    mu, gamma = fit_wrapped_cauchy(phi)
    return _fit_result({"mu": mu, "gamma": gamma}, "wrapped Cauchy ML")


@claims.register(
    "seed002.eq3.2",
    source="seed 002, eq. (3.2) and §3.2.2",
    statement="The Weibull step length's (κ, λ) are recovered by maximum likelihood.",
)
def check_weibull(case: Case | None, ctx: Context) -> list[ClaimResult]:
    """Fit (κ, λ) to ``SAMPLES`` draws of eq. (3.2)."""
    rng = np.random.default_rng(SEED)
    delta = sample_weibull(rng, REFERENCE.kappa, REFERENCE.lam, (SAMPLES,))
    kappa, lam = fit_weibull(delta)
    return _fit_result({"kappa": kappa, "lambda": lam}, "Weibull ML")


@claims.register(
    "seed002.eq3.17",
    source="seed 002, eqs. (3.3)–(3.5) and (3.17)–(3.19)",
    statement=(
        "Headings, wrapped turning angles and step lengths computed from successive positions "
        "of a DCRW path recover its parameters by maximum likelihood."
    ),
)
def check_track_learning(case: Case | None, ctx: Context) -> list[ClaimResult]:
    """Simulate a long exact DCRW path, apply eqs. (3.17)–(3.19), fit all four parameters."""
    rng = np.random.default_rng(SEED)
    path = sample_dcrw_path(REFERENCE, SAMPLES + 1, rng, start=np.zeros(2))
    turns, steps = movement_samples(path)
    mu, gamma = fit_wrapped_cauchy(turns)
    kappa, lam = fit_weibull(steps)
    fitted = {"mu": mu, "gamma": gamma, "kappa": kappa, "lambda": lam}
    return _fit_result(fitted, "eqs. (3.17)–(3.19) on an exact path")
