"""Falsifiable wordings of seed 003's coordination inequality (74) (for ``trackcert falsify``).

With ξ = (I − 1rᵀ)γ, V_c = ξᵀRξ/2 (eq. (73)) and γ̇ = ω̄1 − k_c Lγ + e_γ (eqs. (45)–(47)), the
paper prints V̇_c ≤ −k_c r_min‖ξ‖² + ‖ξ‖‖RW‖‖e_γ‖ (eq. (74)); what the proof supports is
V̇_c ≤ −k_c a(L) ξᵀRξ + ‖ξ‖_R b ‖e_γ‖ with a(L) of Definition 1 and b = √λ_max(WᵀRW)
(``docs/theory/pursuit-iss.md``). Examples are strongly connected digraphs with integer states.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from hypothesis import strategies as st

from theory.falsify import Property, register_property
from theory.iss import generalized_algebraic_connectivity, left_eigenvector
from theory.strategies import digraph_laplacians

__all__ = ["CoordinationExample", "coordination_case", "coordination_terms"]

REL_TOL = 1e-9
"""Relative tolerance on the inequalities (scale: the magnitude of their terms)."""


@dataclass(frozen=True, eq=False)
class CoordinationExample:
    """A digraph Laplacian, a coordination gain, path parameters γ and their errors e_γ.

    Attributes
    ----------
    laplacian : ndarray, shape (N, N)
        Laplacian ``L = D_in − A`` of a strongly connected digraph (seed 003 §II-B).
    k_c : float
        Coordination gain k_c > 0, eq. (45).
    gamma : ndarray, shape (N,)
        Path parameters γ of the trackers.
    e_gamma : ndarray, shape (N,)
        Errors e_γ entering γ̇, eq. (47).
    omega_bar : float
        Nominal path-parameter speed ω̄, eq. (46).
    """

    laplacian: np.ndarray
    k_c: float
    gamma: np.ndarray
    e_gamma: np.ndarray
    omega_bar: float = 0.05


@st.composite
def coordination_examples(draw: st.DrawFn) -> CoordinationExample:
    """Strongly connected digraphs (2–8 trackers, a ring plus at most two edges), small integer
    γ and e_γ (often e_γ = 0), and k_c ∈ {1/5, …, 2}."""
    laplacian = draw(digraph_laplacians(min_agents=2, max_agents=8, max_extra_edges=2))
    n = laplacian.shape[0]
    integers = st.lists(st.integers(-5, 5), min_size=n, max_size=n).map(np.array)
    k_c = draw(st.integers(1, 10)) / 5
    return CoordinationExample(
        laplacian, k_c, draw(integers).astype(float), draw(integers).astype(float)
    )


def coordination_terms(example: CoordinationExample) -> dict[str, float]:
    """V̇_c and both right-hand sides of (74) for ``example`` (with the scale of the terms)."""
    L = example.laplacian.astype(float)
    n = L.shape[0]
    r = np.array([float(x) for x in left_eigenvector(example.laplacian)])
    W = np.eye(n) - np.outer(np.ones(n), r)
    R = np.diag(r)
    xi = W @ example.gamma
    gamma_dot = example.omega_bar * np.ones(n) - example.k_c * L @ example.gamma + example.e_gamma
    v_dot = float(xi @ R @ (W @ gamma_dot))
    xi_norm, e_norm = float(np.linalg.norm(xi)), float(np.linalg.norm(example.e_gamma))
    xi_r = math.sqrt(float(xi @ R @ xi))
    a = generalized_algebraic_connectivity(L, r)
    b = math.sqrt(float(np.linalg.eigvalsh(W.T @ R @ W)[-1]))
    paper = -example.k_c * r.min() * xi_norm**2 + xi_norm * np.linalg.norm(R @ W, 2) * e_norm
    corrected = -example.k_c * a * xi_r**2 + xi_r * b * e_norm
    scale = example.k_c * float(np.abs(L).max()) * xi_norm**2 + xi_norm * e_norm + 1.0
    return {"v_dot": v_dot, "paper": float(paper), "corrected": corrected, "scale": scale}


def coordination_case(example: CoordinationExample) -> dict[str, Any]:
    """A ``kind: pursuit`` case with the example's graph, k_c and γ (as ``gamma0``)."""
    n = example.laplacian.shape[0]
    receives = (example.laplacian < 0).nonzero()
    edges = [[int(j) + 1, int(i) + 1] for i, j in zip(*receives, strict=True)]
    return {
        "name": f"falsify-coordination-{n}-trackers",
        "source": "trackcert falsify (shrunk counterexample to seed 003 eq. (74))",
        "description": f"State of the counterexample: gamma = {example.gamma.tolist()}, "
        f"e_gamma = {example.e_gamma.tolist()}, omega_bar = {example.omega_bar}.",
        "kind": "pursuit",
        "pursuit": {
            "dim": 2,
            "controller": "II",
            "omega_bar": example.omega_bar,
            "epsilon": [-0.5, 0],
            "K_p": [0.4, 0.2],
            "k_gamma": 500,
            "k_c": example.k_c,
            "trackers": [{"r_x": 30, "r_y": 30, "gamma0": float(g)} for g in example.gamma],
            "edges": edges,
        },
    }


def _holds(wording: str):
    def holds(example: CoordinationExample) -> bool:
        terms = coordination_terms(example)
        return terms["v_dot"] <= terms[wording] + REL_TOL * terms["scale"]

    return holds


for _wording, _statement, _expected in (
    ("paper", "V̇_c ≤ −k_c r_min‖ξ‖² + ‖ξ‖‖RW‖‖e_γ‖ (seed 003 eq. (74) as printed).", False),
    ("corrected", "V̇_c ≤ −k_c a(L) ξᵀRξ + ‖ξ‖_R b‖e_γ‖, a(L) of Definition 1.", True),
):
    register_property(
        Property(
            id=f"seed003.eq74/{_wording}",
            claim="seed003.eq74",
            wording=_wording,
            statement=_statement,
            examples=coordination_examples(),
            holds=_holds(_wording),
            to_case=coordination_case,
            expected_to_hold=_expected,
        )
    )
