"""``trackcert simulate`` for ``kind: pursuit`` cases (seed 003, 2-D): run, summary, files.

Adapts a :class:`~theory.pursuit_case.PursuitSpec` to :func:`theory.sim.pursuit.simulate_dec_2d`.
Defaults where the case leaves the simulation unspecified (documented in
``docs/simulation.md``): tracker ``i`` (0-based) starts at ``q(0) + (−40 + 5i, −40 − 5i)`` m
with heading 0 and ``γ^[i](0) = i`` rad; estimates start at ``[q(0) + (5, −5); 0, 0]`` with
``P = 10 I``; steps of ``dt = 0.1`` s.
"""

from __future__ import annotations

import csv
import dataclasses
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from theory.errors import CaseError
from theory.pursuit_case import PursuitSpec
from theory.sim.pursuit import DecRun, DecSettings, simulate_dec_2d

__all__ = [
    "DEFAULT_STEPS",
    "check_pursuit_case",
    "run_pursuit_case",
    "summarize_pursuit",
    "write_pursuit_data",
    "write_pursuit_figures",
]

DEFAULT_STEPS = 4500
"""450 s of 0.1 s (the paper's runs; the issue's 4501 samples)."""
DT = 0.1


def check_pursuit_case(spec: PursuitSpec) -> None:
    """Refuse what the simulation cannot run, naming the field.

    Parameters
    ----------
    spec : PursuitSpec

    Raises
    ------
    CaseError
        3-D cases, missing ``target`` or ``dekf`` blocks, ``ε₁ = 0``.
    """
    if spec.dim != 2:
        raise CaseError("pursuit.dim", "2 (the simulation covers the 2-D DEC loop)", spec.dim)
    if spec.target is None:
        raise CaseError("pursuit.target", "a target motion to simulate", "nothing")
    if spec.dekf is None:
        raise CaseError("pursuit.dekf", "DEKF settings (Ts, sigma, V, Q) to simulate", "nothing")
    if spec.epsilon[0] == 0:
        raise CaseError(
            "pursuit.epsilon[1]", "a non-zero ε₁ (Δ of (22) is singular otherwise)", 0.0
        )


def _target_states(spec: PursuitSpec, steps: int) -> np.ndarray:
    times = DT * np.arange(steps + 1)
    motion = spec.target
    return np.array([np.concatenate([motion.position(t), motion.velocity_at(t)]) for t in times])


def run_pursuit_case(
    spec: PursuitSpec, rng: np.random.Generator, steps: int = DEFAULT_STEPS
) -> DecRun:
    """One run of the 2-D DEC loop for a pursuit case.

    Parameters
    ----------
    spec : PursuitSpec
        A case accepted by :func:`check_pursuit_case`.
    rng : numpy.random.Generator
        Source of the range noise.
    steps : int
        Number of ``0.1 s`` steps.

    Returns
    -------
    DecRun
    """
    dekf = spec.dekf
    target = _target_states(spec, steps)
    positions, headings, gammas = [], [], []
    for i, tracker in enumerate(spec.trackers):
        initial = tracker.initial
        default = target[0, :2] + np.array([-40.0 + 5 * i, -40.0 - 5 * i])
        positions.append(initial.get("position", default))
        headings.append(float(initial["euler"][0]) if "euler" in initial else 0.0)
        gammas.append(initial.get("gamma", float(i)))
    x0 = dekf.x0 if dekf.x0 is not None else np.concatenate([target[0, :2] + [5.0, -5.0], [0, 0]])
    P0 = dekf.P0 if dekf.P0 is not None else 10.0 * np.eye(4)
    settings = DecSettings(
        omega_bar=spec.omega_bar,
        epsilon=tuple(float(e) for e in spec.epsilon),
        Kp=tuple(float(k) for k in np.diag(spec.K_p)),
        k_gamma=spec.k_gamma if spec.k_gamma is not None else 1.0,
        k_c=spec.k_c if spec.k_c is not None else 0.0,
        controller=spec.controller,
        V=dekf.V,
        Q=tuple(float(q) for q in np.diag(dekf.Q)),
        Ts=dekf.Ts,
        dt=DT,
        sigma=dekf.sigma,
    )
    paths = np.array([[t.r_x, t.r_y, t.gamma0] for t in spec.trackers])
    in_neighbours = [list(np.flatnonzero(row)) for row in spec.adjacency]
    return simulate_dec_2d(
        target, np.array(positions, float), np.array(headings), np.array(gammas, float),
        in_neighbours, x0, P0, steps, rng, settings, paths=paths, fusion=dekf.weights,
    )  # fmt: skip


