"""Figures of the distributed PF (seed 002 Figs. 3.1–3.6): errors, particle clouds, learned PDFs.

Built only from :class:`~theory.particle.experiments.MonteCarlo` results; matplotlib with the Agg
backend.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from theory.particle.case import PfSpec
from theory.particle.dcrw import weibull_logpdf, wrapped_cauchy_logpdf
from theory.particle.experiments import MonteCarlo
from theory.sim.figures import save_figure

__all__ = ["plot_errors", "plot_learned_pdfs", "plot_particles", "write_figures"]


def plot_errors(mc: MonteCarlo, spec: PfSpec, path: Path) -> Path:
    """Mean norm error ``E_i(k)`` (eq. 3.20) per node with the 10–90 % band over runs.

    Parameters
    ----------
    mc : MonteCarlo
        The runs.
    spec : PfSpec
        Their scenario.
    path : Path
        PNG file to write.
    """
    fig, ax = plt.subplots(figsize=(6, 3.5))
    steps = np.arange(mc.errors.shape[1])
    for f, node in enumerate(spec.network.filters):
        low, high = np.quantile(mc.errors[:, :, f], [0.1, 0.9], axis=0)
        (line,) = ax.plot(steps, mc.errors[:, :, f].mean(0), label=f"node {node + 1}")
        ax.fill_between(steps, low, high, color=line.get_color(), alpha=0.15)
    ax.set(
        xlabel="time step k",
        ylabel="norm error (m)",
        yscale="log",
        title=f"{mc.errors.shape[0]} runs, model {mc.model}, m = {mc.share}, seed {mc.seed}",
    )
    ax.legend()
    return save_figure(fig, path)


def plot_particles(mc: MonteCarlo, spec: PfSpec, path: Path) -> Path:
    """Run 0's weighted particle clouds at the snapshot steps, with nodes, links and target.

    Parameters
    ----------
    mc, spec, path :
        As for :func:`plot_errors` (``mc.snapshots`` must be filled).
    """
    steps = sorted(mc.snapshots)
    fig, axes = plt.subplots(
        1, max(1, len(steps)), figsize=(4 * max(1, len(steps)), 4), squeeze=False
    )
    nodes = spec.network.nodes
    for ax, k in zip(axes[0], steps, strict=False):
        for i, j in np.argwhere(np.triu(spec.network.hears)):
            ax.plot(*nodes[[i, j]].T, color="0.6", lw=0.8)
        ax.scatter(*nodes.T, marker="D", color="k", s=25)
        for f, node in enumerate(spec.network.filters):
            cloud = mc.snapshots[k][f]
            ax.scatter(
                cloud[:, 0],
                cloud[:, 1],
                s=4 + 400 * cloud[:, 2],
                alpha=0.5,
                label=f"node {node + 1}",
            )
        ax.scatter(*mc.paths[0, k], marker="o", color="red", s=40, label="target")
        ax.set(title=f"k = {k}", aspect="equal")
    axes[0][0].legend(fontsize=7)
    return save_figure(fig, path)


def plot_learned_pdfs(mc: MonteCarlo, spec: PfSpec, path: Path) -> Path:
    """Learned turning-angle and step-length PDFs (every run, per node) against the true ones.

    Parameters
    ----------
    mc, spec, path :
        As for :func:`plot_errors` (``mc.learned`` must be filled).
    """
    fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.5))
    phi = np.linspace(-np.pi, np.pi, 361)
    delta = np.linspace(1e-3, 4 * spec.target.lam, 300)
    for f, node in enumerate(spec.network.filters):
        faint = {"color": f"C{f}", "alpha": 0.15, "lw": 0.7}
        for mu, gamma, kappa, lam in mc.learned[:, f]:
            if np.isfinite(mu):
                left.plot(phi, np.exp(wrapped_cauchy_logpdf(phi, mu, gamma)), **faint)
                right.plot(delta, np.exp(weibull_logpdf(delta, kappa, lam)), **faint)
        left.plot([], [], color=faint["color"], label=f"learned, node {node + 1}")
    true = spec.target
    left.plot(phi, np.exp(wrapped_cauchy_logpdf(phi, true.mu, true.gamma)), "k", lw=2, label="true")
    right.plot(delta, np.exp(weibull_logpdf(delta, true.kappa, true.lam)), "k", lw=2)
    left.set(xlabel="turning angle φ (rad)", ylabel="pdf", title="eq. (3.1)")
    right.set(xlabel="step length δ (m)", title="eq. (3.2)")
    left.legend(fontsize=7)
    return save_figure(fig, path)


def write_figures(mc: MonteCarlo, spec: PfSpec, folder: Path, stem: str) -> list[str]:
    """Every figure that applies to ``mc``, as PNG files in ``folder``; returns their paths.

    Parameters
    ----------
    mc : MonteCarlo
        The runs.
    spec : PfSpec
        Their scenario.
    folder : Path
        Created if missing.
    stem : str
        File-name prefix (the case name).
    """
    folder.mkdir(parents=True, exist_ok=True)
    paths = [plot_errors(mc, spec, folder / f"{stem}-errors.png")]
    if mc.snapshots:
        paths.append(plot_particles(mc, spec, folder / f"{stem}-particles.png"))
    if mc.learned is not None:
        paths.append(plot_learned_pdfs(mc, spec, folder / f"{stem}-learned-pdfs.png"))
    return [str(p) for p in paths]
