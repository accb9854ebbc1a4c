"""How far agents and target may drift before an agent loses the target (seed 000 §4.2).

The margin of a tdoa case is the largest ``ρ`` such that every agent keeps ``rank O_i = 2d``
(seed 000 eq. (4.37)) for every displacement of the target and of each agent by less than ``ρ``
(:data:`NORM`). It is bracketed (``docs/design.md``):

* **below**, certified: for the receivers ``S`` of an agent, rational unit ``û_j`` within ``e_j``
  of the directions ``u_j``; a displacement below ``ρ`` turns ``u_j`` by less than ``h_j`` with
  ``h_j² ≥ 2s²/(2 − s²)``, ``s = 2ρ/‖p − p_j‖``, mostly tangent to the sphere; then no hyperplane
  holds every displaced direction if ``C − (1 + μ)ΣE² I − (1 + 1/μ)Q ≻ 0`` (:func:`margin_matrix`;
  ``C`` the centred Gram matrix of the ``û_j``), checked exactly (a ``tdoa-observability-margin``
  certificate);
* **above**, by a witness: a displacement putting the receivers of one agent on a circular cone
  with apex at the displaced target (Theorem 2 of ``docs/theory/tdoa-observability.md``), found by
  a seeded Nelder–Mead search and built in rationals so that the rank loss is decided exactly.

``ρ = 0`` exactly when an agent is already unobservable. Under a distance rule (``comm_range``)
links that appear only enlarge receivers, and a link ``a–b`` survives displacements below
``(R − ‖p_a − p_b‖)/2``: each agent takes the best of the graphs that drop the links nearest to
breaking.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from math import isqrt
from typing import Any

import numpy as np
from scipy.optimize import brentq, minimize

from proofs_check.linalg import identity, positive_definite, scale, sub
from proofs_check.observability import heard_lists, receivers
from theory.core.case_file import Case
from theory.core.certificate_format import checked, envelope
from theory.core.errors import InconclusiveError
from theory.core.exact import dyadic, fraction_strings, rational_unit_vector
from theory.tdoa.case import TdoaSpec
from theory.tdoa.geometry.exact import exact_direction_rank, rational_points

__all__ = [
    "NORM",
    "AgentMargin",
    "Displacement",
    "Margin",
    "Scene",
    "float_radius",
    "loses_rank",
    "margin_matrix",
    "rational_directions",
    "scenes",
    "sqrt_up",
    "tdoa_margin",
]

NORM = "max over the target and every agent of the Euclidean length of its displacement"
DIRECTION_BITS = 30
"""Stereographic grid ``2^-30`` of the rational unit directions ``û_j``."""
ROOT_BITS = 64
"""Grid ``2^-64`` of the rational upper bounds ``e_j``, ``h_j`` of square roots."""
RADIUS_DIGITS = 6
"""Significant digits of a certified radius (rounded down)."""
SEARCH_STARTS = 4
"""Nelder–Mead starts of the cone search: the ``d`` principal axes, then seeded random ones."""
MU = Fraction(2**20)
"""Young's weight on the rounding of the directions: ``(E + B)² ≤ (1 + μ)E² + (1 + 1/μ)B²``."""
KAPPAS = (1 / 1024, 1 / 256, 1 / 64, 1 / 16, 1 / 4, 1.0, 4.0)
"""Young's weights ``κ`` tried for the two parts of a direction's turn (tangent, radial)."""
SOURCE = "seed 000 §4.2, eqs. (4.36)–(4.37); docs/design.md (margin)"


@dataclass(frozen=True, eq=False)
class Scene:
    """One step of a tdoa case: floats, the exact rationals written, and the links (0-based
    ``(s, r)``, "r hears s"; undirected links once with ``s < r``)."""

    step: int
    dim: int
    target: np.ndarray
    agents: np.ndarray
    exact_target: list[Fraction]
    exact_agents: list[list[Fraction]]
    links: tuple[tuple[int, int], ...]
    undirected: bool
    comm_range: Fraction | None
    _deficient: dict[tuple[int, ...], bool] = field(default_factory=dict, repr=False)

    def deficient(self, members: tuple[int, ...]) -> bool:
        """Whether ``members``' directions have affine rank ``< d`` (exact; Theorem 1)."""
        if members not in self._deficient:
            points = [self.exact_agents[j] for j in members]
            rank = exact_direction_rank(self.exact_target, points) if points else -1
            self._deficient[members] = rank < self.dim
        return self._deficient[members]

    def receivers(self, agent: int, links: tuple[tuple[int, int], ...] | None = None) -> tuple:
        """Sorted 0-based agents whose directions enter ``O_agent`` (seed 000 Lemma 4.2.2)."""
        chosen = self.links if links is None else links
        heard = heard_lists(len(self.agents), list(chosen), self.undirected)
        return tuple(sorted(receivers(agent, heard)[0]))


