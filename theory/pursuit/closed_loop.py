"""Seed 003: the distributed estimation and control (DEC) loop of §V, in 2-D and 3-D.

Trackers (2)–(5) with ``v = [v₁, 0(, 0)]``: ``ṗ = R[v₁, 0(, 0)]ᵀ``, ``Ṙ = R S(ω)`` with
``S(ω) = [ω]×`` (the printed S of eq. (4) swaps p and q; only ``[ω]×`` reproduces Δ of (22),
see docs/errata.md), inputs ``u = (v₁, r)`` in 2-D and ``(v₁, p, q, r)`` in 3-D. Each tracker
runs the DEKF of Algorithm 2 on a range every ``T_s``, tracks its S-T curve ``p_d = r(γ) + q̂``
with (48), (51) (``Δ̄ = Δᵀ(ΔΔᵀ)⁻¹``), coordinates its path parameter with (45)–(47) and uses
Controller Type I (49) or Type II (50), (52).

Choices (not given in the text, see ``docs/simulation.md``): between samples the controller uses
``q̂(t) = q̂_{k|k} + (t − t_k) v̂``; ``p`` advances by forward Euler and ``R`` by the exact
rotation ``R exp(S(ω) dt)`` with the input held over ``dt``; the stiff speed error
``e_γ = γ̇ − ω_d`` of Type II obeys ``ė_γ = −k_γ e_γ + ê_pᵀRᵀr'(γ)`` (from (47), (50b), (52))
and is advanced exactly over ``dt`` with its input frozen.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["DecRun", "DecSettings", "delta_matrix", "euler_rotation", "simulate_dec"]


@dataclass(frozen=True)
class DecSettings:
    """Parameters of the 2-D DEC loop (defaults: seed 003 Table I).

    Attributes
    ----------
    omega_bar : float
        Nominal path speed ``ω̄`` (rad/s).
    radii : tuple of float
        ``(r_x, r_y)`` of (16).
    epsilon : tuple of float
        ``ε`` of (19); ``ε₁ ≠ 0`` makes ``Δ`` of (22) invertible.
    Kp : tuple of float
        Diagonal of ``K_p``.
    k_gamma : float
        ``k_γ`` of (50b).
    k_c : float
        Coupling gain of (45), (52).
    controller : str
        ``"I"`` or ``"II"``.
    V : float
        DEKF inverse range variance.
    Q : tuple of float
        Diagonal of the DEKF's process covariance.
    fusion_weight : float
        ``π^[i,j]`` for the self and the in-neighbour.
    Ts : float
        Range sampling period (s).
    dt : float
        Integration step (s); ``Ts/dt`` must be an integer.
    sigma : float
        Standard deviation of the simulated range noise (m).
    """

    omega_bar: float = 0.05
    radii: tuple[float, float] = (30.0, 30.0)
    epsilon: tuple[float, float] = (-0.5, 0.0)
    Kp: tuple[float, float] = (0.4, 0.2)
    k_gamma: float = 500.0
    k_c: float = 0.2
    controller: str = "II"
    V: float = 10.0
    Q: tuple[float, float, float, float] = (1e-3, 1e-3, 1e-4, 1e-4)
    fusion_weight: float = 0.5
    Ts: float = 2.0
    dt: float = 0.1
    sigma: float = 0.5


@dataclass(frozen=True, eq=False)
class DecRun:
    """Arrays every ``dt``: ``times`` (M+1,), ``positions`` (M+1, N, 2), ``headings``,
    ``gammas``, ``gamma_rates``, ``gamma_errors`` ``e_γ = γ̇ − ω_d`` (M+1, N),
    ``pursuit_errors`` ``‖e_p‖`` with the true target (M+1, N), ``localization_errors``
    ``‖q̂ − q‖`` and ``estimation_errors`` ``‖x̂ − x‖`` (state used by the controller at that
    instant) (M+1, N), ``target`` (M+1, 4)."""

    times: np.ndarray
    positions: np.ndarray
    headings: np.ndarray
    gammas: np.ndarray
    gamma_rates: np.ndarray
    gamma_errors: np.ndarray
    pursuit_errors: np.ndarray
    localization_errors: np.ndarray
    estimation_errors: np.ndarray
    target: np.ndarray


def _skew(omega: np.ndarray, dim: int) -> np.ndarray:
    """``S(ω) = [ω]×`` with ``Ṙ = R S(ω)`` (3-D, ``ω = (p, q, r)``; the correct form, see
    docs/errata.md) or ``[[0, −r], [r, 0]]`` (2-D, ``ω = r``), stacked over trackers."""
    out = np.zeros((omega.shape[0], dim, dim))
    if dim == 2:
        out[:, 0, 1], out[:, 1, 0] = -omega[:, 0], omega[:, 0]
        return out
    p, q, r = omega[:, 0], omega[:, 1], omega[:, 2]
    out[:, 0, 1], out[:, 0, 2], out[:, 1, 2] = -r, q, -p
    out[:, 1, 0], out[:, 2, 0], out[:, 2, 1] = r, -q, p
    return out


def _exp_skew(S: np.ndarray) -> np.ndarray:
    """``exp(S)`` of stacked skew-symmetric 2×2 or 3×3 matrices (Rodrigues)."""
    dim = S.shape[1]
    if dim == 2:
        angle = S[:, 1, 0]
        c, s = np.cos(angle), np.sin(angle)
        return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)
    axis = np.stack([S[:, 2, 1], S[:, 0, 2], S[:, 1, 0]], -1)
    theta = np.linalg.norm(axis, axis=1)[:, None, None]
    safe = np.where(theta > 1e-12, theta, 1.0)
    a = np.where(theta > 1e-12, np.sin(safe) / safe, 1.0)
    b = np.where(theta > 1e-12, (1 - np.cos(safe)) / safe**2, 0.5)
    return np.eye(3) + a * S + b * S @ S


def euler_rotation(euler: np.ndarray) -> np.ndarray:
    """``R(η)`` from roll–pitch–yaw ``η = (φ, θ, ψ)`` (ZYX convention), stacked (N, 3, 3).

    Parameters
    ----------
    euler : ndarray, shape (N, 3)

    Returns
    -------
    ndarray, shape (N, 3, 3)
    """
    phi, theta, psi = euler[:, 0], euler[:, 1], euler[:, 2]
    cf, sf, ct, st, cp, sp = (np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta),
                              np.cos(psi), np.sin(psi))  # fmt: skip
    return np.stack(
        [
            np.stack([cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf], -1),
            np.stack([sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf], -1),
            np.stack([-st, ct * sf, ct * cf], -1),
        ],
        -2,
    )


def delta_matrix(epsilon: np.ndarray) -> np.ndarray:
    """``Δ`` of eq. (22): ``Δu = v − S(ω)ε`` for ``u = (v₁, ω)``.

    Parameters
    ----------
    epsilon : ndarray, shape (d,)

    Returns
    -------
    ndarray, shape (2, 2) or (3, 4)
    """
    e = np.asarray(epsilon, dtype=float)
    if e.shape[0] == 2:
        return np.array([[1.0, e[1]], [0.0, -e[0]]])
    return np.array([[1.0, 0.0, -e[2], e[1]], [0.0, e[2], 0.0, -e[0]], [0.0, -e[1], e[0], 0.0]])


def _path(gamma: np.ndarray, paths: np.ndarray) -> np.ndarray:
    """``r^[i](γ^[i])`` of (15)/(16); ``paths`` rows ``(r_x, r_y, γ0)`` or
    ``(r_x, r_y, r_z, c, γ0)``."""
    phase = gamma + paths[:, -1]
    columns = [paths[:, 0] * np.cos(phase), paths[:, 1] * np.sin(phase)]
    if paths.shape[1] == 5:
        columns.append(paths[:, 2] * np.sin(gamma / paths[:, 3] + paths[:, -1]))
    return np.column_stack(columns)


def _path_derivative(gamma: np.ndarray, paths: np.ndarray) -> np.ndarray:
    """``r'^[i](γ^[i])``."""
    phase = gamma + paths[:, -1]
    columns = [-paths[:, 0] * np.sin(phase), paths[:, 1] * np.cos(phase)]
    if paths.shape[1] == 5:
        columns.append(paths[:, 2] / paths[:, 3] * np.cos(gamma / paths[:, 3] + paths[:, -1]))
    return np.column_stack(columns)


