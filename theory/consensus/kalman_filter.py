"""The consensus Kalman filter of seed 000 ch. 5, both orders, simulated on plain arrays.

``consensus-then-filter`` (eqs. (5.3)–(5.4), (5.7)–(5.9)):
``ξ_i = Σ_j w_ij x̂_j``, ``Π_i = Σ_j w_ij P_j``, ``L_i = AΠ_iC_i'(R_i + C_iΠ_iC_i')⁻¹``,
``x̂_i ← Aξ_i + L_i(y_i − C_iξ_i)``, ``P_i ← AΠ_iA' + Q − AΠ_iC_i'(C_iΠ_iC_i' + R_i)⁻¹C_iΠ_iA'``.

``filter-then-consensus`` (App. C.3, the filter of its ref. [29]): every agent applies the local
step with its own ``x̂_j``, ``P_j``, then averages:
``x̂_i ← Σ_j w_ij [Ax̂_j + L_j(y_j − C_jx̂_j)]``,
``P_i ← Σ_j w_ij [AP_jA' + Q − AP_jC_j'(C_jP_jC_j' + R_j)⁻¹C_jP_jA']``.

The estimation errors ``ε_i = x − x̂_i`` are propagated directly, by (5.5) and its
filter-then-consensus twin ``ε_i ← Σ_j w_ij [(A − L_jC_j)ε_j + ω − L_jv_j]`` (C.4 with noise):
for an unstable ``A`` the state itself overflows the floating-point range long before the
errors do, and ``x − x̂`` computed from two huge numbers would be meaningless. The covariances
and gains come from the one coupled Riccati step of :mod:`theory.consensus.riccati`.

``trackcert simulate`` on a ``kind: dkf`` case (:func:`dkf_simulator`) uses ``P_i(0) = 10 I``
(Example 1's value), every estimate starting at 0 and the initial state drawn from
``N(0, P_i(0))`` with the run's generator. The summary reports per agent the final and mean
estimation error ``‖x̂_i − x‖`` (``final_localization_error`` / ``mean_localization_error``) and
``cov_growth = ‖P_i(K)‖/‖P_i(K/2)‖`` with the verdict ``bounded`` (``|growth − 1| ≤
CONVERGED_TOL``), ``unbounded`` (``growth > GROWTH``) or ``undecided``; and the NEES/NIS tests
of :mod:`theory.core.consistency` (``metrics``; ``anees``, ``mean_nis`` and their verdicts in the
agents' rows).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from theory.consensus.case import DkfSpec, Order, ch5_examples
from theory.consensus.operators import B2_matrix, B_matrix, E_map, closed_loop
from theory.consensus.riccati import coupled_riccati_step, error_noise_covariance
from theory.core.case_file import Case
from theory.core.claims import ClaimResult, ClaimSet, Context, status_of
from theory.core.consistency import agent_columns, filter_metrics, nees, nis, padded
from theory.core.consistency import evidence as metrics_evidence
from theory.core.tolerances import CONVERGED_TOL, GROWTH
from theory.core.verdicts import all_hold
from theory.sim.outputs import save_figure, write_agents_csv, write_runs_npz
from theory.sim.simulate import Finished, Simulator

__all__ = [
    "DEFAULT_STEPS",
    "ConsensusKfRun",
    "claims",
    "consensus_kf_metrics",
    "dkf_simulator",
    "run_dkf_case",
    "simulate_consensus_kf",
    "summarize_dkf",
    "true_error_covariance",
]

claims = ClaimSet()

DEFAULT_STEPS = 400
P0_SCALE = 10.0


@dataclass(frozen=True, eq=False)
class ConsensusKfRun:
    """One run: ``ε_i(k) = x(k) − x̂_i(k)``, shape (K+1, N, n), and ``P_i(k)``, (K+1, N, n, n);
    the innovations ``ν_i(k) = y_i − C_iξ_i`` (K, N, m) and their ``S_i = C_iΠ_iC_i' + R_i``
    (K, N, m, m), zero- and identity-padded to ``m = max_i rank rows of C_i``
    (:func:`theory.core.consistency.padded`)."""

    errors: np.ndarray
    covariances: np.ndarray
    innovations: np.ndarray
    innovation_covariances: np.ndarray

    @property
    def cov_norms(self) -> np.ndarray:
        """Spectral norms ``‖P_i(k)‖``, shape (K+1, N)."""
        return np.linalg.norm(self.covariances, 2, axis=(2, 3))


def simulate_consensus_kf(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    *,
    x0: np.ndarray,
    estimate0: np.ndarray,
    P0: np.ndarray,
    steps: int,
    rng: np.random.Generator,
    order: Order | str = Order.CONSENSUS_THEN_FILTER,
) -> ConsensusKfRun:
    """The filter's errors for ``x(k+1) = Ax + ω``, ``y_i = C_ix + v_i`` over ``steps`` steps,
    noises from ``rng``, every agent starting from ``estimate0`` and ``P0`` (seed 000 eqs.
    (5.1)–(5.9), App. C.3)."""
    consensus_first = Order(order) is Order.CONSENSUS_THEN_FILTER
    n, agents = A.shape[0], W.shape[0]
    m = max(Ci.shape[0] for Ci in C)
    errors = np.empty((steps + 1, agents, n))
    covariances = np.empty((steps + 1, agents, n, n))
    innovations = np.empty((steps, agents, m))
    innovation_covariances = np.empty((steps, agents, m, m))
    errors[0], covariances[0] = np.asarray(x0) - np.asarray(estimate0), P0
    for k in range(steps):
        omega = rng.multivariate_normal(np.zeros(n), Q)
        gains, covariances[k + 1] = coupled_riccati_step(A, C, W, Q, R, covariances[k], order=order)
        es = W @ errors[k] if consensus_first else errors[k]
        base = E_map(W, covariances[k]) if consensus_first else covariances[k]
        updated = []
        for i, (e, L, Ci, Ri) in enumerate(zip(es, gains, C, R, strict=True)):
            v = _measurement_noise(rng, Ri)
            innovations[k, i], innovation_covariances[k, i] = padded(
                Ci @ e + v, Ci @ base[i] @ Ci.T + Ri, m
            )
            updated.append((A - L @ Ci) @ e + omega - L @ v)
        errors[k + 1] = np.array(updated) if consensus_first else W @ np.array(updated)
    return ConsensusKfRun(errors, covariances, innovations, innovation_covariances)


def _measurement_noise(rng: np.random.Generator, R_i: np.ndarray) -> np.ndarray:
    """``v_i ~ N(0, R_i)`` (empty for an agent without sensor)."""
    return rng.multivariate_normal(np.zeros(R_i.shape[0]), R_i) if R_i.shape[0] else np.zeros(0)


def true_error_covariance(
    A: np.ndarray,
    C: Sequence[np.ndarray],
    W: np.ndarray,
    Q: np.ndarray,
    R: Sequence[np.ndarray],
    P0: np.ndarray,
    steps: int,
    *,
    order: Order | str = Order.CONSENSUS_THEN_FILTER,
) -> tuple[np.ndarray, np.ndarray]:
    """``tr Σ(k)`` of the exact network error covariance under the filter's own gains, beside
    ``‖P_i(k)‖`` of its Riccati recursion (seed 000 eqs. (5.5)–(5.11), App. C.3).

    With the gains ``L_i(k)`` of (5.8), ``ε = col(ε_i)`` obeys ``ε⁺ = Bε + 1⊗ω − blkdiag(L_i)v``
    with ``B`` of (5.11) (consensus first) or ``B₂`` of (C.5), so ``Σ⁺ = BΣBᵀ + (11ᵀ⊗Q) +
    blkdiag(L_iR_iL_iᵀ)`` (filter first: the noise term between ``W⊗I`` and its transpose); the
    initial errors are independent with covariance ``P0`` each.
    """
    consensus_first = Order(order) is Order.CONSENSUS_THEN_FILTER
    n, agents = A.shape[0], W.shape[0]
    mix = np.kron(W, np.eye(n))
    P = np.tile(P0, (agents, 1, 1))
    Sigma = np.kron(np.eye(agents), P0)
    traces, p_norms = [np.trace(Sigma)], [np.linalg.norm(P, 2, axis=(1, 2))]
    for _ in range(steps):
        gains, P = coupled_riccati_step(A, C, W, Q, R, P, order=order)
        Gamma = closed_loop(A, C, gains)
        noise = error_noise_covariance(Q, R, gains)
        if consensus_first:
            B = B_matrix(W, Gamma)
        else:
            B, noise = B2_matrix(W, Gamma), mix @ noise @ mix.T
        Sigma = B @ Sigma @ B.T + noise
        traces.append(np.trace(Sigma))
        p_norms.append(np.linalg.norm(P, 2, axis=(1, 2)))
    return np.array(traces), np.array(p_norms)


def run_dkf_case(
    spec: DkfSpec, rng: np.random.Generator, steps: int = DEFAULT_STEPS
) -> ConsensusKfRun:
    """One run of the consensus Kalman filter of a ``dkf`` case (module docstring)."""
    n = spec.A.shape[0]
    P0 = P0_SCALE * np.eye(n)
    x0 = rng.multivariate_normal(np.zeros(n), P0)
    return simulate_consensus_kf(
        spec.A, spec.C, spec.W, spec.Q, spec.R, x0=x0, estimate0=np.zeros(n), P0=P0,
        steps=steps, rng=rng, order=spec.order,
    )  # fmt: skip


def summarize_dkf(spec: DkfSpec, runs: Sequence[ConsensusKfRun]) -> dict[str, Any]:
    """Per-agent estimation errors and covariance growth (means over runs), and the exact
    network error covariance under the filter's gains (module docstring)."""
    errors = np.mean([np.linalg.norm(r.errors, axis=-1) for r in runs], axis=0)
    norms = runs[0].cov_norms  # the Riccati recursion does not depend on the data
    half = norms.shape[0] // 2
    growth = norms[-1] / norms[half]
    agents = []
    for i in range(norms.shape[1]):
        g = float(growth[i])
        verdict = (
            "bounded"
            if abs(g - 1) <= CONVERGED_TOL
            else ("unbounded" if g > GROWTH else "undecided")
        )
        agents.append(
            {
                "id": i + 1,
                "final_localization_error": float(errors[-1, i]),
                "mean_localization_error": float(errors[1:, i].mean()),
                "final_cov_norm": float(norms[-1, i]),
                "cov_growth": g,
                "covariance": verdict,
            }
        )
    traces, _ = true_error_covariance(
        spec.A, spec.C, spec.W, spec.Q, spec.R, P0_SCALE * np.eye(spec.A.shape[0]),
        norms.shape[0] - 1, order=spec.order,
    )  # fmt: skip
    metrics = consensus_kf_metrics(spec.C, runs)
    agents = [{**row, **agent_columns(metrics, i)} for i, row in enumerate(agents)]
    return {
        "agents": agents,
        "metrics": metrics,
        "true_error_trace": {"half": float(traces[half]), "final": float(traces[-1])},
        "tolerances": {"converged_tol": CONVERGED_TOL, "growth": GROWTH},
        "P0": f"{P0_SCALE:g} I",
    }


