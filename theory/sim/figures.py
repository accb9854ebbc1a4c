"""Writing figures: the one place that lays out, saves and closes a matplotlib figure.

Every simulation draws its own figures in its domain package (e.g. :mod:`theory.tdoa.figures`,
:mod:`theory.particle.figures`) and saves them here.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

__all__ = ["save_figure"]


def save_figure(fig: Any, path: Path) -> Path:
    """Lay out ``fig``, write it to ``path`` as a 110-dpi PNG, close it and return ``path``.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : pathlib.Path
        The file to write.
    """
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
