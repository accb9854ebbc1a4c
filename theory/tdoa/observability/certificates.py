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

The weights are taken exactly: Metropolis and uniform weights are rational by definition; an
explicit matrix is read as the decimals it was written with.

The certified quantity depends on the network (who hears whom, ``W``) and ``T`` only, not on
where the agents are: a time-varying scene (seed 000 Cor. 4.2.4) gets one set of certificates per
distinct network along its trajectory, each naming the steps it covers. They are the
certificates ``trackcert certify`` writes for a ``kind: tdoa`` case (:func:`tdoa_certificates`)
and the evidence of the claim ``seed000.eq4.36.certified``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import flint
import numpy as np
import scipy.linalg

from theory.core.case_file import Case
from theory.core.certificate_format import Certified, bundle, certified_result, envelope
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, Status
from theory.core.errors import InconclusiveError
from theory.core.exact import (
    RationalizationError,
    exact_decimal,
    first_success,
    fraction_strings,
    rational_unit_vector,
    stochastic_matrix,
    to_fmpq,
)
from theory.core.network import exact_weights
from theory.core.observability import RANK_TOL, numeric_rank
from theory.tdoa.case import TdoaSpec, WeightRule
from theory.tdoa.model import cv_discrete, neighbour_lists, tdoa_jacobian

__all__ = [
    "claims",
    "generic_rank_certificates",
    "generic_rank_claim",
    "network_observability",
    "scene_weights",
    "tdoa_certificates",
]

claims = ClaimSet()

POINT_BITS = (4, 8, 16, 32)
"""Bits of the stereographic coordinates of the random rational point, tried in turn (small
denominators keep the certified minor short; a zero minor or a lost rank retries finer)."""
SOURCE = "seed 000, eqs. (4.36)–(4.37) (generic rank of the TDOA network observability matrix)"


def scene_weights(spec: TdoaSpec) -> list[list[Fraction]]:
    """The consensus matrix of a static scene in exact rationals: Metropolis or uniform by their
    rules, an explicit matrix as the decimals written projected onto exact row sums one."""
    if spec.weights_rule == WeightRule.EXPLICIT:
        return stochastic_matrix(spec.weights[0])
    return exact_weights(np.asarray(spec.hears[0], dtype=bool), spec.weights_rule)


