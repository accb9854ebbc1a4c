"""Theory ⇄ simulation for the averaged TDOA filter as falsifiable wordings (``trackcert falsify``).

Seed 000 §4.2.2 (after eq. (4.35)): "to ensure the convergence of the networked filter, one has
to ensure that the networked system is observable", and Thm 4.2.3 gives the topology condition.
Each example is a 3D :class:`~theory.tdoa.strategies.TdoaScene` (public strategies, families
``general`` and ``coplanar``, 2–6 receivers) with an undirected network drawn by
:func:`~theory.tdoa.strategies.networks` (connected or not) and Metropolis weights, the noises of
seed 000 §4.4 (``T = 1``, ``P_0 = 100 I``, ``Q = 0.01 I``, ``R_i = I``), and the averaged filter
run by the engine's functions on the frozen geometry for :data:`HORIZON` pings
(:func:`theory.tdoa.averaged_bounds.linearized_run`). What is checked, and why it holds, is the
docstring of :mod:`theory.tdoa.averaged_bounds`:

``corrected``
    for every agent and ping, CRB floor ⪯ mean-square error ⪯ filter covariance; every
    component whose stacked Jacobian has exact rank 3 gets a fixed-gain certificate from the
    gains of ping :data:`BURN_IN` and the run stays below its bound ``Z`` up to :data:`HORIZON`;
    every other component learns nothing along ``ker G_C`` (the three second moments there equal
    the prior's propagation, which grows like ``p_0 (kT)²``).
``paper``
    the averaged filter's error is bounded (certified) iff the agent's component has at least 4
    connected agents that are not coplanar (Thm 4.2.3's wording). False: coplanar receivers
    with the target off their plane localize (rank 3), and agents on a cone through the target
    do not.

Examples are not counted (the property holds vacuously) when a component's floating-point rank
disagrees with its exact rank or its nonzero singular values spread by more than
``1/MIN_CONDITIONING`` (the burn-in is then too short for the certificate, not a
counterexample).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from hypothesis import strategies as st

from theory.core.network import metropolis_weights
from theory.core.observability import RANK_TOL, numeric_rank
from theory.core.tolerances import KERNEL_RTOL, MIN_CONDITIONING
from theory.falsify import Property, register_property
from theory.tdoa.averaged_bounds import (
    PSD_RTOL,
    ComponentGeometry,
    FrozenGeometry,
    LinearizedRun,
    analyze_components,
    certify_boundedness,
    linearized_run,
    prior_propagation,
    psd_violation,
)
from theory.tdoa.case import TdoaSpec
from theory.tdoa.strategies import TdoaScene, networks, tdoa_scenes

__all__ = [
    "BURN_IN",
    "HORIZON",
    "MIN_CONDITIONING",
    "NOISES",
    "ComponentVerdict",
    "ExampleVerdict",
    "FilterExample",
    "check_example",
    "example_from_spec",
    "filter_example_case",
    "filter_examples",
]

BURN_IN = 40
"""Ping whose gains are frozen for the boundedness certificate."""
HORIZON = 2 * BURN_IN
"""Pings run; the certified bound is checked on ``BURN_IN … HORIZON``."""
NOISES = {"T": 1.0, "p0": 100.0, "q": 0.01, "r": 1.0}
"""Seed 000 §4.4: ping period, ``P_0 = p_0 I``, ``Q = q I``, ``R_i = r I``."""


@dataclass(frozen=True, eq=False)
class FilterExample:
    """A scene and the network its receivers form.

    Attributes
    ----------
    scene : TdoaScene
        Target (where the Jacobians are evaluated) and receivers.
    hears : ndarray of bool, shape (N, N)
        Undirected network.
    """

    scene: TdoaScene
    hears: np.ndarray

    def geometry(self) -> FrozenGeometry:
        """The frozen geometry with Metropolis weights and :data:`NOISES`."""
        return FrozenGeometry(
            self.scene.agents,
            self.scene.target,
            self.hears,
            metropolis_weights(self.hears),
            **NOISES,
        )


@dataclass(frozen=True)
class ComponentVerdict:
    """What one component shows.

    Attributes
    ----------
    agents : tuple of int
        1-based agents.
    exact_rank : int
        Rank of the stacked position Jacobian ``G_C``.
    observable : bool
        ``exact_rank`` is the dimension 3.
    paper_condition : bool
        ≥ 4 agents, not coplanar (Thm 4.2.3's wording).
    certified : bool or None
        Observable components: the fixed-gain certificate is valid and the run stays below it.
    decay : float or None
        The certificate's bound on ``ρ(𝓛)``.
    mse_bound : float or None
        ``max_i tr Z_i`` over the position block (m²): bound on the position MSE after the
        burn-in.
    mse_limit : float or None
        ``max_i tr P_∞,i`` over the position block (m²): bound on its limit superior.
    crb_floor : float
        ``max_i tr P_C(HORIZON)`` over the position block (m²).
    kernel_deviation : float or None
        Unobservable components: largest relative gap between ``Π`` and the three second
        moments along ``ker G_C``.
    """

    agents: tuple[int, ...]
    exact_rank: int
    observable: bool
    paper_condition: bool
    certified: bool | None
    decay: float | None
    mse_bound: float | None
    mse_limit: float | None
    crb_floor: float
    kernel_deviation: float | None


@dataclass(frozen=True)
class ExampleVerdict:
    """The checks of the corrected wording on one example.

    Attributes
    ----------
    counted : bool
        False when some component is numerically unsafe (module docstring).
    crb_violation, consistency_violation : float
        ``max psd_violation(P_C, Σ_ii)`` and ``max psd_violation(Σ_ii, P̄_i)`` over agents and
        pings (``≤ PSD_RTOL`` holds).
    components : list of ComponentVerdict
        Per component.
    """

    counted: bool
    crb_violation: float = 0.0
    consistency_violation: float = 0.0
    components: list[ComponentVerdict] = field(default_factory=list)

    @property
    def holds(self) -> bool:
        """Whether the corrected wording holds (vacuously when not counted)."""
        if not self.counted:
            return True
        sandwich = max(self.crb_violation, self.consistency_violation) <= PSD_RTOL
        return sandwich and all(
            c.certified if c.observable else c.kernel_deviation <= KERNEL_RTOL
            for c in self.components
        )


@st.composite
def filter_examples(draw: st.DrawFn, *, max_agents: int = 6) -> FilterExample:
    """3D scenes (families ``general``, ``coplanar``) of 2 to ``max_agents`` receivers with an
    undirected network, connected or not."""
    family = draw(st.sampled_from(("general", "coplanar")))
    scene = draw(tdoa_scenes(dim=3, min_agents=2, max_agents=max_agents, family=family))
    n = len(scene.agents)
    return FilterExample(scene, draw(networks(min_agents=n, max_agents=n, connected=None)))


def check_example(example: FilterExample) -> ExampleVerdict:
    """Run the averaged filter on ``example``'s frozen geometry and check the corrected wording.

    Parameters
    ----------
    example : FilterExample
        Scene and network.

    Returns
    -------
    ExampleVerdict

    References
    ----------
    seed 000, §4.2.2, Thm 4.2.3, App. A (Thm A.1.5); :mod:`theory.tdoa.averaged_bounds`.
    """
    geometry = example.geometry()
    parts = analyze_components(geometry)
    if not all(_safe(part) for part in parts):
        return ExampleVerdict(counted=False)
    run = linearized_run(geometry, HORIZON)
    prior = prior_propagation(geometry, HORIZON)
    return ExampleVerdict(
        counted=True,
        crb_violation=psd_violation(run.crb, run.mse),
        consistency_violation=psd_violation(run.mse, run.covariances),
        components=[_component_verdict(example, geometry, part, run, prior) for part in parts],
    )


def _safe(part: ComponentGeometry) -> bool:
    return part.numeric.rank == part.exact_rank and part.conditioning() >= MIN_CONDITIONING


def _component_verdict(
    example: FilterExample,
    geometry: FrozenGeometry,
    part: ComponentGeometry,
    run: LinearizedRun,
    prior: np.ndarray,
) -> ComponentVerdict:
    members = list(part.agents)
    d = geometry.dim
    floor = float(np.trace(run.crb[HORIZON, members, :d, :d], axis1=-2, axis2=-1).max())
    verdict = {
        "agents": tuple(i + 1 for i in members),
        "exact_rank": part.exact_rank,
        "observable": part.exact_rank == d,
        "paper_condition": _paper_condition(example.scene.agents[members]),
        "crb_floor": floor,
        "certified": None,
        "decay": None,
        "mse_bound": None,
        "mse_limit": None,
        "kernel_deviation": None,
    }
    if verdict["observable"]:
        cert = certify_boundedness(
            geometry, part.agents, run.gains[BURN_IN], run.covariances[BURN_IN]
        )
        later = psd_violation(run.covariances[BURN_IN:, members], cert.Z[None])
        verdict["certified"] = bool(cert.valid and later <= PSD_RTOL)
        verdict["decay"] = cert.decay
        verdict["mse_bound"] = float(np.trace(cert.Z[:, :d, :d], axis1=-2, axis2=-1).max())
        verdict["mse_limit"] = float(np.trace(cert.limit[:, :d, :d], axis1=-2, axis2=-1).max())
    else:
        verdict["kernel_deviation"] = _kernel_deviation(part, run, prior)
    return ComponentVerdict(**verdict)


def _kernel_deviation(part: ComponentGeometry, run: LinearizedRun, prior: np.ndarray) -> float:
    """Largest relative gap, along ``ker G_C`` (positions and velocities), between ``Π(k)`` and
    ``P̄_i(k)``, ``Σ_ii(k)``, ``P_C(k)`` of the component's agents."""
    E = np.kron(np.eye(2), part.kernel)
    reference = E.T @ prior @ E
    scale = np.linalg.norm(reference, 2, axis=(1, 2))[:, None]
    members = list(part.agents)
    gaps = [
        np.linalg.norm(E.T @ moments[:, members] @ E - reference[:, None], 2, axis=(2, 3)) / scale
        for moments in (run.covariances, run.mse, run.crb)
    ]
    return float(np.max(gaps))


def _paper_condition(agents: np.ndarray) -> bool:
    """Thm 4.2.3's wording: at least ``d + 1`` agents, not coplanar (rank of the centred
    positions at :data:`~theory.core.observability.RANK_TOL`)."""
    n, d = agents.shape
    return n >= d + 1 and numeric_rank(agents - agents.mean(axis=0), rank_tol=RANK_TOL).rank == d


def _corrected(example: FilterExample) -> bool:
    return check_example(example).holds


def _paper(example: FilterExample) -> bool:
    verdict = check_example(example)
    if not verdict.counted:
        return True
    return all(bool(c.certified) == c.paper_condition for c in verdict.components)


def filter_example_case(example: FilterExample) -> dict[str, Any]:
    """A ready-to-run ``kind: tdoa`` case reproducing ``example`` (receivers, target, edges,
    Metropolis weights) with the observability each agent's component has; the filter verdicts
    (rank, paper condition, certificate per component) are in its ``description``.

    ``trackcert topology FILE`` reproduces the rank decision the filter's behaviour follows.
    ``example`` is a :class:`FilterExample`; returns the case as plain data.
    """
    scene = example.scene
    n = len(scene.agents)
    edges = [[i + 1, j + 1] for i in range(n) for j in range(i + 1, n) if example.hears[i, j]]
    verdict = check_example(example)
    observable = [False] * n
    for c in verdict.components:
        for agent in c.agents:
            observable[agent - 1] = c.observable
    summary = "; ".join(
        f"agents {list(c.agents)}: rank {c.exact_rank}, paper condition {c.paper_condition}, "
        f"certified bounded {c.certified}"
        for c in verdict.components
    )
    return {
        "name": f"falsify-averaged-filter-{n}-agents",
        "source": "trackcert falsify (shrunk counterexample, seed 000 §4.2.2 / Thm 4.2.3)",
        "description": f"averaged filter on the frozen geometry, {HORIZON} pings, "
        f"T = {NOISES['T']}, P0 = {NOISES['p0']} I, Q = {NOISES['q']} I, R = {NOISES['r']} I: "
        + (summary or "not counted (numerically unsafe component)"),
        "kind": "tdoa",
        "tdoa": {
            "T": NOISES["T"],
            "target": [float(v) for v in scene.target],
            "agents": [[float(v) for v in row] for row in scene.agents],
            "edges": edges,
            "weights": "metropolis",
        },
        "expect": {"observable": observable} if verdict.counted else {},
    }


def example_from_spec(spec: TdoaSpec) -> FilterExample:
    """The example a :func:`filter_example_case` case file describes (its first time step).

    Parameters
    ----------
    spec : TdoaSpec
        A parsed ``tdoa`` block.

    Returns
    -------
    FilterExample
    """
    return FilterExample(TdoaScene(spec.target[0], spec.agents[0], "reloaded"), spec.hears[0])


def _register(wording: str, statement: str, holds: Any, expected_to_hold: bool) -> None:
    register_property(
        Property(
            id=f"seed000.thm4.2.3.averaged-filter/{wording}",
            claim="seed000.thm4.2.3.averaged-filter",
            wording=wording,
            statement=statement,
            examples=filter_examples(),
            holds=holds,
            to_case=filter_example_case,
            expected_to_hold=expected_to_hold,
        )
    )


_register(
    "paper",
    "The averaged filter's error stays bounded iff the agent is part of a (sub)network of at "
    "least 4 connected, non-coplanar agents (Thm 4.2.3 with §4.2.2's convergence remark).",
    _paper,
    expected_to_hold=False,
)
_register(
    "corrected",
    "On a frozen geometry, for every agent i of component C and every ping k: "
    "P_C(k) ⪯ E[e_i e_iᵀ](k) ⪯ P̄_i(k) (posterior CRB of C ⪯ mean-square error ⪯ filter "
    "covariance); if rank G_C = 3 the gains at a burn-in ping certify E[e_i e_iᵀ](k) ⪯ Z_i for "
    "all later k; if rank G_C < 3 nothing is learnt along ker G_C, where the position variance "
    "is p₀(1 + (kT)²) + q Σ_{l<k} ((l + ½)T²)² for every estimator.",
    _corrected,
    expected_to_hold=True,
)
