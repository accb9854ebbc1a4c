"""Public hypothesis strategies for consensus-filter problems (seed 000 ch. 5).

Re-exported by :mod:`theory.strategies`. :func:`dkf_problems` draws random systems, measurements
and networks from one seed; :func:`theory.strategy_helpers.boundary_values` draws parameters
approaching a threshold from both sides (and on it), the sweeps that test that verdicts near a
boundary are correct or inconclusive; :func:`self_weight_examples` builds seed 000 Examples 1–2
with a given self-weight.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.consensus.case import ch5_examples
from theory.strategy_helpers import check_range

__all__ = [
    "SELF_WEIGHT_THRESHOLDS",
    "DkfProblem",
    "dkf_problems",
    "self_weight_examples",
]


@dataclass(frozen=True, eq=False)
class DkfProblem:
    """A consensus-filter problem (seed 000 ch. 5): ``A``, each agent's ``C_i`` (``p_i`` rows,
    possibly 0), row-stochastic ``W``, gains ``L_i``, and the seed of the generator that drew
    them (a failing example is reproduced from it)."""

    seed: int
    A: np.ndarray
    C: tuple[np.ndarray, ...]
    W: np.ndarray
    L: tuple[np.ndarray, ...]


def _directed_weights(rng: np.random.Generator, n: int, decades: float | None) -> np.ndarray:
    """Row-stochastic W on a random directed support with positive diagonal (seed 000 (5.3)):
    raw weights uniform in [0.1, 1] (``decades=None``) or log-uniform over ``decades``."""
    support = rng.random((n, n)) < rng.uniform(0.2, 1.0)
    np.fill_diagonal(support, True)
    spread = rng.uniform(0.1, 1.0, (n, n)) if decades is None else _log_uniform(rng, n, decades)
    raw = np.where(support, spread, 0.0)
    return raw / raw.sum(axis=1, keepdims=True)


def _log_uniform(rng: np.random.Generator, n: int, decades: float) -> np.ndarray:
    return 10.0 ** rng.uniform(-decades, 0.0, (n, n))


def dkf_problems(
    *,
    min_states: int = 1,
    max_states: int = 3,
    min_agents: int = 1,
    max_agents: int = 4,
    max_rows: int = 2,
    a_bound: float = 1.5,
    gain_bound: float = 1.0,
    integer_data: bool = False,
    weight_decades: float | None = None,
) -> st.SearchStrategy[DkfProblem]:
    """Consensus-filter problems built from one drawn seed (a failing example is its seed).

    ``n`` states and ``N`` agents in the given ranges, each ``C_i`` with 0 to ``max_rows`` rows,
    entries of ``A`` within ``a_bound`` (multiples of ``a_bound/2`` with ``integer_data``, which
    also puts ``C_i`` in {−1, 0, 1} so exact arithmetic stays small), gains within
    ``gain_bound``; ``W`` row-stochastic on a random directed support, raw weights uniform in
    [0.1, 1] before normalisation, or with ``weight_decades`` log-uniform over that many decades
    (seed 000 (5.3) allows any positive weights on the links). Impossible bounds raise
    :class:`InvalidArgument` at call time.
    """
    check_range("min_states", min_states, "max_states", max_states, 1)
    check_range("min_agents", min_agents, "max_agents", max_agents, 1)
    if weight_decades is not None and not weight_decades > 0:
        raise InvalidArgument(f"weight_decades={weight_decades} must be > 0")
    if max_rows < 0 or not a_bound > 0 or not gain_bound >= 0:
        raise InvalidArgument(
            "need max_rows ≥ 0, a_bound > 0, gain_bound ≥ 0; "
            f"got {max_rows}, {a_bound}, {gain_bound}"
        )

    def build(seed: int) -> DkfProblem:
        rng = np.random.default_rng(seed)
        n = int(rng.integers(min_states, max_states + 1))
        N = int(rng.integers(min_agents, max_agents + 1))
        rows = [int(rng.integers(0, max_rows + 1)) for _ in range(N)]
        if integer_data:
            A = rng.integers(-2, 3, (n, n)).astype(float) / 2 * a_bound
            C = tuple(rng.integers(-1, 2, (p, n)).astype(float) for p in rows)
        else:
            A = rng.uniform(-a_bound, a_bound, (n, n))
            C = tuple(rng.uniform(-1, 1, (p, n)) for p in rows)
        W = _directed_weights(rng, N, weight_decades)
        L = tuple(rng.uniform(-gain_bound, gain_bound, (n, p)) for p in rows)
        return DkfProblem(seed, A, C, W, L)

    return st.integers(0, 2**32 - 1).map(build)


SELF_WEIGHT_THRESHOLDS = {
    "example 1": Fraction(1, 4),
    "example 2": 1 / Fraction(3441, 2000) ** 2,
}
"""Exact self-weight thresholds of seed 000 §5.3: ``1/r_σ(A_iᵘ)²`` with ``r_σ = 2`` and
``1.7205 = 3441/2000`` (S-detectable iff the varied self-weight is below it; proofs in
``docs/theory/s-detectability.md``, "Boundary sweeps")."""


def self_weight_examples(example: str, w: float) -> tuple[np.ndarray, list[np.ndarray], np.ndarray]:
    """``(A, C, W(w))`` of seed 000 Example 1 (agents 1 and 2 get self-weight ``w ∈ [0, 1]``,
    their other weight ``1 − w``) or Example 2 (agent 3 gets ``w``, ``(1 − w)/2`` to agents 1 and
    2); :class:`InvalidArgument` for another example or ``w``."""
    if example not in SELF_WEIGHT_THRESHOLDS or not 0 <= w <= 1:
        raise InvalidArgument(
            f"example={example!r}, w={w!r}: expected {list(SELF_WEIGHT_THRESHOLDS)}, w in [0, 1]"
        )
    data = ch5_examples()[example]
    if example == "example 1":
        W = np.array([[w, 1 - w, 0], [1 - w, w, 0], [0, 0, 1]])
    else:
        W = np.array([[1, 0, 0], [0, 1, 0], [(1 - w) / 2, (1 - w) / 2, w]])
    return data["A"], list(data["C"]), W
