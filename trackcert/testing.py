"""Assertions for your own test suite: your network, your filter, your pursuit gains.

Each helper takes the same arguments as the function it is named after, returns that function's
result when the property holds, and otherwise raises ``AssertionError`` saying which agent or
condition fails, by how much, and with which tolerances::

    import networkx as nx
    import numpy as np
    from trackcert.testing import assert_observable

    def test_my_formation_localizes():
        agents = np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]])
        assert_observable(agents, [30, 20, 10], nx.complete_graph(4))

An inconclusive verdict (a margin inside its tolerance) fails too: a test should not pass on a
decision the numbers cannot make. ``docs/examples/test_my_network.py`` is a suite to copy.
"""

from __future__ import annotations

from typing import Any

from trackcert import DkfResult, IssResult, TopologyResult, dkf, iss, topology

__all__ = ["assert_iss", "assert_observable", "assert_s_detectable"]


def assert_observable(
    agents: Any,
    target: Any = None,
    graph: Any = None,
    weights: Any = "metropolis",
    T: float = 1.0,
    **options: Any,
) -> TopologyResult:
    """Assert that every agent's distributed TDOA filter can localize the target.

    Parameters
    ----------
    agents, target, graph, weights, T
        As :func:`trackcert.topology` (positions, 0-based graph, weights, ping period), or a
        case as ``agents``.
    **options
        Keyword arguments of :func:`trackcert.topology` (``comm_range``, ``rank_tol``, …).

    Returns
    -------
    TopologyResult
        The result, when every agent localizes the target conclusively.

    Raises
    ------
    AssertionError
        Naming each agent that cannot localize the target (1-based id, its rank of ``O_i``,
        ``σ_min`` and margin, and why the paper's heuristic disagrees), or why the verdict is
        inconclusive.
    """
    result = topology(agents, target, graph, weights, T, **options)
    if result.verdict is not True:
        raise AssertionError(_topology_failure(result))
    return result


def assert_s_detectable(
    A: Any,
    C: Any = None,
    W: Any = None,
    Q: Any = None,
    R: Any = None,
    *,
    self_weight: bool = False,
    **options: Any,
) -> DkfResult:
    """Assert that a consensus Kalman filter is S-detectable (seed 000 Def. 5.2.4).

    Parameters
    ----------
    A, C, W, Q, R
        As :func:`trackcert.dkf` (matrices, or a ``control.StateSpace`` with per-agent output
        selections), or a case as ``A``.
    self_weight : bool
        Also bisect each agent's largest self-weight (not needed for the verdict; slower).
    **options
        Keyword arguments of :func:`trackcert.dkf` (``L``, ``order``, ``lmi_margin``, …).

    Returns
    -------
    DkfResult
        The result, when an exact certificate shows S-detectability.

    Raises
    ------
    AssertionError
        With the decision's reason, every failing necessary condition (which agent's
        self-weight bound, which source component, which blind set, by how much) and, when not
        S-detectable, the kind of the exact infeasibility certificate that proves it.
    """
    result = dkf(A, C, W, Q, R, self_weight=self_weight, **options)
    if result.verdict is not True:
        raise AssertionError(_dkf_failure(result))
    return result


def assert_iss(config: Any = None, /, **options: Any) -> IssResult:
    """Assert that the pursuit and coordination loop is ISS (seed 003, corrected conditions).

    Parameters
    ----------
    config : case or mapping, optional
        As :func:`trackcert.iss`: a pursuit case, or a ``pursuit:`` block as a mapping.
    **options
        ``margin_tol``, ``name`` or the ``pursuit:`` block's fields, as :func:`trackcert.iss`.

    Returns
    -------
    IssResult
        The result, when every condition holds outside its margin tolerance.

    Raises
    ------
    AssertionError
        Listing each condition that fails or is inconclusive, with its value, margin, source
        and detail.
    """
    result = iss(config, **options)
    if result.verdict is not True:
        raise AssertionError(_iss_failure(result))
    return result


def _topology_failure(result: TopologyResult) -> str:
    steps = result.report.result.steps
    lines = [f"{result.summary()} (trackcert.topology, case {result.case.name!r})"]
    if result.verdict is None:
        lines += [f"  undecided: {reason}" for s in steps for reason in s.inconclusive]
    else:
        step = steps[(result.report.result.first_failure_step or 1) - 1]
        for a in step.agents:
            if a.localizes:
                continue
            line = (
                f"  agent {a.id} (component {a.component}): rank O_i = {a.rank} of "
                f"{2 * step.dim}, sigma_min = {a.sigma_min:.3g} (margin {a.margin:.3g})"
            )
            if a.reason:
                line += f"; paper's heuristic says {a.heuristic_4_noncoplanar}: {a.reason}"
            if a.mirror_ambiguous:
                line += "; receivers coplanar: a mirror image has the same TDOAs"
            lines.append(line)
        net = step.network
        lines.append(f"  network: rank {net.rank} of {net.n_states}, detectable {net.detectable}")
    lines.append(f"  tolerances: {result.tolerances}")
    return "\n".join(lines)


def _dkf_failure(result: DkfResult) -> str:
    data = result.to_json()
    lines = [f"{result.summary()} (trackcert.dkf, case {result.case.name!r})"]
    lines += [
        f"  agent {b['agent']}: self-weight w_ii = {b['w_ii']:.6g} is not below "
        f"1/r(A_i^u)^2 = {b['bound']} (margin {b['margin']:.3g}; seed 000 Thm 5.2.10)"
        for b in data["self_weight_bounds"]
        if b["ok"] is not True
    ]
    lines += [
        f"  source component {s['agents']}: not detectable from its own measurements"
        for s in data["source_components"]
        if s["detectable"] is not True
    ]
    lines += [
        f"  blind set {b['agents']}: |lambda|^2 r(W_SS) = {b['value']:.6g} >= 1"
        for b in data["blind_sets"]
        if b["ok"] is not True
    ]
    if result.verdict is False and result.certificate is not None:
        lines.append(
            f"  proved by an exact {result.certificate['kind']} certificate "
            "(trackcert.check(result.certificate) re-verifies it)"
        )
    lines.append(f"  tolerances: {result.tolerances}")
    return "\n".join(lines)


def _iss_failure(result: IssResult) -> str:
    lines = [f"{result.summary()} (trackcert.iss, case {result.case.name!r})"]
    lines += [
        f"  {c['name']}: {c['status']} (value {c['value']}, margin {c['margin']}; "
        f"{c['source']}): {c['detail']}"
        for c in result.conditions
        if c["status"] in ("fails", "inconclusive")
    ]
    lines.append(f"  tolerances: {result.tolerances}")
    return "\n".join(lines)
