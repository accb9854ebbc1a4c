"""``kind: pf`` case files: a distributed TDOA particle-filter scenario (seed 002 §3.3).

The scenario's data (network, filter parameters, target DCRW) are defined here, so that loading a
case imports neither the filter nor scipy. Block fields (seed 002 §3.3.1's defaults where it
gives them, ours otherwise)::

    pf:
      nodes: [[x, y], ...]        # stationary node positions (the thesis gives none: state yours)
      edges: [[1, 2], ...]        # undirected, 1-based (N_i = neighbours of i)
      filters: [1, 4, 5]          # nodes running the PF (default: all)
      workspace: [[-60, 60], [-60, 60]]   # initial particles and target start, uniform
      particles: 100              # P
      share: 10                   # m (0: no consensus step)
      steps: 100                  # target moves (estimates at k = 0..steps)
      runs: 50                    # Monte Carlo runs
      seed: 2                     # base seed (run r uses seeds [seed, r, ·])
      noise_sigma: 1.0            # true TDOA noise std (m)
      filter_sigma: 1.0           # σ assumed in eq. (3.11) (default noise_sigma)
      target: {mu: 0, gamma: 0.7, kappa: 2, lambda: 3}   # the true DCRW
      model: dcrw                 # propagation: dcrw (true) | gaussian | learned
      exchange_weights: sender    # sender | local
      exchange_rounds: 1
      received_heading: sender    # sender | uniform
      uniform_max_step: 8.0       # the learner's uniform prior on step length
      learning: {min_samples: 10, gamma_max: 0.95, burn_in: 5}

``expect`` keys (every node id a filtering node; observed by the claims of
:mod:`theory.particle.experiments` and :mod:`theory.particle.pf_vs_ekf`)::

    converges: {1: true, 5: false}     # node id → whether its PF converges (Figs. 3.2–3.3)
    consensus_helps: 4                 # the consensus step lowers this node's error (Fig. 3.4)
    learned_beats_gaussian: 5          # learned model beats the Gaussian here (Fig. 3.5)
    learned_pdfs_centre: 5             # the paper's Fig. 3.6: no learned parameter is biased
    learned_biased: {5: [gamma, lambda]}   # node id → the biased parameters, in PARAM_NAMES order
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum
from functools import cached_property
from typing import Any, TypeVar

import numpy as np

from theory.core.case_file import Case, KindSpec
from theory.core.errors import CaseError
from theory.core.network import adjacency_from_edges
from theory.core.validation import (
    bounded_coordinates,
    check_count,
    check_estimate,
    check_keys,
    check_length,
    distinct_points,
    finite_matrix,
    finite_number,
    one_of,
    positive_int,
    positive_number,
    require,
)

__all__ = [
    "PARAM_NAMES",
    "PF",
    "DcrwParams",
    "ExchangeWeights",
    "Model",
    "PfConfig",
    "PfNetwork",
    "PfSpec",
    "ReceivedHeading",
    "check_pf_expect",
    "check_pf_runs",
    "check_pf_work",
    "parse_pf",
    "require_pf",
]


E = TypeVar("E", bound=StrEnum)


class Model(StrEnum):
    """The particles' propagation model (seed 002 §3.3.2)."""

    DCRW = "dcrw"  # the target's true DCRW
    GAUSSIAN = "gaussian"  # the thesis's mis-specified truncated normals
    LEARNED = "learned"  # refitted online from the node's own estimates


class ExchangeWeights(StrEnum):
    """The weight a received particle gets (a choice seed 002 §3.2.1 leaves open)."""

    SENDER = "sender"  # the normalised weight its sender gave it (the thesis's message)
    LOCAL = "local"  # re-weighted with the receiver's own likelihood


class ReceivedHeading(StrEnum):
    """The heading a received particle gets."""

    SENDER = "sender"  # the sender's, travelling with the particle
    UNIFORM = "uniform"  # drawn afresh (the thesis's message carries no heading)


PARAM_NAMES = ("mu", "gamma", "kappa", "lambda")
"""The DCRW parameters (μ, γ, κ, λ) of seed 002 eqs. (3.1)–(3.2), in the order fits report them."""


@dataclass(frozen=True)
class DcrwParams:
    """Wrapped-Cauchy turn ``(μ, γ)``, ``0 ≤ γ < 1``, and Weibull step ``(κ, λ)`` (seed 002
    eqs. (3.1)–(3.2))."""

    mu: float
    gamma: float
    kappa: float
    lam: float

    def __post_init__(self) -> None:
        if not (0.0 <= self.gamma < 1.0 and self.kappa > 0 and self.lam > 0):
            raise ValueError(
                f"DCRW parameters need 0 ≤ γ < 1, κ > 0, λ > 0; got γ={self.gamma!r}, "
                f"κ={self.kappa!r}, λ={self.lam!r}"
            )

    def as_array(self) -> np.ndarray:
        """``[μ, γ, κ, λ]`` in :data:`PARAM_NAMES` order."""
        return np.array([self.mu, self.gamma, self.kappa, self.lam])