def consensus_kf_metrics(C: Sequence[np.ndarray], runs: Sequence[ConsensusKfRun]) -> dict:
    """NEES of ``ε_i(k)`` against ``P_i(k)`` and NIS of ``ν_i`` against ``S_i``, per agent, over
    runs (:func:`theory.core.consistency.filter_metrics`; no position is estimated)."""
    n = runs[0].errors.shape[-1]
    errors = nees(np.stack([r.errors for r in runs]), np.stack([r.covariances for r in runs]))
    innovations = nis(
        np.stack([r.innovations for r in runs]),
        np.stack([r.innovation_covariances for r in runs]),
    )
    return filter_metrics(errors, n, innovations, np.array([Ci.shape[0] for Ci in C]))


def dkf_simulator(case: Case, steps: int | None = None) -> Simulator:
    """The simulator of a ``dkf`` case for :func:`theory.sim.simulate.simulate_case` (its keys
    are about S-detectability, so the runs observe no expectation)."""
    steps = steps or DEFAULT_STEPS
    fields = {"order": case.spec.order.value, "steps": steps}
    return Simulator(case.spec, functools.partial(run_dkf_case, steps=steps), fields, _finish)


def _finish(case: Case, spec: DkfSpec, runs: list, folder: Path | None, figures: bool) -> Finished:
    """``runs.npz`` (errors and covariances stacked over runs), ``agents.csv`` and the summary."""
    del case, figures
    summary = summarize_dkf(spec, runs)
    if folder is None:
        return Finished(summary, [])
    files = [
        write_runs_npz(runs, folder / "runs.npz"),
        write_agents_csv(summary["agents"], folder / "agents.csv"),
    ]
    return Finished(summary, files)