def network_observability(
    directions: np.ndarray, neighbours: list[list[int]], W: np.ndarray, T: float
) -> np.ndarray:
    """Float ``O`` of eq. (4.36) at unit ``directions`` (agent to target), rows block ``k`` then
    TDOA row, shape ``(2dN · Σ|N_i|, 2dN)``."""
    n_agents, dim = directions.shape
    target = np.zeros(dim)
    positions = target[None, :] - directions
    H = scipy.linalg.block_diag(
        *[
            tdoa_jacobian(target, positions, i, nb) if len(nb) else np.zeros((0, 2 * dim))
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


def _exact_rows(u, neighbours, W, T, rows, cols) -> list[list[flint.fmpq]]:
    """Exact entries ``O[rows, cols]``: row ``(k, ρ)`` is ``e_ρᵀ D_H (W^k ⊗ A^k)``."""
    n_agents, dim = len(u), len(u[0])
    owners = [(a, j) for a in range(n_agents) for j in neighbours[a]]
    Wq = to_fmpq(W)
    A = to_fmpq(
        [
            [T if c == r + dim else Fraction(int(r == c)) for c in range(2 * dim)]
            for r in range(2 * dim)
        ]
    )
    out = []
    for r in rows:
        k, (a, j) = r // len(owners), owners[r % len(owners)]
        g = [x - y for x, y in zip(u[a], u[j], strict=True)]
        hA = to_fmpq([[*g, *[Fraction(0)] * dim]]) * A**k
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
    """``generic-rank`` certificates for the network ``O`` (``agent = 0``) and every agent's
    non-zero ``O_i`` at a seeded random rational point (seed 000 eqs. (4.7)–(4.10), (4.36)–(4.37)).

    A time-varying scene is certified once per distinct network (Cor. 4.2.4), each certificate's
    statement and ``produced_by.steps`` naming the 1-based steps it covers. ``rank_tol`` proposes
    the rank (the proof is the exact minor). ``RationalizationError`` for a network without TDOA
    rows, or when no exact non-zero minor of the proposed order is found."""
    if spec.steps == 1:
        return _static_certificates(spec, seed, rank_tol, case)
    certs = []
    for steps in spec.networks():
        shown = [k + 1 for k in steps]
        for cert in _static_certificates(spec.at_step(steps[0]), seed, rank_tol, case):
            where = "step" if len(shown) == 1 else "steps"
            cert["claim"]["statement"] += f", at {where} {_ranges(shown)} of the trajectory"
            cert["produced_by"]["steps"] = shown
            certs.append(cert)
    return certs


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
    neighbours = [[int(j) for j in nb] for nb in neighbour_lists(spec.hears[0])]
    if not any(neighbours):
        raise RationalizationError("no agent has a neighbour: the scene has no TDOA rows")
    W = scene_weights(spec)
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
    claim = {
        "statement": f"the generic rank of {what} over target directions "
        f"u ∈ (S^{spec.dim - 1})^{spec.n_agents} is at least {rank} of {size}{full}",
        "agent": agent,
        "rank_at_least": rank,
    }
    data = {
        "model": "tdoa-network-observability",
        "dim": spec.dim,
        "T": str(T),
        "W": fraction_strings(W),
        "neighbours": [[j + 1 for j in nb] for nb in neighbours],
    }
    witness = {
        "directions": fraction_strings(u),
        "rows": [r + 1 for r in rows],
        "cols": [c + 1 for c in cols],
        "minor": str(Fraction(int(minor.p), int(minor.q))),
    }
    return envelope("generic-rank", claim, data, witness, source=SOURCE, case=case)


def tdoa_certificates(case: Case, seed: int) -> Certified:
    """The ``generic-rank`` certificates of a ``kind: tdoa`` case (``trackcert certify``), or
    none and why (a point that cannot be rationalized)."""
    try:
        return generic_rank_certificates(case.spec, seed=seed, case=case.name), []
    except RationalizationError as error:
        return [], [str(error)]


@claims.register(
    "seed000.eq4.36.certified",
    source="seed 000, eqs. (4.36)–(4.37)",
    statement="the generic rank of the TDOA network observability matrix O and of each block "
    "column O_i is certified by an exact non-vanishing minor at a rational point",
    kinds=("tdoa",),
)
def generic_rank_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """One ``verified`` result per distinct network of the scene, carrying its certificates as a
    bundle the report re-checks; ``inconclusive`` when there is none."""
    try:
        certs, reasons = tdoa_certificates(case, 0)
    except InconclusiveError as error:
        return [ClaimResult(Status.INCONCLUSIVE, Method.EXACT, message=str(error))]
    if not certs:
        why = f"no certificate for {case.name}: " + "; ".join(reasons)
        return [ClaimResult(Status.INCONCLUSIVE, Method.EXACT, message=why)]
    networks: dict[tuple[int, ...], list[dict]] = {}
    for cert in certs:
        networks.setdefault(tuple(cert["produced_by"].get("steps", [1])), []).append(cert)
    return [
        certified_result(
            _rank_evidence(steps, group),
            document=bundle(group, case=case.name),
            message=_rank_message(group),
        )
        for steps, group in networks.items()
    ]


def _rank_evidence(steps: tuple[int, ...], group: list[dict]) -> dict[str, Any]:
    return {
        "steps": list(steps),
        "ranks_at_least": {c["claim"]["agent"]: c["claim"]["rank_at_least"] for c in group},
        "certificates": [
            {
                "agent": c["claim"]["agent"],
                "rank_at_least": c["claim"]["rank_at_least"],
                "rows": c["witness"]["rows"],
                "cols": c["witness"]["cols"],
                "minor": c["witness"]["minor"],
            }
            for c in group
        ],
        "seed": group[0]["produced_by"]["seed"],
    }


def _rank_message(group: list[dict]) -> str:
    """The statement of the certificate of ``O``, then the certified ranks of each ``O_i``."""
    ranks = {c["claim"]["agent"]: c["claim"]["rank_at_least"] for c in group}
    whole = [c["claim"]["statement"] for c in group if c["claim"]["agent"] == 0]
    agents = len(group[0]["data"]["neighbours"])
    blocks = ", ".join(str(ranks.get(i, 0)) for i in range(1, agents + 1))
    return "; ".join([*whole, f"block columns O_1 … O_{agents} have rank at least {blocks}"])
