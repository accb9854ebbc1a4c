"""The constant-velocity target and its TDOA measurements (seed 000 eqs. (4.1)–(4.10)).

The target state is ``x = [p; ṗ]``, ``p ∈ R^d``, ``d ∈ {2, 3}``, driven by white acceleration:
``x(k+1) = A x(k) + B w(k)`` (eqs. (4.5)–(4.6)). Agent ``i`` with neighbours ``N_i`` measures
``y_i = h_i(p) + v_i``, ``h_{i,j} = ‖p − p_i‖ − ‖p − p_j‖``, ``v_i ~ N(0, r I)`` independent across
agents (eqs. (4.2)–(4.4)); its Jacobian row is ``u_i − u_j`` with ``u_i = (p − p_i)/‖p − p_i‖``
in the position block and zero in the velocity block (eqs. (4.7)–(4.10)). Seed 002 writes the
same model for its particle filter (eqs. (3.6)–(3.9)).

This is the only implementation of that model. Its functions broadcast over the leading axes of
the points and of the measuring agents, so one call serves one agent at one point (the EKF, the
observability checks), every agent at its own estimate (the network filters), or every filtering
node at each of its particles (``range_differences(particles, nodes, filters[:, None])``).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

from theory.core.claims import ClaimResult, ClaimSet, Context, Method, status_of

if TYPE_CHECKING:
    import sympy as sp

__all__ = [
    "claims",
    "cv_continuous",
    "cv_discrete",
    "cv_discrete_symbolic",
    "discretization_claim",
    "neighbour_lists",
    "range_difference_gradients",
    "range_differences",
    "ranges",
    "simulate_cv_target",
    "tdoa_jacobian",
    "tdoa_jacobians",
    "tdoa_measurement",
    "tdoa_predictions",
    "tdoa_readings",
    "unit_directions",
]

claims = ClaimSet()


def cv_continuous(dim: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """Continuous-time constant-velocity model ``(F, G)`` (seed 000 eq. (4.1))."""
    eye, zero = np.eye(dim), np.zeros((dim, dim))
    return np.block([[zero, eye], [zero, zero]]), np.vstack([zero, eye])


def cv_discrete(T: float, dim: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """``A = exp(F T)`` and ``B = [T²/2 I; T I]`` of seed 000 eqs. (4.5)–(4.6)."""
    eye, zero = np.eye(dim), np.zeros((dim, dim))
    A = np.block([[eye, T * eye], [zero, eye]])
    B = np.vstack([0.5 * T**2 * eye, T * eye])
    return A, B


def cv_discrete_symbolic(T: sp.Expr, dim: int = 3) -> sp.Matrix:
    """``A`` of seed 000 eq. (4.6) with a symbolic sampling period ``T``."""
    import sympy as sp

    eye, zero = sp.eye(dim), sp.zeros(dim, dim)
    return sp.Matrix(sp.BlockMatrix([[eye, T * eye], [zero, eye]]))


def simulate_cv_target(
    x0: np.ndarray, Q: np.ndarray, T: float, steps: int, rng: np.random.Generator
) -> np.ndarray:
    """States ``x(0), …, x(steps)`` at the pings, ``w(k) ~ N(0, Q)`` (seed 000 eqs. (4.5)–(4.6))."""
    dim = Q.shape[0]
    A, B = cv_discrete(T, dim)
    noise = rng.multivariate_normal(np.zeros(dim), Q, size=steps, method="cholesky")
    states = np.empty((steps + 1, 2 * dim))
    states[0] = x0
    for k in range(steps):
        states[k + 1] = A @ states[k] + B @ noise[k]
    return states


def ranges(points: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """``‖p − p_j‖`` from every point (``(..., d)``) to every position, ``(..., N)`` (eq. (4.4))."""
    return np.linalg.norm(_offsets(points, positions), axis=-1)


def unit_directions(target: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Rows ``u_i = (p − p_i)/‖p − p_i‖``, shape ``(..., N, d)`` (seed 000 eqs. (4.8)–(4.10))."""
    diff = _offsets(target, positions)
    return diff / np.linalg.norm(diff, axis=-1, keepdims=True)


def range_differences(
    points: np.ndarray, positions: np.ndarray, agents: int | np.ndarray
) -> np.ndarray:
    """``h_{a,j}(p) = ‖p − p_a‖ − ‖p − p_j‖`` of measuring agent ``a`` against every ``j``.

    ``agents`` broadcasts against the leading shape of ``points``; the result has shape
    ``(S..., N)`` (0 at ``j = a``). Seed 000 eqs. (4.3)–(4.4); seed 002 eq. (3.9).
    """
    distances = ranges(points, positions)
    return _own(distances, agents, tail=0) - distances


def range_difference_gradients(
    points: np.ndarray, positions: np.ndarray, agents: int | np.ndarray
) -> np.ndarray:
    """``∂h_{a,j}/∂p = u_a − u_j`` against every ``j``, shape ``(S..., N, d)`` (eq. (4.7))."""
    units = unit_directions(points, positions)
    return _own(units, agents, tail=1) - units


def tdoa_measurement(
    target: np.ndarray, positions: np.ndarray, agent: int | np.ndarray, neighbours: Sequence[int]
) -> np.ndarray:
    """``h_i(p)`` of seed 000 eqs. (4.3)–(4.4) against ``neighbours``, in their order."""
    return range_differences(target, positions, agent)[..., _index(neighbours)]


