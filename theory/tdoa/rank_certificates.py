"""``generic-rank`` certificates for the TDOA network observability matrix (seed 000 §4.2).

For a TDOA scene the observability matrix of the networked pair ``(W ⊗ A, D_H)`` is

.. math:: O = [D_H;\\ D_H (W ⊗ A);\\ …;\\ D_H (W^p ⊗ A^p)], \\quad p = 2dN − 1

(seed 000 eq. (4.36)) where the rows of agent ``i``'s block ``H_i`` are ``[u_i − u_j, 0]`` for its
neighbours ``j`` (eqs. (4.7)–(4.10)) and ``u_i`` is the unit vector from agent ``i`` to the
target. Every minor of ``O`` is a polynomial in the directions ``u``; one that is non-zero at a
rational point ``u* ∈ (S^{d−1})^N`` does not vanish identically, so it is non-zero for all ``u``
outside a closed set of measure zero: the *generic* rank is at least its order. The point is
drawn at random (seeded) so that, with probability one, the certified bound is the generic rank.
Certified: the whole ``O`` (``agent = 0``) and each agent's block column ``O_i`` (eq. (4.37)).

The weights are taken exactly: Metropolis and uniform weights are rational by definition
(DESIGN.md); an explicit matrix is read as the decimals it was written with.

The certified quantity depends on the network (who hears whom, ``W``) and ``T`` only, not on
where the agents are: a time-varying scene (seed 000 Cor. 4.2.4) gets one set of certificates per
distinct network along its trajectory, each naming the steps it covers
(:func:`network_steps`).
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import flint
import numpy as np
import scipy.linalg

from theory.core.exact import (
    RationalizationError,
    exact_decimal,
    first_success,
    fraction_strings,
    rational_unit_vector,
    stochastic_matrix,
)
from theory.core.observability import RANK_TOL, numeric_rank
from theory.tdoa import networked_observability
from theory.tdoa.case import TdoaSpec
from theory.tdoa.model import cv_discrete, tdoa_jacobian

__all__ = [
    "exact_weights",
    "generic_rank_certificates",
    "neighbour_lists",
    "network_observability",
    "network_steps",
]

POINT_BITS = (4, 8, 16, 32)
"""Bits of the stereographic coordinates of the random rational point, tried in turn (small
denominators keep the certified minor short; a zero minor or a lost rank retries finer)."""
SOURCE = "seed 000, eqs. (4.36)–(4.37) (generic rank of the TDOA network observability matrix)"


def neighbour_lists(hears: np.ndarray) -> list[list[int]]:
    """0-based neighbours of each agent: those it receives from (``hears[i, j]``).

    Parameters
    ----------
    hears : (N, N) bool array
        ``hears[i, j]``: agent ``i`` receives from agent ``j``.

    Returns
    -------
    list of list of int
    """
    return [[int(j) for j in np.flatnonzero(row)] for row in np.asarray(hears, dtype=bool)]


def exact_weights(spec: TdoaSpec) -> list[list[Fraction]]:
    """The consensus matrix of a static scene in exact rationals (DESIGN.md's rules).

    Metropolis: ``w_ij = 1/(1 + max(d_i, d_j))`` on edges, ``w_ii = 1 − Σ_j w_ij``; uniform:
    ``w_ij = 1/(d_i + 1)`` on ``N_i ∪ {i}`` (both by
    :func:`theory.tdoa.networked_observability.exact_weights`); explicit: the decimals of the case
    file, projected onto exact row sums one (:func:`~theory.core.exact.stochastic_matrix`).

    Parameters
    ----------
    spec : TdoaSpec
        A scene; its first step's network is used.

    Returns
    -------
    list of list of Fraction
    """
    if spec.weights_rule == "explicit":
        return stochastic_matrix(spec.weights[0])
    return networked_observability.exact_weights(
        np.asarray(spec.hears[0], dtype=bool), spec.weights_rule
    )


def network_observability(
    directions: np.ndarray, neighbours: list[list[int]], W: np.ndarray, T: float
) -> np.ndarray:
    """Float ``O`` of eq. (4.36) at unit ``directions`` (rows: block ``k`` then TDOA row).

    Parameters
    ----------
    directions : (N, d) array
        Unit vectors from each agent to the target.
    neighbours : list of list of int
        0-based neighbours of each agent (its TDOA pairs).
    W : (N, N) array
        Consensus weights.
    T : float
        Sampling period of eq. (4.6).

    Returns
    -------
    ndarray, shape (2dN · Σ|N_i|, 2dN)
    """
    n_agents, dim = directions.shape
    target = np.zeros(dim)
    positions = target[None, :] - directions
    H = scipy.linalg.block_diag(
        *[
            tdoa_jacobian(target, positions, i, nb) if nb else np.zeros((0, 2 * dim))
            for i, nb in enumerate(neighbours)
        ]
    )
    A = cv_discrete(T, dim)[0]
    blocks, power = [], np.eye(2 * dim * n_agents)
    step = np.kron(np.asarray(W, float), A)
    for _ in range(2 * dim * n_agents):
        blocks.append(H @ power)
        power = power @ step
    return np.vstack(blocks)


def _q(x: Fraction | int) -> flint.fmpq:
    x = Fraction(x)
    return flint.fmpq(x.numerator, x.denominator)


def _exact_rows(u, neighbours, W, T, rows, cols) -> list[list[flint.fmpq]]:
    """Exact entries ``O[rows, cols]``: row ``(k, ρ)`` is ``e_ρᵀ D_H (W^k ⊗ A^k)``."""
    n_agents, dim = len(u), len(u[0])
    owners = [(a, j) for a in range(n_agents) for j in neighbours[a]]
    Wq = flint.fmpq_mat(n_agents, n_agents, [_q(x) for row in W for x in row])
    A = flint.fmpq_mat(
        2 * dim,
        2 * dim,
        [
            _q(T) if c == r + dim else _q(int(r == c))
            for r in range(2 * dim)
            for c in range(2 * dim)
        ],
    )
    out = []
    for r in rows:
        k, (a, j) = r // len(owners), owners[r % len(owners)]
        g = [_q(x - y) for x, y in zip(u[a], u[j], strict=True)]
        hA = flint.fmpq_mat(1, 2 * dim, [*g, *[_q(0)] * dim]) * A**k
        Wk = Wq**k
        full = [Wk[a, b] * hA[0, c] for b in range(n_agents) for c in range(2 * dim)]
        out.append([full[c] for c in cols])
    return out


def _select(matrix: np.ndarray, rank: int, *, rel_tol: float = 1e-8) -> tuple[list[int], list[int]]:
    """``rank`` rows (greedily, first rows first: low powers keep numbers short) then ``rank``
    columns (QR with column pivoting on those rows) proposing a non-singular minor."""
    basis: list[np.ndarray] = []
    rows = []
    scale = float(np.abs(matrix).max(initial=0.0))
    for index, row in enumerate(matrix):
        residual = row - sum((q @ row) * q for q in basis) if basis else row
        norm = float(np.linalg.norm(residual))
        if norm > rel_tol * max(scale, float(np.linalg.norm(row))):
            basis.append(residual / norm)
            rows.append(index)
            if len(rows) == rank:
                break
    cols = scipy.linalg.qr(matrix[rows], pivoting=True, mode="r")[1][:rank]
    return rows, sorted(int(c) for c in cols)


def generic_rank_certificates(
    spec: TdoaSpec,
    *,
    seed: int = 0,
    rank_tol: float = RANK_TOL,
    case: str | None = None,
) -> list[dict]:
    """``generic-rank`` certificates for the network ``O`` and every agent's ``O_i``.

    Parameters
    ----------
    spec : TdoaSpec
        A scene; a time-varying one is certified once per distinct network
        (:func:`network_steps`), each certificate's statement and ``produced_by.steps`` naming
        the (1-based) steps it covers.
    seed : int
        Seed of the random rational evaluation point (recorded in the certificates).
    rank_tol : float
        Relative tolerance of the float rank that proposes ``r`` (the proof is the exact minor).
    case : str, optional
        Case name recorded in the certificates.

    Returns
    -------
    list of dict
        Per network, one certificate for ``agent = 0`` (all of ``O``) and one per agent with a
        non-zero block.

    Raises
    ------
    RationalizationError
        For a network without TDOA rows, or when no exact non-zero minor of the proposed order is
        found.

    References
    ----------
    seed 000, eqs. (4.7)–(4.10), (4.36), (4.37); Cor. 4.2.4 (time-varying networks).
    """
    if spec.steps == 1:
        return _static_certificates(spec, seed, rank_tol, case)
    certs = []
    for steps in network_steps(spec):
        shown = [k + 1 for k in steps]
        for cert in _static_certificates(_at_step(spec, steps[0]), seed, rank_tol, case):
            where = "step" if len(shown) == 1 else "steps"
            cert["claim"]["statement"] += f", at {where} {_ranges(shown)} of the trajectory"
            cert["produced_by"]["steps"] = shown
            certs.append(cert)
    return certs


def network_steps(spec: TdoaSpec) -> list[tuple[int, ...]]:
    """The 0-based steps of a scene grouped by network (``hears`` and ``W`` equal), in order.

    Parameters
    ----------
    spec : TdoaSpec
        A scene.

    Returns
    -------
    list of tuple of int
        One tuple per distinct network, in the order the networks first appear.
    """
    groups: dict[bytes, list[int]] = {}
    for k in range(spec.steps):
        key = np.asarray(spec.hears[k], bool).tobytes() + np.asarray(spec.weights[k]).tobytes()
        groups.setdefault(key, []).append(k)
    return [tuple(steps) for steps in groups.values()]


def _at_step(spec: TdoaSpec, k: int) -> TdoaSpec:
    """The static scene of step ``k``."""
    return dataclasses.replace(
        spec,
        agents=spec.agents[k : k + 1],
        target=spec.target[k : k + 1],
        hears=spec.hears[k : k + 1],
        weights=spec.weights[k : k + 1],
    )


def _ranges(steps: list[int]) -> str:
    """``[1, 2, 3, 5]`` → ``"1–3, 5"``."""
    runs: list[list[int]] = []
    for k in steps:
        if runs and k == runs[-1][-1] + 1:
            runs[-1].append(k)
        else:
            runs.append([k])
    return ", ".join(f"{r[0]}–{r[-1]}" if len(r) > 1 else f"{r[0]}" for r in runs)


def _static_certificates(spec: TdoaSpec, seed: int, rank_tol: float, case: str | None) -> list:
    neighbours = neighbour_lists(spec.hears[0])
    if not any(neighbours):
        raise RationalizationError("no agent has a neighbour: the scene has no TDOA rows")
    W = exact_weights(spec)
    T = exact_decimal(spec.T)
    rng = np.random.default_rng(seed)
    raw = rng.standard_normal((spec.n_agents, spec.dim))

    width = 2 * spec.dim
    blocks = [(0, range(width * spec.n_agents))] + [
        (i + 1, range(i * width, (i + 1) * width)) for i in range(spec.n_agents)
    ]
    unit = raw / np.linalg.norm(raw, axis=1, keepdims=True)
    O_float = network_observability(unit, neighbours, np.array(W, float), float(T))
    ranks = [numeric_rank(O_float[:, list(block)], rank_tol=rank_tol).rank for _, block in blocks]

    def attempt(bits: int) -> list[dict] | None:
        u = [rational_unit_vector(d, bits) for d in raw]
        O = network_observability(np.array(u, float), neighbours, np.array(W, float), float(T))
        certs = []
        for (agent, block), rank in zip(blocks, ranks, strict=True):
            if rank == 0:
                continue
            rows, local = _select(O[:, list(block)], rank)
            cols = [block[c] for c in local]
            entries = _exact_rows(u, neighbours, W, T, rows, cols)
            minor = flint.fmpq_mat(rank, rank, [x for row in entries for x in row]).det()
            if minor == 0:
                return None
            certs.append(
                _certificate(spec, agent, rank, u, W, T, neighbours, rows, cols, minor, case)
            )
        for cert in certs:
            cert["produced_by"] = {
                "tool": "trackcert",
                "seed": seed,
                "significant_bits": bits,
                "rank_tol": f"{rank_tol:g}",
            }
        return certs

    return first_success(attempt, precisions=POINT_BITS, what="generic-rank")[0]


def _certificate(spec, agent, rank, u, W, T, neighbours, rows, cols, minor, case) -> dict:
    whole = agent == 0
    size = 2 * spec.dim * (spec.n_agents if whole else 1)
    what = "O (eq. 4.36)" if whole else f"agent {agent}'s block column O_{agent} (eq. 4.37)"
    full = (
        " (full column rank: generically observable)"
        if rank == size and whole
        else (" (full column rank)" if rank == size else "")
    )
    cert = {
        "format": "trackcert-certificate/1",
        "kind": "generic-rank",
        "source": SOURCE,
        "claim": {
            "statement": f"the generic rank of {what} over target directions "
            f"u ∈ (S^{spec.dim - 1})^{spec.n_agents} is at least {rank} of {size}{full}",
            "agent": agent,
            "rank_at_least": rank,
        },
        "data": {
            "model": "tdoa-network-observability",
            "dim": spec.dim,
            "T": str(T),
            "W": fraction_strings(W),
            "neighbours": [[j + 1 for j in nb] for nb in neighbours],
        },
        "witness": {
            "directions": fraction_strings(u),
            "rows": [r + 1 for r in rows],
            "cols": [c + 1 for c in cols],
            "minor": str(Fraction(int(minor.p), int(minor.q))),
        },
    }
    if case is not None:
        cert["case"] = case
    return cert
