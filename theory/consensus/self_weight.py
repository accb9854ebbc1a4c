"""The largest self-weight keeping S-detectability, by bisection on the LMI decision.

Family (seed 000 Examples 5.3.1–5.3.2): for a set of agents ``a``, ``W(w)`` sets ``w_aa = w`` and
rescales agent a's other weights by ``(1 − w)/(1 − w_aa)`` so the row still sums to 1. Bracket:
``[0, 1]``; the supremum is located by bisection to width ``weight_tol`` after checking that the
bracket's left end is S-detectable. Bisection presumes a single threshold in the bracket; every
probe is returned so the reader can see the decisions it rests on. A probe that is inconclusive
stops the search and the result says so.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from theory.consensus.s_detectability import decide_s_detectability
from theory.core.tolerances import WEIGHT_TOL

__all__ = ["SelfWeightSearch", "max_self_weight", "self_weight_family"]


def self_weight_family(W: np.ndarray, agents: Sequence[int], w: float) -> np.ndarray:
    """``W(w)``: self-weight ``w`` for each 0-based agent in ``agents``, other weights rescaled.

    Parameters
    ----------
    W : ndarray, shape (N, N)
        Base weights.
    agents : sequence of int
        0-based agents whose self-weight is set.
    w : float
        The common self-weight, in ``[0, 1]``.

    Raises
    ------
    ValueError
        If an agent has no other weight to rescale (``w_aa = 1``) or ``w`` is outside ``[0, 1]``.
    """
    if not 0.0 <= w <= 1.0:
        raise ValueError(f"self-weight {w!r} outside [0, 1]")
    out = np.array(W, dtype=float)
    for a in agents:
        rest = 1.0 - W[a, a]
        if rest <= 0:
            raise ValueError(f"agent {a + 1} has w_aa = 1: no other weight to rescale")
        out[a] = W[a] * (1.0 - w) / rest
        out[a, a] = w
    return out


@dataclass(frozen=True)
class SelfWeightSearch:
    """Result of :func:`max_self_weight`.

    Attributes
    ----------
    agents : tuple of int
        1-based ids whose self-weight varies.
    low, high : float
        Bracket of the supremum: ``W(low)`` S-detectable (witness verified), ``W(high)`` not
        (certificate verified) or ``high = 1``.
    status : str
        ``found`` (``high − low ≤ weight_tol``), ``always`` (``W(1)`` is S-detectable),
        ``never`` (``W(0)`` is not), or ``inconclusive`` (a probe was).
    probes : tuple of (float, bool or None)
        Every ``(w, verdict)`` evaluated.
    weight_tol : float
        Target bracket width.
    """

    agents: tuple[int, ...]
    low: float
    high: float
    status: str
    probes: tuple[tuple[float, bool | None], ...]
    weight_tol: float

    @property
    def estimate(self) -> float:
        """Midpoint of the bracket."""
        return (self.low + self.high) / 2


def max_self_weight(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    agents: Sequence[int],
    *,
    weight_tol: float = WEIGHT_TOL,
    solver: str = "CLARABEL",
) -> SelfWeightSearch:
    """Supremum of ``w`` in ``[0, 1]`` such that ``(A, C, W(w))`` is S-detectable.

    Parameters
    ----------
    A, C, W : ndarray
        System, measurements, weights.
    agents : sequence of int
        0-based agents whose self-weight varies together.
    weight_tol : float
        Bracket width at which bisection stops.
    solver : str
        cvxpy solver for each LMI decision.

    Returns
    -------
    SelfWeightSearch

    References
    ----------
    seed 000 Thm 5.2.10 (2), §5.3.1 (bound 0.25), §5.3.2 (bound 0.3378).
    """
    probes: list[tuple[float, bool | None]] = []
    ids = tuple(a + 1 for a in agents)

    def decide(w: float) -> bool | None:
        verdict = decide_s_detectability(
            A, C, self_weight_family(W, agents, w), solver=solver
        ).verdict
        probes.append((w, verdict))
        return verdict

    def done(low: float, high: float, status: str) -> SelfWeightSearch:
        return SelfWeightSearch(ids, low, high, status, tuple(probes), weight_tol)

    first = decide(0.0)
    if first is not True:
        return done(0.0, 0.0, "never" if first is False else "inconclusive")
    last = decide(1.0)
    if last is True:
        return done(1.0, 1.0, "always")
    if last is None:
        return done(0.0, 1.0, "inconclusive")
    low, high = 0.0, 1.0
    while high - low > weight_tol:
        mid = (low + high) / 2
        verdict = decide(mid)
        if verdict is None:
            return done(low, high, "inconclusive")
        low, high = (mid, high) if verdict else (low, mid)
    return done(low, high, "found")
