"""Placing ``N`` agents around a target (seed 000 §4.3.1): the least Cramér–Rao trace of the
complete network, with a certified margin ``≥ ρ₀`` and every link within the communication range.

The trace ``tr J⁻¹`` (eq. (4.43), ``σ = 1``) depends on the directions ``g_i`` only and is at least
``d²/N²``, with equality iff ``Σ g_i = 0`` and ``Σ g_ig_iᵀ = (N/d) I`` (:mod:`.crb`); the margin
(:mod:`.margin`) and the links depend on the positions. So the search

1. minimises the trace over directions (seeded starts, analytic gradient): ``tr*``;
2. maximises a margin ``t`` over positions keeping the trace at ``tr*`` — through the tight-frame
   equalities when ``tr*`` is the bound (smooth, where a constraint on the trace at its minimum is
   degenerate), with the directions fixed otherwise — subject to every pair at most ``R − 2t``
   apart (each link survives), the margin inequality at ``t`` (positive leading minors of
   :func:`~theory.tdoa.geometry.margin.margin_matrix`), every agent ``2t`` from the target and
   ``R/100`` from the others;
3. rounds the agents to 4 decimals and certifies the margin under the range ``R``
   (:func:`~theory.tdoa.geometry.margin.tdoa_margin`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from itertools import combinations
from typing import Any

import numpy as np
from scipy.optimize import minimize

from theory.core.errors import CaseError, InconclusiveError
from theory.tdoa.case import TDOA
from theory.tdoa.geometry.crb import crb_trace, optimal_crb_trace, platonic_solids, unit_circle
from theory.tdoa.geometry.margin import Margin, float_radius, margin_matrix, tdoa_margin

__all__ = ["Formation", "Placement", "fisher_trace", "tdoa_placement"]

SEPARATION = 0.01
"""Least distance between two agents, as a fraction of the range."""
DIGITS = 4
"""Decimals of the placed coordinates (what a case file states)."""


@dataclass(frozen=True)
class Formation:
    """A formation around the target at the origin: its agents, Cramér–Rao trace (complete
    network, ``σ = 1``) and certified margin under the communication range."""

    name: str
    agents: tuple[tuple[float, ...], ...]
    crb_trace: float
    radius: Fraction

    def to_json(self) -> dict[str, Any]:
        """``{"formation", "crb_trace", "radius", "radius_exact", "agents"}``."""
        return {
            "formation": self.name,
            "crb_trace": self.crb_trace,
            "radius": float(self.radius),
            "radius_exact": str(self.radius),
            "agents": [list(a) for a in self.agents],
        }


@dataclass(frozen=True)
class Placement:
    """The placement found for ``n_agents`` agents (``best``, its ``margin`` with certificates),
    the bound ``d²/N²`` of the trace, and the §4.3.1 formations with as many agents."""

    n_agents: int
    dim: int
    comm_range: float
    rho0: float
    best: Formation
    margin: Margin
    bound: float
    compared: tuple[Formation, ...]
    seed: int
    starts: int

    @property
    def verdict(self) -> bool:
        """Whether the certified margin reaches ``ρ₀`` (always: otherwise none is returned)."""
        return self.best.radius >= Fraction(self.rho0)

    def case_data(self) -> dict[str, Any]:
        """The placement as a tdoa case (target at the origin, the distance rule)."""
        tdoa = {"T": 1.0, "target": [0.0] * self.dim, "agents": [list(a) for a in self.best.agents]}
        tdoa |= {"comm_range": self.comm_range, "weights": "metropolis"}
        name = f"placement-{self.n_agents}"
        return {"name": name, "source": "trackcert design placement", "kind": "tdoa", "tdoa": tdoa}

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert design placement --json`` record."""
        return {
            "agents": [list(a) for a in self.best.agents],
            "crb_trace": self.best.crb_trace,
            "radius": float(self.best.radius),
            "compared": [f.to_json() for f in self.compared],
            "radius_exact": str(self.best.radius),
            "upper_bound": self.margin.upper_bound,
            "crb_bound": self.bound,
            "n_agents": self.n_agents,
            "dim": self.dim,
            "comm_range": self.comm_range,
            "rho0": self.rho0,
            "verdict": self.verdict,
            "case": self.case_data(),
            "tolerances": {"seed": self.seed, "starts": self.starts, "digits": DIGITS},
            "certificates": list(self.margin.certificates),
        }


