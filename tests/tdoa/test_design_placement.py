"""Placement of N agents (issue 25 item 3): least Cramér–Rao trace (seed 000 eq. (4.43)) with a
certified margin ≥ ρ₀ under a communication range, compared with the §4.3.1 formations."""

from __future__ import annotations

import json
from itertools import combinations

import numpy as np
import pytest

from proofs_check import check_certificate
from proofs_check.parse import loads
from theory.core.errors import CaseError, InconclusiveError
from theory.kinds import parse_case
from theory.tdoa.geometry.crb import crb_trace, optimal_crb_trace
from theory.tdoa.geometry.margin import tdoa_margin
from theory.tdoa.geometry.placement import fisher_trace, tdoa_placement


@pytest.mark.parametrize(("n", "dim", "rho0"), [(4, 3, 0.0), (6, 3, 1.0), (8, 3, 1.0), (6, 2, 1.0)])
def test_placement_reaches_the_bound_and_the_margin(n: int, dim: int, rho0: float) -> None:
    placed = tdoa_placement(n, 21.0, rho0=rho0, dim=dim)
    agents = np.array(placed.best.agents)
    assert placed.best.crb_trace == pytest.approx(optimal_crb_trace(n, dim), rel=1e-6)
    assert float(placed.best.radius) >= rho0 and placed.verdict
    gaps = [np.linalg.norm(a - b) for a, b in combinations(agents, 2)]
    assert max(gaps) < 21.0  # a complete network under the range
    for other in placed.compared:  # never worse than a §4.3.1 formation of as many agents
        assert placed.best.crb_trace <= other.crb_trace * (1 + 1e-9)
        assert placed.best.radius >= other.radius
    for cert in placed.margin.certificates:
        assert check_certificate(loads(json.dumps(cert))).valid


def test_six_agents_beat_the_octahedron() -> None:
    """Every balanced tight frame reaches the bound (crb.py); at equal distances they have the
    same margin inequality, so the shortest longest chord wins: a triangular prism (longest chord
    1.826 on the unit sphere) against the octahedron's antipodal 2."""
    placed = tdoa_placement(6, 21.0, rho0=1.0)
    (octahedron,) = placed.compared
    assert octahedron.name == "octahedron"
    assert float(placed.best.radius) > 1.05 * float(octahedron.radius)


def test_placement_case_reloads_with_the_same_margin() -> None:
    placed = tdoa_placement(4, 21.0)
    case = parse_case(placed.case_data())
    assert tdoa_margin(case, search=False).radius == placed.best.radius
    assert crb_trace(np.zeros(3), np.array(placed.best.agents)) == placed.best.crb_trace


def test_placement_is_deterministic() -> None:
    first, second = (tdoa_placement(5, 21.0, rho0=1.0, seed=3) for _ in range(2))
    assert first.to_json() == second.to_json()


def test_an_unreachable_margin_is_inconclusive() -> None:
    with pytest.raises(InconclusiveError, match="no formation"):
        tdoa_placement(8, 21.0, rho0=5.0)


@pytest.mark.parametrize(
    ("args", "field"),
    [((3, 21.0), "N"), ((4, -1.0), "--comm-range"), ((4, 21.0, 11.0), "--rho0")],
)
def test_bad_arguments_name_the_field(args: tuple, field: str) -> None:
    n, R, *rest = args
    with pytest.raises(CaseError, match=field):
        tdoa_placement(n, R, rho0=rest[0] if rest else 0.0)


def test_trace_gradient_matches_differences() -> None:
    rng = np.random.default_rng(1)
    x = rng.standard_normal((5, 3)) * 5
    value, grad = fisher_trace(x)
    step = 1e-6
    numeric = np.zeros_like(x)
    for index in np.ndindex(x.shape):
        moved = x.copy()
        moved[index] += step
        numeric[index] = (fisher_trace(moved)[0] - value) / step
    assert np.allclose(numeric, grad, atol=1e-5)
    assert value == pytest.approx(crb_trace(np.zeros(3), -x), rel=1e-9)
