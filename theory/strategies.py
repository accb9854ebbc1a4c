"""Public hypothesis strategies for systems, networks, TDOA scenes and pursuit parameters.

The TDOA scenes, networks and weights live in :mod:`theory.tdoa.strategies` and are re-exported
here, so ``from theory.strategies import tdoa_scenes`` keeps working.

Users import these in their own property tests (STYLE.md, *Adopt* 11)::

    from hypothesis import given
    from theory.strategies import tdoa_scenes

    @given(tdoa_scenes(dim=3, family="cone"))
    def test_cone_scenes_lose_rank(scene): ...

Names are plural nouns, bounds are keyword-only, conditioning is bounded, and impossible
arguments raise :class:`hypothesis.errors.InvalidArgument` with the offending value. The
consensus-filter strategies live in :mod:`theory.consensus.strategies` and are re-exported here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.consensus.strategies import DkfProblem, dkf_problems
from theory.core.case_file import Case, parse_case
from theory.pursuit.case import PursuitSpec
from theory.pursuit.model import closed_loop_rates, path_numeric, rotation_numeric
from theory.strategy_helpers import check_range, generators, orthonormal_matrix
from theory.tdoa.strategies import (
    SCENE_FAMILIES,
    WEIGHT_KINDS,
    TdoaScene,
    is_connected,
    networks,
    tdoa_scenes,
    weight_matrices,
)

__all__ = [
    "SCENE_FAMILIES",
    "WEIGHT_KINDS",
    "DkfProblem",
    "PursuitParameters",
    "TdoaScene",
    "TrackerState",
    "digraph_laplacians",
    "dkf_problems",
    "is_connected",
    "networks",
    "pursuit_cases",
    "pursuit_parameters",
    "state_space_pairs",
    "tdoa_scenes",
    "tracker_states",
    "weight_matrices",
]


@dataclass(frozen=True)
class PursuitParameters:
    """Seed 003 tracking/coordination parameters (ranges of its Tables I–II).

    Attributes
    ----------
    dim : int
        2 or 3.
    radius : tuple of float
        Semi-axes of the path, one per dimension.
    omega_bar : float
        Nominal path-parameter speed ω̄ (rad/s), eqs. (18), (46).
    epsilon : tuple of float
        Offset ε of eq. (19): first entry < 0, last entry 0.
    K_p : tuple of float
        Diagonal of the positive-definite position gain ``K_p``.
    k_gamma : float
        Path-parameter gain k_γ > 0, eq. (50b).
    k_c : float
        Coordination gain k_c > 0, eq. (45).
    """

    dim: int
    radius: tuple[float, ...]
    omega_bar: float
    epsilon: tuple[float, ...]
    K_p: tuple[float, ...]
    k_gamma: float
    k_c: float


@st.composite
def state_space_pairs(
    draw: st.DrawFn,
    *,
    min_states: int = 1,
    max_states: int = 4,
    min_outputs: int = 1,
    max_outputs: int = 2,
    spectral_radius: tuple[float, float] = (0.2, 1.5),
    max_condition: float = 10.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Pairs ``(A, C)`` with real eigenvalues of ``A`` in ``±spectral_radius`` and ``cond(V) ≤
    max_condition`` for its eigenvector matrix ``V`` (so eigenvalue tests are well posed).

    Parameters
    ----------
    min_states, max_states : int
        Bounds on ``n``.
    min_outputs, max_outputs : int
        Bounds on the rows of ``C`` (0 allowed).
    spectral_radius : (float, float)
        Eigenvalue magnitudes are drawn from this interval.
    max_condition : float
        Bound on the condition number of the eigenvector matrix (≥ 1).
    """
    check_range("min_states", min_states, "max_states", max_states, 1)
    check_range("min_outputs", min_outputs, "max_outputs", max_outputs, 0)
    low, high = spectral_radius
    if not 0 <= low <= high:
        raise InvalidArgument(f"spectral_radius={spectral_radius} must satisfy 0 ≤ low ≤ high")
    if max_condition < 1:
        raise InvalidArgument(f"max_condition={max_condition} must be ≥ 1")
    n = draw(st.integers(min_states, max_states))
    m = draw(st.integers(min_outputs, max_outputs))
    rng = draw(generators())
    magnitudes = rng.uniform(low, high, n) * rng.choice([-1.0, 1.0], n)
    singular = np.exp(rng.uniform(0, np.log(max_condition), n))
    V = orthonormal_matrix(rng, n) @ np.diag(singular / singular.max()) @ orthonormal_matrix(rng, n)
    A = V @ np.diag(magnitudes) @ np.linalg.inv(V)
    C = rng.standard_normal((m, n))
    return A, C