def tdoa_jacobian(
    target: np.ndarray, positions: np.ndarray, agent: int | np.ndarray, neighbours: Sequence[int]
) -> np.ndarray:
    """``H_i`` of seed 000 eqs. (4.7)–(4.10), shape ``(..., |N_i|, 2d)`` (velocity block zero)."""
    position_block = range_difference_gradients(target, positions, agent)[
        ..., _index(neighbours), :
    ]
    return np.concatenate([position_block, np.zeros_like(position_block)], axis=-1)


def neighbour_lists(hears: np.ndarray) -> list[np.ndarray]:
    """0-based neighbours ``N_i`` of each agent (``hears[i, j]``: ``i`` receives from ``j``)."""
    return [np.flatnonzero(row) for row in np.asarray(hears, dtype=bool)]


def tdoa_predictions(
    point: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    *,
    agents: np.ndarray | None = None,
) -> list[np.ndarray]:
    """``h_i(point)`` for every measuring agent (eq. (4.3)), each at its own point if ``(M, d)``.

    ``agents`` gives the position of each list's owner (default ``0, 1, …``; seed 002's
    networks pass their filtering nodes).
    """
    full = range_differences(*_per_agent(point, positions, neighbours, agents))
    return [full[i, nbrs] for i, nbrs in enumerate(neighbours)]


def tdoa_jacobians(
    point: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    *,
    agents: np.ndarray | None = None,
) -> list[np.ndarray]:
    """``H_i`` of eqs. (4.7)–(4.10) for every measuring agent, as :func:`tdoa_predictions`."""
    full = range_difference_gradients(*_per_agent(point, positions, neighbours, agents))
    rows = [full[i, nbrs] for i, nbrs in enumerate(neighbours)]
    return [np.hstack([r, np.zeros_like(r)]) for r in rows]


def tdoa_readings(
    target: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    r: float,
    rng: np.random.Generator,
) -> list[np.ndarray]:
    """Noisy ``y_i = h_i(p) + v_i``, ``v_i ~ N(0, r I)`` independent per agent (eq. (4.2))."""
    clean = tdoa_predictions(target, positions, neighbours)
    return [h + np.sqrt(r) * rng.standard_normal(h.shape[0]) for h in clean]


def _per_agent(
    point: np.ndarray,
    positions: np.ndarray,
    neighbours: list[np.ndarray],
    agents: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    count = len(neighbours)
    agents = np.arange(count) if agents is None else np.asarray(agents, dtype=int)
    points = np.asarray(point, dtype=float)
    if points.ndim == 1:
        points = np.broadcast_to(points, (count, positions.shape[1]))
    return points[:count], positions, agents


def _offsets(points: np.ndarray, positions: np.ndarray) -> np.ndarray:
    return np.asarray(points, dtype=float)[..., None, :] - np.asarray(positions, dtype=float)


def _own(values: np.ndarray, agents: int | np.ndarray, *, tail: int) -> np.ndarray:
    """The measuring agent's entry of ``values`` (axis ``−1 − tail`` runs over agents), kept as an
    axis of length 1 and broadcast against the leading shape of ``agents``."""
    lead = np.broadcast_shapes(values.shape[: values.ndim - 1 - tail], np.shape(agents))
    full = np.broadcast_to(values, lead + values.shape[values.ndim - 1 - tail :])
    index = np.broadcast_to(np.asarray(agents, dtype=int), lead)
    index = index.reshape(lead + (1,) * (1 + tail))
    return np.take_along_axis(full, index, axis=-1 - tail)


def _index(neighbours: Sequence[int]) -> np.ndarray:
    return np.asarray(list(neighbours), dtype=int)


DYADIC_PERIODS = (Fraction(1, 4), Fraction(1), Fraction(3))
"""Periods at which the floating model must equal the exact one bit for bit."""


@claims.register(
    "seed000.eq4.6",
    source="seed 000 eqs. (4.1), (4.5)–(4.6)",
    statement="A and B of (4.6) are the exact discretization of (4.1) with w held constant over "
    "each period: A = exp(F T), B = ∫₀ᵀ exp(F s) G ds, for every T > 0 (2D and 3D)",
)
def discretization_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """Prove eq. (4.6) in sympy (2D, 3D) and check :func:`cv_discrete` exactly at dyadic ``T``."""
    per_dim = {f"{dim}d": _discretization_evidence(dim) for dim in (2, 3)}
    holds = all(e["A_exact"] and e["B_exact"] and e["library_exact"] for e in per_dim.values())
    message = (
        "exp(F T) = I + F T (F² = 0) and ∫₀ᵀ exp(F s) G ds = [T²/2 I; T I] identically in T, "
        "as printed in (4.6); the library's floating model matches exactly"
        if holds
        else "the printed A or B (or the library's model) differs from the exact discretization"
    )
    return [ClaimResult(status_of(holds), Method.SYMBOLIC, per_dim, message=message)]


def _discretization_evidence(dim: int) -> dict[str, Any]:
    import sympy as sp

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


def _library_matches(exact_A: Any, exact_B: Any, T: Any, period: Fraction, dim: int) -> bool:
    import sympy as sp

    A, B = cv_discrete(float(period), dim)
    value = sp.Rational(period.numerator, period.denominator)
    want_A = np.array(exact_A.subs(T, value).tolist(), dtype=object)
    want_B = np.array(exact_B.subs(T, value).tolist(), dtype=object)
    as_fraction = np.vectorize(lambda x: Fraction(str(x)) if isinstance(x, sp.Basic) else x)
    return bool(
        np.all(np.vectorize(Fraction)(A) == as_fraction(want_A))
        and np.all(np.vectorize(Fraction)(B) == as_fraction(want_B))
    )
