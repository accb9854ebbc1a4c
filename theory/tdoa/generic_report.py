"""What ``trackcert generic`` reports: the symbolic derivation of seed 000 §4.2.1, or Fig. 4.3.

:func:`generic_report` enumerates every minor of one agent's ``O = [H; HA; …]``
(:func:`theory.tdoa.generic_rank.single_agent_generic_rank`) and decides whether every check
reproduces the statement; :func:`fig43_report` analyses the networked pair of Fig. 4.3
(:func:`theory.tdoa.fig43.fig43_analysis`). The command only prints them and exits with
``holds`` (:mod:`theory.core.verdicts`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from theory.core.errors import CaseError

__all__ = ["MAX_ROWS", "GenericReport", "fig43_report", "generic_report"]

MAX_ROWS = {2: 8, 3: 4}
"""Largest ``rows`` per dimension: C(32, 4) = 35960 and C(24, 6) = 134596 minors."""

WEIGHT_RULES = ("metropolis", "uniform")


@dataclass(frozen=True)
class GenericReport:
    """A derivation and whether it reproduces the statement.

    Attributes
    ----------
    result : object
        :class:`theory.tdoa.generic_rank.SingleAgentGenericRank`, or the Fig. 4.3 dict.
    holds : bool
        Single agent: the random-point rank equals the Kronecker rank, the minors' cross-check
        agrees, ``O`` is generically full rank iff ``rows ≥ dim``, and the closed form of eq.
        (4.20) and footnote 2's factor match where they apply. Fig. 4.3: the symbolic and exact
        ranks of every ``O_i`` agree and the pair is detectable.
    """

    result: Any
    holds: bool


def generic_report(dim: int = 3, rows: int | None = None, *, seed: int = 0) -> GenericReport:
    """The single-agent derivation of seed 000 §4.2.1 (eq. (4.20), footnotes 1–2).

    Parameters
    ----------
    dim : int
        Position dimension, 2 or 3.
    rows : int, optional
        Number of TDOA rows (default ``dim``), at most :data:`MAX_ROWS` for ``dim``.
    seed : int
        Seed of the random evaluation points.

    Returns
    -------
    GenericReport

    Raises
    ------
    CaseError
        If ``dim`` or ``rows`` is out of range.
    """
    if dim not in (2, 3):
        raise CaseError("--dim", "2 or 3", dim, file="<command line>")
    rows = dim if rows is None else rows
    limit = MAX_ROWS[dim]
    if rows < 1 or rows > limit:
        raise CaseError(
            "--rows",
            f"an integer between 1 and {limit} for dim {dim} (all C(2·dim·rows, 2·dim) "
            "minors are enumerated; footnote 2 needs only rows = dim + 1)",
            rows,
            file="<command line>",
        )
    from theory.tdoa.generic_rank import single_agent_generic_rank  # sympy: imported on use

    result = single_agent_generic_rank(dim, rows, seed=seed)
    holds = (
        result.cross_check["all_agree"]
        and result.random_rank.rank == result.kronecker_rank
        and result.generically_full_rank == (rows >= dim)
        and result.closed_form_alpha in (None, True)
        and result.paper_factor_matches in (None, True)
    )
    return GenericReport(result, bool(holds))


def fig43_report(case: str, *, weights: str = "metropolis", seed: int = 0) -> GenericReport:
    """The networked pair of Fig. 4.3 (seed 000 App. B.1): symbolic rank ``O_i``, exact ``O``.

    Parameters
    ----------
    case : str
        The figure's case letter, ``a`` … ``d``.
    weights : str
        ``metropolis`` or ``uniform``.
    seed : int
        Seed of the random exact evaluation point.

    Returns
    -------
    GenericReport

    Raises
    ------
    CaseError
        For an unknown case letter or weight rule.
    """
    from theory.tdoa.fig43 import FIG43_EDGES, fig43_analysis  # sympy: imported on use

    if case not in FIG43_EDGES:
        raise CaseError("--fig43", f"one of {sorted(FIG43_EDGES)}", case, file="<command line>")
    if weights not in WEIGHT_RULES:
        raise CaseError("--weights", " or ".join(WEIGHT_RULES), weights, file="<command line>")
    result = fig43_analysis(case, rule=weights, seed=seed)
    return GenericReport(result, bool(result["agree"] and result["detectable"]))