def fisher_trace(x: np.ndarray) -> tuple[float, np.ndarray]:
    """``tr J⁻¹`` of the complete network, ``J = N Σ g_ig_iᵀ − s sᵀ`` with ``g_i = x_i/‖x_i‖``
    (seed 000 eq. (4.42)), and its gradient ``−2(I − g_ig_iᵀ)(N K g_i − K s)/‖x_i‖``,
    ``K = J⁻²``."""
    r = np.linalg.norm(x, axis=1, keepdims=True)
    g = x / r
    s = g.sum(axis=0)
    J = len(g) * g.T @ g - np.outer(s, s)
    eig = np.linalg.eigvalsh(J)
    if eig[0] <= 1e-9 * eig[-1]:
        return 1e9, np.zeros_like(x)
    inverse = np.linalg.inv(J)
    K = inverse @ inverse
    pull = len(g) * g @ K - K @ s
    radial = np.sum(pull * g, axis=1, keepdims=True) * g
    return float(np.trace(inverse)), -2 * (pull - radial) / r


def _best_directions(n: int, dim: int, rng: np.random.Generator, starts: int) -> list:
    """Unit direction sets of least trace from the §4.3.1 formations (if any) and seeded random
    starts, best first."""
    seeds = [units for _, units in _reference_units(n, dim)]
    seeds += [rng.standard_normal((n, dim)) for _ in range(starts - len(seeds))]
    found = []
    for x0 in seeds:
        result = minimize(
            lambda y: _flat(fisher_trace(y.reshape(n, dim))), x0.ravel(), jac=True, method="BFGS"
        )
        x = result.x.reshape(n, dim)
        found.append((fisher_trace(x)[0], x / np.linalg.norm(x, axis=1, keepdims=True)))
    return sorted(found, key=lambda item: item[0])


def _flat(value: tuple[float, np.ndarray]) -> tuple[float, np.ndarray]:
    return value[0], value[1].ravel()


def _constraints(units: np.ndarray, rho0: float) -> list[dict]:
    """The inequalities of step 2 at range 1 on ``y = (r_1 … r_N, log κ, t)``: agent ``i`` at
    ``r_i g_i``."""
    n = len(units)
    pairs = np.array(list(combinations(range(n), 2)))

    def gaps(y: np.ndarray) -> np.ndarray:
        x = y[:n, None] * units
        return np.linalg.norm(x[pairs[:, 0]] - x[pairs[:, 1]], axis=1)

    def margin(y: np.ndarray) -> np.ndarray:
        t = min(y[-1], 0.49 * float(np.min(y[:n])))  # keeps s < 1 while SLSQP explores
        M = margin_matrix(units, y[:n], t, float(np.exp(y[-2]))) * units.shape[1] / n
        return np.array([np.linalg.det(M[:k, :k]) for k in range(1, len(M) + 1)]) - 1e-9

    inequalities = (
        lambda y: 1 - 1e-6 - 2 * y[-1] - gaps(y),
        lambda y: gaps(y) - SEPARATION,
        lambda y: y[:n] - 2.02 * y[-1] - 1e-6,
        margin,
        lambda y: np.array([y[-1] - rho0]),
    )
    return [{"type": "ineq", "fun": f} for f in inequalities]


def _widest(units: np.ndarray, rho0: float) -> tuple[float, np.ndarray] | None:
    """Step 2 for one direction set at range 1: the uniform scaling that balances margin and
    longest link, then the distances refined (SLSQP); the largest ``t`` and its positions
    (``None``: nothing reaches ``ρ₀``)."""
    n = len(units)
    diameter = max(np.linalg.norm(a - b) for a, b in combinations(units, 2))
    unit_margin, kappa = float_radius(units, np.ones(n))
    scale = 1 / (2 * unit_margin + diameter)
    best = (scale * unit_margin * (1 - 1e-6), units * scale)
    if min(np.linalg.norm(a - b) for a, b in combinations(best[1], 2)) < SEPARATION:
        return None  # repeated directions: agents would coincide
    constraints = _constraints(units, rho0)
    result = minimize(
        lambda y: (-y[-1], np.append(np.zeros(len(y) - 1), -1.0)),
        np.concatenate([np.full(n, scale), [np.log(kappa), best[0] * 0.999]]),
        jac=True,
        method="SLSQP",
        bounds=[(SEPARATION, 1.0)] * n + [(-12.0, 4.0), (0.0, 0.5)],
        constraints=constraints,
        options={"maxiter": 300, "ftol": 1e-12},
    )
    y = result.x
    feasible = np.all(np.isfinite(y)) and min(np.min(c["fun"](y)) for c in constraints) >= -1e-9
    if feasible and y[-1] > best[0]:
        best = (float(y[-1]), y[:n, None] * units)
    return best if best[0] >= rho0 else None