@claims.register(
    "seed000.sec5.3.sim-examples",
    source="seed 000, §5.3, Figs 5.2-5.3",
    statement="Covariances stay bounded for W_g and grow unbounded for W_b (both filter orders).",
)
def check_ch5_examples(case: Case | None, ctx: Context) -> list[ClaimResult]:
    """Both examples, both orders, 400 steps: ``‖P_i‖`` at ``K/2`` and ``K`` (figure
    ``covariance-norms.png``: Figs 5.2–5.3 for the agents that cannot estimate alone)."""
    steps = 400
    evidence: dict[str, Any] = {}
    curves: dict[str, np.ndarray] = {}
    verdicts: list[bool | None] = []
    for name, ex in ch5_examples().items():
        for weights in ("W_g", "W_b"):
            for order in Order:
                run = simulate_consensus_kf(
                    ex["A"], ex["C"], np.array(ex[weights], float), ex["Q"], ex["R"],
                    x0=ex["x0"], estimate0=np.zeros_like(ex["x0"]), P0=ex["P0"], steps=steps,
                    rng=np.random.default_rng(0), order=order,
                )  # fmt: skip
                mid, end = run.cov_norms[steps // 2], run.cov_norms[-1]
                growth = [float(end[i] / mid[i]) for i in ex["unstable_agents"]]
                bounded = all(abs(g - 1) <= CONVERGED_TOL for g in growth)
                unbounded = all(g > GROWTH for g in growth)
                verdicts.append(_growth_verdict(bounded, unbounded, weights == "W_g"))
                evidence[f"{name} {weights} {order}"] = {
                    "growth_K/2_to_K": growth,
                    "filter_metrics": metrics_evidence(consensus_kf_metrics(ex["C"], [run])),
                }
                curves[f"{name} {weights} {order}"] = run.cov_norms[:, ex["unstable_agents"]]
    folder = ctx.figure_folder()
    return [
        ClaimResult(
            status_of(all_hold(verdicts)),
            "simulation",
            evidence,
            tolerance={"converged_tol": CONVERGED_TOL, "growth": GROWTH},
            message=f"norms of P_i at k = {steps // 2} and {steps}",
            figures=() if folder is None else (_norms_figure(curves, folder),),
        )
    ]


def _growth_verdict(bounded: bool, unbounded: bool, expect_bounded: bool) -> bool | None:
    """True when the growth is on the expected side of its band, False on the other side, None
    between ``1 + converged_tol`` and ``growth`` (neither bounded nor unbounded yet)."""
    if bounded or unbounded:
        return bounded == expect_bounded
    return None


def _norms_figure(curves: dict[str, np.ndarray], folder: Path) -> str:
    """``‖P_i(k)‖`` (log scale) of each example, weights and order (seed 000 Figs 5.2–5.3)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4))
    for label, norms in curves.items():
        style = "-" if "W_g" in label else "--"
        ax.plot(norms.max(axis=1), style, label=label, linewidth=1)
    ax.set(xlabel="time step k", ylabel="max ‖P_i(k)‖, agents needing neighbours")
    ax.set_yscale("log")
    ax.legend(fontsize=6)
    ax.grid(True, alpha=0.3)
    return str(save_figure(fig, folder / "covariance-norms.png"))
