"""Observability and detectability of the networked pair ``(W ⊗ A, D_H)`` (seed 000 §4.2.2).

The distributed TDOA filter of seed 000 eqs. (4.26)–(4.31) has the network-wide error dynamics
``x̃(k+1) = (W ⊗ A)(I − K D_H) x̃(k) + η(k)`` with ``D_H = blkdiag(H_1, …, H_N)`` (eq. 4.21). Its
observability matrix is eq. (4.36),

.. math:: O = [D_H;\\ D_H (W ⊗ A);\\ …;\\ D_H (W ⊗ A)^{nN-1}] = [O_1\\ …\\ O_N],

where the block column of agent ``i`` stacks ``[W^l]_{mi} H_m A^l`` over powers ``l`` and agents
``m`` (eq. 4.37). The paper asserts ``rank O = Σ_i rank O_i``; this module computes both and
reports whether they agree (they do not when ``W`` is singular or has eigenvectors supported on
agents that cannot localize the target: ``docs/errata.md``).

What is true (proved in ``docs/theory/tdoa-observability.md``): the modes of ``W ⊗ A`` are the
eigenvalues of ``W`` (``A`` is unipotent). A mode is unobservable iff some eigenvector ``z ⊗ x``
of it is annihilated by every ``H_m`` with ``z_m ≠ 0``. For a row-stochastic ``W`` with positive
diagonal, the only modes on the unit circle are at 1 and they are observable iff each closed
communication class's stacked Jacobian has full column rank in position; all other modes are
stable. Hence the pair is *detectable* under exactly the geometric condition of Thm 4.2.3, but it
is *observable* only if moreover ``W`` is non-singular and no other eigenvector of ``W`` hides a
direction, which fails e.g. for uniform weights on a complete graph. Detectability is what a
(centralised-gain) estimator of eq. (4.25) needs; observability is not.

:func:`network_generic_rank` decides the generic ranks of ``O`` and the ``O_i`` exactly at a random
integer point (python-flint), with the Schwartz–Zippel bound of the chance that a rank found is
below the generic one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from fractions import Fraction
from math import lcm

import numpy as np

from theory.core.observability import RANK_TOL, numeric_rank, observability_matrix
from theory.core.tolerances import (
    INCONCLUSIVE_FACTOR,
    MODE_ZERO_TOL,
    SNAP_RTOL,
    UNIT_CIRCLE_FACTOR,
    UNIT_CIRCLE_TOL,
)
from theory.tdoa.observability.single_agent import exact_rank

__all__ = [
    "NetworkGenericRank",
    "NetworkObservability",
    "Parametrization",
    "agent_observability_blocks",
    "analyze_network",
    "exact_network_matrix",
    "network_generic_rank",
    "network_observability_matrix",
    "networked_pair",
    "unobservable_subspace",
]


class Parametrization(StrEnum):
    """How :func:`network_generic_rank` draws the TDOA rows."""

    GEOMETRY = "geometry"  # unit vectors u_i on the sphere (inverse stereographic), rows u_r − u_s
    EDGES = "edges"  # App. B.1: a shared λ per undirected edge, +λ for the lower-numbered agent


@dataclass(frozen=True)
class NetworkObservability:
    """Verdicts on the networked pair ``(W ⊗ A, D_H)`` with the evidence that decided them.

    ``network_rank`` is ``rank O`` of eq. (4.36) (``n_states = nN`` minus the unobservable
    dimension); ``detectable``: every unobservable mode has ``|μ| < 1 − unit_circle_tol``; the
    ``unobservable_eigenvalues`` (with multiplicity) are snapped to the nearest ``λ(W)·λ(A)``;
    ``agent_ranks`` are the ``rank O_i`` and ``rank_sum_claim_holds`` says whether
    ``Σ rank O_i = rank O``. ``margin`` is the least factor by which a rank decision cleared
    ``rank_tol · σ_max``, ``unit_circle_margin`` the least ``max(d/tol, tol/d)`` over the modes'
    ``d = ||μ| − 1|``; ``conclusive`` when they reach ``inconclusive_factor`` and
    ``unit_circle_factor``. ``rank_method`` says which computation of ``rank O`` decided
    (``staircase`` or ``svd``, or a note of their disagreement, then inconclusive)."""

    network_rank: int
    n_states: int
    observable: bool
    detectable: bool
    unobservable_eigenvalues: list[complex]
    agent_ranks: list[int]
    rank_sum: int
    rank_sum_claim_holds: bool
    rank_tol: float
    margin: float
    unit_circle_tol: float
    unit_circle_margin: float
    conclusive: bool
    rank_method: str = "staircase"


def networked_pair(
    A: np.ndarray, W: np.ndarray, H_blocks: Sequence[np.ndarray]
) -> tuple[np.ndarray, np.ndarray]:
    """``(W ⊗ A, D_H)`` with ``D_H = blkdiag(H_1, …, H_N)`` (``m_i = 0`` rows allowed;
    ``ValueError`` for shapes that do not match). Seed 000 eqs. (4.21), (4.24)."""
    A, W, blocks = _checked(A, W, H_blocks)
    n, N = A.shape[0], W.shape[0]
    D_H = np.zeros((sum(b.shape[0] for b in blocks), n * N))
    row = 0
    for i, block in enumerate(blocks):
        D_H[row : row + block.shape[0], i * n : (i + 1) * n] = block
        row += block.shape[0]
    return np.kron(W, A), D_H


def agent_observability_blocks(
    A: np.ndarray, W: np.ndarray, H_blocks: Sequence[np.ndarray], *, steps: int | None = None
) -> list[np.ndarray]:
    """Block columns ``O_i`` of ``O`` (seed 000 eqs. (4.36)–(4.37)): ``[W^l]_{mi} H_m A^l`` for
    ``l < steps`` (outer, default ``nN``) and agents ``m`` (inner), so ``O = [O_1 … O_N]``."""
    A, W, blocks = _checked(A, W, H_blocks)
    n, N = A.shape[0], W.shape[0]
    steps = n * N if steps is None else steps
    H = np.vstack(blocks)
    owner = np.concatenate([np.full(b.shape[0], m) for m, b in enumerate(blocks)]).astype(int)
    columns: list[list[np.ndarray]] = [[] for _ in range(N)]
    W_power, A_power = np.eye(N), np.eye(n)
    for _ in range(steps):
        HA = H @ A_power
        for i in range(N):
            columns[i].append(W_power[owner, i][:, None] * HA)
        W_power, A_power = W_power @ W, A_power @ A
    return [np.vstack(parts) if parts else np.zeros((0, n)) for parts in columns]


def network_observability_matrix(
    A: np.ndarray, W: np.ndarray, H_blocks: Sequence[np.ndarray]
) -> np.ndarray:
    """The whole ``O = [O_1 … O_N]`` of seed 000 eq. (4.36), shape ``(nN·Σ m, nN)``."""
    return np.hstack(agent_observability_blocks(A, W, H_blocks))


def unobservable_subspace(
    F: np.ndarray, C: np.ndarray, *, rank_tol: float = RANK_TOL
) -> tuple[np.ndarray, float]:
    """Orthonormal basis of ``∩_k ker(C F^k)`` by an orthogonal staircase, and the least factor by
    which a singular value cleared its threshold.

    From ``U_0 = ker C`` each step keeps ``U_{k+1} = {x ∈ U_k : F x ∈ U_k}`` until the dimension
    stops falling; every kernel is read from an SVD against ``rank_tol · ‖M‖₂``. The Krylov matrix
    ``[C; CF; …]`` is never formed, so no power of ``F`` spoils the conditioning."""
    n = F.shape[0]
    scale_F = max(float(np.linalg.norm(F, 2)), 1.0) if n else 1.0
    basis, margin = _null_space(C.reshape(-1, n), rank_tol, scale=None)
    while basis.shape[1]:
        leak = F @ basis - basis @ (basis.T @ (F @ basis))
        keep, step_margin = _null_space(leak, rank_tol, scale=scale_F)
        margin = min(margin, step_margin)
        if keep.shape[1] == basis.shape[1]:
            break
        basis = basis @ keep
        basis, _ = np.linalg.qr(basis)
    return basis, margin


def analyze_network(
    A: np.ndarray,
    W: np.ndarray,
    H_blocks: Sequence[np.ndarray],
    *,
    rank_tol: float = RANK_TOL,
    unit_circle_tol: float = UNIT_CIRCLE_TOL,
    inconclusive_factor: float = INCONCLUSIVE_FACTOR,
    unit_circle_factor: float = UNIT_CIRCLE_FACTOR,
) -> NetworkObservability:
    """Observability, detectability and the paper's rank-sum claim for ``(W ⊗ A, D_H)``.

    ``rank_tol`` decides every rank (threshold ``rank_tol · σ_max``); a mode with
    ``||μ| − 1| ≤ unit_circle_tol`` counts as on the unit circle; decisions within
    ``inconclusive_factor`` (ranks) or ``unit_circle_factor`` (modes, either side) of their
    thresholds make the result inconclusive. Seed 000 §4.2.2, eqs. (4.24), (4.31), (4.36)."""
    A, W, blocks = _checked(A, W, H_blocks)
    WA, D_H = networked_pair(A, W, blocks)
    basis, margin, method = _unobservable_basis(WA, D_H, rank_tol)
    n_states = WA.shape[0]
    network_rank = n_states - basis.shape[1]
    eigenvalues = _snap(np.linalg.eigvals(basis.T @ WA @ basis), _mode_candidates(A, W))
    agent = [
        numeric_rank(block, rank_tol=rank_tol) for block in agent_observability_blocks(A, W, blocks)
    ]
    agent_ranks = [r.rank for r in agent]
    margin = min([margin, *(r.margin for r in agent)])
    unit_margin = _unit_circle_margin(eigenvalues, unit_circle_tol)
    return NetworkObservability(
        network_rank=network_rank,
        n_states=n_states,
        observable=network_rank == n_states,
        detectable=all(abs(z) < 1.0 - unit_circle_tol for z in eigenvalues),
        unobservable_eigenvalues=eigenvalues,
        agent_ranks=agent_ranks,
        rank_sum=sum(agent_ranks),
        rank_sum_claim_holds=sum(agent_ranks) == network_rank,
        rank_tol=rank_tol,
        margin=float(margin),
        unit_circle_tol=unit_circle_tol,
        unit_circle_margin=float(unit_margin),
        conclusive=bool(margin >= inconclusive_factor and unit_margin >= unit_circle_factor),
        rank_method=method,
    )


def _unit_circle_margin(eigenvalues: list[complex], unit_circle_tol: float) -> float:
    """Least factor by which an unobservable mode's ``||λ| − 1|`` clears ``unit_circle_tol``."""
    distances = [abs(abs(z) - 1.0) for z in eigenvalues]
    return min(
        (max(d / unit_circle_tol, unit_circle_tol / d) if d > 0 else np.inf for d in distances),
        default=np.inf,
    )


