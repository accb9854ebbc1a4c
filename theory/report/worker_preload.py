"""Preload for Dask workers started by hand: ``dask worker ADDRESS --preload`` this module.

``dask worker tcp://HOST:8786 --preload theory.report.worker_preload --nthreads 1``.

A local cluster's workers are forked from a forkserver that has already imported every claim
module (:func:`theory.core.parallel.engine`, ``preload``). Workers started apart with ``dask
worker`` are spawned, and each would import those modules (about 3 s of CPU) inside its first
check, where the import shows up in that check's time. With this preload each worker imports
them when it starts, before it accepts a task, so that a cluster kept running between commands
pays the imports once and the checks' times measure the checks (docs/parallel.md, *Running on a
cluster*).
"""

from __future__ import annotations

import importlib
from typing import Any

from theory.report.tasks import worker_modules

__all__ = ["dask_setup"]


def dask_setup(worker: Any) -> None:
    """Import every module a report task needs (Dask calls this as the worker starts).

    Parameters
    ----------
    worker : distributed.Worker
        The starting worker (unused: the imports are the process's).
    """
    for module in worker_modules():
        importlib.import_module(module)
