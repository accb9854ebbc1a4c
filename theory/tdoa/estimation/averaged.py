"""Mean-square error bounds of the averaged filter on a frozen TDOA geometry (seed 000 §4.2.2).

Setting: static receivers, the Jacobians ``H_i = [G_i, 0]`` of eqs. (4.7)–(4.10) at the target,
so the measurements are ``y_i = H_i x + v_i`` (the linearization App. A analyses), the
constant-velocity target (4.5) with ``Q = q I``, ``R_i = r I``, ``P_0 = p_0 I`` and the true
initial state drawn from ``N(x̂_0, P_0)``. Every agent runs the averaged filter of eqs.
(4.26)–(4.28), (4.32)–(4.35) — the engine's :func:`~theory.tdoa.estimation.filters.ekf_update`,
``average_round`` and ``ekf_predict``, i.e. the
filter ``trackcert simulate`` runs with ``linearize: truth`` — and the error
``e_i = x − x̂_i`` after the averaging of ping ``k`` has the second moment ``Σ_ii(k)``.
With ``C`` the connected component of agent ``i`` and ``G_C`` its stacked position Jacobian:

1. **CRB floor and consistency**, for every geometry and every ``k``:
   ``P_C(k) ⪯ Σ_ii(k) ⪯ P̄_i(k)``. ``P_C`` is the posterior CRB of the component (its
   centralized Kalman filter, :func:`~theory.tdoa.geometry.crb.pcrb_along` on its rows):
   ``x̂_i(k)`` is a function of the component's data only, and the Kalman filter is the MMSE
   estimator of a linear-Gaussian model. The upper bound: ``z ↦ zzᵀ`` is matrix-convex, so
   averaging errors with weights summing to 1 gives ``E[ēēᵀ] ⪯ Σ_j w_ij E[ẽ_jẽ_jᵀ]``; the
   Joseph update with a fixed gain and the prediction are monotone; and ``Σ_ii(0|−1) = P_0``.
   The filter is conservative even though averaging covariances ignores the agents' correlations.
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

**Falsifiable wordings** (``trackcert falsify``): examples are 3D scenes (strategy families
``general`` and ``coplanar``, 2–6 receivers) with an undirected network (connected or not),
any row-stochastic ``W`` with ``w_ij > 0`` exactly on the links and the diagonal (the class of
seed 000 §4.2.2, the paragraph before eq. (4.26): "a stochastic matrix with entries w_ij > 0 if
i = j or if agents i and j can exchange information", links bidirectional;
:func:`~theory.tdoa.strategies.stochastic_weights`: Metropolis, uniform, or random weights over
four decades) and the noises of seed 000 §4.4, run for :data:`HORIZON` pings. ``corrected``:
items 1–3 above, the certificate built from the gains of the first ping of :data:`BURN_INS` that
certifies; ``paper``: the
error is bounded (certified) iff the component has ≥ 4 connected non-coplanar agents (false:
coplanar receivers with the target off their plane localize, agents on a cone do not). An
example is not counted when a component's float rank disagrees with its exact rank or its
nonzero singular values spread by more than ``1/MIN_CONDITIONING``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from hypothesis import strategies as st
from scipy.linalg import block_diag, eigh

from theory.core.claims import Property
from theory.core.network import components, metropolis_weights
from theory.core.observability import RANK_TOL, RankResult, numeric_rank
from theory.core.tolerances import KERNEL_RTOL, MIN_CONDITIONING, PSD_RTOL
from theory.tdoa.case import TdoaSpec
from theory.tdoa.estimation.filters import average_round, ekf_predict, ekf_update, kalman_gain
from theory.tdoa.geometry.exact import exact_direction_rank
from theory.tdoa.model import cv_discrete, tdoa_jacobian
from theory.tdoa.strategies import TdoaScene, networks, stochastic_weights, tdoa_scenes

__all__ = [
    "BURN_IN",
    "BURN_INS",
    "HORIZON",
    "NOISES",
    "PROPERTIES",
    "ComponentGeometry",
    "ComponentVerdict",
    "ExampleVerdict",
    "FilterExample",
    "FixedGainCertificate",
    "FrozenGeometry",
    "LinearizedRun",
    "analyze_components",
    "certify_boundedness",
    "check_example",
    "example_from_spec",
    "filter_example_case",
    "filter_examples",
    "linearized_run",
    "prior_propagation",
    "psd_violation",
    "simulate_linearized",
]


@dataclass(frozen=True, eq=False)
class FrozenGeometry:
    """Static receivers ``agents`` (N, d), the ``target`` where the Jacobians are evaluated, an
    undirected network ``hears`` with row-stochastic weights ``W`` (positive diagonal), the ping
    period ``T`` and ``P_0 = p0 I``, ``Q = q I``, ``R_i = r I``."""

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
    """One connected component (0-based ``agents``): the exact rank of its stacked position
    Jacobian ``G_C`` (0 for a lone agent), the float rank beside it, and an orthonormal basis of
    ``ker G_C``."""

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
    """At pings ``0 … K``: the filter's own ``P̄_i(k)`` after (4.35), the second moment
    ``Σ_ii(k) = E[e_i e_iᵀ]`` of its errors after (4.28), the posterior CRB ``P_C(k)`` of agent
    ``i``'s component, and the gains ``K_i(k)`` of eq. (4.32)."""

    covariances: np.ndarray
    mse: np.ndarray
    crb: np.ndarray
    gains: list[list[np.ndarray]]


