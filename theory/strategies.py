"""Public hypothesis strategies for systems, networks, TDOA scenes and pursuit parameters.

The TDOA scenes, networks and weights live in :mod:`theory.tdoa.strategies` and are re-exported
here, so ``from theory.strategies import tdoa_scenes`` keeps working.

Users import these in their own property tests (docs/property-based.md)::

    from hypothesis import given
    from theory.strategies import tdoa_scenes

    @given(tdoa_scenes(dim=3, family="cone"))
    def test_cone_scenes_lose_rank(scene): ...

Names are plural nouns, bounds are keyword-only, conditioning is bounded, and impossible
arguments raise :class:`hypothesis.errors.InvalidArgument` with the offending value. The
consensus-filter strategies live in :mod:`theory.consensus.strategies` and the seed 003 ones in
:mod:`theory.pursuit.strategies`; both are re-exported here.
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.consensus.strategies import DkfProblem, dkf_problems
from theory.pursuit.strategies import (
    PursuitParameters,
    TrackerState,
    digraph_laplacians,
    pursuit_cases,
    pursuit_parameters,
    simulated_pursuit_blocks,
    simulated_pursuit_cases,
    tracker_states,
)
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
    "simulated_pursuit_blocks",
    "simulated_pursuit_cases",
    "state_space_pairs",
    "tdoa_scenes",
    "tracker_states",
    "weight_matrices",
]


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
