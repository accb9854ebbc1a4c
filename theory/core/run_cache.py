"""Results shared by the claims of one case within one run, held explicitly (no global memo).

Several claims of one case often need the same expensive object: the consensus filter's LMI
solution and Riccati iterations, a pursuit case's closed-loop simulation, a particle filter's
Monte Carlo runs. A claim whose ``run`` accepts the keyword ``cache`` receives the
:class:`RunCache` of the case from the report (:mod:`theory.report.tasks`): the report runs all
such claims of one case in one task, one after the other, with one cache, and throws the cache
away when the task ends. Called without one (``cache=None``, e.g. from a command or a test), a
claim computes for itself: :func:`shared` makes that one line.

Keys are plain values naming the computation and its parameters (``("riccati", steps)``), never
object identities, so a cache cannot hand a result computed for one case to another.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from theory.core.parallel import TaskRunner

__all__ = ["RunCache", "shared"]

T = TypeVar("T")


class RunCache:
    """Values computed once per case and run, by key.

    Parameters
    ----------
    runner : TaskRunner, optional
        An open engine on which a computation made of independent runs may spread them (e.g.
        ``trackcert pf``'s Monte Carlo variants); ``None`` (inside a report task): serially.

    Attributes
    ----------
    runner : TaskRunner or None
        As given.
    hits, misses : int
        How many :meth:`get` calls found their key, and how many computed it.
    """

    def __init__(self, runner: TaskRunner | None = None) -> None:
        self.runner = runner
        self._values: dict[Hashable, Any] = {}
        self.hits = 0
        self.misses = 0

    def get(self, key: Hashable, compute: Callable[[], T]) -> T:
        """The value stored under ``key``, computed by ``compute()`` the first time.

        Parameters
        ----------
        key : hashable
            Names the computation and its parameters (plain values).
        compute : callable
            Called without arguments when ``key`` is not stored yet.

        Returns
        -------
        object
            The stored value (shared: callers must not mutate it).
        """
        if key in self._values:
            self.hits += 1
            return self._values[key]
        self.misses += 1
        value = compute()
        self._values[key] = value
        return value


def shared(cache: RunCache | None, key: Hashable, compute: Callable[[], T]) -> T:
    """``cache.get(key, compute)``, or ``compute()`` when there is no cache.

    Parameters
    ----------
    cache : RunCache or None
        The case's cache (the keyword a claim's ``run`` received).
    key : hashable
        As for :meth:`RunCache.get`.
    compute : callable
        As for :meth:`RunCache.get`.

    Returns
    -------
    object
    """
    return compute() if cache is None else cache.get(key, compute)