@st.composite
def digraph_laplacians(
    draw: st.DrawFn,
    *,
    min_agents: int = 2,
    max_agents: int = 7,
    max_extra_edges: int | None = None,
) -> np.ndarray:
    """Integer Laplacians ``L = D_in − A`` of strongly connected digraphs (seed 003 §II-B).

    The digraph is a random Hamiltonian cycle (so it is strongly connected) plus random edges;
    ``a_ij = 1`` means i receives from j.

    Parameters
    ----------
    min_agents, max_agents : int
        Bounds on the number of nodes ``n`` (``2 ≤ min_agents ≤ max_agents``).
    max_extra_edges : int, optional
        At most this many random edges beyond the cycle (default ``2n``; ``≥ 0``).

    Returns
    -------
    SearchStrategy of ndarray of int, shape (n, n)

    Raises
    ------
    InvalidArgument
        For impossible bounds.
    """
    check_range("min_agents", min_agents, "max_agents", max_agents, 2)
    if max_extra_edges is not None and max_extra_edges < 0:
        raise InvalidArgument(f"max_extra_edges={max_extra_edges} must be ≥ 0")
    n = draw(st.integers(min_agents, max_agents))
    order = draw(st.permutations(range(n)))
    adjacency = np.zeros((n, n), dtype=int)
    for k in range(n):
        adjacency[order[k], order[(k + 1) % n]] = 1
    pairs = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1))
    extra = draw(st.lists(pairs, max_size=2 * n if max_extra_edges is None else max_extra_edges))
    for i, j in extra:
        if i != j:
            adjacency[i, j] = 1
    return np.diag(adjacency.sum(axis=1)) - adjacency


@st.composite
def pursuit_parameters(draw: st.DrawFn, *, dim: int = 2) -> PursuitParameters:
    """Parameters in ``dim`` dimensions in the ranges of seed 003 Tables I (2D) and II (3D),
    widened by about 2×."""
    if dim not in (2, 3):
        raise InvalidArgument(f"dim={dim}; expected 2 or 3")
    positive = st.floats(0.05, 1.0)
    radius = tuple(draw(st.floats(10.0, 100.0)) for _ in range(dim))
    epsilon_head = draw(st.floats(-2.0, -0.1))
    epsilon = (epsilon_head, *(draw(st.floats(-2.0, 0.0)) for _ in range(dim - 2)), 0.0)
    return PursuitParameters(
        dim=dim,
        radius=radius,
        omega_bar=draw(st.floats(0.01, 0.2)),
        epsilon=epsilon,
        K_p=tuple(draw(positive) for _ in range(dim)),
        k_gamma=draw(st.floats(50.0, 1000.0)),
        k_c=draw(st.floats(0.05, 1.0)),
    )


@dataclass(frozen=True, eq=False)
class TrackerState:
    """One tracker's state and the estimation errors it acts on (seed 003 §IV, eqs. (19)–(31)).

    Attributes
    ----------
    e_p : ndarray, shape (dim,)
        Position tracking error e_p in the body frame, eq. (19).
    e_gamma : float
        Path-parameter error e_γ = γ̇ − ω_d (0 for controller Type I).
    rotation : ndarray, shape (dim, dim)
        Attitude R(η).
    gamma : float
        Path parameter γ.
    q_err, v_err : ndarray, shape (dim,)
        Target position and velocity estimation errors q̃, ṽ, eq. (67).
    omega_d, omega_d_dot : float
        Desired path-parameter speed ω_d = ω̄ + v_c and its derivative.
    target, target_v : ndarray, shape (dim,)
        Target position q and velocity v.
    """

    e_p: np.ndarray
    e_gamma: float
    rotation: np.ndarray
    gamma: float
    q_err: np.ndarray
    v_err: np.ndarray
    omega_d: float
    omega_d_dot: float
    target: np.ndarray
    target_v: np.ndarray

    def rates(self, spec: PursuitSpec, *, tracker: int = 0):
        """The closed-loop rates (V̇, ė_p, ė_γ, u) of tracker ``tracker`` of ``spec`` in this
        state, from the kinematics (:func:`theory.pursuit.model.closed_loop_rates`).

        Parameters
        ----------
        spec : PursuitSpec
            The case: gains, offset ε and the tracker's path.
        tracker : int
            0-based tracker whose path is used.
        """
        path = spec.trackers[tracker]
        params = {"r_x": path.r_x, "r_y": path.r_y, "gamma0": path.gamma0}
        params |= {"r_z": path.r_z, "c": path.c} if spec.dim == 3 else {}
        position = (
            self.rotation @ (self.e_p + spec.epsilon)
            + path_numeric(self.gamma, **params)
            + self.target
        )
        return closed_loop_rates(
            position=position,
            rotation=self.rotation,
            gamma=self.gamma,
            gamma_dot=self.omega_d + self.e_gamma,
            target_position=self.target,
            target_velocity=self.target_v,
            estimate_position=self.target + self.q_err,
            estimate_velocity=self.target_v + self.v_err,
            epsilon=spec.epsilon,
            K_p=spec.K_p,
            k_gamma=spec.k_gamma,
            controller=spec.controller,
            omega_d=self.omega_d,
            omega_d_dot=self.omega_d_dot,
            path_params=params,
        )


def _check_interval(name: str, interval: tuple[float, float]) -> None:
    low, high = interval
    if not 0 < low <= high < math.inf:
        raise InvalidArgument(f"{name}={interval} must satisfy 0 < low ≤ high < ∞")


