"""PNG figures of TDOA closed-loop runs: 3D trajectories, error and covariance norms, distance.

Built from the same :class:`~theory.tdoa.scenario.TdoaRun` objects the summary comes from
(seed 000 §4.4, Figs. 4.7–4.10); saved by :func:`theory.sim.figures.save_figure`.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from theory.sim.figures import save_figure
from theory.tdoa.scenario import TdoaRun

__all__ = ["write_figures"]


def write_figures(runs: Sequence[TdoaRun], folder: Path) -> list[Path]:
    """Write ``trajectories.png``, ``errors.png``, ``covariance.png``, ``distance.png``.

    Parameters
    ----------
    runs : sequence of TdoaRun
        Runs of one scenario; trajectories show run 0, curves the mean over runs.
    folder : pathlib.Path
        Output folder (must exist).

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    per_ping = (
        ("localization_errors", "localization error ‖p̄ᵢ − p‖ (m)", "errors.png"),
        ("cov_norms", "covariance norm ‖P̄ᵢ‖", "covariance.png"),
    )
    return [
        _trajectories(runs[0], folder / "trajectories.png"),
        *(
            _per_agent(
                runs[0].ping_times,
                np.mean([getattr(r, name) for r in runs], axis=0),
                label,
                folder / file,
                log=True,
            )
            for name, label, file in per_ping
        ),
        _per_agent(
            runs[0].fine_times,
            np.mean([r.distance for r in runs], axis=0).sum(axis=1, keepdims=True),
            "distance travelled by the network (m)",
            folder / "distance.png",
        ),
    ]


def _trajectories(run: TdoaRun, path: Path) -> Path:
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    ax.plot(*run.truth[:, :3].T, "k-", lw=2, label="target")
    for i in range(run.paths.shape[1]):
        ax.plot(*run.paths[:, i].T, lw=1, label=f"agent {i + 1}")
        ax.scatter(*run.paths[-1, i], s=12)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.legend(fontsize=6, loc="upper left")
    return save_figure(fig, path)


def _per_agent(
    times: np.ndarray, values: np.ndarray, label: str, path: Path, *, log: bool = False
) -> Path:
    fig, ax = plt.subplots(figsize=(7, 4))
    for i in range(values.shape[1]):
        name = f"agent {i + 1}" if values.shape[1] > 1 else "network"
        ax.plot(times, values[:, i], lw=1, label=name)
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(label)
    ax.legend(fontsize=6, ncol=2)
    ax.grid(True, alpha=0.3)
    return save_figure(fig, path)
