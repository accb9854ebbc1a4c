"""Claim ``seed000.sec5.3.sim-examples``: Examples 1–2 of §5.3 simulated (Figs 5.2–5.3).

Covariances of the consensus Kalman filter (:mod:`theory.consensus.kalman_filter`) stay bounded
for ``W_g`` and grow without bound for ``W_b``, for both filter orders.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from theory.consensus.kalman_filter import ORDERS, ch5_examples, simulate_consensus_kf
from theory.core.claims import ClaimResult, register
from theory.core.tolerances import CONVERGED_TOL, GROWTH
from theory.sim.figures import save_figure

__all__ = ["check_ch5_examples"]


@register(
    "seed000.sec5.3.sim-examples",
    source="seed 000, §5.3, Figs 5.2-5.3",
    statement="Covariances stay bounded for W_g and grow unbounded for W_b (both filter orders).",
)
def check_ch5_examples(
    case: Any = None, *, steps: int = 400, figure_dir: Path | None = None
) -> list[ClaimResult]:
    """Simulate both examples, both orders; compare ``‖P_i‖`` at ``K/2`` and ``K``.

    Parameters
    ----------
    case : None
        Model claim (no case).
    steps : int
        Horizon ``K``.
    figure_dir : Path, optional
        Folder for ``covariance-norms.png`` (Figs 5.2–5.3: ``‖P_i(k)‖`` of the agents that cannot
        estimate alone, for ``W_g`` and ``W_b``).
    """
    evidence: dict[str, Any] = {}
    curves: dict[str, np.ndarray] = {}
    verdicts: list[bool | None] = []
    for name, ex in ch5_examples().items():
        for weights in ("W_g", "W_b"):
            for order in ORDERS:
                run = simulate_consensus_kf(
                    ex["A"], ex["C"], np.array(ex[weights], float), ex["Q"], ex["R"],
                    x0=ex["x0"], estimate0=np.zeros_like(ex["x0"]), P0=ex["P0"], steps=steps,
                    rng=np.random.default_rng(0), order=order,
                )  # fmt: skip
                mid, end = run.cov_norms[steps // 2], run.cov_norms[-1]
                growth = [float(end[i] / mid[i]) for i in ex["unstable_agents"]]
                bounded = all(abs(g - 1) <= CONVERGED_TOL for g in growth)
                unbounded = all(g > GROWTH for g in growth)
                expect_bounded = weights == "W_g"
                verdicts.append(_growth_verdict(bounded, unbounded, expect_bounded=expect_bounded))
                evidence[f"{name} {weights} {order}"] = {"growth_K/2_to_K": growth}
                curves[f"{name} {weights} {order}"] = run.cov_norms[:, ex["unstable_agents"]]
    figures = () if figure_dir is None else (_norms_figure(curves, figure_dir),)
    return [
        ClaimResult(
            claim="seed000.sec5.3.sim-examples",
            case="-",
            method="simulation",
            status=_status(verdicts),
            evidence=evidence,
            tolerance={"converged_tol": CONVERGED_TOL, "growth": GROWTH},
            message=f"norms of P_i at k = {steps // 2} and {steps}",
            figures=figures,
        )
    ]


def _growth_verdict(bounded: bool, unbounded: bool, *, expect_bounded: bool) -> bool | None:
    """True when the growth is on the expected side of its band, False on the other side, None
    between ``1 + converged_tol`` and ``growth`` (neither bounded nor unbounded yet)."""
    if bounded or unbounded:
        return bounded == expect_bounded
    return None


def _status(verdicts: list[bool | None]) -> str:
    if False in verdicts:
        return "refuted"
    return "inconclusive" if None in verdicts else "verified"


def _norms_figure(curves: dict[str, np.ndarray], folder: Path) -> str:
    """``‖P_i(k)‖`` (log scale) of each example, weights and order (seed 000 Figs 5.2–5.3)."""
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for label, norms in curves.items():
        style = "-" if "W_g" in label else "--"
        ax.plot(norms.max(axis=1), style, label=label, linewidth=1)
    ax.set(xlabel="time step k", ylabel="max ‖P_i(k)‖, agents needing neighbours")
    ax.set_yscale("log")
    ax.legend(fontsize=6)
    ax.grid(True, alpha=0.3)
    return str(save_figure(fig, folder / "covariance-norms.png"))
