"""The four positive operators on N-tuples of symmetric matrices (seed 000 ch. 5, App. A.2, C.3).

With weights ``W`` (entries ``w_ij ≥ 0``) and matrices ``Γ_1 … Γ_N`` acting on ``V = (V_1 … V_N)``:

* ``L``:  ``L_i(V) = Γ_i (Σ_j w_ij V_j) Γ_iᵀ`` — consensus then filtering, seed 000 eq. (5.13);
* ``J``:  ``J_i(V) = Σ_j w_ij Γ_j V_j Γ_jᵀ`` — filtering then consensus, eq. (C.6); this is
  ``f₁ⁱ(M, V)`` of Lemma A.2.1, eq. (A.54), with ``M = Γ``;
* ``L-adjoint``: ``L*_j(V) = Σ_i w_ij Γ_iᵀ V_i Γ_i`` and ``J-adjoint``:
  ``J*_j(V) = Γ_jᵀ (Σ_i w_ij V_i) Γ_j`` — their adjoints for ``⟨V, S⟩ = Σ_i tr(V_i S_i)``.

All four map positive semidefinite tuples to positive semidefinite tuples and have the same
spectral radius (``r(DE) = r(ED)`` for ``L = D∘E``, ``J = E∘D``; an adjoint has the same
spectrum). For any of them, ``P ≻ 0`` and ``ρ P − T(P) ≻ 0`` imply ``r_σ(L) < ρ``.
"""

from __future__ import annotations

from fractions import Fraction

from proofs_check.linalg import Matrix, add, matmul, scale, transpose

__all__ = ["OPERATORS", "apply_operator"]

OPERATORS = ("L", "J", "L-adjoint", "J-adjoint")


def _weighted_sum(weights: list[Fraction], mats: list[Matrix]) -> Matrix:
    n = len(mats[0])
    total = [[Fraction(0)] * n for _ in range(n)]
    for weight, mat in zip(weights, mats, strict=True):
        if weight:
            total = add(total, scale(weight, mat))
    return total


def _congruence(gamma: Matrix, v: Matrix) -> Matrix:
    return matmul(matmul(gamma, v), transpose(gamma))


def apply_operator(name: str, W: Matrix, gammas: list[Matrix], V: list[Matrix]) -> list[Matrix]:
    """``T(V)`` for ``T`` one of :data:`OPERATORS` (see the module docstring)."""
    n_agents = len(W)
    column = [[W[i][j] for i in range(n_agents)] for j in range(n_agents)]
    if name == "L":
        return [_congruence(gammas[i], _weighted_sum(W[i], V)) for i in range(n_agents)]
    if name == "J":
        moved = [_congruence(g, v) for g, v in zip(gammas, V, strict=True)]
        return [_weighted_sum(W[i], moved) for i in range(n_agents)]
    transposed = [transpose(g) for g in gammas]
    if name == "L-adjoint":
        moved = [_congruence(t, v) for t, v in zip(transposed, V, strict=True)]
        return [_weighted_sum(column[j], moved) for j in range(n_agents)]
    if name == "J-adjoint":
        return [_congruence(transposed[j], _weighted_sum(column[j], V)) for j in range(n_agents)]
    raise ValueError(f"unknown operator {name!r}")
