"""Parameter sweeps of a case (``trackcert sweep``, ``docs/sweep.md``).

:mod:`~theory.sweep.grid` parses ``--param PATH=SPEC`` and expands the grid,
:mod:`~theory.sweep.paths` finds and sets the swept fields, :mod:`~theory.sweep.kinds` holds
each kind's verdict and what its simulation is compared with, :mod:`~theory.sweep.points`
evaluates one point, :mod:`~theory.sweep.run` runs the grid on the task engine and
:mod:`~theory.sweep.outputs` writes ``sweep.csv``, ``sweep.json`` and ``sweep.png``.
"""

from __future__ import annotations

__all__: list[str] = []