@dataclass(frozen=True, eq=False)
class FixedGainCertificate:
    """Certificate that one component's covariances stay bounded (item 2 of the module docstring).

    ``X = 𝓛(X) + I`` (valid iff every ``X_i ≻ 0``, ``margin = min λ_min/λ_max``), the bound ``Z``
    (``P̄_i(k) ⪯ Z_i`` after the burn-in), ``limit = P_∞``, ``decay = 1 − 1/max λ_max(X_i) ≥ ρ(𝓛)``,
    the largest recomputed relative ``residual``; ``valid``: ``margin > 0``,
    ``residual ≤ PSD_RTOL`` and ``Z ⪰ P̄(K)``."""

    agents: tuple[int, ...]
    X: np.ndarray
    Z: np.ndarray
    limit: np.ndarray
    decay: float
    margin: float
    residual: float
    valid: bool


def psd_violation(lower: np.ndarray, upper: np.ndarray) -> float:
    """``λ_max(lower − upper)`` over the larger Frobenius norm (at least 1), worst of a stack:
    ``≤ PSD_RTOL`` means ``lower ⪯ upper`` within tolerance."""
    gap = np.linalg.eigvalsh(0.5 * ((lower - upper) + np.swapaxes(lower - upper, -1, -2)))[..., -1]
    scale = np.maximum(
        np.maximum(np.linalg.norm(lower, axis=(-2, -1)), np.linalg.norm(upper, axis=(-2, -1))), 1.0
    )
    return float(np.max(gap / scale))


def analyze_components(geometry: FrozenGeometry) -> list[ComponentGeometry]:
    """Every connected component with the exact and float rank of its ``G_C`` (Thm 4.2.3)."""
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
    """The averaged filter's covariances, its errors' second moments and the CRB floor over
    ``steps`` pings (seed 000 eqs. (4.26)–(4.35); App. A, eqs. (A.12)–(A.17))."""
    H = geometry.jacobians
    covariances, gains, _ = _filter_loop(geometry, H, geometry.W, steps)
    mse = _error_moments(geometry, H, gains)
    return LinearizedRun(covariances, mse, _component_crb(geometry, steps), gains)