@dataclass(frozen=True)
class PfConfig:
    """The distributed PF's parameters (seed 002 §3.2.1; §3.3.1: P = 100, m = 10).

    ``share`` is ``m`` (0 disables the consensus step), ``sigma`` the TDOA noise the filter
    assumes (eq. 3.11), ``estimate_fraction`` the share of particles averaged (eq. 3.13);
    ``exchange_rounds`` rounds of exchange per step let received particles travel on.
    """

    particles: int = 100
    share: int = 10
    sigma: float = 1.0
    estimate_fraction: float = 0.2
    exchange_weights: ExchangeWeights = ExchangeWeights.SENDER
    exchange_rounds: int = 1
    received_heading: ReceivedHeading = ReceivedHeading.SENDER

    def __post_init__(self) -> None:
        object.__setattr__(self, "exchange_weights", ExchangeWeights(self.exchange_weights))
        object.__setattr__(self, "received_heading", ReceivedHeading(self.received_heading))
        if not (0 < self.estimate_fraction <= 1 and self.sigma > 0 and self.particles >= 1):
            raise ValueError("need P ≥ 1, σ > 0 and 0 < estimate_fraction ≤ 1")
        if self.share < 0 or self.exchange_rounds < 1:
            raise ValueError("need m ≥ 0 and exchange_rounds ≥ 1")


@dataclass(frozen=True, eq=False)
class PfNetwork:
    """Node positions ``(N, 2)``, who hears whom (``hears[i, j]``: ``j ∈ N_i``) and the nodes
    running a filter (all 0-based; seed 002 §3.3.1 filters at nodes 1, 4 and 5)."""

    nodes: np.ndarray
    hears: np.ndarray
    filters: tuple[int, ...]

    @cached_property
    def filter_array(self) -> np.ndarray:
        """``(F,)`` the filtering nodes as an index array."""
        return np.asarray(self.filters, dtype=int)

    @cached_property
    def measurement_mask(self) -> np.ndarray:
        """``(F, N)`` mask of the TDOA components each filtering node measures."""
        return self.hears[list(self.filters)]

    @cached_property
    def filter_neighbours(self) -> np.ndarray:
        """``(F, D)`` filter-indices of each filter's filtering neighbours, padded with −1 last."""
        index = {node: f for f, node in enumerate(self.filters)}
        rows = [
            [index[j] for j in np.flatnonzero(self.hears[i]) if j in index] for i in self.filters
        ]
        width = max((len(r) for r in rows), default=0)
        return np.array([r + [-1] * (width - len(r)) for r in rows], dtype=int).reshape(
            len(rows), width
        )


@dataclass(frozen=True, eq=False)
class PfSpec:
    """A validated PF scenario (the module docstring gives the fields); ``workspace`` is
    ``[[xmin, xmax], [ymin, ymax]]``, ``learning`` overrides the online learner's guards."""

    network: PfNetwork
    config: PfConfig
    workspace: np.ndarray
    steps: int
    runs: int
    seed: int
    noise_sigma: float
    target: DcrwParams
    model: Model
    uniform_max_step: float
    learning: dict[str, float]


FIELDS = tuple(
    "nodes edges filters workspace particles share steps runs seed noise_sigma filter_sigma target"
    " model exchange_weights exchange_rounds received_heading uniform_max_step learning".split()
)
EXPECT_KEYS = (
    "converges",
    "consensus_helps",
    "learned_beats_gaussian",
    "learned_pdfs_centre",
    "learned_biased",
)
NODE_KEYS = ("consensus_helps", "learned_beats_gaussian", "learned_pdfs_centre")
TOLERANCE_KEYS = ("converge_tol", "diverge_tol", "improvement_tol")
LEARNING_FIELDS = ("min_samples", "gamma_max", "burn_in")
COINCIDENT_WHY = (
    " (the TDOA of seed 002 eq. (3.9) between coincident nodes is identically 0: it carries no"
    " information, so such a scene is refused as for kind tdoa)"
)


