"""Seed 003 in 2-D: the distributed estimation and control (DEC) loop of §V.

Trackers (2) with ``v = [v₁, 0]`` (Remark 2): ``ṗ = R(ψ)[v₁, 0]ᵀ``, ``ψ̇ = r``. Each tracker
runs the DEKF of Algorithm 2 (:mod:`theory.sim.range_dekf`) on a range every ``T_s``, tracks its
S-T curve ``p_d = r(γ) + q̂`` with (48), (51), coordinates its path parameter with (45)–(47) and
uses Controller Type I (49) or Type II (50), (52).

Choices (not given in the text, see ``docs/simulation.md``): between samples the controller uses
``q̂(t) = q̂_{k|k} + (t − t_k) v̂``; the communication graph of Fig. VI.1 is the directed ring
``1 ← 2 ← 3 ← 1`` for both fusion and coordination; ``(p, ψ, γ)`` advance by forward Euler with
``dt``; the stiff speed error ``e_γ = γ̇ − ω_d`` of Type II (``k_γ = 500``) obeys
``ė_γ = −k_γ e_γ + ê_pᵀRᵀr'(γ)`` (from (47), (50b), (52)) and is advanced exactly over ``dt``
with its input frozen.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["DecRun", "DecSettings", "simulate_dec_2d"]


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


def _rotation(psi: np.ndarray) -> np.ndarray:
    c, s = np.cos(psi), np.sin(psi)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def _path(gamma: np.ndarray, radii: np.ndarray, gamma0: np.ndarray) -> np.ndarray:
    """``r^[i](γ^[i])`` of (16) for every tracker, shape (N, 2)."""
    return radii * np.column_stack([np.cos(gamma + gamma0), np.sin(gamma + gamma0)])


def _path_derivative(gamma: np.ndarray, radii: np.ndarray, gamma0: np.ndarray) -> np.ndarray:
    """``r'^[i](γ^[i])``, shape (N, 2)."""
    return radii * np.column_stack([-np.sin(gamma + gamma0), np.cos(gamma + gamma0)])