def simulate_linearized(
    geometry: FrozenGeometry, rng: np.random.Generator, *, steps: int
) -> np.ndarray:
    """The errors ``e_i(k) = x(k) − x̄_i(k)`` of one run of the averaged filter on the linearized
    model (true state from ``x̂_0 + N(0, P_0)``, ``y_i = H_i x + v_i``); their second moment over
    runs is :attr:`LinearizedRun.mse`. Seed 000 eqs. (4.2), (4.5), (4.26)–(4.35)."""
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
        closed = block_diag(*[np.eye(n) - K_i @ H_i for K_i, H_i in zip(K, H, strict=True)])
        noise = block_diag(*[geometry.r * K_i @ K_i.T for K_i in K])
        sigma = mix @ (closed @ sigma @ closed.T + noise) @ mix.T
        out.append(np.array([sigma[i * n : (i + 1) * n, i * n : (i + 1) * n] for i in range(N)]))
        sigma = predict @ sigma @ predict.T + process
    return np.array(out)


def _component_crb(geometry: FrozenGeometry, steps: int) -> np.ndarray:
    """``P_C(k)`` of each agent's component: the centralized filter on the component's rows,
    which for this linear-Gaussian model is the posterior CRB (``pcrb_along`` computes the same
    bound in information form)."""
    H = geometry.jacobians
    n = 2 * geometry.dim
    out = np.empty((steps + 1, len(H), n, n))
    for part in components(geometry.hears):
        stacked = [np.vstack([H[i] for i in part])]
        bound = _filter_loop(geometry, stacked, np.ones((1, 1)), steps)[0]
        out[:, part] = bound[:, :1]
    return out


def prior_propagation(geometry: FrozenGeometry, steps: int) -> np.ndarray:
    """``Π(k) = A^k P_0 A^kᵀ + Σ_{l<k} A^l BQBᵀ A^lᵀ``, the covariance without measurements
    (seed 000 eqs. (4.5)–(4.6), (4.33))."""
    A, BQB = geometry.model
    out = [geometry.p0 * np.eye(A.shape[0])]
    for _ in range(steps):
        out.append(A @ out[-1] @ A.T + BQB)
    return np.array(out)


def certify_boundedness(
    geometry: FrozenGeometry, agents: tuple[int, ...], gains: list[np.ndarray], start: np.ndarray
) -> FixedGainCertificate:
    """Certificate that the covariances of the component ``agents`` stay below ``Z`` (item 2),
    from every agent's gain at the burn-in ping and ``start = P̄(K)`` (seed 000 eqs. (4.32)–(4.35),
    Lemma 5.2.2's operator, Lemma A.2.1)."""
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
    operator = np.kron(W, np.eye(n * n)) @ block_diag(*blocks)
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


BURN_IN = 40
"""First ping whose gains are frozen for the boundedness certificate."""
HORIZON = 2 * BURN_IN
"""Pings run; the certified bound is checked on ``BURN_IN … HORIZON``."""
BURN_INS = tuple(BURN_IN * 2**m for m in range(6))
"""Pings ``40, 80, …, 1280`` whose gains are tried in turn for the certificate (each checked on
``K … 2K``): with weights spread over decades the covariances settle over hundreds of pings and
the gains of ping 40 need not contract (docs/errata.md, "The averaged filter with slowly mixing
weights")."""
SETTLE_RTOL = 1e-3
"""Relative growth of the largest position-covariance trace from ping 1280 to 2560 above which
an uncertified observable component is still in its transient: the example is not counted
(inconclusive), since weights can be arbitrarily small and the transient arbitrarily long."""
NOISES = {"T": 1.0, "p0": 100.0, "q": 0.01, "r": 1.0}
"""Seed 000 §4.4: ping period, ``P_0 = p_0 I``, ``Q = q I``, ``R_i = r I``."""


@dataclass(frozen=True, eq=False)
class FilterExample:
    """A scene (the target is where the Jacobians are evaluated), its undirected network and
    row-stochastic weights ``W`` on it (``None``: Metropolis weights)."""

    scene: TdoaScene
    hears: np.ndarray
    W: np.ndarray | None = None

    def weights(self) -> np.ndarray:
        """``W``, or the Metropolis weights of :attr:`hears` when none were given."""
        return metropolis_weights(self.hears) if self.W is None else self.W

    def geometry(self) -> FrozenGeometry:
        """The frozen geometry with :meth:`weights` and :data:`NOISES`."""
        return FrozenGeometry(
            self.scene.agents, self.scene.target, self.hears, self.weights(), **NOISES
        )