def parse_pf(block: Mapping[str, Any]) -> PfSpec:
    """Validate a ``pf:`` block (a :class:`CaseError` names any bad field)."""
    check_keys(block, FIELDS, "pf")
    raw_nodes = require(block, "nodes", "pf")
    check_length(raw_nodes, "agents", "pf.nodes")
    nodes = bounded_coordinates(finite_matrix(raw_nodes, "pf.nodes", cols=2), "pf.nodes")
    n = nodes.shape[0]
    if n < 2:
        raise CaseError("pf.nodes", "at least 2 nodes [x, y]", n)
    distinct_points(nodes, "pf.nodes", noun="node", why=COINCIDENT_WHY)
    hears = adjacency_from_edges(n, _edges(block.get("edges", []), n))
    filters = _ids(block.get("filters", list(range(1, n + 1))), n, "pf.filters")
    workspace = bounded_coordinates(
        finite_matrix(
            block.get("workspace", [[-60, 60], [-60, 60]]), "pf.workspace", rows=2, cols=2
        ),
        "pf.workspace",
    )
    if np.any(workspace[:, 1] <= workspace[:, 0]):
        raise CaseError(
            "pf.workspace", "[[xmin, xmax], [ymin, ymax]] with min < max", workspace.tolist()
        )
    noise = positive_number(block.get("noise_sigma", 1.0), "pf.noise_sigma")
    config = _config(block, noise, hears, filters)
    steps = check_count("steps", positive_int(block.get("steps", 100), "pf.steps"), "pf.steps")
    runs = check_count("runs", positive_int(block.get("runs", 50), "pf.runs"), "pf.runs")
    check_pf_work(config, len(filters), steps, runs, "pf.runs")
    return PfSpec(
        network=PfNetwork(nodes, hears, filters),
        config=config,
        workspace=workspace,
        steps=steps,
        runs=runs,
        seed=positive_int(block.get("seed", 0), "pf.seed", minimum=0),
        noise_sigma=noise,
        target=_target(block.get("target", {"mu": 0, "gamma": 0.7, "kappa": 2, "lambda": 3})),
        model=_choice(block, "model", Model.DCRW),
        uniform_max_step=positive_number(block.get("uniform_max_step", 8.0), "pf.uniform_max_step"),
        learning=_learning(block.get("learning", {})),
    )


def check_pf_work(config: PfConfig, filters: int, steps: int, runs: int, field: str) -> None:
    """Refuse a pf run whose memory or work would exceed :mod:`theory.core.validation`, naming
    ``field`` (``pf.particles`` when the particles take most memory).

    Each filter keeps, per particle, a position, a heading and a weight (seed 002 §3.2.1) plus
    the resampling and likelihood temporaries: 16 floats (128 B) are counted per particle; the
    error records add 16 B per filter, step and run. The work is one particle update per
    particle, filter, exchange round, step and run.
    """
    particles, rounds = config.particles, config.exchange_rounds
    states, records = 128.0 * filters * particles, 16.0 * filters * (steps + 1) * runs
    check_estimate(
        "memory_bytes",
        states + records,
        "pf.particles" if states >= records else field,
        f"128 B × {filters} filters × {particles:,} particles + 16 B × filters × steps × runs",
    )
    work = float(filters) * particles * rounds * (steps + 1) * runs
    what = f"{filters} filters × {particles:,} particles × {rounds} exchange rounds × steps × runs"
    check_estimate("work", work, field, what)


def require_pf(case: Case) -> PfSpec:
    """The spec of a ``kind: pf`` case; a :class:`CaseError` naming the kind otherwise."""
    if case.kind != "pf":
        raise CaseError(
            "kind", "pf (this command runs particle-filter cases)", case.kind, file=case.file
        )
    return case.spec


def check_pf_runs(case: Case, runs: int, field: str, *, file: str = "<data>") -> None:
    """Refuse ``runs`` Monte Carlo runs of a pf case past :mod:`theory.core.limits` (the count,
    then :func:`check_pf_work`), naming ``field`` in ``file``; :func:`require_pf` first."""
    spec = require_pf(case)
    try:
        check_count("runs", positive_int(runs, field), field)
        check_pf_work(spec.config, len(spec.network.filters), spec.steps, runs, field)
    except CaseError as error:
        raise error.in_file(file) from None


def _choice(block: Mapping[str, Any], key: str, default: E) -> E:
    kind = type(default)
    return kind(one_of(block.get(key, default.value), [e.value for e in kind], f"pf.{key}"))


def _config(block: Mapping[str, Any], noise: float, hears: np.ndarray, filters: tuple) -> PfConfig:
    particles = positive_int(block.get("particles", 100), "pf.particles", minimum=2)
    check_count("particles", particles, "pf.particles")
    share = positive_int(block.get("share", 10), "pf.share", minimum=0)
    degree = max((int(hears[i, list(filters)].sum()) for i in filters), default=0)
    if share * degree >= particles:
        raise CaseError(
            "pf.share",
            f"m with m·(max filter degree {degree}) < P = {particles}",
            share,
            hint="seed 002 §3.2.1 asks m < P/N.",
        )
    return PfConfig(
        particles=particles,
        share=share,
        sigma=positive_number(block.get("filter_sigma", noise), "pf.filter_sigma"),
        exchange_weights=_choice(block, "exchange_weights", ExchangeWeights.SENDER),
        exchange_rounds=positive_int(block.get("exchange_rounds", 1), "pf.exchange_rounds"),
        received_heading=_choice(block, "received_heading", ReceivedHeading.SENDER),
    )