def _vectors(dim: int, bound: float) -> st.SearchStrategy[np.ndarray]:
    return st.lists(st.floats(-bound, bound), min_size=dim, max_size=dim).map(np.array)


@st.composite
def pursuit_cases(
    draw: st.DrawFn,
    *,
    n_trackers: int = 1,
    dims: tuple[int, ...] = (2, 3),
    controllers: tuple[str, ...] = ("I", "II"),
    gains: tuple[float, float] = (0.05, 5.0),
    path_sizes: tuple[float, float] = (0.5, 50.0),
) -> Case:
    """Valid ``kind: pursuit`` cases (parsed) with ``n_trackers`` trackers on a directed ring.

    Symmetric ``K_p`` with eigenvalues in ``gains`` (condition number ≤ high/low) and a random
    eigenbasis; ``k_γ`` and ``k_c`` in ``gains``; ε₁ ≠ 0 (|ε₁| ≥ 0.1, so Δ̄ exists); path
    semi-axes in ``path_sizes`` and, in 3D, |c| ∈ [1.2, 5].

    Parameters
    ----------
    n_trackers : int
        Number of trackers (≥ 1); with more than one, a directed ring and ``k_c``.
    dims : tuple of int
        Dimensions to draw from (2 and/or 3).
    controllers : tuple of str
        Controller types to draw from (``I`` and/or ``II``).
    gains : (float, float)
        Interval of the gains.
    path_sizes : (float, float)
        Interval of the path semi-axes r_x, r_y, r_z.
    """
    if n_trackers < 1:
        raise InvalidArgument(f"n_trackers={n_trackers} must be at least 1")
    if not dims or not set(dims) <= {2, 3}:
        raise InvalidArgument(f"dims={dims}; expected a non-empty subset of (2, 3)")
    if not controllers or not set(controllers) <= {"I", "II"}:
        raise InvalidArgument(f"controllers={controllers}; expected a subset of ('I', 'II')")
    _check_interval("gains", gains)
    _check_interval("path_sizes", path_sizes)
    positive_gains, sizes = st.floats(*gains), st.floats(*path_sizes)
    dim = draw(st.sampled_from(dims))
    eigen = draw(st.lists(positive_gains, min_size=dim, max_size=dim))
    q_rot = rotation_numeric(draw(_vectors(1 if dim == 2 else 3, 3.0)))
    K_p = q_rot @ np.diag(eigen) @ q_rot.T
    eps1 = draw(st.floats(0.1, 3.0)) * draw(st.sampled_from([-1, 1]))
    epsilon = [eps1, *draw(st.lists(st.floats(-3, 3), min_size=dim - 1, max_size=dim - 1))]
    trackers = []
    for _ in range(n_trackers):
        path = {"r_x": draw(sizes), "r_y": draw(sizes)}
        path["gamma0"] = draw(st.floats(-math.pi, math.pi))
        if dim == 3:
            path["r_z"] = draw(sizes)
            path["c"] = draw(st.floats(1.2, 5)) * draw(st.sampled_from([-1, 1]))
        trackers.append(path)
    block = {
        "dim": dim,
        "controller": draw(st.sampled_from(controllers)),
        "omega_bar": draw(st.floats(-1, 1)),
        "epsilon": epsilon,
        "K_p": ((K_p + K_p.T) / 2).tolist(),
        "k_gamma": draw(positive_gains),
        "trackers": trackers,
    }
    if n_trackers > 1:
        block["k_c"] = draw(positive_gains)
        block["edges"] = [[(i + 1) % n_trackers + 1, i + 1] for i in range(n_trackers)]
    return parse_case({"name": "random", "kind": "pursuit", "pursuit": block})


@st.composite
def tracker_states(draw: st.DrawFn, *, spec: PursuitSpec, bound: float = 10.0) -> TrackerState:
    """States of one tracker of ``spec``: errors, attitude, γ, estimation errors, ω_d, target.

    Vectors have entries in ``[−bound, bound]``; e_γ = 0 for controller Type I.

    Parameters
    ----------
    spec : PursuitSpec
        The case (gives the dimension and the controller).
    bound : float
        Bound on the entries of the error, estimation-error and target vectors (> 0).
    """
    if not 0 < bound < math.inf:
        raise InvalidArgument(f"bound={bound} must be positive and finite")
    dim = spec.dim
    reals = st.floats(-bound, bound)
    return TrackerState(
        e_p=draw(_vectors(dim, bound)),
        e_gamma=draw(reals) if spec.controller == "II" else 0.0,
        rotation=rotation_numeric(draw(_vectors(1 if dim == 2 else 3, 3.1))),
        gamma=draw(st.floats(-20, 20)),
        q_err=draw(_vectors(dim, bound)),
        v_err=draw(_vectors(dim, bound)),
        omega_d=draw(st.floats(-2, 2)),
        omega_d_dot=draw(st.floats(-2, 2)),
        target=draw(_vectors(dim, bound)),
        target_v=draw(_vectors(dim, bound)),
    )
