"""Exact certificates that ``(A, C, W)`` is **not** S-detectable: Farkas witnesses of the LMI.

The LMI of ``docs/theory/s-detectability.md`` (Theorem 3) has no solution iff multipliers
``Λ_j ⪰ 0``, ``Ψ_i ⪰ 0``, not all zero, annihilate it (``F*(Λ, Ψ) = 0``). A floating dual
``ε_cert ≈ 1e-8`` proves nothing (seed 000 Example 1 at ``w = 0.249999999`` *is* S-detectable),
so a negative verdict rests only on multipliers that are exact rationals and that
:mod:`proofs_check` (kind ``s-detectability-infeasible``) accepts.

**Construction from a blind set** (the dual of Theorem 4's proof). Let ``λ ≠ 0`` be a rational
eigenvalue of ``A`` with a rational eigenvector ``v`` and ``S ⊆ {i : C_i v = 0}``, and let
``c ≥ 0``, ``c ≠ 0`` (supported on S) satisfy ``λ² (W_SS c)_i ≥ ρ c_i`` for ``i ∈ S`` (so
``λ² r_σ(W_SS) ≥ ρ``, Collatz–Wielandt). With ``a_i = Σ_j w_ij c_j / ρ`` and ``V = v vᵀ``::

    Λ_j = c_j V,    Ψ_i = [[a_i, −c_i/λ], [−c_i/λ, c_i]] ⊗ V   (i ∈ S),
                    Ψ_i = [[a_i, 0], [0, 0]] ⊗ V              (i ∉ S)

``Ψ_i ⪰ 0`` since ``a_i c_i ≥ c_i²/λ²``; ``F*_Z = 0`` by the choice of ``a``, ``F*_G =
−2 Ψ_i,21 C_iᵀ ∝ v (C_i v)ᵀ = 0`` on S, and ``F*_Y = (2 c_i − 2 c_i) V = 0``. The vector ``c`` is
a rounded Perron vector of a class of ``W_SS`` when ``λ² r_σ > ρ`` strictly, or the exact kernel
vector of ``λ² W_KK − ρ I`` on the boundary ``λ² r_σ = ρ`` (e.g. Example 1's ``W_c``).

Blind sets are found exactly: for each rational eigenvalue, the eigenspace is intersected with the
kernels of the ``C_i`` (a search over the lattice of flats). Irrational eigenvectors give no
rational witness this way; such problems are reported inconclusive, never guessed.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from fractions import Fraction
from typing import Any

import networkx as nx
import numpy as np

from proofs_check.linalg import matmul
from theory.core.certificate_format import checked, envelope, rational_bound, strings
from theory.core.exact import (
    Matrix,
    RationalizationError,
    fraction_strings,
    null_basis,
    rational_eigenvalues,
    rational_matrix,
    stochastic_matrix,
)
from theory.core.tolerances import MAX_FLATS, PERRON_BITS, bits_ladder

__all__ = [
    "SOURCE",
    "blind_flats",
    "blind_set_witness",
    "infeasibility_certificate",
]

SOURCE = "seed 000, Definition 5.2.4; docs/theory/s-detectability.md, Theorems 3 and 4"


def blind_flats(
    A: Matrix, C: Sequence[Matrix], lam: Fraction
) -> Iterator[tuple[list, tuple[int, ...]]]:
    """``(v, S)``: a rational vector of a flat of ``ker(A − λI)`` (λ a rational eigenvalue)
    and the 0-based agents S blind to the whole flat, once per distinct non-empty S (``[]`` is an
    agent without sensor; at most ``MAX_FLATS`` flats are explored)."""
    n = len(A)
    shifted = [[A[r][c] - (lam if r == c else 0) for c in range(n)] for r in range(n)]
    queue, seen = [null_basis(shifted, n)], set()
    while queue and len(seen) < MAX_FLATS:
        basis = queue.pop()
        F = [list(col) for col in zip(*basis, strict=True)]  # n × k
        images = [matmul(Ci, F) if Ci else [] for Ci in C]
        S = tuple(i for i, im in enumerate(images) if not any(x for row in im for x in row))
        if S in seen:
            continue
        seen.add(S)
        if S:
            yield basis[0], S
        for i, im in enumerate(images):
            if i not in S:
                sub = null_basis(im, len(basis))
                if sub:
                    queue.append(
                        [
                            [
                                sum((s[k] * basis[k][r] for k in range(len(basis))), Fraction(0))
                                for r in range(n)
                            ]
                            for s in sub
                        ]
                    )


def _perron_vectors(M: Matrix, rho: Fraction) -> Iterator[list[Fraction]]:
    """Non-negative ``c ≠ 0`` candidates with ``M c ≥ ρ c``, one class of ``M`` at a time."""
    size = len(M)
    graph = nx.DiGraph()
    graph.add_nodes_from(range(size))
    graph.add_edges_from((i, j) for i in range(size) for j in range(size) if M[i][j])
    for members in nx.strongly_connected_components(graph):
        K = sorted(members)
        block = [[M[i][j] for j in K] for i in K]
        for c_K in _class_vectors(block, rho):
            c = [Fraction(0)] * size
            for k, value in zip(K, c_K, strict=True):
                c[k] = value
            yield c


def _class_vectors(block: Matrix, rho: Fraction) -> Iterator[list[Fraction]]:
    m = len(block)
    shifted = [[block[r][c] - (rho if r == c else 0) for c in range(m)] for r in range(m)]
    for v in null_basis(shifted, m):
        yield v if sum(v) >= 0 else [-x for x in v]
    values, vectors = np.linalg.eig(np.array(block, dtype=float))
    top = int(np.argmax(values.real))
    if values[top].real < float(rho) or abs(values[top].imag) > 0:
        return
    perron = np.abs(np.real(vectors[:, top]))
    for bits in bits_ladder(PERRON_BITS):
        yield [Fraction(float(x)).limit_denominator(2**bits) for x in perron / perron.max()]


def _supersolution(M: Matrix, c: list[Fraction], rho: Fraction) -> bool:
    return (
        any(c)
        and all(x >= 0 for x in c)
        and all(
            sum((M[i][j] * c[j] for j in range(len(c))), Fraction(0)) >= rho * c[i]
            for i in range(len(c))
        )
    )


def blind_set_witness(
    A: Matrix, C: Sequence[Matrix], W: Matrix, rho: Fraction = Fraction(1)
) -> dict[str, Any] | None:
    """Exact multipliers ``{"Lambda", "Psi", "eigenvalue", "agents" (0-based), "c"}`` from a
    rational blind set with ``λ² r_σ(W_SS) ≥ ρ`` (module docstring), or None when there is none
    (``docs/theory/s-detectability.md``, Theorem 4, "Exact negative verdicts")."""
    for lam in rational_eigenvalues(A):
        if lam == 0:
            continue
        for v, S in blind_flats(A, C, lam):
            M = [[lam * lam * W[i][j] for j in S] for i in S]
            for c_S in _perron_vectors(M, rho):
                if _supersolution(M, c_S, rho):
                    c = [Fraction(0)] * len(W)
                    for i, value in zip(S, c_S, strict=True):
                        c[i] = value
                    return _multipliers(W, v, lam, c, rho) | {
                        "eigenvalue": lam,
                        "agents": S,
                        "c": c,
                    }
    return None


def _multipliers(
    W: Matrix, v: list[Fraction], lam: Fraction, c: list[Fraction], rho: Fraction
) -> dict:
    n = len(v)
    V = [[x * y for y in v] for x in v]
    zero = [[Fraction(0)] * n for _ in range(n)]

    def block(coefficients: list[list[Fraction]]) -> Matrix:
        return [
            [coefficients[r][s] * V[i][j] for s in range(2) for j in range(n)]
            for r in range(2)
            for i in range(n)
        ]

    Lam = [[[c_j * x for x in row] for row in V] if c_j else zero for c_j in c]
    Psi = []
    for i, row in enumerate(W):
        a = sum((w * c_j for w, c_j in zip(row, c, strict=True)), Fraction(0)) / rho
        b = -c[i] / lam
        Psi.append(block([[a, b], [b, c[i]]]))
    return {"Lambda": Lam, "Psi": Psi}


def infeasibility_certificate(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    *,
    rho: float | Fraction = 1,
    case: str | None = None,
) -> dict:
    """The certificate that no gains give ``r_σ(L) < ρ``, checked by proofs_check: kind
    ``s-detectability-infeasible`` (not S-detectable) when ``ρ ≥ 1``, else
    ``gains-radius-below-infeasible`` (multipliers at ``ρ < 1`` leave ``r_σ(L) < 1`` open). Data
    read as written decimals, rows of ``W`` summing to exactly 1 (seed 000 Def. 5.2.4;
    ``docs/theory/s-detectability.md``, Theorems 3 and 4). :class:`RationalizationError` when no
    exact Farkas witness is found (then inconclusive)."""
    n = np.asarray(A).shape[0]
    bound = rational_bound(rho)
    kind = "s-detectability-infeasible" if bound >= 1 else "gains-radius-below-infeasible"
    A_q, W_q = rational_matrix(A), stochastic_matrix(W)
    C_q = [rational_matrix(np.asarray(c, float).reshape(-1, n)) if np.size(c) else [] for c in C]
    found = blind_set_witness(A_q, C_q, W_q, bound)
    if found is None:
        raise RationalizationError(
            f"{kind}: no rational blind set with λ² r_σ(W_SS) ≥ ρ, so no "
            "exact Farkas witness of the LMI"
        )
    padded = [c if c else [[Fraction(0)] * n] for c in C_q]
    claim = {
        "statement": ("(A, C, W) is not S-detectable: " if bound >= 1 else "")
        + "no gains L_i give r_σ(L) < ρ",
        "spectral_radius_below": str(bound),
    }
    data = {"A": fraction_strings(A_q), "C": strings(padded), "W": fraction_strings(W_q)}
    witness = {"Lambda": strings(found["Lambda"]), "Psi": strings(found["Psi"])}
    cert = envelope(kind, claim, data, witness, source=SOURCE, case=case)
    why = checked(cert)
    if why is not None:  # too costly to check, or a bug: never a reason to weaken the claim
        raise RationalizationError(f"{kind}: {why}")
    cert["produced_by"] = {
        "tool": "trackcert",
        "construction": "blind set",
        "eigenvalue": str(found["eigenvalue"]),
        "agents": [i + 1 for i in found["agents"]],
    }
    return cert
