"""Certified design: "what will work?" answered with certificates (``trackcert design …``).

Each function is the library call of the ``trackcert design`` subcommand of the same name. It
takes a case the way every trackcert function takes one (a path, a bundled case name, a mapping
in the case-file format, a :func:`trackcert.load_case` result or a result) — except
:func:`placement`, which designs a formation from numbers — and returns a
:class:`trackcert.DesignResult` around the library's frozen answer: ``to_json()`` gives the
command's JSON keys (agents 1-based there, as the command prints them), ``certificates`` the
documents :func:`trackcert.check` re-verifies, ``exit_code`` the command's. Agents given to
these functions are 0-based, like numpy indices.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from trackcert import DesignResult

__all__ = ["gains", "margin", "placement", "redundancy", "self_weight", "weights"]


def _designed(case: Any, answer: Callable[[Any], Any]) -> DesignResult:
    """``answer(loaded case)`` wrapped as a :class:`trackcert.DesignResult`."""
    from trackcert import DesignResult, _resolve

    loaded, data = _resolve(case)
    return DesignResult(answer(loaded), loaded, data)


def self_weight(
    case: Any,
    agent: int | Sequence[int] | None = None,
    *,
    links: Sequence[str] = (),
    width: float | Fraction = Fraction(1, 10**4),
) -> DesignResult:
    """The supremum of the self-weight keeping S-detectability (seed 000 Thm 5.2.10, §5.3).

    Exact (a rational, or an algebraic number by its minimal polynomial and an isolating
    interval) when Thm 5.2.10 (2), decided exactly, is tight: then an ``s-detectability``
    certificate holds within ``width`` below it. Otherwise a bracket of ``width`` whose ends are
    decided by exact certificates.

    Parameters
    ----------
    case : str, path, mapping, Case or Result
        A case of kind ``dkf``.
    agent : int or sequence of int, optional
        The 0-based agent(s) whose self-weight ``w`` varies, their rows rescaled by
        ``(1 − w)/(1 − w_aa)``; several vary together. Default: the agents with the least exact
        self-weight bound.
    links : sequence of str, optional
        ``"W.i.j=EXPR"`` texts, ``EXPR`` affine in ``w`` (e.g. ``"W.0.1=1-w"``), as ``trackcert
        sweep --link`` reads them; they give the family instead of ``agent``.
    width : float or Fraction, optional
        Largest distance from the supremum of the certified point below it (and the width of a
        bracket).

    Returns
    -------
    DesignResult
        ``to_json()``: ``agent``, ``supremum`` (``exact``, ``value``, ``rational`` or
        ``polynomial``, ``interval``), ``below`` and ``at_or_above`` (``w`` and certificate).

    Examples
    --------
    >>> import trackcert.design
    >>> trackcert.design.self_weight("ch5-example-2-wg").to_json()["supremum"]["rational"]
    '4000000/11840481'
    """
    from theory.consensus.design import self_weight_design

    agents = [agent] if isinstance(agent, int) else None if agent is None else list(agent)
    return _designed(
        case,
        lambda c: self_weight_design(c, agents=agents, links=tuple(links), width=width),
    )


def weights(case: Any, *, max_evaluations: int = 300) -> DesignResult:
    """Rational row-stochastic weights on the case's graph with a small certified ``r_σ(L)``.

    A local search (Nelder–Mead over each row's softmax on the case's support), rounded to
    rationals and certified by an ``s-detectability`` certificate claiming ``r_σ(L) < ρ``;
    compared with the case's, uniform and (on a symmetric graph) Metropolis weights.

    Parameters
    ----------
    case : str, path, mapping, Case or Result
        A case of kind ``dkf``; its ``W``'s support is the graph.
    max_evaluations : int, optional
        Objective evaluations (one LMI solve each) of the search, over all its starts.

    Returns
    -------
    DesignResult
        ``to_json()``: ``W`` (exact strings), ``spectral_radius`` (the certified ``ρ``),
        ``certificate``, ``compared`` (``weights``, ``spectral_radius``, ...).
    """
    from theory.consensus.weight_design import weight_design

    return _designed(case, lambda c: weight_design(c, max_evaluations=max_evaluations))


def gains(
    case: Any,
    box: Sequence[str] | None = None,
    *,
    grid: int = 4,
    depth: int = 6,
    max_cells: int = 1024,
    max_gain: Fraction | None = None,
    min_rate: Fraction | None = None,
    gain_rtol: Fraction | None = None,
    margin_tol: float | None = None,
) -> DesignResult:
    """Certified, refuted and undecided cells of seed 003's corrected ISS conditions over a box.

    Parameters
    ----------
    case : str, path, mapping, Case or Result
        A case of kind ``pursuit``.
    box : sequence of str, optional
        ``"PATH=LO:HI"`` or ``"PATH=LO:HI:log"`` sides (``k_gamma``, ``k_c``, ``K_p_scale``,
        ``epsilon.I`` 0-based); default: ``k_gamma`` (or ``K_p_scale``) × ``k_c`` from a tenth
        to ten times the case's values.
    grid : int, optional
        Initial cells per side.
    depth : int, optional
        Most halvings of an initial cell.
    max_cells : int, optional
        Most cells in the map.
    max_gain : Fraction, optional
        Require an ISS gain at most this.
    min_rate : Fraction, optional
        Require decay rates at least this.
    gain_rtol : Fraction, optional
        Split certified cells until their ISS gain bounds agree to this relative tolerance.
    margin_tol : float, optional
        ``|ε₁|/‖ε‖`` below this is undecided (as ``trackcert iss``).

    Returns
    -------
    DesignResult
        ``to_json()``: ``cells`` (``box``, ``status``, ``certificate`` or
        ``failing_condition``, ``iss_gain``).
    """
    from theory.pursuit.design import default_box, gain_regions, parse_box

    def answer(loaded: Any) -> Any:
        axes = parse_box(loaded, list(box)) if box else default_box(loaded)
        return gain_regions(
            loaded, axes, grid=grid, depth=depth, max_cells=max_cells, max_gain=max_gain,
            min_rate=min_rate, gain_rtol=gain_rtol, margin_tol=margin_tol,
        )  # fmt: skip

    return _designed(case, answer)


def margin(case: Any, *, search: bool = True, seed: int = 0) -> DesignResult:
    """The certified displacement radius ρ keeping every agent observable (seed 000 ch. 4).

    Parameters
    ----------
    case : str, path, mapping, Case or Result
        A case of kind ``tdoa``.
    search : bool, optional
        Search a witness displacement (an upper bound ρ̄) too.
    seed : int, optional
        Seed of the witness search's random starts.

    Returns
    -------
    DesignResult
        ``to_json()``: ``radius``, ``exact``, ``witness_displacement``, ``per_agent``.
    """
    from theory.tdoa.geometry.margin import tdoa_margin

    return _designed(case, lambda c: tdoa_margin(c, search=search, seed=seed))


def placement(
    n_agents: int,
    comm_range: float,
    *,
    rho0: float = 0.0,
    dim: int = 3,
    seed: int = 0,
    starts: int = 6,
) -> DesignResult:
    """A formation of ``n_agents`` minimising the Cramér–Rao trace with a certified margin.

    Parameters
    ----------
    n_agents : int
        Number of agents around the target at the origin.
    comm_range : float
        Communication range every pair of agents must be within.
    rho0 : float, optional
        Least certified displacement margin ρ₀.
    dim : int, optional
        2 or 3.
    seed : int, optional
        Seed of the random starting formations.
    starts : int, optional
        Starting formations of the search.

    Returns
    -------
    DesignResult
        ``to_json()``: ``agents``, ``crb_trace``, ``radius``, ``compared``.
    """
    from theory.tdoa.geometry.placement import tdoa_placement
    from trackcert import DesignResult

    return DesignResult(
        tdoa_placement(n_agents, comm_range, rho0=rho0, dim=dim, seed=seed, starts=starts)
    )


def redundancy(case: Any, *, links: bool = True) -> DesignResult:
    """The fewest links (or agents) whose loss breaks observability (``tdoa``) or
    S-detectability (``dkf``), with certificates that no smaller set does.

    Parameters
    ----------
    case : str, path, mapping, Case or Result
        A case of kind ``tdoa`` or ``dkf``.
    links : bool, optional
        Remove links (True) or agents (False).

    Returns
    -------
    DesignResult
        ``to_json()``: ``k``, ``witness`` (1-based), ``certified_below``, ``certificates``.

    Raises
    ------
    CaseError
        For a case of another kind.
    """
    from theory.cli.design import REDUNDANCY
    from theory.core.errors import CaseError

    def answer(loaded: Any) -> Any:
        if loaded.kind not in REDUNDANCY:
            raise CaseError("kind", " or ".join(REDUNDANCY), loaded.kind, file=loaded.file)
        return REDUNDANCY[loaded.kind](loaded, links=links)

    return _designed(case, answer)
