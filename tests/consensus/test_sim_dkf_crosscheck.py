"""Theory ↔ simulation for ch. 5: the dkf LMI's S-detectability verdict against the coupled
Riccati recursion (5.7)–(5.9), both orders (App. C.3), over random systems and networks."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st

from theory.consensus.case import ORDERS
from theory.consensus.riccati import coupled_riccati
from theory.consensus.s_detectability import decide_s_detectability

CONVERGED_TOL = 1e-6
"""Relative change of max ‖P_i‖ between K/2 and K under which the recursion counts as converged."""
GROWTH = 2.0
"""Growth factor of max ‖P_i‖ between K/2 and K over which it counts as diverging."""
HORIZONS = (400, 3200, 25600)
"""Horizons tried in turn; near the detectability boundary convergence is slow."""


@st.composite
def networked_systems(draw):
    """n = 2, N = 3: A with spectral radius in [0.6, 1.8], scalar sensors (some blind), random
    row-stochastic W with positive self-weights (entries ≥ 0.1 before normalisation)."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    A = rng.normal(size=(2, 2))
    radius = max(abs(np.linalg.eigvals(A)))
    assume(radius > 1e-3)
    A *= rng.uniform(0.6, 1.8) / radius
    C = [rng.normal(size=(1, 2)) if rng.random() < 0.6 else np.zeros((1, 2)) for _ in range(3)]
    mask = rng.random((3, 3)) < 0.5
    np.fill_diagonal(mask, True)
    W = mask * rng.uniform(0.1, 1.0, (3, 3))
    return A, C, W / W.sum(axis=1, keepdims=True)


def _behaviour(A, C, W, order: str) -> str:
    for steps in HORIZONS:
        norms = coupled_riccati(
            A, C, W, 0.1 * np.eye(2), [0.1 * np.eye(1)] * 3, np.eye(2),
            order=order, max_iter=steps, fixed_steps=True,
        ).norms  # fmt: skip
        mid, end = norms[steps // 2], norms[-1]
        if abs(end - mid) <= CONVERGED_TOL * mid:
            return "converges"
        if end > GROWTH * mid:
            return "diverges"
    return "undecided"


@given(system=networked_systems(), order=st.sampled_from(ORDERS))
def test_s_detectable_iff_riccati_converges(system, order: str) -> None:
    """S-detectable (LMI witness) ⇒ the coupled Riccati recursion converges; not S-detectable
    (LMI certificate) ⇒ it diverges. Inconclusive LMI verdicts are skipped, not guessed."""
    A, C, W = system
    verdict = decide_s_detectability(A, C, W).verdict
    assume(verdict is not None)
    behaviour = _behaviour(A, C, W, order)
    assume(behaviour != "undecided")
    assert behaviour == ("converges" if verdict else "diverges"), (verdict, behaviour)
