"""Self-weight bisection probes with the LMI built once (issue 28 item 4) against a rebuild per
probe, in the same run.

Each probe of a weight bisection changes only ``W``; ``LmiCache`` keeps the built problem with
``W/ρ`` as a cvxpy Parameter (DPP), so a probe is a re-solve. The baseline builds (and cvxpy
canonicalises) the problem at every probe, as every probe did before. Two figures per system,
CPU seconds of 8 probes (``time.process_time``):

* LMI: the float LMI alone (what the reuse changes);
* decision: the whole exact decision of each probe (LMI, exact certificate routes, proofs_check),
  through :func:`~theory.consensus.s_detectability.max_self_weight` with ``reuse`` off and on;
  both must return the same bracket;
* sweep: 11 whole decisions of Example 1's self-weight sweep, one per point as ``trackcert
  sweep`` makes them, each with a fresh build against the thread's default cache;
* case: every self-weight search ``trackcert dkf`` runs on a ring of ``--case-agents`` 2-state
  agents (one per agent with a finite bound, and their joint family), each search with its own
  problems (as until 7 December 2026) against one cache for the case (``analyze_dkf``).

Systems: seed 000 Example 2 (agent 3) and a directed ring of N agents (``--agents``, default 10)
watching ``A = 1.2 I₃``, agent 1 without a sensor (its self-weight varies; Thm 5.2.10 (2) puts the
threshold at 1/1.44), the others one random row with two decimals. Run from the repository root:
``python -m benchmarks.bench_dkf_reuse [--agents 10]``; it prints the ratio rebuild / reuse
(issue 28 measured 2.60 s → 0.29 s for the LMI alone).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from benchmarks.bench_dkf import ring
from theory.consensus.s_detectability import (
    LmiCache,
    decide_s_detectability,
    lmi_radius,
    max_self_weight,
    self_weight_family,
)
from theory.consensus.strategies import self_weight_examples

PROBES = 8
WEIGHT_TOL = 2.0**-6  # [0, 1] halved 6 times, plus the probes at 0 and 1: 8 probes
ROW = "{:14} {:>10} {:>10} {:>7}   {:>10} {:>10} {:>7}"


def _lmi(A, C, W, agent: int, reuse: bool) -> float:
    """CPU seconds of ``PROBES`` LMI solves at the bisection's weights."""
    shared = LmiCache()
    start = time.process_time()
    for w in np.linspace(0.1, 0.9, PROBES):
        lmi_radius(
            A, C, self_weight_family(W, [agent], w), problems=shared if reuse else LmiCache()
        )
    return time.process_time() - start


def _decisions(A, C, W, agent: int, reuse: bool) -> tuple[float, tuple]:
    start = time.process_time()
    search = max_self_weight(A, C, W, [agent], weight_tol=WEIGHT_TOL, reuse=reuse)
    return time.process_time() - start, search.probes


def _sweep(fresh: bool) -> float:
    """CPU seconds of an 11-point sweep of Example 1's self-weight, one decision per point as
    ``trackcert sweep`` makes them: ``fresh`` builds each point's LMI, else the thread's cache."""
    start = time.process_time()
    for w in np.linspace(0.2, 0.3, 11):
        A, C, W = self_weight_examples("example 1", float(w))
        decide_s_detectability(A, C, W, problems=LmiCache() if fresh else None)
    return time.process_time() - start


def ring_case(agents: int):
    """A ring of 2-state agents, alternate ones seeing one coordinate, self-weight 1/2."""
    from theory.kinds import parse_case

    W = np.zeros((agents, agents))
    for i in range(agents):
        W[i, i], W[i, (i + 1) % agents], W[i, (i - 1) % agents] = 0.5, 0.25, 0.25
    C = [[[1, 0]] if i % 2 == 0 else [[0, 1]] for i in range(agents)]
    block = {"A": [[1.05, 0.1], [0, 1.02]], "C": C, "W": W.tolist(), "Q": np.eye(2).tolist()}
    block["R"] = [[[1]]] * agents
    return parse_case({"name": f"ring{agents}", "kind": "dkf", "dkf": block})


def _case_searches(case, shared: bool) -> tuple[float, list]:
    """CPU seconds and answers of the case's self-weight searches, as ``analyze_dkf`` runs them."""
    from theory.consensus.conditions import necessary_conditions
    from theory.consensus.design import self_weight_design

    spec = case.spec
    bounds = necessary_conditions(spec.A, spec.C, spec.W).self_weights
    bounded = [b.agent - 1 for b in bounds if np.isfinite(b.bound) and b.weight < 1]
    groups = [[a] for a in bounded] + ([bounded] if len(bounded) > 1 else [])
    problems = LmiCache(support=(spec.W != 0) | np.eye(len(spec.W), dtype=bool))
    start = time.process_time()
    answers = [
        self_weight_design(case, agents=group, problems=problems if shared else None)
        for group in groups
    ]
    return time.process_time() - start, [(a.status, a.supremum) for a in answers]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--agents", type=int, default=10)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--case-agents", type=int, default=16)
    args = parser.parse_args()
    A2, C2, W2 = self_weight_examples("example 2", 0.32)
    rng = np.random.default_rng(args.seed)
    C = [np.zeros((0, 3))] + [np.round(rng.normal(size=(1, 3)), 2) for _ in range(args.agents - 1)]
    ring_system = (1.2 * np.eye(3), C, ring(args.agents), 0)
    systems = {"example 2": (A2, C2, W2, 2), f"ring N={args.agents}": ring_system}
    print(f"CPU seconds of {PROBES} self-weight probes; ratio = rebuild / reuse (same run)")
    print(ROW.format("system", "LMI build", "LMI reuse", "ratio", "decide old", "decide new",
                     "ratio"))  # fmt: skip
    for name, (A_, C_, W_, agent) in systems.items():
        old, new = _lmi(A_, C_, W_, agent, False), _lmi(A_, C_, W_, agent, True)
        (d_old, b_old), (d_new, b_new) = (_decisions(A_, C_, W_, agent, r) for r in (False, True))
        assert b_old == b_new and len(b_new) == PROBES, (b_old, b_new)
        print(ROW.format(name, f"{old:.3f}", f"{new:.3f}", f"{old / new:.1f}x",
                         f"{d_old:.3f}", f"{d_new:.3f}", f"{d_old / d_new:.1f}x"))  # fmt: skip
    _sweep(fresh=False)  # the thread's cache warm, as after a sweep's first point
    old, new = _sweep(fresh=True), _sweep(fresh=False)
    print(
        f"sweep of 11 decisions (example 1): rebuilt {old:.3f}, reused {new:.3f}, "
        f"ratio {old / new:.1f}x"
    )
    case = ring_case(args.case_agents)
    (old, a_old), (new, a_new) = (_case_searches(case, shared) for shared in (False, True))
    assert a_old == a_new, (a_old, a_new)
    print(
        f"self-weight searches of trackcert dkf, ring of {args.case_agents}: a cache per search "
        f"{old:.3f}, one per case {new:.3f}, ratio {old / new:.1f}x"
    )


if __name__ == "__main__":
    main()