def _unobservable_basis(
    WA: np.ndarray, D_H: np.ndarray, rank_tol: float
) -> tuple[np.ndarray, float, str]:
    """Kernel of ``O`` two ways: the staircase and the SVD of the whole ``O`` (eq. 4.36).

    ``A`` has all eigenvalues 1 and ``W`` none outside the unit disc, so the rows of ``O`` grow
    at most linearly and its SVD is usually well conditioned; the staircase never forms ``O``.
    When both find the same rank, the one with the larger margin supplies the basis and the
    margin; when they disagree the verdict is inconclusive (margin 0).
    """
    staircase, staircase_margin = unobservable_subspace(WA, D_H, rank_tol=rank_tol)
    whole, whole_margin = _null_space(observability_matrix(WA, D_H), rank_tol, scale=None)
    if staircase.shape[1] != whole.shape[1]:
        return staircase, 0.0, "disagreement: staircase vs SVD of O"
    if whole_margin > staircase_margin:
        return whole, whole_margin, "svd"
    return staircase, staircase_margin, "staircase"


def _checked(
    A: np.ndarray, W: np.ndarray, H_blocks: Sequence[np.ndarray]
) -> tuple[np.ndarray, np.ndarray, list[np.ndarray]]:
    A, W = np.asarray(A, dtype=float), np.asarray(W, dtype=float)
    n = A.shape[0]
    if A.shape != (n, n) or W.ndim != 2 or W.shape[0] != W.shape[1]:
        raise ValueError(f"A and W must be square; got shapes {A.shape} and {W.shape}")
    if len(H_blocks) != W.shape[0]:
        raise ValueError(f"need one Jacobian per agent ({W.shape[0]}); got {len(H_blocks)}")
    blocks = [np.asarray(h, dtype=float).reshape(-1, n) for h in H_blocks]
    return A, W, blocks