@dataclass(frozen=True)
class ComponentVerdict:
    """What one component (1-based ``agents``) shows: the exact rank of ``G_C``, whether it is
    observable (rank 3) and meets the paper's condition (≥ 4 agents, not coplanar); observable:
    whether the fixed-gain certificate holds along the run and the ping ``burn_in`` of
    :data:`BURN_INS` whose gains it froze (uncertified: whether the covariances had
    ``settled``), its ``decay`` bound on ``ρ(𝓛)``,
    ``max_i tr Z_i`` and ``max_i tr P_∞,i`` over the position block (m²); always the CRB floor
    ``max_i tr P_C(HORIZON)``; unobservable: the largest relative gap along ``ker G_C`` between
    ``Π`` and the three second moments."""

    agents: tuple[int, ...]
    exact_rank: int
    observable: bool
    paper_condition: bool
    certified: bool | None
    burn_in: int | None
    settled: bool | None
    decay: float | None
    mse_bound: float | None
    mse_limit: float | None
    crb_floor: float
    kernel_deviation: float | None


@dataclass(frozen=True)
class ExampleVerdict:
    """The corrected wording on one example: ``counted`` is False when a component is numerically
    unsafe or an uncertified observable one has not settled by ping 2560; ``crb_violation`` and
    ``consistency_violation`` are the worst ``psd_violation(P_C, Σ_ii)`` and
    ``psd_violation(Σ_ii, P̄_i)`` over agents and pings."""

    counted: bool
    crb_violation: float = 0.0
    consistency_violation: float = 0.0
    components: list[ComponentVerdict] = field(default_factory=list)

    @property
    def holds(self) -> bool:
        """Whether the corrected wording holds (vacuously when not counted)."""
        if not self.counted:
            return True
        sandwich = max(self.crb_violation, self.consistency_violation) <= PSD_RTOL
        return sandwich and all(
            c.certified if c.observable else c.kernel_deviation <= KERNEL_RTOL
            for c in self.components
        )


@st.composite
def filter_examples(draw: st.DrawFn, *, max_agents: int = 6) -> FilterExample:
    """3D scenes (families ``general``, ``coplanar``) of 2 to ``max_agents`` receivers with an
    undirected network, connected or not, and any row-stochastic ``W`` positive exactly on its
    links and diagonal (seed 000 §4.2.2, before eq. (4.26))."""
    family = draw(st.sampled_from(("general", "coplanar")))
    scene = draw(tdoa_scenes(dim=3, min_agents=2, max_agents=max_agents, family=family))
    n = len(scene.agents)
    hears = draw(networks(min_agents=n, max_agents=n, connected=None))
    return FilterExample(scene, hears, draw(stochastic_weights(hears)))


def check_example(example: FilterExample) -> ExampleVerdict:
    """Run the averaged filter on ``example``'s frozen geometry and check the corrected wording
    (seed 000 §4.2.2, Thm 4.2.3, App. A)."""
    geometry = example.geometry()
    parts = analyze_components(geometry)
    if not all(_safe(part) for part in parts):
        return ExampleVerdict(counted=False)
    run = linearized_run(geometry, HORIZON)
    prior = prior_propagation(geometry, HORIZON)
    components = [_component_verdict(example, geometry, part, run, prior) for part in parts]
    return ExampleVerdict(
        counted=not any(c.settled is False for c in components),
        crb_violation=psd_violation(run.crb, run.mse),
        consistency_violation=psd_violation(run.mse, run.covariances),
        components=components,
    )


def _safe(part: ComponentGeometry) -> bool:
    return part.numeric.rank == part.exact_rank and part.conditioning() >= MIN_CONDITIONING


