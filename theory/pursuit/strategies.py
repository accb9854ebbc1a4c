"""Hypothesis strategies for seed 003 pursuit: parameters, digraphs, cases, tracker states.

Re-exported by the public :mod:`theory.strategies`. Names are plural nouns, bounds are
keyword-only, conditioning is bounded, and impossible arguments raise
:class:`hypothesis.errors.InvalidArgument` with the offending value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import pairwise

import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.core.case_file import Case
from theory.pursuit.case import PURSUIT, PursuitSpec
from theory.pursuit.model import ClosedLoopRates, closed_loop_rates, exp_skew
from theory.pursuit.model import path as path_point
from theory.strategy_helpers import case_floats, check_range, flush_tiny

__all__ = [
    "SIMULATED_BOUNDS",
    "PursuitParameters",
    "TrackerState",
    "digraph_laplacians",
    "pursuit_cases",
    "pursuit_parameters",
    "simulated_pursuit_blocks",
    "simulated_pursuit_cases",
    "tracker_states",
]


@dataclass(frozen=True)
class PursuitParameters:
    """Seed 003 tracking/coordination parameters (ranges of its Tables I–II).

    ``radius``: path semi-axes, one per dimension; ``epsilon``: ε of (19), first entry < 0, last
    0; ``K_p``: the diagonal of the position gain; ω̄ (18), k_γ (50b), k_c (45).
    """

    dim: int
    radius: tuple[float, ...]
    omega_bar: float
    epsilon: tuple[float, ...]
    K_p: tuple[float, ...]
    k_gamma: float
    k_c: float


@st.composite
def pursuit_parameters(draw: st.DrawFn, *, dim: int = 2) -> PursuitParameters:
    """Parameters in ``dim`` dimensions in the ranges of seed 003 Tables I (2D) and II (3D),
    widened by about 2×."""
    if dim not in (2, 3):
        raise InvalidArgument(f"dim={dim}; expected 2 or 3")
    positive = case_floats(0.05, 1.0)
    radius = tuple(draw(case_floats(10.0, 100.0)) for _ in range(dim))
    epsilon_head = draw(case_floats(-2.0, -0.1))
    epsilon = (epsilon_head, *(draw(case_floats(-2.0, 0.0)) for _ in range(dim - 2)), 0.0)
    return PursuitParameters(
        dim=dim,
        radius=radius,
        omega_bar=draw(case_floats(0.01, 0.2)),
        epsilon=epsilon,
        K_p=tuple(draw(positive) for _ in range(dim)),
        k_gamma=draw(case_floats(50.0, 1000.0)),
        k_c=draw(case_floats(0.05, 1.0)),
    )


@st.composite
def digraph_laplacians(
    draw: st.DrawFn,
    *,
    min_agents: int = 2,
    max_agents: int = 7,
    max_extra_edges: int | None = None,
    weighted: bool = False,
) -> np.ndarray:
    """Laplacians ``L = D_in − A`` of strongly connected digraphs (seed 003 §II-B); every
    strongly connected digraph of ``min_agents`` to ``max_agents`` vertices can be drawn.

    A digraph is strongly connected iff it has an ear decomposition, so it is grown by ears: a
    cycle, then directed paths from a placed vertex through new ones back to a placed one until
    every vertex is placed, then at most ``max_extra_edges`` random edges (default 2n).
    ``a_ij > 0`` means i receives from j: ``a_ij = 1`` (seed 003 §II-B; an integer ``L``), or
    with ``weighted`` a decimal ``k·10^e`` (``k`` = 1…99 per edge, ``e`` = −2…0 per digraph) as
    a case file writes it (the weighted digraphs of Lemma 1's reference [28]; a float ``L``).
    """
    check_range("min_agents", min_agents, "max_agents", max_agents, 2)
    if max_extra_edges is not None and max_extra_edges < 0:
        raise InvalidArgument(f"max_extra_edges={max_extra_edges} must be ≥ 0")
    n = draw(st.integers(min_agents, max_agents))
    order = draw(st.permutations(range(n)))
    adjacency = np.zeros((n, n), dtype=int)
    cycle = draw(st.integers(2, n))
    _add_path(adjacency, [*order[:cycle], order[0]])
    placed = cycle
    while placed < n:
        length = draw(st.integers(1, n - placed))
        ends = st.sampled_from(order[:placed])
        _add_path(adjacency, [draw(ends), *order[placed : placed + length], draw(ends)])
        placed += length
    pairs = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1))
    extra = draw(st.lists(pairs, max_size=2 * n if max_extra_edges is None else max_extra_edges))
    for i, j in extra:
        if i != j:
            adjacency[i, j] = 1
    if weighted:
        exponent = draw(st.integers(-2, 0))  # one scale per digraph: a(L) scales with it
        decimals = st.integers(1, 99).map(lambda k: float(f"{k}e{exponent}"))
        adjacency = np.array([[draw(decimals) if a else 0.0 for a in row] for row in adjacency])
    return np.diag(adjacency.sum(axis=1)) - adjacency


def _add_path(adjacency: np.ndarray, vertices: list[int]) -> None:
    """Edges ``v_k → v_{k+1}`` along ``vertices`` (``a_{v_{k+1} v_k} = 1``)."""
    for sender, receiver in pairwise(vertices):
        adjacency[receiver, sender] = 1


@dataclass(frozen=True, eq=False)
class TrackerState:
    """One tracker's state and the estimation errors it acts on (seed 003 §IV, eqs. (19)–(31)).

    e_p (19) in the body frame, e_γ = γ̇ − ω_d (0 for Type I), attitude R, path parameter γ,
    estimation errors q̃, ṽ (67), ω_d = ω̄ + v_c and its derivative, the target's q and v.
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

    def rates(self, spec: PursuitSpec, *, tracker: int = 0) -> ClosedLoopRates:
        """The closed-loop rates of tracker ``tracker`` (0-based) of ``spec`` in this state, from
        the kinematics (:func:`theory.pursuit.model.closed_loop_rates`)."""
        path = spec.trackers[tracker]
        params = {"r_x": path.r_x, "r_y": path.r_y, "gamma0": path.gamma0}
        params |= {"r_z": path.r_z, "c": path.c} if spec.dim == 3 else {}
        position = (
            self.rotation @ (self.e_p + spec.epsilon)
            + path_point(self.gamma, **params)
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
    return st.lists(case_floats(-bound, bound), min_size=dim, max_size=dim).map(np.array)


def _check_choices(dims: tuple[int, ...], controllers: tuple[str, ...]) -> None:
    if not dims or not set(dims) <= {2, 3}:
        raise InvalidArgument(f"dims={dims}; expected a non-empty subset of (2, 3)")
    if not controllers or not set(controllers) <= {"I", "II"}:
        raise InvalidArgument(f"controllers={controllers}; expected a subset of ('I', 'II')")


def _pursuit_block(draw: st.DrawFn, n: int, dim: int, controller: str, bounds: dict) -> dict:
    """A ``pursuit:`` block's gains, ε, ω̄ and paths (no graph, target or DEKF)."""
    positive_gains, sizes = case_floats(*bounds["gains"]), case_floats(*bounds["path_sizes"])
    eigen = draw(st.lists(positive_gains, min_size=dim, max_size=dim))
    q_rot = exp_skew(draw(_vectors(1 if dim == 2 else 3, 3.0)))
    K_p = q_rot @ np.diag(eigen) @ q_rot.T
    eps1 = draw(case_floats(*bounds["epsilon_1"])) * draw(st.sampled_from([-1, 1]))
    epsilon = [eps1, *draw(st.lists(case_floats(-3, 3), min_size=dim - 1, max_size=dim - 1))]
    trackers = []
    for _ in range(n):
        path = {"r_x": draw(sizes), "r_y": draw(sizes)}
        path["gamma0"] = draw(case_floats(-math.pi, math.pi))
        if dim == 3:
            path["r_z"] = draw(sizes)
            path["c"] = draw(case_floats(1.2, 5)) * draw(st.sampled_from([-1, 1]))
        trackers.append(path)
    block = {
        "dim": dim,
        "controller": controller,
        "omega_bar": draw(case_floats(*bounds["omega_bar"])),
        "epsilon": epsilon,
        "K_p": flush_tiny((K_p + K_p.T) / 2).tolist(),
        "k_gamma": draw(case_floats(*bounds.get("k_gamma", bounds["gains"]))),
        "trackers": trackers,
    }
    if n > 1:
        block["k_c"] = draw(positive_gains)
    return block


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
    """
    if n_trackers < 1:
        raise InvalidArgument(f"n_trackers={n_trackers} must be at least 1")
    _check_choices(dims, controllers)
    _check_interval("gains", gains)
    _check_interval("path_sizes", path_sizes)
    bounds = {"gains": gains, "path_sizes": path_sizes, "epsilon_1": (0.1, 3.0)}
    bounds["omega_bar"] = (-1.0, 1.0)
    dim, controller = draw(st.sampled_from(dims)), draw(st.sampled_from(controllers))
    block = _pursuit_block(draw, n_trackers, dim, controller, bounds)
    if n_trackers > 1:
        block["edges"] = [[(i + 1) % n_trackers + 1, i + 1] for i in range(n_trackers)]
    return PURSUIT.parse_case({"name": "random", "kind": "pursuit", "pursuit": block})


SIMULATED_BOUNDS = {
    "gains": (0.1, 1.0),
    "k_gamma": (1.0, 500.0),
    "path_sizes": (5.0, 40.0),
    "epsilon_1": (0.3, 2.0),
    "omega_bar": (-0.2, 0.2),
}
"""Ranges of :func:`simulated_pursuit_cases`: Tables I–II widened (k_γ down to 1, where the
path-parameter loop is weakly damped), kept where a short run integrates in well under a second."""


def _target_and_filter(draw: st.DrawFn, dim: int) -> dict:
    """``target`` and ``dekf`` blocks: drift, a slow sinusoid, ranges every 1 or 2 s."""
    speeds = st.lists(case_floats(-0.5, 0.5), min_size=dim, max_size=dim)
    target = {
        "velocity": draw(speeds),
        "amplitude": draw(st.lists(case_floats(0, 20), min_size=dim, max_size=dim)),
        "frequency": draw(st.lists(case_floats(0, 0.02), min_size=dim, max_size=dim)),
        "phase": draw(st.lists(case_floats(-math.pi, math.pi), min_size=dim, max_size=dim)),
    }
    sigma = draw(case_floats(0.1, 1.0))
    q = [1e-3] * dim + [1e-4] * dim
    dekf = {"Ts": draw(st.sampled_from([1, 2])), "sigma": sigma, "V": 1 / sigma**2}
    dekf["Q"] = np.diag(q).tolist()
    return {"target": target, "dekf": dekf}


def simulated_pursuit_cases(
    *,
    max_trackers: int = 3,
    dims: tuple[int, ...] = (2, 3),
    controllers: tuple[str, ...] = ("I", "II"),
) -> st.SearchStrategy[Case]:
    """:func:`simulated_pursuit_blocks`, parsed into cases."""
    blocks = simulated_pursuit_blocks(max_trackers=max_trackers, dims=dims, controllers=controllers)
    return blocks.map(
        lambda block: PURSUIT.parse_case(
            {"name": "random-simulated", "kind": "pursuit", "pursuit": block}
        )
    )


@st.composite
def simulated_pursuit_blocks(
    draw: st.DrawFn,
    *,
    max_trackers: int = 3,
    dims: tuple[int, ...] = (2, 3),
    controllers: tuple[str, ...] = ("I", "II"),
) -> dict:
    """``pursuit:`` blocks (plain data) of simulatable cases every ISS condition holds for
    (seed 003 §V–VI).

    1 to ``max_trackers`` trackers on a random strongly connected digraph
    (:func:`digraph_laplacians`), gains, ε, ω̄ and paths in :data:`SIMULATED_BOUNDS`, a target
    drifting at up to 0.5 m/s with a slow sinusoid, DEKF settings (uniform fusion weights), and
    initial tracker positions within 30 m of the target, random attitudes and path parameters.
    """
    if max_trackers < 1:
        raise InvalidArgument(f"max_trackers={max_trackers} must be at least 1")
    _check_choices(dims, controllers)
    n = draw(st.integers(1, max_trackers))
    dim, controller = draw(st.sampled_from(dims)), draw(st.sampled_from(controllers))
    block = _pursuit_block(draw, n, dim, controller, SIMULATED_BOUNDS)
    if n > 1:
        laplacian = draw(digraph_laplacians(min_agents=n, max_agents=n, max_extra_edges=n))
        receives = np.argwhere(laplacian < 0)
        block["edges"] = [[int(j) + 1, int(i) + 1] for i, j in receives]
    block |= _target_and_filter(draw, dim)
    target = block["target"]
    start = np.array(target["amplitude"]) * np.sin(target["phase"])  # q(0), eq. of TargetMotion
    for tracker in block["trackers"]:
        offset = draw(_vectors(dim, 30.0))
        tracker["initial"] = {
            "position": (start + offset).tolist(),
            "euler": draw(_vectors(1 if dim == 2 else 3, 1.5)).tolist(),
            "gamma": draw(case_floats(-math.pi, math.pi)),
        }
    return block


@st.composite
def tracker_states(draw: st.DrawFn, *, spec: PursuitSpec, bound: float = 10.0) -> TrackerState:
    """States of one tracker of ``spec``: errors, attitude, γ, estimation errors, ω_d, target.

    Vectors have entries in ``[−bound, bound]``; e_γ = 0 for controller Type I.
    """
    if not 0 < bound < math.inf:
        raise InvalidArgument(f"bound={bound} must be positive and finite")
    dim = spec.dim
    reals = case_floats(-bound, bound)
    return TrackerState(
        e_p=draw(_vectors(dim, bound)),
        e_gamma=draw(reals) if spec.controller == "II" else 0.0,
        rotation=exp_skew(draw(_vectors(1 if dim == 2 else 3, 3.1))),
        gamma=draw(case_floats(-20, 20)),
        q_err=draw(_vectors(dim, bound)),
        v_err=draw(_vectors(dim, bound)),
        omega_d=draw(case_floats(-2, 2)),
        omega_d_dot=draw(case_floats(-2, 2)),
        target=draw(_vectors(dim, bound)),
        target_v=draw(_vectors(dim, bound)),
    )