def _edges(raw: object, n: int) -> np.ndarray:
    if not isinstance(raw, list) or not all(isinstance(e, list) and len(e) == 2 for e in raw):
        raise CaseError("pf.edges", "a list of pairs [i, j] of 1-based node ids", raw)
    pairs = [_ids(e, n, f"pf.edges[{k + 1}]") for k, e in enumerate(raw)]
    for k, (i, j) in enumerate(pairs):
        if i == j:
            raise CaseError(f"pf.edges[{k + 1}]", "two different nodes", [i + 1, j + 1])
    return np.asarray(pairs, dtype=int).reshape(-1, 2)


def _ids(raw: object, n: int, field: str) -> tuple[int, ...]:
    if not isinstance(raw, list) or not raw:
        raise CaseError(field, f"a non-empty list of node ids between 1 and {n}", raw)
    for value in raw:
        if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= n:
            raise CaseError(field, f"node ids between 1 and {n}", raw)
    if field == "pf.filters" and len(set(raw)) != len(raw):
        raise CaseError(field, "distinct node ids", raw)
    return tuple(v - 1 for v in raw)


def _target(raw: object) -> DcrwParams:
    block = check_keys(raw, PARAM_NAMES, "pf.target")
    mu = finite_number(require(block, "mu", "pf.target"), "pf.target.mu")
    gamma = positive_number(
        require(block, "gamma", "pf.target"), "pf.target.gamma", allow_zero=True
    )
    if gamma >= 1:
        raise CaseError("pf.target.gamma", "0 ≤ γ < 1", gamma)
    kappa = positive_number(require(block, "kappa", "pf.target"), "pf.target.kappa")
    lam = positive_number(require(block, "lambda", "pf.target"), "pf.target.lambda")
    return DcrwParams(float(mu), gamma, kappa, lam)


def _learning(raw: object) -> dict[str, float]:
    block = check_keys(raw, LEARNING_FIELDS, "pf.learning")
    out: dict[str, float] = {}
    if "min_samples" in block:
        out["min_samples"] = positive_int(block["min_samples"], "pf.learning.min_samples")
    if "burn_in" in block:
        out["burn_in"] = positive_int(block["burn_in"], "pf.learning.burn_in", minimum=0)
    if "gamma_max" in block:
        gamma_max = positive_number(block["gamma_max"], "pf.learning.gamma_max")
        if gamma_max >= 1:
            raise CaseError("pf.learning.gamma_max", "a clamp 0 < γ_max < 1", gamma_max)
        out["gamma_max"] = gamma_max
    return out


def check_pf_expect(spec: PfSpec, expect: Mapping[str, Any]) -> None:
    """Validate the values of a pf case's ``expect`` block: node ids are filtering nodes
    (1-based), ``converges`` maps them to true/false and ``learned_biased`` to parameter names of
    :data:`PARAM_NAMES`, in that order."""
    filters = sorted(f + 1 for f in spec.network.filters)
    node = f"a filtering node id (one of {filters})"
    for key, value in expect.items():
        field = f"expect.{key}"
        if key in NODE_KEYS and not _filtering_node(value, filters):
            raise CaseError(field, node, value)
        if key in ("converges", "learned_biased"):
            if not isinstance(value, Mapping) or not value:
                raise CaseError(field, f"a non-empty map from {node} to a value", value)
            for k, v in value.items():
                _check_node_entry(f"{field}.{k}", key, k, v, filters)


def _filtering_node(value: object, filters: list[int]) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value in filters


def _check_node_entry(field: str, key: str, node: object, value: object, filters: list) -> None:
    if not _filtering_node(node, filters):
        raise CaseError(field, f"a filtering node id (one of {filters}) as the key", node)
    if key == "converges" and not isinstance(value, bool):
        raise CaseError(field, "true or false", value)
    if key == "learned_biased" and not (
        isinstance(value, list)
        and all(v in PARAM_NAMES for v in value)
        and list(value) == [p for p in PARAM_NAMES if p in value]
    ):
        raise CaseError(
            field, f"a list of distinct names of {list(PARAM_NAMES)}, in that order", value
        )


PF = KindSpec(
    "pf",
    parse_pf,
    expect_keys=EXPECT_KEYS,
    tolerance_keys=TOLERANCE_KEYS,
    check_expect=check_pf_expect,
)
"""The ``pf`` case kind."""
