"""Claims ``seed002.sec3.measurements`` and ``seed002.sec4.pf_vs_ekf`` on ``kind: pf`` cases.

The computations (the measurement ranks, the PF and the averaged EKF on identical data) are in
:mod:`theory.particle.pf_vs_ekf`; this module turns them into verdicts.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from theory.core.claims import ClaimResult, register
from theory.core.observability import RANK_TOL
from theory.core.tolerances import INCONCLUSIVE_FACTOR
from theory.particle.experiments import DEFAULT_TOLERANCES, convergence_margin, convergence_verdicts
from theory.particle.pf_vs_ekf import EkfConfig, compare_on_same_data, measurement_ranks

__all__ = ["check_measurements", "check_pf_vs_ekf"]


@register(
    "seed002.sec3.measurements",
    source="seed 002, §3.1 and §3.3.1 (citing [35, 36]); §4.1.1",
    statement=(
        "In 2D a node needs two TDOA measurements (three non-collinear nodes) to localize the "
        "target on its own; with fewer it can still estimate it if connected to a network with "
        "enough measurements."
    ),
    kinds=("pf",),
)
def check_measurements(case: Any) -> list[ClaimResult]:
    """Rank form of the claim at seeded target positions (see :func:`measurement_ranks`).

    Parameters
    ----------
    case : Case
        A ``kind: pf`` case (its nodes and links).

    Returns
    -------
    list of ClaimResult
        One ``numeric`` result: ``verified`` when every node's local and pooled observability
        ranks are the predicted ones (seed 002 §3.1), ``refuted`` otherwise, ``inconclusive``
        when a rank decision lies within ``inconclusive_factor`` of its threshold.
    """
    records = measurement_ranks(case.spec)
    failures = []
    for r in records:
        alone = 4 if r["measurements"] >= 2 else 2 * r["measurements"]
        if r["local_observability_rank"] != [alone, alone]:
            failures.append(f"node {r['id']}: local rank {r['local_observability_rank']}")
        pooled = 4 if len(r["component"]) >= 3 else 2 * (len(r["component"]) - 1)
        if r["component_observability_rank"] != [pooled, pooled]:
            failures.append(f"node {r['id']}: component rank {r['component_observability_rank']}")
    margin = min(r["min_margin"] for r in records)
    inconclusive = margin < INCONCLUSIVE_FACTOR
    status = "refuted" if failures else "inconclusive" if inconclusive else "verified"
    return [
        ClaimResult(
            "seed002.sec3.measurements",
            case.name,
            "numeric",
            status,
            evidence={
                "nodes": records,
                "failures": failures,
                "points": 25,
                "seed": 0,
                "cross_check": "compare with `trackcert topology` on the tdoa case of "
                "the same network (cases/pf-tdoa-*.yaml)",
            },
            margin=margin,
            tolerance={"rank_tol": RANK_TOL, "inconclusive_factor": INCONCLUSIVE_FACTOR},
            message="local observability needs ≥ 2 TDOA rows; every node of a component of "
            "≥ 3 non-collinear nodes is observable when the component's rows are pooled"
            if not failures
            else "; ".join(failures),
        )
    ]


@register(
    "seed002.sec4.pf_vs_ekf",
    source="seed 002, §4.3.3 and Figs. 4.8–4.11",
    statement=(
        "On a three-node path graph (ends with one TDOA measurement) the distributed PF "
        "converges at every node, while the distributed EKF may diverge."
    ),
    kinds=("pf",),
)
def check_pf_vs_ekf(case: Any) -> list[ClaimResult]:
    """PF convergence per node (the verdict) with the EKF's errors on the same data beside it.

    Parameters
    ----------
    case : Case
        A ``kind: pf`` case; only three-node networks whose case expects ``converges`` are
        checked (an empty list otherwise).

    Returns
    -------
    list of ClaimResult
        One ``simulation`` result: ``verified`` when the PF converges at every node (seed 002
        §4.3.3), ``refuted`` when it does not converge at one, ``inconclusive`` otherwise.
    """
    if "converges" not in case.expect or len(case.spec.network.nodes) != 3:
        return []
    tol = {**DEFAULT_TOLERANCES, **case.tolerances}
    comparison = compare_on_same_data(case.spec)
    spec = case.spec
    verdicts = {
        name: convergence_verdicts(
            comparison.tail(errors),
            spec.network.filters,
            converge_tol=tol["converge_tol"],
            diverge_tol=tol["diverge_tol"],
        )
        for name, errors in (("pf", comparison.pf_errors), ("ekf", comparison.ekf_errors))
    }
    per_node = _per_node(spec, comparison, verdicts, tol["diverge_tol"])
    return [_result(case, comparison, verdicts, per_node, tol)]


def _status(pf_verdicts: dict[int, str]) -> str:
    """``verified`` when every node converges, ``refuted`` when one does not, else
    ``inconclusive`` (a node whose median tail error lies between the two tolerances)."""
    states = set(pf_verdicts.values())
    if states == {"converges"}:
        return "verified"
    return "refuted" if "does not converge" in states else "inconclusive"


def _result(
    case: Any,
    comparison: Any,
    verdicts: dict[str, dict],
    per_node: list[dict[str, Any]],
    tol: dict[str, float],
) -> ClaimResult:
    """The claim's record: status, per-node evidence, margin and the tolerances used."""
    spec = case.spec
    return ClaimResult(
        "seed002.sec4.pf_vs_ekf",
        case.name,
        "simulation",
        _status(verdicts["pf"]),
        evidence={
            "nodes": per_node,
            "runs": int(comparison.pf_errors.shape[0]),
            "seed": comparison.seed,
            "ekf": vars(EkfConfig(sigma=spec.config.sigma)),
        },
        margin=convergence_margin(
            comparison.tail(comparison.pf_errors),
            spec.network.filters,
            {node + 1: "converges" for node in spec.network.filters},
            converge_tol=tol["converge_tol"],
            diverge_tol=tol["diverge_tol"],
        ),
        tolerance={k: tol[k] for k in ("converge_tol", "diverge_tol")},
        message=f"PF {verdicts['pf']}; EKF on the same data {verdicts['ekf']}; runs with "
        f"tail error ≥ diverge_tol per node: PF "
        f"{[row['pf']['diverged_fraction'] for row in per_node]}, EKF "
        f"{[row['ekf']['diverged_fraction'] for row in per_node]}",
    )


def _per_node(
    spec: Any, comparison: Any, verdicts: dict[str, dict], diverge_tol: float
) -> list[dict[str, Any]]:
    """Per filtering node: its TDOA count and the PF's and the EKF's error statistics."""
    rows = []
    for f, node in enumerate(spec.network.filters):
        row = {"id": node + 1, "measurements": int(spec.network.measurement_mask[f].sum())}
        for name, errors in (("pf", comparison.pf_errors), ("ekf", comparison.ekf_errors)):
            tail = comparison.tail(errors)[:, f]
            row[name] = {
                "mean_error": float(errors[:, :, f].mean()),
                "tail_error_mean": float(tail.mean()),
                "tail_error_median": float(np.median(tail)),
                "tail_error_q90": float(np.quantile(tail, 0.9)),
                "diverged_fraction": float(np.mean(tail >= diverge_tol)),
                "verdict": verdicts[name][node + 1],
            }
        rows.append(row)
    return rows
