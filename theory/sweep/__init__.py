"""Parameter sweeps of a case (``trackcert sweep``, ``docs/sweep.md``).

:mod:`~theory.sweep.grid` parses ``--param`` and ``--link``, expands the grid and sets the swept
fields; :mod:`~theory.sweep.points` judges and simulates one point; :mod:`~theory.sweep.run` runs
the grid on the task engine; :mod:`~theory.sweep.outputs` writes ``sweep.csv``, ``sweep.json`` and
``sweep.png``.
"""

from __future__ import annotations

__all__: list[str] = []