def _component_verdict(
    example: FilterExample,
    geometry: FrozenGeometry,
    part: ComponentGeometry,
    run: LinearizedRun,
    prior: np.ndarray,
) -> ComponentVerdict:
    members = list(part.agents)
    d = geometry.dim
    floor = float(np.trace(run.crb[HORIZON, members, :d, :d], axis1=-2, axis2=-1).max())
    verdict = {
        "agents": tuple(i + 1 for i in members),
        "exact_rank": part.exact_rank,
        "observable": part.exact_rank == d,
        "paper_condition": _paper_condition(example.scene.agents[members]),
        "crb_floor": floor,
        "certified": None,
        "burn_in": None,
        "settled": None,
        "decay": None,
        "mse_bound": None,
        "mse_limit": None,
        "kernel_deviation": None,
    }
    if verdict["observable"]:
        cert, verdict["burn_in"], verdict["settled"] = _first_certificate(geometry, part, run)
        verdict["certified"] = verdict["burn_in"] is not None
        verdict["decay"] = cert.decay
        verdict["mse_bound"] = float(np.trace(cert.Z[:, :d, :d], axis1=-2, axis2=-1).max())
        verdict["mse_limit"] = float(np.trace(cert.limit[:, :d, :d], axis1=-2, axis2=-1).max())
    else:
        verdict["kernel_deviation"] = _kernel_deviation(part, run, prior)
    return ComponentVerdict(**verdict)


def _first_certificate(
    geometry: FrozenGeometry, part: ComponentGeometry, run: LinearizedRun
) -> tuple[FixedGainCertificate, int | None, bool | None]:
    """The certificate from the first ping ``K`` of :data:`BURN_INS` whose bound ``Z`` holds on
    the filter's ``P̄_i(K … 2K)``, and ``K``; if none does, the last attempt, ``None`` and
    whether the covariances had settled (:func:`_settled`; else the run is inconclusive)."""
    covariances, gains = run.covariances, run.gains
    members = list(part.agents)
    for burn_in in BURN_INS:
        if len(covariances) <= 2 * burn_in:
            covariances, gains, _ = _filter_loop(
                geometry, geometry.jacobians, geometry.W, 2 * burn_in
            )
        cert = certify_boundedness(geometry, part.agents, gains[burn_in], covariances[burn_in])
        later = psd_violation(covariances[burn_in : 2 * burn_in + 1, members], cert.Z[None])
        if cert.valid and later <= PSD_RTOL:
            return cert, burn_in, None
    return cert, None, _settled(covariances[:, members, :3, :3], BURN_INS[-1])


def _settled(positions: np.ndarray, ping: int) -> bool:
    """Whether the largest position-covariance trace grew by at most :data:`SETTLE_RTOL` from
    ping ``K`` to ``2K`` (a longer transient leaves boundedness undecided at this horizon)."""
    trace = np.trace(positions, axis1=-2, axis2=-1).max(axis=1)
    return bool(trace[2 * ping] <= (1 + SETTLE_RTOL) * trace[ping])


def _kernel_deviation(part: ComponentGeometry, run: LinearizedRun, prior: np.ndarray) -> float:
    """Largest relative gap, along ``ker G_C`` (positions and velocities), between ``Π(k)`` and
    ``P̄_i(k)``, ``Σ_ii(k)``, ``P_C(k)`` of the component's agents."""
    E = np.kron(np.eye(2), part.kernel)
    reference = E.T @ prior @ E
    scale = np.linalg.norm(reference, 2, axis=(1, 2))[:, None]
    members = list(part.agents)
    gaps = [
        np.linalg.norm(E.T @ moments[:, members] @ E - reference[:, None], 2, axis=(2, 3)) / scale
        for moments in (run.covariances, run.mse, run.crb)
    ]
    return float(np.max(gaps))


def _paper_condition(agents: np.ndarray) -> bool:
    """Thm 4.2.3's wording: at least ``d + 1`` agents, not coplanar (rank of the centred
    positions at :data:`~theory.core.observability.RANK_TOL`)."""
    n, d = agents.shape
    return n >= d + 1 and numeric_rank(agents - agents.mean(axis=0), rank_tol=RANK_TOL).rank == d


