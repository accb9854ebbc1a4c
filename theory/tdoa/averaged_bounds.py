"""Mean-square error bounds of the averaged filter on a frozen TDOA geometry (seed 000 §4.2.2).

Setting: static receivers, the Jacobians ``H_i = [G_i, 0]`` of eqs. (4.7)–(4.10) at the target,
so the measurements are ``y_i = H_i x + v_i`` (the linearization App. A analyses), the
constant-velocity target (4.5) with ``Q = q I``, ``R_i = r I``, ``P_0 = p_0 I`` and the true
initial state drawn from ``N(x̂_0, P_0)``. Every agent runs the averaged filter of eqs.
(4.26)–(4.28), (4.32)–(4.35) — the engine's :func:`~theory.tdoa.ekf.ekf_update`,
:func:`~theory.tdoa.averaging.average_round` and :func:`~theory.tdoa.ekf.ekf_predict`, i.e. the
filter ``trackcert simulate`` runs with ``linearize: truth`` — and the error
``e_i = x − x̂_i`` after the averaging of ping ``k`` has the second moment ``Σ_ii(k)``.
With ``C`` the connected component of agent ``i`` and ``G_C`` its stacked position Jacobian:

1. **CRB floor and consistency**, for every geometry and every ``k``:
   ``P_C(k) ⪯ Σ_ii(k) ⪯ P̄_i(k)``. ``P_C`` is the posterior CRB of the component (its
   centralized Kalman filter, :func:`theory.tdoa.crb.pcrb_along` on its rows): ``x̂_i(k)`` is a
   function of the component's data only, and the Kalman filter is the MMSE estimator of a
   linear-Gaussian model. The upper bound: ``z ↦ zzᵀ`` is matrix-convex, so averaging errors
   with weights summing to 1 gives ``E[ēēᵀ] ⪯ Σ_j w_ij E[ẽ_jẽ_jᵀ]``; the Joseph update with a
   fixed gain and the prediction are monotone; and ``Σ_ii(0|−1) = P_0``. The filter is
   conservative even though averaging covariances ignores the agents' correlations.
2. **Observable ⇒ bounded** (``rank G_C = d``): with the gains ``K_j`` the filter uses at a
   burn-in ping ``K`` frozen, ``P ↦ 𝓛(P) + U``, ``𝓛(P)_i = Σ_j w_ij M_j P_j M_jᵀ``,
   ``M_j = (I − K_jH_j)A``, dominates the filter's own recursion (the optimal gain minimizes
   the Joseph form and the map is monotone). If ``X = 𝓛(X) + I`` has a solution ``X ≻ 0`` then
   ``ρ(𝓛) < 1`` (``𝓛X ⪯ (1 − 1/λ_max X)X``), and ``Z = P_∞ + sX`` with ``P_∞ = 𝓛(P_∞) + U``
   and ``s = max(0, λ_max(X⁻¹(P̄(K) − P_∞)))`` (so ``Z ⪰ P̄(K)``) is a supersolution
   (``𝓛(Z) + U = Z − sI``); the fixed-gain recursion converges to ``P_∞``, so
   ``Σ_ii(k) ⪯ P̄_i(k) ⪯ Z_i`` for every ``k ≥ K``: the mean-square error stays bounded for
   ever, by a certificate whose residuals are re-computed (:func:`certify_boundedness`), and
   ``limsup_k P̄_i(k) ⪯ P_∞``.
3. **Unobservable ⇒ nothing learnt along the kernel** (``rank G_C < d``): for ``c ∈ ker G_C``
   the components of position and velocity along ``c`` are never corrected (every ``H_j`` of the
   component, and hence every gain, vanishes on them; ``P_0`` and ``Q`` are isotropic so they
   stay uncorrelated with the rest), so ``P_C``, ``Σ_ii`` and ``P̄_i`` restricted to them all
   equal the prior's propagation ``Π(k) = A^k P_0 A^kᵀ + Σ_{l<k} A^l BQBᵀ A^lᵀ``; the position
   variance along ``c`` is ``p_0(1 + (kT)²) + q Σ_{l<k} ((l + ½)T²)²`` — it grows without
   bound, whatever the filter (the CRB floor of 1 is this large).

Thm 4.2.3 (the paper's "4 connected non-coplanar agents", corrected to the rank of ``G_C`` in
``docs/theory/tdoa-observability.md``) therefore decides mean-square boundedness of the
averaged filter on a frozen geometry; App. A's Thm A.1.5 gives the EKF only a local version
(its Lemma A.1.3 needs ``‖x̃‖ ≤ ε``), and the EKF linearized at its estimate can diverge or show
false observability (``docs/simulation.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.linalg import eigh

from theory.core.network import components
from theory.core.observability import RankResult, numeric_rank
from theory.core.tolerances import PSD_RTOL
from theory.tdoa.averaging import average_round
from theory.tdoa.ekf import ekf_predict, ekf_update, kalman_gain
from theory.tdoa.geometry import exact_direction_rank
from theory.tdoa.model import cv_discrete, tdoa_jacobian

__all__ = [
    "PSD_RTOL",
    "ComponentGeometry",
    "FixedGainCertificate",
    "FrozenGeometry",
    "LinearizedRun",
    "analyze_components",
    "certify_boundedness",
    "linearized_run",
    "prior_propagation",
    "psd_violation",
    "simulate_linearized",
]


@dataclass(frozen=True, eq=False)
class FrozenGeometry:
    """Static receivers, a target where the Jacobians are evaluated, a network and the noises.

    Attributes
    ----------
    agents : ndarray, shape (N, d)
        Receiver positions.
    target : ndarray, shape (d,)
        Where the Jacobians ``H_i`` are evaluated (eqs. (4.7)–(4.10)).
    hears : ndarray of bool, shape (N, N)
        Undirected network: agent ``i`` hears agent ``j`` (``j ∈ N_i``).
    W : ndarray, shape (N, N)
        Row-stochastic consensus weights supported on ``hears`` (positive diagonal).
    T, p0, q, r : float
        Ping period, ``P_0 = p_0 I``, ``Q = q I``, ``R_i = r I``.
    """

    agents: np.ndarray
    target: np.ndarray
    hears: np.ndarray
    W: np.ndarray
    T: float
    p0: float
    q: float
    r: float

    @property
    def dim(self) -> int:
        """Space dimension ``d``."""
        return self.agents.shape[1]

    @cached_property
    def jacobians(self) -> list[np.ndarray]:
        """``H_i`` of every agent over the agents it hears (eqs. (4.7)–(4.10))."""
        return [
            tdoa_jacobian(self.target, self.agents, i, np.flatnonzero(self.hears[i]))
            for i in range(len(self.agents))
        ]

    @property
    def model(self) -> tuple[np.ndarray, np.ndarray]:
        """``A`` of eq. (4.6) and the process-noise covariance ``B Q Bᵀ``."""
        A, B = cv_discrete(self.T, self.dim)
        return A, self.q * B @ B.T


@dataclass(frozen=True, eq=False)
class ComponentGeometry:
    """One connected component: its agents, the rank of its stacked position Jacobian ``G_C``.

    Attributes
    ----------
    agents : tuple of int
        0-based agents of the component.
    exact_rank : int
        ``rank G_C`` decided exactly over the rationals the coordinates are
        (:func:`theory.tdoa.geometry.exact_direction_rank`; 0 for a lone agent).
    numeric : RankResult
        The floating-point rank of ``G_C`` with its singular values and margin.
    kernel : ndarray, shape (d, d − exact_rank)
        Orthonormal basis of ``ker G_C`` (its last right singular vectors).
    """

    agents: tuple[int, ...]
    exact_rank: int
    numeric: RankResult
    kernel: np.ndarray

    def conditioning(self) -> float:
        """``σ_r/σ_1`` over the ``r = exact_rank`` nonzero singular values of ``G_C``
        (1 if there are none)."""
        sv = self.numeric.singular_values
        return sv[self.exact_rank - 1] / sv[0] if self.exact_rank else 1.0


@dataclass(frozen=True, eq=False)
class LinearizedRun:
    """Second moments of the averaged filter on a frozen geometry, at pings ``0 … K``.

    Attributes
    ----------
    covariances : ndarray, shape (K+1, N, n, n)
        The filter's own ``P̄_i(k)`` after the averaging (4.35).
    mse : ndarray, shape (K+1, N, n, n)
        ``Σ_ii(k) = E[e_i e_iᵀ]`` of its estimates after the averaging (4.28).
    crb : ndarray, shape (K+1, N, n, n)
        ``P_C(k)``: the posterior CRB of agent ``i``'s component.
    gains : list of list of ndarray
        ``gains[k][i]``: the gain ``K_i(k)`` of eq. (4.32) used at ping ``k``.
    """

    covariances: np.ndarray
    mse: np.ndarray
    crb: np.ndarray
    gains: list[list[np.ndarray]]


@dataclass(frozen=True, eq=False)
class FixedGainCertificate:
    """A certificate that the averaged filter's covariances of one component stay bounded.

    Attributes
    ----------
    agents : tuple of int
        The component.
    X : ndarray, shape (m, n, n)
        Solution of ``X = 𝓛(X) + I`` (valid iff every ``X_i ≻ 0``).
    Z : ndarray, shape (m, n, n)
        The bound ``P̄_i(k) ⪯ Z_i`` for every ``k`` after the burn-in.
    limit : ndarray, shape (m, n, n)
        ``P_∞ = 𝓛(P_∞) + U``, the limit of the fixed-gain recursion: ``limsup_k P̄_i(k) ⪯ P_∞``.
    decay : float
        ``1 − 1/max_i λ_max(X_i) ≥ ρ(𝓛)`` (``inf`` when not valid).
    margin : float
        ``min_i λ_min(X_i)/λ_max(X_i)``: how clearly ``X ≻ 0`` (≤ 0 when not valid).
    residual : float
        Largest relative residual of ``X = 𝓛(X) + I`` and ``Z ⪰ 𝓛(Z) + U`` recomputed.
    valid : bool
        ``margin > 0``, ``residual ≤ PSD_RTOL`` and ``Z ⪰ P̄(K)``.
    """

    agents: tuple[int, ...]
    X: np.ndarray
    Z: np.ndarray
    limit: np.ndarray
    decay: float
    margin: float
    residual: float
    valid: bool


def psd_violation(lower: np.ndarray, upper: np.ndarray) -> float:
    """``λ_max(lower − upper)`` relative to the matrices' size (the larger Frobenius norm, at
    least 1): ``≤ PSD_RTOL`` means ``lower ⪯ upper`` holds within tolerance.

    Parameters
    ----------
    lower, upper : ndarray, shape (..., n, n)
        Symmetric matrices (stacks allowed; the worst of the stack is returned).

    Returns
    -------
    float
    """
    gap = np.linalg.eigvalsh(0.5 * ((lower - upper) + np.swapaxes(lower - upper, -1, -2)))[..., -1]
    scale = np.maximum(
        np.maximum(np.linalg.norm(lower, axis=(-2, -1)), np.linalg.norm(upper, axis=(-2, -1))), 1.0
    )
    return float(np.max(gap / scale))


def analyze_components(geometry: FrozenGeometry) -> list[ComponentGeometry]:
    """Every connected component with the exact and numeric rank of its ``G_C``.

    Parameters
    ----------
    geometry : FrozenGeometry
        Receivers, target and network.

    Returns
    -------
    list of ComponentGeometry

    References
    ----------
    seed 000, Thm 4.2.3; ``docs/theory/tdoa-observability.md`` (rank = dim aff{u_i}).
    """
    H = geometry.jacobians
    d = geometry.dim
    out = []
    for part in components(geometry.hears):
        G = np.vstack([H[i][:, :d] for i in part])
        rank = exact_direction_rank(geometry.target, geometry.agents[part]) if len(part) > 1 else 0
        numeric = numeric_rank(G) if G.size else numeric_rank(np.zeros((1, d)))
        kernel = np.linalg.svd(G if G.size else np.zeros((1, d)))[2][rank:].T
        out.append(ComponentGeometry(tuple(part), rank, numeric, kernel))
    return out


def linearized_run(geometry: FrozenGeometry, steps: int) -> LinearizedRun:
    """Run the averaged filter's covariance, its error's second moment and the CRB floor.

    Parameters
    ----------
    geometry : FrozenGeometry
        Receivers, Jacobians' point, network, weights and noises.
    steps : int
        Number of pings after ping 0.

    Returns
    -------
    LinearizedRun

    References
    ----------
    seed 000, eqs. (4.26)–(4.28), (4.32)–(4.35); App. A, eqs. (A.12)–(A.17).
    """
    H = geometry.jacobians
    covariances, gains, _ = _filter_loop(geometry, H, geometry.W, steps)
    mse = _error_moments(geometry, H, gains)
    return LinearizedRun(covariances, mse, _component_crb(geometry, steps), gains)


def simulate_linearized(
    geometry: FrozenGeometry, rng: np.random.Generator, *, steps: int
) -> np.ndarray:
    """One run of the averaged filter on the linearized model: the errors it makes.

    The true state starts at ``x̂_0 + N(0, P_0)`` with ``x̂_0 = [target; 0]`` and moves by (4.5)
    with ``w ~ N(0, q I)``; agent ``i`` measures ``y_i = H_i x + v_i``, ``v_i ~ N(0, r I)``, and
    runs the engine's update, averaging and prediction. The second moment of the returned errors
    over runs is :attr:`LinearizedRun.mse` (``run(spec, rng)`` of
    :func:`theory.sim.runner.monte_carlo`, with ``functools.partial`` for ``steps``).

    Parameters
    ----------
    geometry : FrozenGeometry
        The frozen scene.
    rng : numpy.random.Generator
        Source of the initial state, process and measurement noises.
    steps : int
        Number of pings after ping 0.

    Returns
    -------
    ndarray, shape (steps + 1, N, n)
        ``e_i(k) = x(k) − x̄_i(k)`` after the averaging of ping ``k``.

    References
    ----------
    seed 000, eqs. (4.2), (4.5), (4.26)–(4.28), (4.32)–(4.35).
    """
    return _filter_loop(geometry, geometry.jacobians, geometry.W, steps, rng)[2]


def _filter_loop(
    geometry: FrozenGeometry,
    H: list[np.ndarray],
    W: np.ndarray,
    steps: int,
    rng: np.random.Generator | None = None,
) -> tuple[np.ndarray, list[list[np.ndarray]], np.ndarray | None]:
    """The engine's averaged filter — gain (4.32), Joseph update (4.34), averaging (4.28),
    (4.35), prediction (4.26), (4.33) — for agents with rows ``H_i`` and weights ``W``.

    Returns ``P̄_i(k)`` after the averaging, the gains, and (with ``rng``) the errors of a run on
    simulated linear measurements (without ``rng`` the innovations are zero: the covariances and
    gains do not depend on them)."""
    A, B = cv_discrete(geometry.T, geometry.dim)
    BQB = geometry.q * B @ B.T
    N, n = len(H), A.shape[0]
    R = [geometry.r * np.eye(H_i.shape[0]) for H_i in H]
    P = np.tile(geometry.p0 * np.eye(n), (N, 1, 1))
    estimates = np.tile(np.concatenate([geometry.target, np.zeros(geometry.dim)]), (N, 1))
    truth = estimates[0] + (np.sqrt(geometry.p0) * rng.standard_normal(n) if rng else 0.0)
    covariances, gains, errors = [], [], []
    for _ in range(steps + 1):
        gains.append([kalman_gain(P_i, H_i, R_i) for P_i, H_i, R_i in zip(P, H, R, strict=True)])
        updates = [
            ekf_update(x_i, P_i, _innovation(H_i, truth, x_i, geometry.r, rng), H_i, R_i)
            for x_i, P_i, H_i, R_i in zip(estimates, P, H, R, strict=True)
        ]
        estimates, P = average_round(W, *(np.array(part) for part in zip(*updates, strict=True)))
        covariances.append(P)
        errors.append(truth - estimates)
        estimates, P = ekf_predict(estimates, P, A, BQB)
        if rng is not None:
            truth = A @ truth + B @ (np.sqrt(geometry.q) * rng.standard_normal(geometry.dim))
    return np.array(covariances), gains, np.array(errors) if rng is not None else None


def _innovation(
    H_i: np.ndarray,
    truth: np.ndarray,
    estimate: np.ndarray,
    r: float,
    rng: np.random.Generator | None,
) -> np.ndarray:
    """``y_i − H_i x̂_i`` with ``y_i = H_i x + v_i`` (zero without ``rng``)."""
    if rng is None:
        return np.zeros(H_i.shape[0])
    return H_i @ (truth - estimate) + np.sqrt(r) * rng.standard_normal(H_i.shape[0])


def _error_moments(
    geometry: FrozenGeometry, H: list[np.ndarray], gains: list[list[np.ndarray]]
) -> np.ndarray:
    """``Σ_ii(k)`` of the network error ``(I_N ⊗ A)``-propagated, corrected by the gains and
    averaged (eq. (A.12)), from the common initial error ``x(0) − x̂_0 ~ N(0, P_0)``.

    The process noise is common to all agents (one target), the measurement noises are
    independent (eq. (4.2))."""
    A, BQB = geometry.model
    N, n = len(H), A.shape[0]
    common = np.ones((N, N))
    sigma = np.kron(common, geometry.p0 * np.eye(n))
    mix, predict, process = (
        np.kron(geometry.W, np.eye(n)),
        np.kron(np.eye(N), A),
        np.kron(common, BQB),
    )
    out = []
    for K in gains:
        closed = _block_diagonal([np.eye(n) - K_i @ H_i for K_i, H_i in zip(K, H, strict=True)])
        noise = _block_diagonal([geometry.r * K_i @ K_i.T for K_i in K])
        sigma = mix @ (closed @ sigma @ closed.T + noise) @ mix.T
        out.append(np.array([sigma[i * n : (i + 1) * n, i * n : (i + 1) * n] for i in range(N)]))
        sigma = predict @ sigma @ predict.T + process
    return np.array(out)


def _block_diagonal(blocks: list[np.ndarray]) -> np.ndarray:
    """``blkdiag(blocks)`` of equal square blocks."""
    n = blocks[0].shape[0]
    out = np.zeros((n * len(blocks), n * len(blocks)))
    for i, block in enumerate(blocks):
        out[i * n : (i + 1) * n, i * n : (i + 1) * n] = block
    return out


def _component_crb(geometry: FrozenGeometry, steps: int) -> np.ndarray:
    """``P_C(k)`` of each agent's component: the centralized filter on the component's rows,
    which for this linear-Gaussian model is the posterior CRB (:func:`theory.tdoa.crb.pcrb_along`
    computes the same bound in information form)."""
    H = geometry.jacobians
    n = 2 * geometry.dim
    out = np.empty((steps + 1, len(H), n, n))
    for part in components(geometry.hears):
        stacked = [np.vstack([H[i] for i in part])]
        bound = _filter_loop(geometry, stacked, np.ones((1, 1)), steps)[0]
        out[:, part] = bound[:, :1]
    return out


def prior_propagation(geometry: FrozenGeometry, steps: int) -> np.ndarray:
    """``Π(k) = A^k P_0 A^kᵀ + Σ_{l<k} A^l BQBᵀ A^lᵀ``: the covariance with no measurement.

    Parameters
    ----------
    geometry : FrozenGeometry
        Supplies ``A``, ``BQBᵀ`` and ``P_0``.
    steps : int
        Number of pings after ping 0.

    Returns
    -------
    ndarray, shape (steps + 1, n, n)

    References
    ----------
    seed 000, eqs. (4.5)–(4.6), (4.33).
    """
    A, BQB = geometry.model
    out = [geometry.p0 * np.eye(A.shape[0])]
    for _ in range(steps):
        out.append(A @ out[-1] @ A.T + BQB)
    return np.array(out)


def certify_boundedness(
    geometry: FrozenGeometry, agents: tuple[int, ...], gains: list[np.ndarray], start: np.ndarray
) -> FixedGainCertificate:
    """Certificate that the filter's covariances of one component stay below ``Z`` (item 2).

    Parameters
    ----------
    geometry : FrozenGeometry
        The scene.
    agents : tuple of int
        A connected component.
    gains : list of ndarray
        The gain ``K_j`` of every agent of the network at the burn-in ping (frozen).
    start : ndarray, shape (N, n, n)
        ``P̄(K)`` of every agent at that ping.

    Returns
    -------
    FixedGainCertificate

    References
    ----------
    seed 000, eqs. (4.32)–(4.35), Lemma 5.2.2 (the operator ``𝓛``), App. A.2 (Lemma A.2.1).
    """
    part = list(agents)
    operator, U = _fixed_gain_operator(geometry, part, gains)
    m, n = len(part), start.shape[-1]
    identity = np.tile(np.eye(n), (m, 1, 1))
    try:
        X, limit = (_fixed_point(operator, rhs) for rhs in (identity, U))
    except np.linalg.LinAlgError:
        nothing = np.full_like(identity, np.nan)
        return FixedGainCertificate(
            agents, nothing, nothing, nothing, np.inf, -np.inf, np.inf, False
        )
    eig = np.linalg.eigvalsh(X)
    margin = float(np.min(eig[:, 0] / eig[:, -1]))
    if not margin > 0:
        return FixedGainCertificate(agents, X, limit, limit, np.inf, margin, np.inf, False)
    excess = [eigh(start[i] - limit[f], X[f], eigvals_only=True)[-1] for f, i in enumerate(part)]
    Z = limit + max(0.0, float(max(excess))) * X
    residual = max(
        _relative(X - _apply(operator, X) - identity, X),
        _relative(np.minimum(0.0, np.linalg.eigvalsh(Z - _apply(operator, Z) - U)), Z),
    )
    valid = residual <= PSD_RTOL and psd_violation(start[part], Z) <= PSD_RTOL
    decay = 1 - 1 / float(eig[:, -1].max())
    return FixedGainCertificate(agents, X, Z, limit, decay, margin, residual, valid)


def _fixed_point(operator: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """The solution ``P = 𝓛(P) + rhs`` (symmetrized)."""
    solution = np.linalg.solve(np.eye(operator.shape[0]) - operator, rhs.reshape(-1))
    return _sym(solution.reshape(rhs.shape))


def _apply(operator: np.ndarray, P: np.ndarray) -> np.ndarray:
    """``𝓛(P)`` for a stack ``P`` of the component's matrices."""
    return (operator @ P.reshape(-1)).reshape(P.shape)


def _fixed_gain_operator(
    geometry: FrozenGeometry, part: list[int], gains: list[np.ndarray]
) -> tuple[np.ndarray, np.ndarray]:
    """``𝓛`` on stacked ``vec P_j`` (``(W_CC ⊗ I) blkdiag(M_j ⊗ M_j)``) and the noise term ``U``."""
    A, BQB = geometry.model
    H = geometry.jacobians
    n = A.shape[0]
    closed = [np.eye(n) - gains[j] @ H[j] for j in part]
    W = geometry.W[np.ix_(part, part)]
    blocks = [np.kron(c @ A, c @ A) for c in closed]
    operator = np.kron(W, np.eye(n * n)) @ _block_diagonal(blocks)
    local = np.array(
        [
            c @ BQB @ c.T + geometry.r * gains[j] @ gains[j].T
            for c, j in zip(closed, part, strict=True)
        ]
    )
    return operator, np.einsum("ij,jkl->ikl", W, local)


def _sym(P: np.ndarray) -> np.ndarray:
    return 0.5 * (P + np.swapaxes(P, -1, -2))


def _relative(values: np.ndarray, reference: np.ndarray) -> float:
    return float(np.max(np.abs(values)) / max(float(np.max(np.abs(reference))), 1.0))
