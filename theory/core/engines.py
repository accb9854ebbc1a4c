"""The simulation engines: compiled numba kernels or the NumPy reference (the tests' oracle), the
choice between them (:func:`resolve_engine`) and the decorator every kernel is compiled with
(:func:`compiled`); used by the seed 003 pursuit loop and the seed 002 online learner."""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any

from theory.core.errors import ENVIRONMENT, CaseError

__all__ = ["ENGINES", "ENGINE_SETTING", "NUMBA_MIN_RECORDS", "compiled", "resolve_engine"]

ENGINES = ("numba", "numpy")
"""The engines: compiled kernels (default) and the NumPy reference (the tests' oracle)."""

ENGINE_SETTING = "TRACKCERT_ENGINE"
"""The environment variable that chooses the engine when the caller does not."""

NUMBA_MIN_RECORDS = 3000
"""A job of fewer records (runs × 0.1 s records) than this runs on the NumPy engine by default.

Importing numba and loading the cached kernels (the run's and the DEKF replay's) costs a process
about 0.35 s of CPU once; the NumPy engine costs about 85 µs more a record in 2-D, 140–160 µs in
3-D, the replay included. Measured on the four Table cases, the whole ``trackcert simulate
--no-figures`` command at 1,000, 2,500 and 4,500 records in one sitting (docs/simulation.md, *A
short job runs on NumPy*): the break-even is about 4,500 records in 2-D and 2,500–3,000 in 3-D,
so below 3,000 the NumPy engine finishes first in every case. Both engines agree within the
integrator's tolerance (``tests/pursuit/test_kernels.py``)."""


def resolve_engine(
    engine: str | None = None, records: int | None = None, minimum: int = NUMBA_MIN_RECORDS
) -> str:
    """The simulation engine: ``engine``, else ``$TRACKCERT_ENGINE``, else ``"numba"`` — or
    ``"numpy"`` for a job of fewer than ``minimum`` ``records``.

    Parameters
    ----------
    engine : {"numba", "numpy"}, optional
        ``"numba"``: the compiled kernels; ``"numpy"``: the NumPy reference.
    records : int, optional
        The records the whole job integrates (runs × steps); unknown: the kernels' rule applies
        (``"numba"``).
    minimum : int, optional
        The job size from which the kernels pay for loading them: :data:`NUMBA_MIN_RECORDS`
        for a simulation, :data:`theory.pursuit.filter_metrics.REPLAY_MIN_STEPS` filter steps
        for the DEKF replay.

    Returns
    -------
    str
        One of :data:`ENGINES`.

    Raises
    ------
    CaseError
        If the engine (or the environment variable) names no engine.
    """
    if engine is not None:
        if engine not in ENGINES:
            raise CaseError("engine", " or ".join(map(repr, ENGINES)), engine)
        return engine
    chosen = os.environ.get(ENGINE_SETTING, "").strip()
    if not chosen:
        return "numpy" if records is not None and records < minimum else "numba"
    if chosen not in ENGINES:
        raise CaseError(ENGINE_SETTING, " or ".join(ENGINES), chosen, file=ENVIRONMENT)
    return chosen


def compiled(function: Callable) -> Any:
    """``numba.njit(cache=True)``, or without the on-disk cache when no cache folder is writable."""
    import numba

    try:
        return numba.njit(cache=True)(function)
    except RuntimeError:  # numba: "cannot cache function …: no locator available"
        return numba.njit(function)