def _corrected(example: FilterExample) -> bool:
    return check_example(example).holds


def _paper(example: FilterExample) -> bool:
    verdict = check_example(example)
    if not verdict.counted:
        return True
    return all(bool(c.certified) == c.paper_condition for c in verdict.components)


def filter_example_case(example: FilterExample) -> dict[str, Any]:
    """A ``kind: tdoa`` case reproducing ``example`` (its weights as an explicit matrix, or
    ``metropolis``), expecting the observability of each agent's component; the filter's
    verdicts are in its description."""
    scene = example.scene
    n = len(scene.agents)
    edges = [[i + 1, j + 1] for i in range(n) for j in range(i + 1, n) if example.hears[i, j]]
    verdict = check_example(example)
    observable = [False] * n
    for c in verdict.components:
        for agent in c.agents:
            observable[agent - 1] = c.observable
    summary = "; ".join(
        f"agents {list(c.agents)}: rank {c.exact_rank}, paper condition {c.paper_condition}, "
        f"certified bounded {c.certified}" + (f" (gains of ping {c.burn_in})" if c.burn_in else "")
        for c in verdict.components
    )
    return {
        "name": f"falsify-averaged-filter-{n}-agents",
        "source": "trackcert falsify (shrunk counterexample, seed 000 §4.2.2 / Thm 4.2.3)",
        "description": f"averaged filter on the frozen geometry, {HORIZON} pings, "
        f"T = {NOISES['T']}, P0 = {NOISES['p0']} I, Q = {NOISES['q']} I, R = {NOISES['r']} I: "
        + (summary or "not counted (numerically unsafe component)"),
        "kind": "tdoa",
        "tdoa": {
            "T": NOISES["T"],
            "target": [float(v) for v in scene.target],
            "agents": [[float(v) for v in row] for row in scene.agents],
            "edges": edges,
            "weights": "metropolis" if example.W is None else example.W.tolist(),
        },
        "expect": {"observable": observable} if verdict.counted else {},
    }


def example_from_spec(spec: TdoaSpec) -> FilterExample:
    """The example a :func:`filter_example_case` case file describes (its first step)."""
    scene = TdoaScene(spec.target[0], spec.agents[0], "reloaded")
    return FilterExample(scene, spec.hears[0], spec.weights[0])


def _property(wording: str, statement: str, holds: Any, expected_to_hold: bool) -> Property:
    return Property(
        id=f"seed000.thm4.2.3.averaged-filter/{wording}",
        claim="seed000.thm4.2.3.averaged-filter",
        wording=wording,
        statement=statement,
        examples=filter_examples(),
        holds=holds,
        to_case=filter_example_case,
        expected_to_hold=expected_to_hold,
    )


PROPERTIES = (
    _property(
        "paper",
        "The averaged filter's error stays bounded iff the agent is part of a (sub)network of at "
        "least 4 connected, non-coplanar agents (Thm 4.2.3 with §4.2.2's convergence remark).",
        _paper,
        expected_to_hold=False,
    ),
    _property(
        "corrected",
        "On a frozen geometry, for every agent i of component C and every ping k: "
        "P_C(k) ⪯ E[e_i e_iᵀ](k) ⪯ P̄_i(k) (posterior CRB of C ⪯ mean-square error ⪯ filter "
        "covariance); if rank G_C = 3 the gains at one of the pings K = 40, 80, …, 1280 "
        "certify E[e_i e_iᵀ](k) ⪯ Z_i for all k ≥ K (or the covariances are still growing at "
        "ping 2560: inconclusive); if rank G_C < 3 nothing is learnt along "
        "ker G_C, where the position variance is p₀(1 + (kT)²) + q Σ_{l<k} ((l + ½)T²)² for "
        "every estimator.",
        _corrected,
        expected_to_hold=True,
    ),
)
