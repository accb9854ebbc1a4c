"""The consensus weights of a TDOA network: §4.2.2's conditions on Metropolis weights and
Lemma 4.2.2 (seed 001 Lemma 1), the zero pattern of the powers of ``W``.

**Metropolis weights** (claim ``seed000.sec4.2.2.metropolis``): on every ``tdoa`` case with
Metropolis weights, the matrix the suite uses is stochastic with ``w_ii > 0`` and ``w_ij > 0``
exactly on the links, and symmetric (hence doubly stochastic), in exact rationals at every step.

**Lemma 4.2.2**: for a stochastic ``W`` with ``w_ii > 0``, ``[W^l]_ij > 0`` if a path of length
at most ``l`` joins ``i`` and ``j``, and ``[W^l]_ij = 0`` otherwise. With non-negative entries no
cancellation can happen, so ``[W^l]_ij > 0`` exactly when a *walk* of length ``l`` runs from
``i`` to ``j`` along positive entries (``i`` receives from ``j`` when ``w_ij > 0``: directed
paths on a directed network); the self-loops pad any shorter path to length ``l``. Hence the
support of ``W^l`` grows with ``l`` and equals reachability from ``l = N − 1`` on, so checking
``l = 0, …, N − 1`` decides the lemma for every ``l``. Without ``w_ii > 0`` it fails:
``W = [[0, 1], [1, 0]]`` has ``[W²]_12 = 0`` although agents 1 and 2 are adjacent.
:func:`path_lemma_failures` compares the two patterns exactly on the floats the suite uses.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import flint
import networkx as nx
import numpy as np

from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, Method, status_of
from theory.core.exact import exact_float, to_fmpq
from theory.core.network import exact_metropolis_weights
from theory.core.tolerances import ROUNDING_TOL
from theory.tdoa.case import WeightRule

__all__ = [
    "claims",
    "metropolis_claim",
    "path_lemma_claim",
    "path_lemma_failures",
    "path_lengths",
]

claims = ClaimSet()

STEPS_SHOWN = 20
"""Time steps whose exact weights the evidence lists (all steps are checked)."""


@claims.register(
    "seed000.sec4.2.2.metropolis",
    source="seed 000 §4.2.2 (conditions on W before eq. (4.26)); docs/topology.md Metropolis rule",
    statement="Metropolis weights meet §4.2.2's conditions on W (stochastic, w_ii > 0, w_ij > 0 "
    "exactly on the bidirectional links) and are symmetric, hence doubly stochastic, with every "
    "eigenvalue in (−1, 1]",
    kinds=("tdoa",),
)
def metropolis_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """The case's Metropolis weights checked exactly at every step (no result for other rules).

    The margin is the smallest self-weight; the evidence has the exact facts per step and the
    largest deviation of the floating weights from the exact ones (``rounding_tol``). Seed 000
    §4.2.2, the conditions on W before eq. (4.26)."""
    spec = case.spec
    if spec.weights_rule != WeightRule.METROPOLIS:
        return []
    steps = [_metropolis_step(spec.hears[k], spec.weights[k]) for k in range(spec.steps)]
    exact_ok = all(
        s["stochastic"] and s["column_sums_one"] and s["symmetric"] and s["support_matches"]
        for s in steps
    )
    positive = all(Fraction(s["min_self_weight"]) > 0 for s in steps)
    library_ok = all(s["max_float_deviation"] <= ROUNDING_TOL for s in steps)
    holds = exact_ok and positive and library_ok
    margin = float(min(Fraction(s["min_self_weight"]) for s in steps))
    return [
        ClaimResult(
            status_of(holds),
            Method.EXACT,
            margin=margin,
            tolerance={"rounding_tol": ROUNDING_TOL},
            evidence={"steps_shown": steps[:STEPS_SHOWN], "n_steps": len(steps)},
            message=_metropolis_message(holds, exact_ok, positive, margin, len(steps)),
        )
    ]


def _metropolis_step(hears: np.ndarray, used: np.ndarray) -> dict[str, Any]:
    exact = exact_metropolis_weights(hears)
    n = len(exact)
    rows = [sum(row) for row in exact]
    columns = [sum(exact[i][j] for i in range(n)) for j in range(n)]
    self_weights = [exact[i][i] for i in range(n)]
    deviation = max(
        abs(float(exact_float(used[i, j]) - exact[i][j])) for i in range(n) for j in range(n)
    )
    return {
        "W": [[str(w) for w in row] for row in exact],
        "stochastic": all(r == 1 for r in rows) and all(w >= 0 for row in exact for w in row),
        "column_sums_one": all(c == 1 for c in columns),
        "symmetric": all(exact[i][j] == exact[j][i] for i in range(n) for j in range(n)),
        "support_matches": all(
            (exact[i][j] > 0) == bool(hears[i, j]) for i in range(n) for j in range(n) if i != j
        ),
        "min_self_weight": str(min(self_weights)),
        "gershgorin_lower_eigenvalue_bound": str(min(2 * w - 1 for w in self_weights)),
        "max_float_deviation": deviation,
    }


def _metropolis_message(
    holds: bool, exact_ok: bool, positive: bool, margin: float, steps: int
) -> str:
    where = f"at all {steps} steps" if steps > 1 else "for the case's network"
    if holds:
        return (
            f"W is stochastic, symmetric and doubly stochastic {where}; "
            f"min w_ii = {margin:.4g} > 0, so by Gershgorin every eigenvalue lies in "
            "[2 min w_ii − 1, 1] ⊂ (−1, 1]"
        )
    if not (exact_ok and positive):
        return f"the exact Metropolis weights violate §4.2.2's conditions {where}"
    return "the floating weights the suite uses differ from the exact Metropolis weights"


def path_lengths(W: np.ndarray) -> list[list[int | None]]:
    """Shortest path lengths along positive off-diagonal entries (``i → j`` when ``w_ij > 0``;
    ``None``: no path)."""
    n = len(W)
    graph = nx.DiGraph()
    graph.add_nodes_from(range(n))
    graph.add_edges_from((i, j) for i in range(n) for j in range(n) if i != j and W[i][j] > 0)
    lengths = dict(nx.all_pairs_shortest_path_length(graph))
    return [[lengths[i].get(j) for j in range(n)] for i in range(n)]


def path_lemma_failures(W: np.ndarray, powers: Sequence[int]) -> list[dict[str, Any]]:
    """Entries (``l``, 1-based ``i``, ``j``) where the support of ``W^l`` differs from "a path of
    length ≤ l", in exact arithmetic on the floats as stored."""
    n = len(W)
    exact = to_fmpq([[exact_float(w) for w in row] for row in np.asarray(W)])  # floats as stored
    distance = path_lengths(np.asarray(W))
    failures: list[dict[str, Any]] = []
    power = flint.fmpq_mat(n, n, [int(i == j) for i in range(n) for j in range(n)])  # W^0
    current = 0
    for l in sorted(powers):
        while current < l:
            power, current = power * exact, current + 1
        for i in range(n):
            for j in range(n):
                near = distance[i][j] is not None and distance[i][j] <= l
                if (power[i, j] > 0) != near:
                    failures.append(
                        {
                            "l": l,
                            "i": i + 1,
                            "j": j + 1,
                            "positive": power[i, j] > 0,
                            "path_length": distance[i][j],
                        }
                    )
    return failures