def _null_space(
    matrix: np.ndarray, rank_tol: float, *, scale: float | None
) -> tuple[np.ndarray, float]:
    cols = matrix.shape[1]
    if matrix.shape[0] == 0:
        return np.eye(cols), np.inf
    # Tall matrices: the thin SVD already carries every right singular vector (and the full U of
    # a tall O would cost O(rows²)); wide ones need the full V for their kernel.
    _, sv, vh = np.linalg.svd(matrix, full_matrices=matrix.shape[0] < cols)
    top = float(sv[0]) if sv.size else 0.0
    reference = max(top, scale) if scale is not None else top
    threshold = rank_tol * reference if reference > 0 else rank_tol
    rank = int(np.sum(sv > threshold))
    above = sv[rank - 1] / threshold if rank > 0 else np.inf
    below = threshold / sv[rank] if rank < sv.size and sv[rank] > 0 else np.inf
    return vh[rank:].T.copy(), float(min(above, below))


def _mode_candidates(
    A: np.ndarray, W: np.ndarray, *, zero_tol: float = MODE_ZERO_TOL
) -> np.ndarray:
    products = np.outer(np.linalg.eigvals(W), np.linalg.eigvals(A)).ravel()
    scale = max(1.0, float(np.abs(W).max(initial=0.0)) * float(np.abs(A).max(initial=0.0)))
    return np.where(np.abs(products) <= zero_tol * scale, 0.0, products)