def simulate_dec(
    target: np.ndarray,
    initial_positions: np.ndarray,
    initial_headings: np.ndarray,
    initial_gammas: np.ndarray,
    in_neighbours: list[list[int]],
    x0: np.ndarray,
    P0: np.ndarray,
    steps: int,
    rng: np.random.Generator,
    settings: DecSettings = DecSettings(),
    *,
    paths: np.ndarray | None = None,
    fusion: np.ndarray | None = None,
) -> DecRun:
    """Simulate the DEC system of seed 003 §V (2-D or 3-D) for ``steps`` steps of ``settings.dt``.

    Parameters
    ----------
    target : ndarray, shape (steps+1, 2d)
        True target states ``[q; v]`` at ``t = k·dt`` (e.g. :func:`table_target`).
    initial_positions : ndarray, shape (N, d)
    initial_headings : ndarray, shape (N,) or (N, 3)
        Yaw ``ψ`` (2-D) or roll–pitch–yaw (3-D).
    initial_gammas : ndarray, shape (N,)
    in_neighbours : list of list of int
        0-based in-neighbours ``N_in^[i]`` (fusion and coordination).
    x0 : ndarray, shape (2d,) or (N, 2d)
        Initial estimates ``x̂_{1|0}`` (one for all trackers, or one each).
    P0 : ndarray, shape (2d, 2d) or (N, 2d, 2d)
        Initial covariances ``P_{1|0}``.
    steps : int
    rng : numpy.random.Generator
        Source of the range noise.
    settings : DecSettings
        Gains and DEKF settings (``epsilon``, ``Kp`` and ``Q`` of matching dimension).
    paths : ndarray, shape (N, 3) or (N, 5), optional
        Rows ``(r_x, r_y, γ0)`` (16) or ``(r_x, r_y, r_z, c, γ0)`` (15); default (2-D)
        ``settings.radii`` and ``γ0^[i] = 2π(i−1)/N``.
    fusion : ndarray, shape (N, N), optional
        Fusion weights ``π^[i,j]``; default ``settings.fusion_weight`` on each in-edge and the
        rest on the tracker itself.

    Returns
    -------
    DecRun

    Raises
    ------
    ValueError
        If ``Δ`` of (22) is not of full row rank (e.g. ``ε₁ = 0`` in 2-D, Remark 6),
        ``T_s/dt`` is not an integer, or the controller type is unknown.

    References
    ----------
    seed 003, eqs. (2)–(5), (15)–(16), (22), (41)–(52).
    """
    s = settings
    n, d = initial_positions.shape
    delta = delta_matrix(np.array(s.epsilon))
    if np.linalg.matrix_rank(delta) < d:
        raise ValueError("epsilon gives a rank-deficient Delta of (22) (Remark 6)")
    if s.controller not in ("I", "II"):
        raise ValueError(f"controller must be 'I' or 'II', got {s.controller!r}")
    every = round(s.Ts / s.dt)
    if abs(every * s.dt - s.Ts) > 1e-9 * s.Ts:
        raise ValueError("Ts must be an integer multiple of dt")
    delta_bar = delta.T @ np.linalg.inv(delta @ delta.T)
    Kp, eps = np.diag(s.Kp), np.array(s.epsilon)
    if paths is None:
        paths = np.column_stack(
            [np.tile(s.radii, (n, 1)), 2 * np.pi * np.arange(n) / n if n > 1 else np.zeros(1)]
        )
    adjacency = np.zeros((n, n))
    for i, nbrs in enumerate(in_neighbours):
        adjacency[i, nbrs] = 1.0
    laplacian = np.diag(adjacency.sum(axis=1)) - adjacency
    if fusion is None:
        fusion = np.diag(1 - s.fusion_weight * adjacency.sum(axis=1)) + s.fusion_weight * adjacency
    F = np.block([[np.eye(d), s.Ts * np.eye(d)], [np.zeros((d, d)), np.eye(d)]])
    W_proc = np.diag(1.0 / np.array(s.Q))
    p = initial_positions.astype(float).copy()
    headings = np.asarray(initial_headings, dtype=float)
    R = _exp_skew(_skew(headings[:, None], 2)) if d == 2 else euler_rotation(headings)
    gamma, e_gamma = initial_gammas.astype(float).copy(), np.zeros(n)
    Omega = np.linalg.inv(np.broadcast_to(P0, (n, 2 * d, 2 * d)))
    x_pred = np.broadcast_to(x0, (n, 2 * d)).astype(float)
    x_hat, t_hat = x_pred.copy(), 0.0
    record = {k: [] for k in ("p", "yaw", "g", "gd", "ge", "pe", "le", "xe")}
    surge = np.zeros((n, d))
    for m in range(steps + 1):
        t = m * s.dt
        if m % every == 0:
            x_hat, Omega, x_pred = _dekf_step(
                x_pred, Omega, p, target[m], fusion, F, W_proc, s, rng
            )
            t_hat = t
        q_hat = x_hat[:, :d] + (t - t_hat) * x_hat[:, d:]
        path, dpath = _path(gamma, paths), _path_derivative(gamma, paths)
        omega_d = s.omega_bar - s.k_c * laplacian @ gamma
        gamma_rate = omega_d + e_gamma
        e_hat = np.einsum("nji,nj->ni", R, p - path - q_hat) - eps
        e_true = np.einsum("nji,nj->ni", R, p - path - target[m, :d]) - eps
        for key, value in zip(
            record,
            (p.copy(), np.arctan2(R[:, 1, 0], R[:, 0, 0]), gamma.copy(), gamma_rate,
             e_gamma.copy(), np.linalg.norm(e_true, axis=1),
             np.linalg.norm(q_hat - target[m, :d], axis=1),
             np.linalg.norm(np.hstack([q_hat, x_hat[:, d:]]) - target[m], axis=1)),
            strict=True,
        ):  # fmt: skip
            record[key].append(value)
        if m == steps:
            break
        feed = np.einsum("nji,nj->ni", R, dpath * omega_d[:, None] + x_hat[:, d:])
        u = (feed - e_hat @ Kp.T) @ delta_bar.T
        surge[:, 0] = u[:, 0]
        p = p + s.dt * np.einsum("nij,nj->ni", R, surge)
        R = R @ _exp_skew(s.dt * _skew(u[:, 1:], d))
        gamma = gamma + s.dt * gamma_rate
        if s.controller == "II":
            drive = np.einsum("ni,nji,nj->n", e_hat, R, dpath)
            decay = np.exp(-s.k_gamma * s.dt)
            e_gamma = decay * e_gamma + (1 - decay) / s.k_gamma * drive
    return DecRun(
        times=s.dt * np.arange(steps + 1),
        positions=np.array(record["p"]),
        headings=np.array(record["yaw"]),
        gammas=np.array(record["g"]),
        gamma_rates=np.array(record["gd"]),
        gamma_errors=np.array(record["ge"]),
        pursuit_errors=np.array(record["pe"]),
        localization_errors=np.array(record["le"]),
        estimation_errors=np.array(record["xe"]),
        target=target[: steps + 1],
    )


def _dekf_step(x_pred, Omega, positions, truth, fusion, F, W_proc, s, rng):
    """Correction (41), fusion (43), prediction (44) at one sampling instant."""
    n, d = positions.shape
    y = np.linalg.norm(positions - truth[:d], axis=1) + s.sigma * rng.standard_normal(n)
    z_tilde = np.einsum("nij,nj->ni", Omega, x_pred)
    Omega_tilde = Omega.copy()
    for i in range(n):
        diff = x_pred[i, :d] - positions[i]
        predicted = np.linalg.norm(diff)
        C = np.concatenate([diff / predicted, np.zeros(d)])
        z_tilde[i] += C * s.V * (y[i] - predicted + C @ x_pred[i])
        Omega_tilde[i] += s.V * np.outer(C, C)
    Omega_post = np.einsum("ij,jkl->ikl", fusion, Omega_tilde)
    x_hat = np.linalg.solve(Omega_post, (fusion @ z_tilde)[..., None])[..., 0]
    inner = np.linalg.inv(Omega_post + F.T @ W_proc @ F)
    Omega_next = W_proc - W_proc @ F @ inner @ F.T @ W_proc
    return x_hat, Omega_next, x_hat @ F.T