def simulate_dec_2d(
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
    """Simulate the 2-D DEC system of seed 003 §V for ``steps`` steps of ``settings.dt``.

    Parameters
    ----------
    target : ndarray, shape (steps+1, 4)
        True target states ``[q; v]`` at ``t = k·dt`` (e.g. :func:`table_target`).
    initial_positions : ndarray, shape (N, 2)
    initial_headings : ndarray, shape (N,)
    initial_gammas : ndarray, shape (N,)
    in_neighbours : list of list of int
        0-based in-neighbours ``N_in^[i]`` (fusion and coordination).
    x0 : ndarray, shape (4,) or (N, 4)
        Initial estimates ``x̂_{1|0}`` (one for all trackers, or one each).
    P0 : ndarray, shape (4, 4) or (N, 4, 4)
        Initial covariances ``P_{1|0}``.
    steps : int
    rng : numpy.random.Generator
        Source of the range noise.
    settings : DecSettings
    paths : ndarray, shape (N, 3), optional
        Rows ``(r_x, r_y, γ0)`` of each tracker's path (16); default ``settings.radii`` and
        ``γ0^[i] = 2π(i−1)/N``.
    fusion : ndarray, shape (N, N), optional
        Fusion weights ``π^[i,j]``; default ``settings.fusion_weight`` on each in-edge and the
        rest on the tracker itself.

    Returns
    -------
    DecRun

    Raises
    ------
    ValueError
        If ``ε₁ = 0`` (``Δ`` singular, seed 003 Remark 6 / eq. (22)), ``T_s/dt`` is not an
        integer, or the controller type is unknown.

    References
    ----------
    seed 003, eqs. (2), (16), (22), (41)–(52).
    """
    s = settings
    if s.epsilon[0] == 0:
        raise ValueError("epsilon[0] must be non-zero: Delta of (22) is singular otherwise")
    if s.controller not in ("I", "II"):
        raise ValueError(f"controller must be 'I' or 'II', got {s.controller!r}")
    every = round(s.Ts / s.dt)
    if abs(every * s.dt - s.Ts) > 1e-9 * s.Ts:
        raise ValueError("Ts must be an integer multiple of dt")
    n = initial_positions.shape[0]
    delta_inv = np.linalg.inv(np.array([[1.0, s.epsilon[1]], [0.0, -s.epsilon[0]]]))
    Kp, eps = np.diag(s.Kp), np.array(s.epsilon)
    if paths is None:
        paths = np.column_stack(
            [np.tile(s.radii, (n, 1)), 2 * np.pi * np.arange(n) / n if n > 1 else np.zeros(1)]
        )
    radii, gamma0 = paths[:, :2], paths[:, 2]
    adjacency = np.zeros((n, n))
    for i, nbrs in enumerate(in_neighbours):
        adjacency[i, nbrs] = 1.0
    laplacian = np.diag(adjacency.sum(axis=1)) - adjacency
    if fusion is None:
        fusion = np.diag(1 - s.fusion_weight * adjacency.sum(axis=1)) + s.fusion_weight * adjacency
    F = np.array([[1, 0, s.Ts, 0], [0, 1, 0, s.Ts], [0, 0, 1, 0], [0, 0, 0, 1.0]])
    W_proc = np.diag(1.0 / np.array(s.Q))
    p, psi = initial_positions.astype(float).copy(), initial_headings.astype(float).copy()
    gamma, e_gamma = initial_gammas.astype(float).copy(), np.zeros(n)
    Omega = np.linalg.inv(np.broadcast_to(P0, (n, 4, 4)))
    x_pred = np.broadcast_to(x0, (n, 4)).astype(float)
    x_hat, t_hat = x_pred.copy(), 0.0
    record = {k: [] for k in ("p", "psi", "g", "gd", "ge", "pe", "le", "xe")}
    for m in range(steps + 1):
        t = m * s.dt
        if m % every == 0:
            x_hat, Omega, x_pred = _dekf_step(
                x_pred, Omega, p, target[m], fusion, F, W_proc, s, rng
            )
            t_hat = t
        q_hat = x_hat[:, :2] + (t - t_hat) * x_hat[:, 2:]
        R = _rotation(psi)
        path = _path(gamma, radii, gamma0)
        dpath = _path_derivative(gamma, radii, gamma0)
        omega_d = s.omega_bar - s.k_c * laplacian @ gamma
        gamma_rate = omega_d + e_gamma
        e_hat = np.einsum("nji,nj->ni", R, p - path - q_hat) - eps
        e_true = np.einsum("nji,nj->ni", R, p - path - target[m, :2]) - eps
        for key, value in zip(
            record,
            (p.copy(), psi.copy(), gamma.copy(), gamma_rate, e_gamma.copy(),
             np.linalg.norm(e_true, axis=1), np.linalg.norm(q_hat - target[m, :2], axis=1),
             np.linalg.norm(np.hstack([q_hat, x_hat[:, 2:]]) - target[m], axis=1)),
            strict=True,
        ):  # fmt: skip
            record[key].append(value)
        if m == steps:
            break
        feed = np.einsum("nji,nj->ni", R, dpath * omega_d[:, None] + x_hat[:, 2:])
        u = (feed - e_hat @ Kp.T) @ delta_inv.T
        p = p + s.dt * np.einsum("nij,nj->ni", R, np.column_stack([u[:, 0], np.zeros(n)]))
        psi = psi + s.dt * u[:, 1]
        gamma = gamma + s.dt * gamma_rate
        if s.controller == "II":
            drive = np.einsum("ni,nji,nj->n", e_hat, R, dpath)
            decay = np.exp(-s.k_gamma * s.dt)
            e_gamma = decay * e_gamma + (1 - decay) / s.k_gamma * drive
    return DecRun(
        times=s.dt * np.arange(steps + 1),
        positions=np.array(record["p"]),
        headings=np.array(record["psi"]),
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
    n = positions.shape[0]
    y = np.linalg.norm(positions - truth[:2], axis=1) + s.sigma * rng.standard_normal(n)
    z_tilde = np.einsum("nij,nj->ni", Omega, x_pred)
    Omega_tilde = Omega.copy()
    for i in range(n):
        diff = x_pred[i, :2] - positions[i]
        predicted = np.linalg.norm(diff)
        C = np.concatenate([diff / predicted, np.zeros(2)])
        z_tilde[i] += C * s.V * (y[i] - predicted + C @ x_pred[i])
        Omega_tilde[i] += s.V * np.outer(C, C)
    Omega_post = np.einsum("ij,jkl->ikl", fusion, Omega_tilde)
    x_hat = np.linalg.solve(Omega_post, (fusion @ z_tilde)[..., None])[..., 0]
    inner = np.linalg.inv(Omega_post + F.T @ W_proc @ F)
    Omega_next = W_proc - W_proc @ F @ inner @ F.T @ W_proc
    return x_hat, Omega_next, x_hat @ F.T