def _snap(values: np.ndarray, candidates: np.ndarray, *, rel: float = SNAP_RTOL) -> list[complex]:
    """Replace each computed eigenvalue by the nearest exact-structure candidate if close.

    Eigenvalues of a restriction with Jordan blocks are perturbed by ~ε^{1/k}; the candidates
    ``λ(W)·λ(A)`` are computed from the (well-conditioned) factors separately.
    """
    out = []
    for value in values:
        nearest = candidates[np.argmin(np.abs(candidates - value))] if candidates.size else value
        close = abs(nearest - value) <= rel * max(1.0, abs(value))
        out.append(complex(nearest if close else value))
    return sorted(out, key=lambda z: (abs(z), z.real, z.imag))


@dataclass(frozen=True)
class NetworkGenericRank:
    """Exact ranks of the networked ``O`` and its block columns at one random point.

    ``network_rank`` (a lower bound on the generic rank), ``agent_ranks``, their sum and whether it
    equals ``network_rank``; the ``parametrization``, the period ``T`` (``None``: drawn as a free
    parameter), the ``field`` and ``seed``; free parameters uniform on ``[0, sample_size)``. Any
    minor of ``O`` has degree at most ``degree_bound = c · nN`` (``c``: geometry 4, edges 1; +1 with
    random ``T``), so ``error_bound = degree_bound / sample_size`` bounds the chance that a rank
    found here is below the generic rank; ranks found full are certain."""

    network_rank: int
    agent_ranks: list[int]
    rank_sum: int
    rank_sum_claim_holds: bool
    n_states: int
    parametrization: Parametrization
    T: Fraction | None
    field: str
    seed: int
    sample_size: int
    degree_bound: int
    error_bound: float


def network_generic_rank(
    adjacency: np.ndarray,
    W: Sequence[Sequence[Fraction | int]],
    *,
    dim: int = 3,
    parametrization: Parametrization = Parametrization.GEOMETRY,
    T: Fraction | None = None,
    seed: int = 0,
    field: str = "rationals",
    sample_bits: int = 40,
) -> NetworkGenericRank:
    """Generic ranks of ``O`` and the ``O_i`` for the fixed exact ``W`` (and ``T`` if given),
    exactly at a random point of the ``parametrization``.

    The matrix of eq. (4.36) is built over the integers (each block row scaled by a common
    denominator, which leaves ranks unchanged) and ranked with python-flint over ℚ or modulo
    :data:`~theory.tdoa.observability.single_agent.MERSENNE_PRIME`; free parameters are drawn from
    ``[0, 2**sample_bits)``. Seed 000 eqs. (4.36)–(4.37), App. B.1; Schwartz (1980), Zippel
    (1979)."""
    n_agents = adjacency.shape[0]
    if len(W) != n_agents:
        raise ValueError(f"W has {len(W)} rows for {n_agents} agents")
    parametrization = Parametrization(parametrization)
    rng = np.random.default_rng(seed)
    sample = 2**sample_bits
    rows = _random_rows(adjacency, dim, parametrization, rng, sample)
    period = Fraction(T) if T is not None else Fraction(1 + int(rng.integers(0, sample - 1)))
    O = exact_network_matrix(rows, [[Fraction(x) for x in r] for r in W], dim, period)
    n = 2 * dim
    network_rank = exact_rank(O, field=field)
    agent_ranks = [
        exact_rank([row[i * n : (i + 1) * n] for row in O], field=field) for i in range(n_agents)
    ]
    free_period = 1 if T is None else 0
    entry_degree = (4 if parametrization is Parametrization.GEOMETRY else 1) + free_period
    return _generic_record(
        network_rank, agent_ranks, n, parametrization, T, field, seed, sample, entry_degree
    )