def _narrowest(units: np.ndarray) -> np.ndarray:
    """A balanced tight frame near ``units`` with the least largest chord ``max ‖g_i − g_j‖``
    (SLSQP; ``units`` itself if that fails). Every balanced tight frame has ``C = (N/d) I`` and,
    at equal distances, the same margin inequality, so the chord alone decides its margin under
    a range."""
    n, dim = units.shape
    pairs = np.array(list(combinations(range(n), 2)))
    rows, cols = np.triu_indices(dim)
    upper = (rows[:-1], cols[:-1])  # the trace of Σ g gᵀ is N for any unit vectors

    def frame(y: np.ndarray) -> np.ndarray:
        x = y[:-1].reshape(n, dim)
        return x / np.linalg.norm(x, axis=1, keepdims=True)

    def tight(y: np.ndarray) -> np.ndarray:
        g = frame(y)
        return np.concatenate([g.sum(axis=0), (g.T @ g - n / dim * np.eye(dim))[upper]])

    def chords(y: np.ndarray) -> np.ndarray:
        g = frame(y)
        return y[-1] - np.sum((g[pairs[:, 0]] - g[pairs[:, 1]]) ** 2, axis=1)

    start = np.append(units.ravel(), 4.0)
    result = minimize(
        lambda y: (y[-1], np.append(np.zeros(len(y) - 1), 1.0)),
        start,
        jac=True,
        method="SLSQP",
        constraints=[{"type": "eq", "fun": tight}, {"type": "ineq", "fun": chords}],
        options={"maxiter": 300, "ftol": 1e-12},
    )
    ok = np.all(np.isfinite(result.x)) and np.max(np.abs(tight(result.x))) < 1e-10
    return frame(result.x) if ok and np.min(chords(result.x)) >= -1e-10 else units


def _search(n: int, dim: int, R: float, rho0: float, seed: int, starts: int) -> np.ndarray:
    """Steps 1–2: the positions of the widest margin among the direction sets of least trace."""
    found = _best_directions(n, dim, np.random.default_rng(seed), starts)
    bound = optimal_crb_trace(n, dim)
    least = found[0][0]
    if least <= bound * (1 + 1e-6):  # balanced tight frames: make them exact, then narrow
        found = [
            (fisher_trace(v)[0], v)
            for v in (_narrowest(u) for t, u in found if t <= bound * (1 + 1e-6))
        ]
        least = bound
    widest = None
    for trace, units in found:
        if trace <= least * (1 + 1e-9):
            candidate = _widest(units, rho0 / R)
            if candidate is not None and (widest is None or candidate[0] > widest[0]):
                widest = candidate
    if widest is None:
        raise InconclusiveError(
            f"no formation of {n} agents with least Cramér–Rao trace {least:.6g}, every pair "
            f"within the range {R:g} and a margin ≥ {rho0:g} was found from {starts} starts "
            "(the search is not exhaustive)"
        )
    return widest[1] * R


def _formation(name: str, x: np.ndarray, R: float) -> tuple[Formation, Margin]:
    """Round ``x`` to :data:`DIGITS` decimals, make it a tdoa case under the range ``R`` and
    certify its margin (:func:`~theory.tdoa.geometry.margin.tdoa_margin`)."""
    agents = tuple(tuple(round(float(v), DIGITS) + 0.0 for v in row) for row in x)
    dim = x.shape[1]
    tdoa = {"T": 1.0, "target": [0.0] * dim, "agents": [list(a) for a in agents]}
    tdoa |= {"comm_range": R, "weights": "metropolis"}
    margin = tdoa_margin(TDOA.parse_case({"name": name, "kind": "tdoa", "tdoa": tdoa}))
    trace = crb_trace(np.zeros(dim), np.array(agents))
    return Formation(name, agents, trace, margin.radius), margin


