"""Claim ``seed000.lem4.2.2``: Lemma 4.2.2 checked exactly on every network of a case.

The mathematics is in :mod:`theory.tdoa.path_lemma`; this module runs it on every distinct
network of a ``tdoa`` case and on the ``W`` of a ``dkf`` case.
"""

from __future__ import annotations

import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, register
from theory.tdoa.path_lemma import path_lemma_failures, path_lengths
from theory.tdoa.rank_certificates import network_steps

__all__ = ["check_path_lemma"]

CLAIM = "seed000.lem4.2.2"


def _networks(case: Case) -> list[tuple[list[int], np.ndarray]]:
    """(1-based steps, W) of every distinct network of the case."""
    spec = case.spec
    if case.kind == "dkf":
        return [([1], np.asarray(spec.W, float))]
    return [([k + 1 for k in steps], spec.weights[steps[0]]) for steps in network_steps(spec)]


@register(
    CLAIM,
    source="seed 000 Lemma 4.2.2 (from [61]); seed 001 Lemma 1",
    statement="for a stochastic W with w_ii > 0, [W^l]_ij > 0 if a path of length ≤ l joins "
    "agents i and j, and [W^l]_ij = 0 otherwise",
    kinds=("tdoa", "dkf"),
)
def check_path_lemma(case: Case) -> list[ClaimResult]:
    """The lemma on the case's ``W`` (every distinct network), in exact arithmetic.

    Parameters
    ----------
    case : Case
        A ``tdoa`` or ``dkf`` case.

    Returns
    -------
    list of ClaimResult
        One ``exact`` result: ``verified`` when the supports of ``W^0 … W^{N−1}`` match the path
        lengths on every network (which settles every ``l``, module docstring). The hypothesis
        ``w_ii > 0`` holds by construction: case validation refuses any other ``W`` (the
        smallest self-weight is in the evidence).
    """
    networks = _networks(case)
    checked = [
        {
            "steps": steps,
            "min_self_weight": float(np.diag(W).min()),
            "path_lengths": path_lengths(W),
            "failures": path_lemma_failures(W, range(len(W))),
        }
        for steps, W in networks
    ]
    failed = [c for c in checked if c["failures"]]
    directed = any(not np.array_equal(W > 0, (W > 0).T) for _, W in networks)
    paths = "directed paths (i receives from j)" if directed else "paths"
    return [
        ClaimResult(
            CLAIM,
            case.name,
            "exact",
            "refuted" if failed else "verified",
            evidence={"networks": checked, "directed": directed, "powers_checked": "0 … N − 1"},
            message=(
                f"the support of W^l differs from the {paths} of length ≤ l at "
                f"{sum(len(c['failures']) for c in failed)} entries"
                if failed
                else f"on {len(checked)} network(s), [W^l]_ij > 0 exactly when {paths} of "
                "length ≤ l join i and j, for l = 0 … N − 1 and hence (w_ii > 0) for every l"
            ),
        )
    ]