def _generic_record(
    network_rank: int,
    agent_ranks: list[int],
    n: int,
    parametrization: Parametrization,
    T: Fraction | None,
    field: str,
    seed: int,
    sample: int,
    entry_degree: int,
) -> NetworkGenericRank:
    """The record of :func:`network_generic_rank`, with its Schwartz–Zippel bound
    ``degree / sample`` (``degree = entry_degree · n · N``: the order of a full minor)."""
    degree = entry_degree * n * len(agent_ranks)
    return NetworkGenericRank(
        network_rank=network_rank,
        agent_ranks=agent_ranks,
        rank_sum=sum(agent_ranks),
        rank_sum_claim_holds=sum(agent_ranks) == network_rank,
        n_states=n * len(agent_ranks),
        parametrization=parametrization,
        T=Fraction(T) if T is not None else None,
        field=field,
        seed=seed,
        sample_size=sample,
        degree_bound=degree,
        error_bound=degree / sample,
    )


def _random_rows(
    adjacency: np.ndarray,
    dim: int,
    parametrization: Parametrization,
    rng: np.random.Generator,
    sample: int,
) -> list[list[list[int]]]:
    """Integer TDOA rows per agent (each row scaled by a positive constant)."""
    n_agents = adjacency.shape[0]

    def draw() -> int:
        return int(rng.integers(0, sample))

    if parametrization is Parametrization.GEOMETRY:
        points = []
        for _ in range(n_agents):
            params = [draw() for _ in range(dim - 1)]
            square = sum(t * t for t in params)
            points.append(([2 * t for t in params] + [square - 1], square + 1))
        return [
            [
                [
                    points[s][1] * a - points[r][1] * b
                    for a, b in zip(points[r][0], points[s][0], strict=True)
                ]
                for s in np.flatnonzero(adjacency[r])
            ]
            for r in range(n_agents)
        ]
    lam: dict[tuple[int, int], list[int]] = {}
    rows = []
    for r in range(n_agents):
        agent_rows = []
        for s in np.flatnonzero(adjacency[r]):
            key = (min(r, int(s)), max(r, int(s)))
            vector = lam.setdefault(key, [draw() for _ in range(dim)])
            agent_rows.append(vector if r < s else [-x for x in vector])
        rows.append(agent_rows)
    return rows


def exact_network_matrix(
    rows: list[list[list[int]]], W: list[list[Fraction]], dim: int, T: Fraction
) -> list[list[int]]:
    """Eq. (4.36) over the integers: the rows of agent ``m`` (integer position parts) through
    ``W^l`` and ``A^l``, each block row scaled by its denominators' lcm, so every rank (of ``O`` and
    of each block column) is that of ``O``; row order of :func:`agent_observability_blocks`."""
    N, n = len(W), 2 * dim
    out: list[list[int]] = []
    power = [[Fraction(int(i == j)) for j in range(N)] for i in range(N)]
    for step in range(n * N):
        shift = step * T
        block = []
        for m, agent_rows in enumerate(rows):
            for row in agent_rows:
                line = []
                for i in range(N):
                    w = power[m][i]
                    line += [w * x for x in row] + [w * shift * x for x in row]
                block.append(line)
        scale = lcm(*(x.denominator for line in block for x in line)) if block else 1
        out += [[int(x * scale) for x in line] for line in block]
        power = [[sum(power[i][k] * W[k][j] for k in range(N)) for j in range(N)] for i in range(N)]
    return out