def summarize_pursuit(spec: PursuitSpec, runs: Sequence[DecRun]) -> dict[str, Any]:
    """Per-tracker means over runs and the coordination outcome.

    Parameters
    ----------
    spec : PursuitSpec
    runs : sequence of DecRun

    Returns
    -------
    dict
        ``{"agents": [{"id", "final_localization_error", "mean_localization_error",
        "final_pursuit_error", "mean_pursuit_error"}], "final_gamma_spread",
        "final_gamma_rate_error", "omega_bar"}`` (means over runs; errors in m, γ in rad).
    """
    loc = np.mean([r.localization_errors for r in runs], axis=0)
    pur = np.mean([r.pursuit_errors for r in runs], axis=0)
    agents = [
        {
            "id": i + 1,
            "final_localization_error": float(loc[-1, i]),
            "mean_localization_error": float(loc[:, i].mean()),
            "final_pursuit_error": float(pur[-1, i]),
            "mean_pursuit_error": float(pur[:, i].mean()),
        }
        for i in range(loc.shape[1])
    ]
    return {
        "agents": agents,
        "final_gamma_spread": float(np.mean([np.ptp(r.gammas[-1]) for r in runs])),
        "final_gamma_rate_error": float(
            np.mean([np.abs(r.gamma_rates[-1] - spec.omega_bar).max() for r in runs])
        ),
        "omega_bar": spec.omega_bar,
    }


def write_pursuit_data(runs: Sequence[DecRun], summary: dict[str, Any], folder: Path) -> list[Path]:
    """``runs.npz`` (every array stacked over runs), ``agents.csv``, ``timeseries.csv``.

    Parameters
    ----------
    runs : sequence of DecRun
    summary : dict
        From :func:`summarize_pursuit`.
    folder : pathlib.Path
        Existing output folder.

    Returns
    -------
    list of pathlib.Path
    """
    npz = folder / "runs.npz"
    np.savez_compressed(
        npz,
        **{
            f.name: np.stack([getattr(r, f.name) for r in runs]) for f in dataclasses.fields(DecRun)
        },
    )
    agents_csv = folder / "agents.csv"
    with agents_csv.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(summary["agents"][0]))
        writer.writeheader()
        writer.writerows(summary["agents"])
    series = folder / "timeseries.csv"
    loc = np.mean([r.localization_errors for r in runs], axis=0)
    pur = np.mean([r.pursuit_errors for r in runs], axis=0)
    n = loc.shape[1]
    with series.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(
            ["time"]
            + [f"localization_error_{i + 1}" for i in range(n)]
            + [f"pursuit_error_{i + 1}" for i in range(n)]
        )
        for k in range(0, len(runs[0].times), 10):
            writer.writerow(
                [
                    f"{runs[0].times[k]:g}",
                    *(f"{v:.6g}" for v in loc[k]),
                    *(f"{v:.6g}" for v in pur[k]),
                ]
            )
    return [npz, agents_csv, series]


def write_pursuit_figures(runs: Sequence[DecRun], folder: Path) -> list[Path]:
    """``trajectories.png`` (run 0), ``errors.png`` and ``coordination.png``.

    Parameters
    ----------
    runs : sequence of DecRun
    folder : pathlib.Path
        Existing output folder.

    Returns
    -------
    list of pathlib.Path
    """
    run = runs[0]
    paths = []
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.plot(*run.target[:, :2].T, "k-", lw=2, label="target")
    for i in range(run.positions.shape[1]):
        ax.plot(*run.positions[:, i].T, lw=1, label=f"tracker {i + 1}")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=7)
    paths.append(_save(fig, folder / "trajectories.png"))
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for name, ax in zip(("pursuit_errors", "localization_errors"), axes, strict=True):
        values = np.mean([getattr(r, name) for r in runs], axis=0)
        for i in range(values.shape[1]):
            ax.plot(run.times, values[:, i], lw=1, label=f"tracker {i + 1}")
        ax.set_yscale("log")
        ax.set_ylabel(name.replace("_", " ") + " (m)")
        ax.legend(fontsize=7)
    axes[-1].set_xlabel("time (s)")
    paths.append(_save(fig, folder / "errors.png"))
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    axes[0].plot(run.times, run.gammas - run.gammas.mean(axis=1, keepdims=True), lw=1)
    axes[0].set_ylabel("γ_i − mean γ (rad)")
    axes[1].plot(run.times, run.gamma_rates, lw=1)
    axes[1].set_ylabel("dγ_i/dt (rad/s)")
    axes[1].set_xlabel("time (s)")
    paths.append(_save(fig, folder / "coordination.png"))
    return paths


def _save(fig: Any, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
