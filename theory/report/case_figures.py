"""Figures of a case for its report page, drawn from the case file alone: the geometry and the
communication graph of a tdoa, tdoa-sim or pf case (agents, links, target; seed 000 §4.2.2,
seed 002 §3.3), the communication digraph of a pursuit case (seed 003 §II-B), and the
eigenvalues of A and W of a dkf case against the unit circle (seed 000 eqs. (5.1), (5.3)).

:data:`DRAWINGS` maps a kind to its drawing; each returns ``(file name, caption)`` pairs of
figures written into a folder, as PNG without time stamps so that the same case gives the same
bytes.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from theory.core.case_file import Case

__all__ = ["DRAWINGS", "draw_case"]

_DPI = 90


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig: Any, folder: Path, name: str) -> str:
    fig.savefig(folder / name, dpi=_DPI, metadata={"Software": None})
    _pyplot().close(fig)
    return name


def _links(hears: np.ndarray) -> tuple[list[tuple[int, int]], bool]:
    """Links of an adjacency ``hears[r, s]`` (r receives from s), and whether it is directed."""
    directed = not np.array_equal(hears, hears.T)
    pairs = [(int(s), int(r)) for r, s in np.argwhere(hears) if r != s and (directed or s < r)]
    return pairs, directed


def _scene(
    ax: Any,
    points: np.ndarray,
    hears: np.ndarray | None,
    axes: tuple[int, int],
    target: np.ndarray | None,
    labels: tuple[str, str],
) -> None:
    """Agents (numbered from 1), links (arrows when directed) and the target on ``axes``."""
    i, j = axes
    if hears is not None:
        pairs, directed = _links(hears)
        for s, r in pairs:
            start, end = points[s, [i, j]], points[r, [i, j]]
            style = "-|>" if directed else "-"
            ax.annotate(
                "",
                end,
                start,
                arrowprops={
                    "arrowstyle": style,
                    "color": "#8a94a6",
                    "lw": 1.0,
                    "shrinkA": 6,
                    "shrinkB": 6,
                },
            )
    ax.scatter(points[:, i], points[:, j], s=40, color="#1f5fa8", zorder=3, label="agents")
    for k, p in enumerate(points):
        ax.annotate(str(k + 1), (p[i], p[j]), textcoords="offset points", xytext=(5, 5), fontsize=8)
    if target is not None:
        ax.scatter(
            [target[i]], [target[j]], marker="*", s=160, color="#b3261e", zorder=4, label="target"
        )
    shown = points[:, [i, j]] if target is None else np.vstack([points[:, [i, j]], target[[i, j]]])
    lo, hi = shown.min(axis=0), shown.max(axis=0)
    pad = max(0.15 * float((hi - lo).max()), 1.0)  # one agent, or all on a line: still a frame
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_xlabel(f"{labels[0]} (m)")
    ax.set_ylabel(f"{labels[1]} (m)")
    ax.set_aspect("equal", adjustable="box")
    ax.grid(True, alpha=0.3)


def _geometry(
    points: np.ndarray,
    hears: np.ndarray | None,
    target: np.ndarray | None,
    folder: Path,
    caption: str,
) -> list[tuple[str, str]]:
    """One panel (2-D) or the x–y and x–z projections (3-D) of a scene."""
    plt = _pyplot()
    views = (
        [((0, 1), ("x", "y"))]
        if points.shape[1] == 2
        else [((0, 1), ("x", "y")), ((0, 2), ("x", "z"))]
    )
    fig, axes = plt.subplots(1, len(views), figsize=(4.2 * len(views), 4.0), squeeze=False)
    for ax, (pair, labels) in zip(axes[0], views, strict=True):
        _scene(ax, points, hears, pair, target, labels)
    axes[0][0].legend(loc="best", fontsize=8)
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.12, top=0.93, wspace=0.3)
    return [(_save(fig, folder, "geometry.png"), caption)]


def _tdoa(case: Case, folder: Path) -> list[tuple[str, str]]:
    """seed 000 §4.2.2: agents, links and target at the first step."""
    spec = case.spec
    rule = f"links closer than {spec.comm_range:g} m" if spec.comm_range else "links as given"
    caption = (
        f"Geometry and communication graph at step 1 of {spec.steps} ({rule}; "
        f"{'directed' if spec.directed else 'undirected'}); target ★."
    )
    return _geometry(spec.agents[0], spec.hears[0], spec.target[0], folder, caption)


def _tdoa_sim(case: Case, folder: Path) -> list[tuple[str, str]]:
    """seed 000 §4.4: the initial formation, links and target."""
    spec = case.spec
    hears = spec.hears
    if hears is None:
        from theory.core.network import adjacency_from_range

        hears = adjacency_from_range(spec.agents, spec.comm_range)
    rule = f"links closer than {spec.comm_range:g} m" if spec.comm_range else "fixed links"
    caption = f"Initial agents, communication graph ({rule}) and target ★."
    return _geometry(spec.agents, hears, spec.target[:3], folder, caption)


def _pf(case: Case, folder: Path) -> list[tuple[str, str]]:
    """seed 002 §3.3: the nodes and their links."""
    network = case.spec.network
    filters = ", ".join(str(i + 1) for i in network.filters)
    caption = f"Nodes and links; nodes {filters} run a particle filter."
    return _geometry(network.nodes, network.hears, None, folder, caption)


def _pursuit(case: Case, folder: Path) -> list[tuple[str, str]]:
    """seed 003 §II-B: tracker i receives from j when a_ij = 1, drawn j → i."""
    plt = _pyplot()
    n = len(case.spec.trackers)
    angles = 2 * np.pi * np.arange(n) / max(n, 1) + np.pi / 2
    points = np.column_stack([np.cos(angles), np.sin(angles)])
    fig, ax = plt.subplots(figsize=(3.6, 3.6))
    hears = case.spec.adjacency.astype(bool)
    hears = hears | hears.T if n == 1 else hears
    _scene(ax, points, hears, (0, 1), None, ("", ""))
    ax.set_xlabel("")
    ax.set_ylabel("")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title("communication digraph (s → r: r receives)", fontsize=9)
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.12, top=0.93, wspace=0.3)
    caption = f"The {n} trackers' communication digraph (a_ij = 1: i receives from j)."
    return [(_save(fig, folder, "graph.png"), caption)]


def _dkf(case: Case, folder: Path) -> list[tuple[str, str]]:
    """seed 000 eqs. (5.1), (5.3): the spectra that decide stability and consensus."""
    plt = _pyplot()
    spec = case.spec
    fig, ax = plt.subplots(figsize=(4.2, 4.0))
    circle = np.exp(1j * np.linspace(0, 2 * np.pi, 361))
    ax.plot(circle.real, circle.imag, color="#8a94a6", lw=1, label="unit circle")
    eig_a, eig_w = np.linalg.eigvals(spec.A), np.linalg.eigvals(spec.W)
    ax.scatter(eig_a.real, eig_a.imag, marker="x", s=60, color="#b3261e", label="eig(A)")
    ax.scatter(
        eig_w.real,
        eig_w.imag,
        marker="o",
        s=60,
        facecolors="none",
        edgecolors="#1f5fa8",
        label="eig(W)",
    )
    ax.set_xlabel("Re λ")
    ax.set_ylabel("Im λ")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.subplots_adjust(left=0.18, right=0.97, bottom=0.12, top=0.93, wspace=0.3)
    caption = (
        "Eigenvalues of A (modes outside the unit circle are unstable) and of the "
        "consensus weights W."
    )
    return [(_save(fig, folder, "eigenvalues.png"), caption)]


DRAWINGS: dict[str, Callable[[Case, Path], list[tuple[str, str]]]] = {
    "tdoa": _tdoa,
    "tdoa-sim": _tdoa_sim,
    "pf": _pf,
    "pursuit": _pursuit,
    "dkf": _dkf,
}
"""Case kind → its drawing (figures written into a folder: (file name, caption) pairs)."""


def draw_case(case: Case, folder: Path) -> list[tuple[str, str]]:
    """The figures of ``case`` written into ``folder`` (none for a kind without a drawing)."""
    drawing = DRAWINGS.get(case.kind)
    if drawing is None:
        return []
    folder.mkdir(parents=True, exist_ok=True)
    return drawing(case, folder)
