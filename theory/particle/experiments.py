"""Monte Carlo experiments of seed 002 §3.3 (Figs. 3.2–3.6), judged by
:mod:`theory.particle.claims`.

:func:`monte_carlo` runs a :class:`~theory.particle.case.PfSpec` ``runs`` times. Run ``r`` draws the
target's start (uniform on the workspace) and DCRW path from ``default_rng([seed, r, 0])``, the
filter's randomness (initial particles, resampling, propagation) from ``default_rng([seed, r, 1])``
and the TDOA noise from ``default_rng([seed, r, 2])``, so variants of one case (consensus on/off,
another propagation model, the EKF) see the same paths and the same measurements.

Verdicts use the per-run *tail error*: the mean of ``E_i(k)`` (eq. 3.20) over the second half of
the steps. A node **converges** when the median tail error over runs is ``≤ converge_tol`` and
**does not** when it is ``≥ diverge_tol``; in between the verdict is inconclusive. A variant
**improves** on another when the paired mean difference of tail errors exceeds
``improvement_tol`` times its standard error (a paired z-test over runs, one-sided).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import partial
from typing import Any

import numpy as np

from theory.core.parallel import TaskRunner, engine
from theory.core.run_cache import RunCache, shared
from theory.core.tolerances import PF_TOLERANCES
from theory.particle.case import PfSpec
from theory.particle.dcrw import sample_dcrw_path
from theory.particle.filter import PfConfig, PfRun, run_filter, simulate_measurements
from theory.particle.learning import OnlineLearner
from theory.particle.motion import DcrwMotion, GaussianMotion, UniformMotion

__all__ = [
    "DEFAULT_TOLERANCES",
    "MonteCarlo",
    "build_motion",
    "compare_variants",
    "convergence_margin",
    "convergence_verdicts",
    "monte_carlo",
    "node_summary",
    "shared_monte_carlo",
    "summary_table",
]

DEFAULT_TOLERANCES = dict(PF_TOLERANCES)
"""converge_tol / diverge_tol: metres of median tail error; improvement_tol: standard errors."""


@dataclass(frozen=True, eq=False)
class MonteCarlo:
    """Results of ``R`` runs.

    Attributes
    ----------
    errors : ndarray, shape (R, K+1, F)
        ``E_i(k)`` per run.
    estimates : ndarray, shape (R, K+1, F, 2)
    paths : ndarray, shape (R, K+1, 2)
    learned : ndarray or None
        Final fitted ``(μ, γ, κ, λ)`` per run and node ``(R, F, 4)`` (NaN where a node never
        fitted) for the learned model, else ``None``.
    snapshots : dict
        Run 0's particle sets at the requested steps.
    seed : int
        Base seed.
    model : str
        Propagation model used.
    share : int
        ``m`` used.
    """

    errors: np.ndarray
    estimates: np.ndarray
    paths: np.ndarray
    learned: np.ndarray | None
    snapshots: dict[int, np.ndarray]
    seed: int
    model: str
    share: int

    @property
    def tail_errors(self) -> np.ndarray:
        """``(R, F)``: mean error over the second half of the steps, per run and node."""
        half = self.errors.shape[1] // 2
        return self.errors[:, half:].mean(axis=1)


def build_motion(spec: PfSpec, model: str) -> Any:
    """The propagation model ``model`` (``dcrw`` | ``gaussian`` | ``learned``) for ``spec``.

    Parameters
    ----------
    spec : PfSpec
        The scenario: gives the DCRW target parameters, the uniform proposal's maximum step and
        the learning settings.
    model : str
        ``dcrw`` (the true target model), ``gaussian`` or ``learned`` (an online learner over a
        uniform proposal).

    Returns
    -------
    DcrwMotion or GaussianMotion or OnlineLearner

    Raises
    ------
    ValueError
        For an unknown ``model``.
    """
    if model == "dcrw":
        return DcrwMotion(spec.target)
    if model == "gaussian":
        return GaussianMotion()
    if model == "learned":
        return OnlineLearner(UniformMotion(spec.uniform_max_step), **spec.learning)
    raise ValueError(f"unknown model {model!r}")


def monte_carlo(
    spec: PfSpec,
    *,
    runs: int | None = None,
    seed: int | None = None,
    model: str | None = None,
    share: int | None = None,
    snapshot_steps: tuple[int, ...] = (),
    runner: TaskRunner | None = None,
    progress: Callable[[int], None] | None = None,
) -> MonteCarlo:
    """Run the scenario ``runs`` times (defaults from ``spec``); see the module docstring.

    The runs are independent tasks on the engine (:mod:`theory.core.parallel`); run ``r`` draws
    only from ``default_rng([seed, r, ·])``, so the result is the same whatever the runner.

    Parameters
    ----------
    spec : PfSpec
        The scenario.
    runs, seed : int, optional
        Override the case's number of runs and base seed.
    model : str, optional
        Override the propagation model.
    share : int, optional
        Override ``m`` (0 disables consensus).
    snapshot_steps : tuple of int
        Steps at which run 0 keeps its particle sets.
    runner : TaskRunner, optional
        An open engine (:func:`theory.core.parallel.engine`); default: this process, serially.
    progress : callable, optional
        Called with the number of runs finished so far.

    Returns
    -------
    MonteCarlo
    """
    runs = spec.runs if runs is None else runs
    seed = spec.seed if seed is None else seed
    model = spec.model if model is None else model
    config = spec.config if share is None else replace(spec.config, share=share)
    task = partial(_run_record, spec, config, model, seed, snapshot_steps)
    if runner is None:
        with engine(1) as serial:
            records = serial.map(task, range(runs), progress=progress)
    else:
        records = runner.map(task, range(runs), progress=progress)
    errors, estimates, paths, learned, snapshots = zip(*records, strict=True)
    return MonteCarlo(
        np.asarray(errors),
        np.asarray(estimates),
        np.asarray(paths),
        np.asarray(learned) if model == "learned" else None,
        snapshots[0],
        seed,
        model,
        config.share,
    )


def _run_record(
    spec: PfSpec,
    config: PfConfig,
    model: str,
    seed: int,
    snapshot_steps: tuple[int, ...],
    r: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None, dict[int, np.ndarray]]:
    """Run ``r`` as plain arrays (errors, estimates, path, learned fits, run 0's snapshots)."""
    path, run = _one_run(spec, config, model, [seed, r], snapshot_steps if r == 0 else ())
    learned = run.motion.params if model == "learned" else None
    return run.errors, run.estimates, path, learned, run.snapshots


def _one_run(
    spec: PfSpec, config: PfConfig, model: str, key: list[int], snapshot_steps: tuple[int, ...]
) -> tuple[np.ndarray, PfRun]:
    """Run ``key = [seed, r]``: DCRW path (stream 0), filter (stream 1), measurements (stream 2)."""
    low, high = spec.workspace[:, 0], spec.workspace[:, 1]
    path_rng = np.random.default_rng([*key, 0])
    start = low + (high - low) * path_rng.random(2)
    path = sample_dcrw_path(spec.target, spec.steps, path_rng, start=start)
    measurements = simulate_measurements(
        path, spec.network, spec.noise_sigma, np.random.default_rng([*key, 2])
    )
    run = run_filter(
        path,
        spec.network,
        config,
        build_motion(spec, model),
        np.random.default_rng([*key, 1]),
        bounds=spec.workspace,
        measurements=measurements,
        snapshot_steps=snapshot_steps,
    )
    return path, run


def node_summary(mc: MonteCarlo, spec: PfSpec) -> list[dict[str, Any]]:
    """Per filtering node: mean/final error and the spread over runs (numbers the thesis omits).

    ``mean_localization_error`` averages ``E_i(k)`` over all steps and runs;
    ``final_localization_error`` averages ``E_i(K)`` over runs; ``tail_error_*`` summarise the
    per-run tail errors (mean, standard deviation, 10/50/90 % quantiles).

    Parameters
    ----------
    mc : MonteCarlo
        The runs.
    spec : PfSpec
        Their scenario.
    """
    tail = mc.tail_errors
    rows = []
    for f, node in enumerate(spec.network.filters):
        q10, q50, q90 = np.quantile(tail[:, f], [0.1, 0.5, 0.9])
        rows.append(
            {
                "id": node + 1,
                "mean_localization_error": float(mc.errors[:, :, f].mean()),
                "final_localization_error": float(mc.errors[:, -1, f].mean()),
                "tail_error_mean": float(tail[:, f].mean()),
                "tail_error_std": float(tail[:, f].std(ddof=1)) if len(tail) > 1 else 0.0,
                "tail_error_q10": float(q10),
                "tail_error_median": float(q50),
                "tail_error_q90": float(q90),
                "measurements": int(spec.network.measurement_mask[f].sum()),
            }
        )
    return rows


def convergence_verdicts(
    tail_errors: np.ndarray, filters: tuple[int, ...], *, converge_tol: float, diverge_tol: float
) -> dict[int, str]:
    """``{node id: "converges" | "does not converge" | "inconclusive"}`` (module docstring).

    Parameters
    ----------
    tail_errors : ndarray, shape (R, F)
        E.g. :attr:`MonteCarlo.tail_errors`.
    filters : tuple of int
        The 0-based filtering nodes.
    converge_tol, diverge_tol : float
        Median tail error (m) at or below which a node converges / at or above which it does not.
    """
    median = np.median(tail_errors, axis=0)
    verdicts = {}
    for f, node in enumerate(filters):
        if median[f] <= converge_tol:
            verdicts[node + 1] = "converges"
        elif median[f] >= diverge_tol:
            verdicts[node + 1] = "does not converge"
        else:
            verdicts[node + 1] = "inconclusive"
    return verdicts


def convergence_margin(
    tail_errors: np.ndarray,
    filters: tuple[int, ...],
    wanted: dict[int, str],
    *,
    converge_tol: float,
    diverge_tol: float,
) -> float:
    """Smallest distance (m) of a node's median tail error from the threshold its expected
    verdict needs (``converge_tol − median`` or ``median − diverge_tol``); < 0 when one fails.

    Parameters
    ----------
    tail_errors, filters, converge_tol, diverge_tol :
        As for :func:`convergence_verdicts`.
    wanted : dict
        Node id → ``"converges"`` or ``"does not converge"``.
    """
    median = np.median(tail_errors, axis=0)
    gaps = [
        converge_tol - median[filters.index(node - 1)]
        if verdict == "converges"
        else median[filters.index(node - 1)] - diverge_tol
        for node, verdict in wanted.items()
    ]
    return float(min(gaps))


def compare_variants(
    better: MonteCarlo,
    worse: MonteCarlo,
    column: int,
    *,
    improvement_tol: float,
    metric: str = "tail",
) -> dict[str, Any]:
    """Paired comparison at filter ``column``: is ``better``'s error lower than ``worse``'s?

    Parameters
    ----------
    better : MonteCarlo
        The variant expected to have the lower error.
    worse : MonteCarlo
        The variant it is compared with (same runs, paired by run).
    column : int
        Index of the filtering node (the last axis of ``errors``).
    improvement_tol : float
        Number of standard errors ``z`` must reach for the verdict ``"lower"``.
    metric : str
        ``"tail"`` (mean error over the second half of the steps) or ``"cumulative"``
        (``Σ_k E_i(k)``, the quantity of seed 002 Fig. 3.5).

    Returns
    -------
    dict
        ``mean_difference`` (worse − better), its ``standard_error``, ``z`` = their ratio and the
        ``verdict``: ``"lower"`` (z ≥ improvement_tol), ``"not lower"`` (z ≤ 0) or
        ``"inconclusive"``.

    Raises
    ------
    ValueError
        For an unknown ``metric``.
    """
    if metric not in ("tail", "cumulative"):
        raise ValueError(f"metric must be 'tail' or 'cumulative', got {metric!r}")
    if metric == "tail":
        diff = worse.tail_errors[:, column] - better.tail_errors[:, column]
    else:
        diff = worse.errors[:, :, column].sum(1) - better.errors[:, :, column].sum(1)
    se = float(diff.std(ddof=1) / np.sqrt(diff.size)) if diff.size > 1 else float("inf")
    if se > 0:
        z = float(diff.mean() / se)
    else:  # identical differences in every run: the sign decides
        z = float(np.sign(diff.mean())) * float("inf") if diff.mean() != 0 else 0.0
    verdict = "lower" if z >= improvement_tol else "not lower" if z <= 0 else "inconclusive"
    return {"mean_difference": float(diff.mean()), "standard_error": se, "z": z, "verdict": verdict}


def shared_monte_carlo(
    spec: PfSpec,
    *,
    model: str | None = None,
    share: int | None = None,
    cache: RunCache | None = None,
    progress: Callable[[int], None] | None = None,
) -> MonteCarlo:
    """:func:`monte_carlo` of ``spec`` once per ``cache``, model and ``m``.

    Thus the claims run on one case with one :class:`~theory.core.run_cache.RunCache` (the
    report's task of the case, ``trackcert pf``) share their runs instead of repeating them.

    Parameters
    ----------
    spec : PfSpec
        The scenario (the cache belongs to its case).
    model : str, optional
        Override the propagation model (default: the case's).
    share : int, optional
        Override ``m`` (0 disables consensus; default: the case's).
    cache : RunCache, optional
        The case's cache (``None``: run); the runs go to its ``runner`` when it has one.
    progress : callable, optional
        Called with the number of runs finished, when they run.

    Returns
    -------
    MonteCarlo
    """
    model = spec.model if model is None else model
    share = spec.config.share if share is None else share
    key = ("pf_monte_carlo", spec.runs, spec.seed, model, share)
    runner = None if cache is None else cache.runner
    return shared(
        cache,
        key,
        lambda: monte_carlo(spec, model=model, share=share, runner=runner, progress=progress),
    )


VARIANTS = {
    "pf-topology-a": ((None, None),),
    "pf-topology-b": ((None, None), (None, 0)),
    "pf-path3": ((None, None),),
    "pf-learning": (("dcrw", None), ("learned", None), ("gaussian", None)),
    "pf-long-step-learning": (("dcrw", None), ("learned", None), ("gaussian", None)),
}
"""Item 4's variants per bundled case: (model override, m override)."""


def summary_table(runs: int | None = None, seed: int | None = None) -> str:
    """Markdown table of per-node errors for every bundled PF case and variant (seed 002 §3.3).

    Parameters
    ----------
    runs, seed : int, optional
        Override the cases' Monte Carlo runs and base seed.

    Returns
    -------
    str
    """
    from theory.core.case_file import load_case

    lines = [
        "| case | model | m | node | TDOA | mean E (m) | final E (m) | tail E mean ± sd (m) "
        "| tail E 10/50/90 % (m) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name, variants in VARIANTS.items():
        spec = load_case(name).spec
        for model, share in variants:
            mc = monte_carlo(spec, runs=runs, seed=seed, model=model, share=share)
            for row in node_summary(mc, spec):
                lines.append(
                    f"| {name} | {mc.model} | {mc.share} | {row['id']} | {row['measurements']} "
                    f"| {row['mean_localization_error']:.2f} "
                    f"| {row['final_localization_error']:.2f} "
                    f"| {row['tail_error_mean']:.2f} ± {row['tail_error_std']:.2f} "
                    f"| {row['tail_error_q10']:.2f} / {row['tail_error_median']:.2f} / "
                    f"{row['tail_error_q90']:.2f} |"
                )
    return "\n".join(lines)


if __name__ == "__main__":
    import sys

    print(summary_table(*(int(a) for a in sys.argv[1:3])))