def scenes(spec: TdoaSpec) -> list[Scene]:
    """Every step of ``spec`` as a :class:`Scene`."""
    out = []
    for k in range(spec.steps):
        hears = np.asarray(spec.hears[k], bool)
        undirected = bool(np.array_equal(hears, hears.T))
        pairs = zip(*np.nonzero(hears), strict=True)
        if undirected:
            links = tuple(sorted({(int(min(r, s)), int(max(r, s))) for r, s in pairs}))
        else:
            links = tuple(sorted((int(s), int(r)) for r, s in pairs))
        comm = None if spec.comm_range is None else rational_points([[spec.comm_range]])[0][0]
        out.append(
            Scene(
                k,
                spec.dim,
                np.asarray(spec.target[k], float),
                np.asarray(spec.agents[k], float),
                rational_points([spec.target[k]])[0],
                rational_points(spec.agents[k]),
                links,
                undirected,
                comm,
            )
        )
    return out


def sqrt_up(x: Fraction, bits: int = ROOT_BITS) -> Fraction:
    """A dyadic rational ``≥ √x`` within ``2^-bits`` (integer square root, exact)."""
    scaled = x * 4**bits
    return Fraction(isqrt(scaled.numerator // scaled.denominator) + 1, 2**bits)


def _gram(units: np.ndarray) -> np.ndarray:
    centred = units - units.mean(axis=0)
    return centred.T @ centred


def _eta2(eps: float, r: np.ndarray) -> np.ndarray:
    s2 = 4 * eps * eps / (r * r)
    return 2 * s2 / (2 - s2)


def _motion_form(units: np.ndarray, eta2: np.ndarray, kappa: float) -> np.ndarray:
    """``Q = Σ_j (1 + κ)η_j²(I − u_ju_jᵀ) + (1 + 1/κ)(η_j⁴/4)u_ju_jᵀ``: ``xᵀQx`` bounds
    ``Σ_j (x·Δu_j)²`` for unit ``x`` (a unit vector turned by ``‖Δu‖ ≤ η`` moves by at most
    ``√(1 − (x·u)²)η + |x·u|η²/2`` along ``x``)."""
    outer = units[:, :, None] * units[:, None, :]
    tangent = np.eye(units.shape[1]) - outer
    return np.einsum("j,jab->ab", (1 + kappa) * eta2, tangent) + np.einsum(
        "j,jab->ab", (1 + 1 / kappa) * eta2**2 / 4, outer
    )


def margin_matrix(units: np.ndarray, distances: np.ndarray, eps: float, kappa: float) -> np.ndarray:
    """``C − (1 + 1/μ)Q(ε, κ)`` at exact unit ``units`` (no rounding term): positive definite iff
    the margin inequality holds at ``ε`` (``docs/design.md``)."""
    form = _motion_form(units, _eta2(eps, distances), kappa)
    return _gram(units) - (1 + 1 / float(MU)) * form


def float_radius(
    units: np.ndarray, distances: np.ndarray, errors: np.ndarray | None = None
) -> tuple[float, float]:
    """The largest float ``ε`` (and its Young weight ``κ`` among :data:`KAPPAS`) with
    ``C − (1 + μ)ΣE² I − (1 + 1/μ)Q(ε, κ) ≻ 0`` (``docs/design.md``): the radius a certificate can
    reach for unit ``units`` at ``distances`` (0 if none), capped below ``min r_j / 2``."""
    dim = units.shape[1]
    if len(distances) <= dim:
        return 0.0, 1.0
    e2 = 0.0 if errors is None else float(np.sum(errors**2))
    floor = (1 + float(MU)) * e2 + 1e-9 * float(np.linalg.eigvalsh(_gram(units))[-1])

    def room(eps: float, kappa: float) -> float:
        matrix = margin_matrix(units, distances, eps, kappa)
        return float(np.linalg.eigvalsh(matrix)[0]) - floor

    if room(0.0, 1.0) <= 0:
        return 0.0, 1.0
    top = float(distances.min()) / 2 * (1 - 1e-12)
    best = (0.0, 1.0)
    for kappa in KAPPAS:
        if room(top, kappa) > 0:
            return top, kappa
        eps = float(brentq(lambda e, k=kappa: room(e, k), 0.0, top, xtol=1e-13 * top))
        best = max(best, (eps, kappa))
    return best


def _round_down(x: float | Fraction) -> Fraction:
    """``x`` rounded down to :data:`RADIUS_DIGITS` significant digits (exactly)."""
    value = Fraction(x)
    if value <= 0:
        return Fraction(0)
    exponent = RADIUS_DIGITS - 1 - int(np.floor(np.log10(float(value))))
    grid = Fraction(10) ** exponent
    return Fraction(int(value * grid), 1) / grid


@dataclass(frozen=True)
class _SetBound:
    """A certified radius of one receivers set, with what its certificate needs."""

    members: tuple[int, ...]
    radius: Fraction
    directions: list[list[Fraction]]
    errors: list[Fraction]
    bounds: list[Fraction]
    kappa: Fraction


def rational_directions(scene: Scene, members: tuple[int, ...]) -> tuple[list, list[Fraction]]:
    """Rational unit ``û_j`` near ``u_j`` and exact ``e_j ≥ ‖û_j − u_j‖``:
    ``‖û − v/‖v‖‖² = 2 − 2 û·v/‖v‖ ≤ 2 − 2 û·v/√⁺(‖v‖²)`` when ``û·v > 0``."""
    units, errors = [], []
    for j in members:
        v = [t - x for t, x in zip(scene.exact_target, scene.exact_agents[j], strict=True)]
        u = rational_unit_vector([float(x) for x in v], DIRECTION_BITS)
        dot = sum(a * b for a, b in zip(u, v, strict=True))
        units.append(u)
        errors.append(sqrt_up(2 - 2 * dot / sqrt_up(sum(x * x for x in v), 2 * ROOT_BITS)))
    return units, errors


def _certify(scene: Scene, members: tuple[int, ...], cap: Fraction | None) -> _SetBound | None:
    """The largest radius (≤ ``cap``) at which the margin inequality holds exactly, or ``None``."""
    units, errors = rational_directions(scene, members)
    offsets = [
        [t - x for t, x in zip(scene.exact_target, scene.exact_agents[j], strict=True)]
        for j in members
    ]
    q = [sum(x * x for x in v) for v in offsets]
    floats = np.array([[float(x) for x in u] for u in units])
    eps, kappa_f = float_radius(
        floats, np.sqrt([float(x) for x in q]), np.array([float(e) for e in errors])
    )
    kappa = Fraction(kappa_f).limit_denominator(1 << 20)
    everyone = [_squared(scene.exact_target, p) for p in scene.exact_agents]
    reach = _round_down(float(np.sqrt(float(min(everyone)))) / 2 * (1 - 1e-9))  # TDOAs defined
    rho = min(_round_down(eps), reach, cap if cap is not None else reach)
    projections = [[[a * b / q_j for b in v] for a in v] for v, q_j in zip(offsets, q, strict=True)]
    base = sub(
        _exact_gram(units), scale((1 + MU) * sum(e * e for e in errors), identity(scene.dim))
    )
    for _ in range(40):
        if rho <= 0:
            return None
        bounds = [sqrt_up(2 * s2 / (2 - s2)) for s2 in (4 * rho * rho / q_j for q_j in q)]
        form = _exact_form(projections, bounds, kappa, scene.dim)
        if (
            all(4 * rho * rho < q_j for q_j in everyone)
            and positive_definite(sub(base, scale(1 + 1 / MU, form))).positive
        ):
            return _SetBound(members, rho, units, errors, bounds, kappa)
        rho = _round_down(rho * Fraction(9999, 10000))
    return None


def _exact_form(projections: list, bounds: list[Fraction], kappa: Fraction, dim: int) -> list:
    """:func:`_motion_form` in rationals, ``u_ju_jᵀ = v_jv_jᵀ/‖v_j‖²`` exactly."""
    eye = identity(dim)
    form = [[Fraction(0)] * dim for _ in range(dim)]
    for P, h in zip(projections, bounds, strict=True):
        tangent, radial = (1 + kappa) * h * h, (1 + 1 / kappa) * h**4 / 4
        form = [
            [f + tangent * (e - p) + radial * p for f, e, p in zip(fr, er, pr, strict=True)]
            for fr, er, pr in zip(form, eye, P, strict=True)
        ]
    return form


def _squared(a: list[Fraction], b: list[Fraction]) -> Fraction:
    return sum(((x - y) ** 2 for x, y in zip(a, b, strict=True)), Fraction(0))


def _exact_gram(units: list[list[Fraction]]) -> list[list[Fraction]]:
    mean = [sum(column) / len(units) for column in zip(*units, strict=True)]
    centred = [[x - c for x, c in zip(u, mean, strict=True)] for u in units]
    return [[sum(a[r] * a[c] for a in centred) for c in range(len(mean))] for r in range(len(mean))]


@dataclass(frozen=True)
class _Level:
    """The links kept for every displacement below ``cap`` (``None``: links fixed by the case)."""

    cap: Fraction | None
    links: tuple[tuple[int, int], ...]


def _levels(scene: Scene) -> list[_Level]:
    """Fixed links: one level. A distance rule: drop the links nearest to breaking, one slack at a
    time; a link survives below the exact lower bound ``(R − √⁺‖p_a − p_b‖²)/2`` of its slack."""
    if scene.comm_range is None or not scene.links:
        return [_Level(None, scene.links)]
    R = scene.comm_range
    slack = {
        (a, b): _round_down(
            (R - sqrt_up(_squared(scene.exact_agents[a], scene.exact_agents[b]))) / 2
        )
        for a, b in scene.links
    }
    return [
        _Level(bound, tuple(link for link in scene.links if slack[link] >= bound))
        for bound in sorted(set(slack.values()))
        if bound > 0
    ]


@dataclass(frozen=True)
class _AgentStep:
    """One agent at one step: its certified radius, or why it has none."""

    radius: Fraction
    degenerate: bool
    bound: _SetBound | None = None
    level: _Level | None = None


def _step_bounds(scene: Scene) -> list[_AgentStep]:
    """Each agent's best certified radius over the levels (exactly 0 when already unobservable)."""
    levels = _levels(scene)
    floats: dict[tuple[int, ...], float] = {}
    certified: dict[tuple, _SetBound | None] = {}
    out = []
    for agent in range(len(scene.agents)):
        nominal = scene.receivers(agent)
        if scene.deficient(nominal):
            out.append(_AgentStep(Fraction(0), True))
            continue
        best: tuple[float, tuple[int, ...], _Level] | None = None
        for level in levels:
            members = scene.receivers(agent, level.links)
            if scene.deficient(members):
                continue
            if members not in floats:
                floats[members] = _set_float_radius(scene, members)
            value = floats[members] if level.cap is None else min(floats[members], level.cap)
            if best is None or value > best[0]:
                best = (float(value), members, level)
        out.append(_certified_step(scene, best, certified))
    return out


def _set_float_radius(scene: Scene, members: tuple[int, ...]) -> float:
    offsets = scene.target - scene.agents[list(members)]
    distances = np.linalg.norm(offsets, axis=1)
    return float_radius(offsets / distances[:, None], distances)[0]


def _certified_step(scene: Scene, best: tuple | None, cache: dict) -> _AgentStep:
    if best is None:
        return _AgentStep(Fraction(0), False)
    _, members, level = best
    key = (members, level.cap)
    if key not in cache:
        cache[key] = _certify(scene, members, level.cap)
    bound = cache[key]
    return (
        _AgentStep(Fraction(0), False)
        if bound is None
        else _AgentStep(bound.radius, False, bound, level)
    )


def _certificates(scene: Scene, steps: list[_AgentStep], case: str | None) -> list[dict]:
    """One ``tdoa-observability-margin`` certificate per receivers set and level, re-checked."""
    groups: dict[tuple, list[int]] = {}
    for agent, step in enumerate(steps):
        if step.bound is not None:
            groups.setdefault((step.bound.members, step.level.cap), []).append(agent)
    out = []
    for agents in groups.values():
        step = steps[agents[0]]
        cert = _certificate(scene, step.bound, step.level, agents, case)
        why = checked(cert)
        if why is not None:
            raise InconclusiveError(f"step {scene.step + 1}: the margin certificate fails: {why}")
        out.append(cert)
    return out


def _certificate(
    scene: Scene, bound: _SetBound, level: _Level, covers: list[int], case: str | None
) -> dict[str, Any]:
    ids = [i + 1 for i in covers]
    claim = {
        "statement": f"step {scene.step + 1}: agents {ids} keep rank O_i = 2d for every "
        f"displacement of the target and the agents by less than {float(bound.radius):.6g} "
        "(each point, Euclidean)",
        "radius": str(bound.radius),
        "agents": ids,
    }
    data: dict[str, Any] = {
        "dim": scene.dim,
        "target": fraction_strings(scene.exact_target),
        "agents": fraction_strings(scene.exact_agents),
        "links": [[s + 1, r + 1] for s, r in level.links],
        "graph": "undirected" if scene.undirected else "directed",
    }
    if scene.comm_range is not None:
        data["comm_range"] = str(scene.comm_range)
    witness = {
        "sets": [
            {
                "agents": [j + 1 for j in bound.members],
                "covers": ids,
                "directions": fraction_strings(bound.directions),
                "errors": fraction_strings(bound.errors),
                "motion_bounds": fraction_strings(bound.bounds),
                "kappa": str(bound.kappa),
                "mu": str(MU),
            }
        ]
    }
    return envelope("tdoa-observability-margin", claim, data, witness, source=SOURCE, case=case)


@dataclass(frozen=True)
class Displacement:
    """A displacement of size ``size`` (:data:`NORM`) after which agent ``agent`` (0-based) has
    lost rank at 0-based ``step``, decided exactly on the displaced rational ``target`` and
    ``agents``. ``mechanism``: ``none`` (already unobservable), ``cone`` (its receivers moved
    onto one circular cone with apex at the target) or ``link`` (a link stretched to the range)."""

    step: int
    agent: int
    size: float
    mechanism: str
    target: tuple[Fraction, ...]
    agents: tuple[tuple[Fraction, ...], ...]
    moves: tuple[tuple[float, ...], ...]

    def to_json(self) -> dict[str, Any]:
        """Sizes and moves as floats, the displaced positions as exact rational strings."""
        return {
            "step": self.step + 1,
            "agent": self.agent + 1,
            "size": self.size,
            "mechanism": self.mechanism,
            "target_move": list(self.moves[0]),
            "agent_moves": [list(m) for m in self.moves[1:]],
            "positions": {
                "target": fraction_strings(list(self.target)),
                "agents": [fraction_strings(list(a)) for a in self.agents],
            },
        }


def loses_rank(
    scene: Scene, target: list[Fraction], agents: list[list[Fraction]], agent: int
) -> bool:
    """Whether ``agent`` has rank ``O_i < 2d`` at the displaced rational positions (the links of
    the case, or the distance rule re-applied), decided exactly."""
    if scene.comm_range is None:
        links = scene.links
    else:
        R2 = scene.comm_range**2
        links = tuple(
            (a, b)
            for a in range(len(agents))
            for b in range(a + 1, len(agents))
            if _squared(agents[a], agents[b]) < R2
        )
    heard = heard_lists(len(agents), list(links), scene.undirected)
    members = sorted(receivers(agent, heard)[0])
    try:
        return exact_direction_rank(target, [agents[j] for j in members]) < scene.dim
    except ValueError:  # an agent on the target: TDOAs undefined, not a witness
        return False


def _displacement(
    scene: Scene, agent: int, mechanism: str, target: list[Fraction], agents: list[list[Fraction]]
) -> Displacement:
    before = [scene.exact_target, *scene.exact_agents]
    after = [target, *agents]
    moves = [
        [float(y - x) for x, y in zip(a, b, strict=True)]
        for a, b in zip(before, after, strict=True)
    ]
    size = max(float(np.sqrt(float(_squared(a, b)))) for a, b in zip(before, after, strict=True))
    return Displacement(
        scene.step,
        agent,
        size * (1 + 1e-12),
        mechanism,
        tuple(target),
        tuple(tuple(a) for a in agents),
        tuple(tuple(m) for m in moves),
    )


def _cone_distances(offsets: np.ndarray, axis: np.ndarray, alpha: float) -> np.ndarray:
    """Distances from points (apex at 0) to the cone of half-angle ``alpha`` around ``axis``."""
    r = np.linalg.norm(offsets, axis=1)
    beta = np.arccos(np.clip(offsets @ axis / r, -1.0, 1.0))
    gamma = np.abs(beta - alpha)
    return np.where(gamma < np.pi / 2, r * np.sin(np.minimum(gamma, np.pi / 2)), r)


def _cone_fit(scene: Scene, members: tuple[int, ...], rng: np.random.Generator) -> np.ndarray:
    """``z = (δ₀, axis, α)`` minimising ``max(‖δ₀‖, max_j dist(p_j, cone))``: Nelder–Mead from the
    principal axes of the directions and seeded random axes, then SLSQP on the epigraph."""
    d, points = scene.dim, scene.agents[list(members)]
    offsets = points - scene.target
    r = np.linalg.norm(offsets, axis=1)
    g = offsets / r[:, None]

    def parts(z: np.ndarray) -> np.ndarray:
        axis = z[d : 2 * d] / max(np.linalg.norm(z[d : 2 * d]), 1e-300)
        moved = points - (scene.target + z[:d])
        return np.append(_cone_distances(moved, axis, z[2 * d]), np.linalg.norm(z[:d]))

    axes = list(np.linalg.eigh(_gram(g))[1].T)
    axes += [v / np.linalg.norm(v) for v in rng.standard_normal((SEARCH_STARTS - d, d))]
    steps = np.concatenate([np.full(d, 0.1 * r.min()), np.full(d, 0.2), [0.1]])
    best = None
    for axis in axes:
        z0 = np.concatenate([np.zeros(d), axis, [np.arccos(np.clip(np.mean(g @ axis), -1, 1))]])
        simplex = np.vstack([z0, z0 + np.diag(steps)])
        options = {"initial_simplex": simplex, "maxfev": 600, "xatol": 1e-9, "fatol": 1e-12}
        result = minimize(lambda z: parts(z).max(), z0, method="Nelder-Mead", options=options)
        if best is None or result.fun < best.fun:
            best = result
    start = np.append(best.x, best.fun)
    constraints = [
        {"type": "ineq", "fun": lambda y: y[-1] - parts(y[:-1])},
        {"type": "eq", "fun": lambda y: np.linalg.norm(y[d : 2 * d]) ** 2 - 1},
    ]
    polished = minimize(
        lambda y: y[-1], start, method="SLSQP", constraints=constraints, options={"maxiter": 300}
    )
    better = polished.success and parts(polished.x[:-1]).max() < best.fun
    return polished.x[:-1] if better else best.x


def _cone_witness(scene: Scene, members: tuple[int, ...], z: np.ndarray) -> tuple[list, list]:
    """Rational positions with ``members`` exactly on one circular cone with apex at the displaced
    target: generators ``g_j`` rational unit vectors on the circle ``n·g = c`` (second
    intersections of rational lines through ``g_1`` with the sphere), distances rational."""
    d = scene.dim
    axis = z[d : 2 * d] / np.linalg.norm(z[d : 2 * d])
    apex = [dyadic(float(x), -40) for x in scene.target + z[:d]]
    apex_f = np.array([float(x) for x in apex])
    points = scene.agents[list(members)] - apex_f
    r = np.linalg.norm(points, axis=1)
    beta = np.arccos(np.clip(points @ axis / r, -1, 1))
    gamma = np.abs(beta - z[-1])
    side = points - np.outer(points @ axis, axis)
    norms = np.linalg.norm(side, axis=1)
    side = np.where(
        norms[:, None] > 1e-12, side / np.maximum(norms, 1e-300)[:, None], _normal(axis)
    )
    target_g = np.cos(z[-1]) * axis + np.sin(z[-1]) * side
    lengths = np.maximum(r * np.cos(np.minimum(gamma, np.pi / 2)), 1e-6 * r)
    first = rational_unit_vector(target_g[0], DIRECTION_BITS)
    n = [dyadic(float(x), -30) for x in axis]
    nn = sum(x * x for x in n)
    generators = []
    for goal in target_g:
        step = [dyadic(float(x), -30) for x in goal - np.array([float(v) for v in first])]
        along = sum(a * b for a, b in zip(n, step, strict=True)) / nn
        step = [x - along * a for x, a in zip(step, n, strict=True)]
        size = sum(x * x for x in step)
        second = first
        if size > 0:
            t = -2 * sum(a * b for a, b in zip(first, step, strict=True)) / size
            second = [a + t * b for a, b in zip(first, step, strict=True)]
        pick = min((first, second), key=lambda g: np.linalg.norm(goal - [float(x) for x in g]))
        generators.append(pick)
    agents = [list(a) for a in scene.exact_agents]
    for j, g, length in zip(members, generators, lengths, strict=True):
        ell = dyadic(float(length), -40)
        agents[j] = [a + ell * x for a, x in zip(apex, g, strict=True)]
    return apex, agents


def _normal(axis: np.ndarray) -> np.ndarray:
    """A unit vector orthogonal to ``axis``."""
    helper = np.eye(len(axis))[int(np.argmin(np.abs(axis)))]
    v = helper - (helper @ axis) * axis
    return v / np.linalg.norm(v)


def _link_witnesses(scene: Scene) -> list[Displacement]:
    """Under a distance rule: for each link whose loss alone leaves an agent unobservable, move
    its two ends apart along it until they are exactly ``R`` or more apart."""
    if scene.comm_range is None:
        return []
    out = []
    for a, b in scene.links:
        kept = tuple(link for link in scene.links if link != (a, b))
        broken = [i for i in range(len(scene.agents)) if scene.deficient(scene.receivers(i, kept))]
        if not broken:
            continue
        pa, pb = scene.exact_agents[a], scene.exact_agents[b]
        d2 = _squared(pa, pb)
        lam = Fraction(float(scene.comm_range) / np.sqrt(float(d2)) - 1) / 2 + Fraction(1, 10**12)
        while (1 + 2 * lam) ** 2 * d2 < scene.comm_range**2:
            lam += Fraction(1, 10**9)
        agents = [list(p) for p in scene.exact_agents]
        agents[a] = [x + lam * (x - y) for x, y in zip(pa, pb, strict=True)]
        agents[b] = [y - lam * (x - y) for x, y in zip(pa, pb, strict=True)]
        out += [
            _displacement(scene, i, "link", scene.exact_target, agents)
            for i in broken
            if loses_rank(scene, scene.exact_target, agents, i)
        ]
    return out


def _step_witnesses(scene: Scene, rng: np.random.Generator) -> dict[int, Displacement]:
    """The smallest verified witness found for each agent at this step."""
    best: dict[int, Displacement] = {}
    sets: dict[tuple[int, ...], list[int]] = {}
    for agent in range(len(scene.agents)):
        members = scene.receivers(agent)
        if scene.deficient(members):
            zero = _displacement(scene, agent, "none", scene.exact_target, scene.exact_agents)
            best[agent] = zero
        else:
            sets.setdefault(members, []).append(agent)
    found = _link_witnesses(scene)
    for members, agents in sets.items():
        target, moved = _cone_witness(scene, members, _cone_fit(scene, members, rng))
        for agent in agents:
            if loses_rank(scene, target, moved, agent):
                found.append(_displacement(scene, agent, "cone", target, moved))
    for witness in found:
        if witness.agent not in best or witness.size < best[witness.agent].size:
            best[witness.agent] = witness
    return best


@dataclass(frozen=True)
class AgentMargin:
    """One agent's certified radius (``0`` exactly when ``degenerate``: unobservable already) and
    the size of the smallest verified witness displacement found for it (``None``: none found)."""

    id: int
    radius: Fraction
    upper_bound: float | None
    degenerate: bool

    def to_json(self) -> dict[str, Any]:
        """``{"id", "radius", "radius_exact", "upper_bound", "degenerate"}``."""
        return {
            "id": self.id,
            "radius": float(self.radius),
            "radius_exact": str(self.radius),
            "upper_bound": self.upper_bound,
            "degenerate": self.degenerate,
        }


@dataclass(frozen=True)
class Margin:
    """The margin of a tdoa case: certified ``radius ≤`` true margin ``≤ upper_bound``.

    ``exact`` when the two meet (``radius = 0`` on a degenerate geometry); ``witness`` realises
    ``upper_bound``; ``verdict``: True (``radius > 0``), False (an agent is unobservable already),
    None (an observable agent's radius could not be certified)."""

    case: str
    radius: Fraction
    exact: bool
    upper_bound: float | None
    witness: Displacement | None
    per_agent: tuple[AgentMargin, ...]
    certificates: tuple[dict[str, Any], ...]
    verdict: bool | None
    note: str
    tolerances: dict[str, Any]

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert design margin --json`` record."""
        gap = (
            None
            if self.upper_bound is None or self.radius == 0
            else self.upper_bound / float(self.radius)
        )
        return {
            "case": self.case,
            "radius": float(self.radius),
            "exact": self.exact,
            "witness_displacement": None if self.witness is None else self.witness.to_json(),
            "per_agent": [a.to_json() for a in self.per_agent],
            "radius_exact": str(self.radius),
            "upper_bound": self.upper_bound,
            "gap": gap,
            "norm": NORM,
            "verdict": self.verdict,
            "note": self.note,
            "tolerances": dict(self.tolerances),
            "certificates": list(self.certificates),
        }


def tdoa_margin(case: Case, *, search: bool = True, seed: int = 0) -> Margin:
    """Certified margin of every agent's observability under displacements (``docs/design.md``).

    Witnesses are searched at the step where each agent's certified radius is smallest;
    ``search=False`` skips them (no upper bound but ``0`` on a degenerate geometry); ``seed``
    seeds the search's random starting axes."""
    rng = np.random.default_rng(seed)
    all_scenes = scenes(case.spec)
    bounds = [_step_bounds(scene) for scene in all_scenes]
    certificates = [
        cert
        for scene, steps in zip(all_scenes, bounds, strict=True)
        for cert in _certificates(scene, steps, case.name)
    ]
    n = case.spec.n_agents
    worst = [min(range(len(bounds)), key=lambda k, i=i: bounds[k][i].radius) for i in range(n)]
    upper: list[Displacement | None] = [None] * n
    for k in sorted(set(worst)) if search else []:
        for i, witness in _step_witnesses(all_scenes[k], rng).items():
            if upper[i] is None or witness.size < upper[i].size:
                upper[i] = witness
    for i, k in enumerate(worst):
        if bounds[k][i].degenerate and (upper[i] is None or upper[i].size > 0):
            scene = all_scenes[k]
            upper[i] = _displacement(scene, i, "none", scene.exact_target, scene.exact_agents)
    radius = [bounds[k][i].radius for i, k in enumerate(worst)]
    degenerate = [bounds[k][i].degenerate for i, k in enumerate(worst)]
    return _assemble(case.name, radius, degenerate, upper, certificates, seed, search)


def _assemble(
    name: str,
    radius: list,
    degenerate: list[bool],
    upper: list[Displacement | None],
    certificates: list[dict],
    seed: int,
    search: bool,
) -> Margin:
    agents = tuple(
        AgentMargin(i + 1, r, None if w is None else w.size, d)
        for i, (r, d, w) in enumerate(zip(radius, degenerate, upper, strict=True))
    )
    overall = min(a.radius for a in agents)
    found = [w for w in upper if w is not None]
    witness = min(found, key=lambda w: w.size) if found else None
    uncertified = [a.id for a in agents if a.radius == 0 and not a.degenerate]
    verdict = None if uncertified else overall > 0
    if any(degenerate):
        verdict = False
    note = _note(agents, uncertified, witness)
    tolerances = {"direction_bits": DIRECTION_BITS, "root_bits": ROOT_BITS, "seed": seed}
    tolerances |= {"radius_digits": RADIUS_DIGITS, "search": search}
    return Margin(
        name,
        overall,
        any(degenerate),
        None if witness is None else witness.size,
        witness,
        agents,
        tuple(certificates),
        verdict,
        note,
        tolerances,
    )


def _note(
    agents: tuple[AgentMargin, ...], uncertified: list[int], witness: Displacement | None
) -> str:
    if any(a.degenerate for a in agents):
        ids = [a.id for a in agents if a.degenerate]
        return f"agents {ids} are unobservable at the stated geometry: the margin is exactly 0"
    if uncertified:
        return (
            f"agents {uncertified} are observable but too close to losing rank for the "
            f"certificate at {DIRECTION_BITS}-bit directions: their radius is not certified"
        )
    if witness is None:
        return "certified lower bound; no witness displacement was found (no upper bound)"
    return (
        "the true margin lies between the certified radius and the witness size; the lower "
        "bound treats every direction's turn separately (Weyl, Frobenius norm)"
    )
