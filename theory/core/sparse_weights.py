"""A network's links and consensus weights held by their entries: ``O(N + E)``, no ``N × N`` array.

``SparseWeights`` is what a ``tdoa`` case keeps per time step (:mod:`theory.tdoa.case`) and what
``trackcert topology`` reads: the TDOA rows, the components and the per-agent verdicts need only
the links; a dense ``W`` is made per component where a dense method needs one
(:meth:`SparseWeights.block`), or whole for the commands that want it (:meth:`SparseWeights.dense`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from theory.core.network import link_component_labels, metropolis_entries, uniform_entries

__all__ = ["SparseWeights"]


@dataclass(frozen=True, eq=False)
class SparseWeights:
    """Row-stochastic weights ``W`` of ``n`` agents by their entries.

    ``W[receiver[k], sender[k]] = weight[k] > 0`` (agent ``receiver[k]`` hears ``sender[k]``),
    sorted by receiver then sender, no diagonal entries among them; ``diagonal[i] = w_ii``.
    The links are the off-diagonal support of ``W`` (seed 000 §4.2.2: ``w_ij > 0`` exactly
    when ``i`` hears ``j``).
    """

    n: int
    receiver: np.ndarray
    sender: np.ndarray
    weight: np.ndarray
    diagonal: np.ndarray

    @classmethod
    def named(cls, n: int, receiver: np.ndarray, sender: np.ndarray, rule: str) -> SparseWeights:
        """The ``metropolis`` or ``uniform`` weights (:mod:`theory.core.network`) on the links
        ``(receiver, sender)`` (each undirected link listed in both directions)."""
        receiver, sender = _sorted_links(n, receiver, sender)
        entries = {"metropolis": metropolis_entries, "uniform": uniform_entries}[rule]
        weight, diagonal = entries(n, receiver, sender)
        return cls(n, receiver, sender, weight, diagonal)

    @classmethod
    def from_dense(cls, W: np.ndarray) -> SparseWeights:
        """The entries of a dense ``W`` (its positive off-diagonal entries are the links)."""
        W = np.asarray(W, dtype=float)
        support = W > 0
        np.fill_diagonal(support, False)
        receiver, sender = np.nonzero(support)
        return cls(W.shape[0], receiver, sender, W[receiver, sender], np.diag(W).copy())

    @property
    def count(self) -> int:
        """Number of links ``E`` (directed: each undirected link counts twice)."""
        return int(self.receiver.size)

    def symmetric(self) -> bool:
        """Whether every link has its reverse (sorted keys compared: ``O(E log E)``)."""
        forward = np.sort(self.receiver * self.n + self.sender)
        backward = np.sort(self.sender * self.n + self.receiver)
        return bool(np.array_equal(forward, backward))

    def component_labels(self) -> np.ndarray:
        """Each agent's weakly connected component, labelled by its smallest agent."""
        return link_component_labels(self.n, self.receiver, self.sender)

    def block(self, rows: np.ndarray | list[int], cols: np.ndarray | list[int] | None = None):
        """The dense sub-matrix ``W[rows, cols]`` (``cols`` defaults to ``rows``)."""
        rows = np.asarray(rows, dtype=np.int64)
        cols = rows if cols is None else np.asarray(cols, dtype=np.int64)
        where_row = np.full(self.n, -1)
        where_row[rows] = np.arange(rows.size)
        where_col = np.full(self.n, -1)
        where_col[cols] = np.arange(cols.size)
        out = np.zeros((rows.size, cols.size))
        r, c = where_row[self.receiver], where_col[self.sender]
        keep = (r >= 0) & (c >= 0)
        out[r[keep], c[keep]] = self.weight[keep]
        r, c = where_row, where_col
        on = (r >= 0) & (c >= 0)
        out[r[on], c[on]] = self.diagonal[on]
        return out

    def restrict(self, part: np.ndarray | list[int]) -> SparseWeights:
        """The weights among the agents ``part`` (sorted; a component: no link leaves it),
        renumbered ``0 … len(part) − 1``."""
        part = np.asarray(part, dtype=np.int64)
        local = np.full(self.n, -1)
        local[part] = np.arange(part.size)
        keep = (local[self.receiver] >= 0) & (local[self.sender] >= 0)
        return SparseWeights(
            int(part.size),
            local[self.receiver[keep]],
            local[self.sender[keep]],
            self.weight[keep],
            self.diagonal[part],
        )

    def reverse_weights(self) -> np.ndarray | None:
        """``w_ji`` for each entry ``w_ij`` (in entry order), or ``None`` if a link has no
        reverse."""
        keys = self.receiver * self.n + self.sender  # sorted: receiver, then sender
        where = np.searchsorted(keys, self.sender * self.n + self.receiver)
        where = np.minimum(where, max(keys.size - 1, 0))
        if keys.size and not np.array_equal(keys[where], self.sender * self.n + self.receiver):
            return None
        return self.weight[where]

    def dense(self) -> np.ndarray:
        """``W`` as an ``n × n`` array."""
        return self.block(np.arange(self.n))

    def hears(self) -> np.ndarray:
        """The ``n × n`` boolean "hears" matrix (the off-diagonal support of ``W``)."""
        out = np.zeros((self.n, self.n), dtype=bool)
        out[self.receiver, self.sender] = True
        return out

    def key(self) -> bytes:
        """Bytes equal for equal ``W`` (to group the steps of a trajectory by network)."""
        return b"".join(
            np.ascontiguousarray(a).tobytes()
            for a in (self.receiver, self.sender, self.weight, self.diagonal)
        )


def _sorted_links(n: int, receiver: np.ndarray, sender: np.ndarray) -> tuple[np.ndarray, ...]:
    """The links sorted by receiver then sender, as int64 arrays."""
    receiver = np.asarray(receiver, dtype=np.int64)
    sender = np.asarray(sender, dtype=np.int64)
    order = np.argsort(receiver * n + sender, kind="stable")
    return receiver[order], sender[order]