def _reference_units(n: int, dim: int) -> list[tuple[str, np.ndarray]]:
    """The formations of seed 000 §4.3.1 with ``n`` agents on the unit sphere (circle), and the
    square antiprism (also of least trace) for ``n = 8``."""
    if dim == 2:
        return [(f"uniform {n}-gon", unit_circle([360 * k / n for k in range(n)]))]
    solids = [(name, v) for name, v in platonic_solids().items() if len(v) == n]
    if n == 8:
        h = 1 / math.sqrt(3)
        angles = np.arange(8) * math.pi / 4
        ring, z = math.sqrt(1 - h * h), np.where(np.arange(8) % 2 == 0, h, -h)
        antiprism = np.column_stack([ring * np.cos(angles), ring * np.sin(angles), z])
        solids.append(("square antiprism", antiprism))
    return solids


def _scaled(name: str, units: np.ndarray, R: float) -> tuple[Formation, Margin]:
    """The unit formation scaled so that its margin ``s g₁`` meets its longest link's
    ``(R − sD)/2`` (``g₁`` the float margin at unit scale, ``D`` the diameter)."""
    diameter = max(np.linalg.norm(a - b) for a, b in combinations(units, 2))
    g1 = float_radius(units, np.ones(len(units)))[0]
    return _formation(name, units * R / (2 * g1 + diameter) * (1 - 1e-4), R)


def _optimised(n: int, dim: int, R: float, rho0: float, seed: int, starts: int) -> list:
    """The searched formation (growing safety factors on ``ρ₀`` against the rounding), or none."""
    for safety in (1e-3, 1e-2, 5e-2):
        try:
            x = _search(n, dim, R, rho0 * (1 + safety), seed, starts)
        except InconclusiveError:
            return []
        found = _formation(f"optimised, {n} agents", x, R)
        if found[0].radius >= Fraction(rho0) and found[1].verdict:
            return [found]
    return []


def tdoa_placement(
    n_agents: int,
    comm_range: float,
    *,
    rho0: float = 0.0,
    dim: int = 3,
    seed: int = 0,
    starts: int = 6,
) -> Placement:
    """``n_agents`` agents around a target minimising the complete network's Cramér–Rao trace
    (seed 000 eqs. (4.42)–(4.43)) with every pair within ``comm_range`` and a certified margin
    ``≥ rho0``, compared with the §4.3.1 formations of as many agents (``docs/design.md``).

    The answer is the formation of least trace, then widest certified margin, among the one
    searched and the §4.3.1 ones (each scaled to its best margin). Deterministic for a ``seed``;
    ``InconclusiveError`` when none reaches ``rho0``."""
    _check_placement(n_agents, comm_range, rho0, dim, starts)
    compared = [_scaled(name, u, comm_range) for name, u in _reference_units(n_agents, dim)]
    candidates = [
        (f, m)
        for f, m in _optimised(n_agents, dim, comm_range, rho0, seed, starts) + compared
        if f.radius >= Fraction(rho0) and m.verdict
    ]
    if not candidates:
        raise InconclusiveError(
            f"no formation of {n_agents} agents with every pair within the range {comm_range:g} "
            f"and a certified margin ≥ {rho0:g} was found ({starts} starts; the search is not "
            "exhaustive)"
        )
    least = min(f.crb_trace for f, _ in candidates)
    best, margin = max(
        ((f, m) for f, m in candidates if f.crb_trace <= least * (1 + 1e-9)),
        key=lambda item: item[0].radius,
    )
    bound = optimal_crb_trace(n_agents, dim)
    references = tuple(f for f, _ in compared)
    return Placement(n_agents, dim, comm_range, rho0, best, margin, bound, references, seed, starts)


def _check_placement(n: int, R: float, rho0: float, dim: int, starts: int) -> None:
    where = "<command line>"
    if dim not in (2, 3):
        raise CaseError("--dim", "2 or 3", dim, file=where)
    if not dim + 1 <= n <= 30:
        hint = "fewer than d + 1 agents never localize (docs/theory/tdoa-observability.md)"
        raise CaseError("N", f"an integer from {dim + 1} to 30", n, file=where, hint=hint)
    if not (math.isfinite(R) and R > 0):
        raise CaseError("--comm-range", "a positive range", R, file=where)
    if not (math.isfinite(rho0) and 0 <= rho0 < R / 2):
        hint = "a link of length ℓ survives displacements below (R − ℓ)/2"
        raise CaseError("--rho0", f"a margin in [0, {R / 2:g})", rho0, file=where, hint=hint)
    if starts < 1:
        raise CaseError("--starts", "a positive number of starts", starts, file=where)
