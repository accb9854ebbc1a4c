"""``kind: dkf`` case files: a linear system watched by a network running a consensus Kalman filter.

Seed 000 ch. 5, eqs. (5.1)–(5.4) and App. C.3. Block fields::

    dkf:
      A: [[2, 0], [0, 2]]                 # n × n system matrix
      C: [[[1, 0]], [[0, 1]], [[1, 0], [0, 1]]]   # one p_i × n matrix per agent ([] = no sensor)
      W: [[0.24, 0.76, 0], ...]           # N × N row-stochastic, w_ii > 0, directed allowed
      Q: [[0.1, 0], [0, 0.1]]             # n × n process noise covariance, positive definite
      R: [[[0.1]], [[0.1]], [[0.1, 0], [0, 0.1]]]  # one p_i × p_i covariance per agent, pos. def.
      L: [[[2], [0]], ...]                # optional: one n × p_i gain per agent
      order: consensus-then-filter        # or filter-then-consensus (App. C.3)

An agent with ``C_i = []`` (zero rows) has no sensor; its ``R_i`` is ``[]`` and its gain
``L_i`` (if given) is ``[]`` too.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, NoReturn

import numpy as np

from theory.core.case_file import KindSpec
from theory.core.errors import CaseError
from theory.core.tolerances import WEIGHT_SUM_TOL
from theory.core.validation import (
    check_count,
    check_keys,
    check_length,
    finite_matrix,
    one_of,
    positive_definite,
    require,
    row_stochastic,
)

__all__ = ["DKF", "DkfSpec", "Order", "ch5_examples", "parse_dkf"]


class Order(StrEnum):
    """The order of the consensus and filter steps; ``Order(name)`` refuses any other name."""

    CONSENSUS_THEN_FILTER = "consensus-then-filter"  # eqs. (5.3)–(5.4), operator L (5.13)
    FILTER_THEN_CONSENSUS = "filter-then-consensus"  # App. C.3 eq. (C.4), operator J

    @classmethod
    def _missing_(cls, value: object) -> NoReturn:
        raise ValueError(f"order {value!r} is not one of {[order.value for order in cls]}")

    @property
    def operator(self) -> str:
        """The covariance operator of the order: ``L`` (eq. (5.13)) or ``J`` (App. C.3)."""
        return "L" if self is Order.CONSENSUS_THEN_FILTER else "J"


FIELDS = ("A", "C", "W", "Q", "R", "L", "order")
EXPECT_KEYS = (
    "s_detectable",
    "spectral_radius_B",
    "spectral_radius_L",
    "self_weight_ok",
    "paper_conditions_ok",
    "blind_set_condition_ok",
    "riccati_converges",
)
TOLERANCE_KEYS = ("rank_tol", "lmi_margin", "cert_tol", "value_tol")


@dataclass(frozen=True, eq=False)
class DkfSpec:
    """A validated problem: ``A`` (5.1), ``C_i`` (5.2; ``p_i = 0`` allowed), ``W`` (5.3),
    ``Q``, ``R_i``, the gains ``L_i`` of (5.4) when the case fixes them, and the order."""

    A: np.ndarray
    C: tuple[np.ndarray, ...]
    W: np.ndarray
    Q: np.ndarray
    R: tuple[np.ndarray, ...]
    L: tuple[np.ndarray, ...] | None
    order: Order

    @property
    def n(self) -> int:
        """State dimension."""
        return self.A.shape[0]

    @property
    def n_agents(self) -> int:
        """Number of agents ``N``."""
        return self.W.shape[0]


def parse_dkf(block: Mapping[str, Any], *, weight_sum_tol: float = WEIGHT_SUM_TOL) -> DkfSpec:
    """Validate a ``dkf:`` block (fields in the module docstring); :class:`CaseError` names
    any missing, unknown or invalid field."""
    check_keys(block, FIELDS, "dkf")
    raw_A, raw_W = require(block, "A", "dkf"), require(block, "W", "dkf")
    check_length(raw_A, "dkf_dimension", "dkf.A")
    check_length(raw_W, "agents", "dkf.W")
    A = finite_matrix(raw_A, "dkf.A")
    n = A.shape[0]
    if A.shape != (n, n) or n == 0:
        raise CaseError("dkf.A", "a non-empty square matrix", f"shape {A.shape}")
    W = finite_matrix(raw_W, "dkf.W")
    row_stochastic(W, "dkf.W", tol=weight_sum_tol)
    N = W.shape[0]
    check_count("dkf_dimension", N * n, "dkf.W")
    C = _per_agent(require(block, "C", "dkf"), "dkf.C", N, lambda c, f: _measurement(c, f, n))
    Q = positive_definite(
        finite_matrix(require(block, "Q", "dkf"), "dkf.Q", rows=n, cols=n), "dkf.Q"
    )
    R = _per_agent(
        require(block, "R", "dkf"), "dkf.R", N, lambda r, f: _covariance(r, f, C[_index(f)])
    )
    L = None
    if "L" in block:
        L = _per_agent(block["L"], "dkf.L", N, lambda g, f: _gain(g, f, n, C[_index(f)]))
    names = [order.value for order in Order]
    order = Order(one_of(block.get("order", names[0]), names, "dkf.order"))
    return DkfSpec(A, C, W, Q, R, L, order)


def _per_agent(raw: object, field: str, N: int, parse: Any) -> tuple[np.ndarray, ...]:
    if not isinstance(raw, list) or len(raw) != N:
        got = f"{len(raw)} entries" if isinstance(raw, list) else raw
        raise CaseError(field, f"a list of {N} matrices (one per agent, as W has {N} rows)", got)
    return tuple(parse(item, f"{field}[{i + 1}]") for i, item in enumerate(raw))


def _index(field: str) -> int:
    return int(field.rsplit("[", 1)[1].rstrip("]")) - 1


def _measurement(raw: object, field: str, n: int) -> np.ndarray:
    return finite_matrix(raw, field, cols=n, allow_empty_rows=True)


def _covariance(raw: object, field: str, C_i: np.ndarray) -> np.ndarray:
    p = C_i.shape[0]
    if p == 0:
        if raw != []:
            raise CaseError(field, "[] (the agent has no measurement rows)", raw)
        return np.zeros((0, 0))
    return positive_definite(finite_matrix(raw, field, rows=p, cols=p), field)


def _gain(raw: object, field: str, n: int, C_i: np.ndarray) -> np.ndarray:
    p = C_i.shape[0]
    if p == 0:
        if raw != []:
            raise CaseError(field, "[] (the agent has no measurement rows)", raw)
        return np.zeros((n, 0))
    return finite_matrix(raw, field, rows=n, cols=p)


def ch5_examples() -> dict[str, dict[str, Any]]:
    """Seed 000 §5.3 Examples 1–2: matrices, initial data, every W of the text, and the agents
    whose pair ``(A, C_i)`` is not detectable (``unstable_agents``, 0-based)."""
    return {
        "example 1": {
            "A": 2.0 * np.eye(2),
            "C": [np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.eye(2)],
            "R": [0.1 * np.eye(1), 0.1 * np.eye(1), 0.1 * np.eye(2)],
            "Q": 0.1 * np.eye(2),
            "x0": np.array([-15.0, 15.0]),
            "P0": 10.0 * np.eye(2),
            "W_g": [[0.24, 0.76, 0], [0.76, 0.24, 0], [0, 0, 1]],
            "W_c": [[0.25, 0.75, 0], [0.75, 0.25, 0], [0, 0, 1]],
            "W_b": [[0.26, 0.74, 0], [0.74, 0.26, 0], [0, 0, 1]],
            "unstable_agents": [0, 1],
        },
        "example 2": {
            "A": np.array([[0.8147, 0.8147, 0.2785], [0.9058, 0.9058, 0.5469], [0, 0, 0.9575]]),
            "C": [np.eye(3)[[i]] for i in range(3)],
            "R": [np.eye(1)] * 3,
            "Q": np.eye(3),
            "x0": np.array([-2.2691, -2.0143, 1.6173]),
            "P0": 100.0 * np.eye(3),
            "W_g": [[1, 0, 0], [0, 1, 0], [0.34, 0.34, 0.32]],
            "W_b": [[1, 0, 0], [0, 1, 0], [0.33, 0.33, 0.34]],
            "unstable_agents": [2],
        },
    }


DKF = KindSpec("dkf", parse_dkf, expect_keys=EXPECT_KEYS, tolerance_keys=TOLERANCE_KEYS)
"""The ``dkf`` case kind."""