def _networks(case: Case) -> list[tuple[list[int], np.ndarray]]:
    """(1-based steps, W) of every distinct network of the case."""
    spec = case.spec
    if case.kind == "dkf":
        return [([1], np.asarray(spec.W, float))]
    return [([k + 1 for k in steps], spec.weights[steps[0]]) for steps in spec.networks()]


@claims.register(
    "seed000.lem4.2.2",
    source="seed 000 Lemma 4.2.2 (from [61]); seed 001 Lemma 1",
    statement="for a stochastic W with w_ii > 0, [W^l]_ij > 0 if a path of length ≤ l joins "
    "agents i and j, and [W^l]_ij = 0 otherwise",
    kinds=("tdoa", "dkf"),
)
def path_lemma_claim(case: Case, ctx: Context) -> list[ClaimResult]:
    """The lemma on the supports of ``W^0 … W^{N−1}`` of every distinct network of the case
    (which settles every ``l``); ``w_ii > 0`` holds because case validation refuses any other
    ``W`` (the smallest self-weight is in the evidence)."""
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
    message = (
        f"the support of W^l differs from the {paths} of length ≤ l at "
        f"{sum(len(c['failures']) for c in failed)} entries"
        if failed
        else f"on {len(checked)} network(s), [W^l]_ij > 0 exactly when {paths} of "
        "length ≤ l join i and j, for l = 0 … N − 1 and hence (w_ii > 0) for every l"
    )
    evidence = {"networks": checked, "directed": directed, "powers_checked": "0 … N − 1"}
    return [ClaimResult(status_of(not failed), Method.EXACT, evidence, message=message)]
