"""``trackcert design self-weight | weights | redundancy`` for dkf cases (issue 25 items 1, 4):
seed 000 Examples 5.3.1–5.3.2 exactly (1/4 and 1/1.7205² = 4000000/11840481), brackets where the
paper's bound is not tight, and every certificate re-verified by proofs_check.

The truths: Thm 5.2.10 (2) and, for scalar systems, Theorem 6 of docs/theory/s-detectability.md
(``A = a``: S-detectable iff ``a² r_σ(W_SS) < 1``, S the agents without sensor)."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from proofs_check import check_certificate
from theory.consensus.design import exact_system, self_weight_design, self_weight_family_exact
from theory.consensus.properties import dkf_case
from theory.consensus.redundancy import dkf_redundancy
from theory.consensus.s_detectability import decide_s_detectability
from theory.consensus.strategies import dkf_problems
from theory.consensus.weight_design import weight_design
from theory.core.errors import CaseError
from theory.core.exact import stochastic_matrix
from theory.kinds import load_case, parse_case

EXAMPLES = {
    "ch5-example-1-wg": Fraction(1, 4),
    "ch5-example-1-wb": Fraction(1, 4),
    "ch5-example-1-wc": Fraction(1, 4),
    "ch5-example-2-wg": Fraction(4_000_000, 11_840_481),
    "ch5-example-2-wb": Fraction(4_000_000, 11_840_481),
}


def _valid(cert: dict) -> bool:
    return check_certificate(cert).valid


def _scalar_case(a: Fraction, W: list[list[Fraction]], sensing: list[bool]) -> object:
    """A scalar dkf case (Theorem 6): agents with ``C_i = [[1]]`` or no sensor."""
    block = {
        "A": [[float(a)]],
        "C": [[[1]] if s else [] for s in sensing],
        "W": [[float(x) for x in row] for row in W],
        "Q": [[1]],
        "R": [[[1]] if s else [] for s in sensing],
    }
    return parse_case({"name": "scalar", "kind": "dkf", "dkf": block})


@pytest.mark.parametrize(("name", "supremum"), sorted(EXAMPLES.items()))
def test_examples_supremum_is_exact_with_certificates_both_sides(name: str, supremum) -> None:
    result = self_weight_design(load_case(name))
    data = result.to_json()
    assert result.status == "exact" and data["supremum"]["rational"] == str(supremum)
    assert supremum - result.width <= result.below.w < supremum == result.at_or_above.w
    assert result.below.certificate["kind"] == "s-detectability"
    above = result.at_or_above.certificate  # Thm 5.2.10 (2) for every w ≥ the supremum
    assert above["kind"] == "self-weight-necessary-violated" and above["claim"]["exact"] is True
    assert above["claim"]["threshold"] == str(supremum)
    assert all(_valid(c) for c in result.certificates) and result.verdict is True
    W_below = result.below.certificate["data"]["W"]
    agent = data["agent"][0] - 1
    assert Fraction(W_below[agent][agent]) == result.below.w  # the certified point is the family's


def test_a_width_moves_the_certified_point_closer() -> None:
    result = self_weight_design(load_case("ch5-example-2-wg"), width=Fraction(1, 10**9))
    assert EXAMPLES["ch5-example-2-wg"] - result.below.w <= Fraction(1, 10**9)
    assert _valid(result.below.certificate)


def test_links_give_the_same_family_as_the_agent() -> None:
    by_links = self_weight_design(load_case("ch5-example-1-wg"), links=("W.0.0=w", "W.0.1=1-w"))
    by_agent = self_weight_design(load_case("ch5-example-1-wg"), agents=[0])
    assert by_links.supremum.rational == by_agent.supremum.rational == Fraction(1, 4)
    assert by_links.below.certificate["data"]["W"] == by_agent.below.certificate["data"]["W"]


@pytest.mark.parametrize(
    ("links", "field"),
    [
        (("W.0.0=w",), "--link"),
        (("W.0.9=w", "W.0.0=1-w"), "--link"),
        (("W.0.0=2*v",), "--link"),
        (("W.0.0=0*w",), "--link"),
        (("W.0.0=w", "W.0.1=1-w", "W.1.1=-2+w", "W.1.0=3-w"), "--link"),  # no common w
    ],
)
def test_bad_links_are_refused_naming_the_option(links: tuple[str, ...], field: str) -> None:
    with pytest.raises(CaseError) as raised:
        self_weight_design(load_case("ch5-example-1-wg"), links=links)
    assert raised.value.field == field


def test_a_cycle_of_blind_agents_is_exact_by_the_blind_set_condition() -> None:
    """A = 2, agents 1, 2 blind: Theorem 6's threshold (4 r_σ(W_SS(w)) = 1, here 19/100) lies
    below the self-weight bound 1/4; the blind-set condition decides it exactly."""
    tenth = Fraction(1, 10)
    W = [[tenth, tenth, 8 * tenth], [tenth, tenth, 8 * tenth], [0, 0, Fraction(1)]]
    result = self_weight_design(_scalar_case(Fraction(2), W, [False, False, True]), agents=[0],
                                width=Fraction(1, 1000))  # fmt: skip
    # 4 r_σ([[w, (1 − w)/9], [1/10, 1/10]]) = 1  ⇔  (w − 1/4)(1/10 − 1/4) = (1 − w)/90
    threshold = (Fraction(3, 80) - Fraction(1, 90)) / (Fraction(3, 20) - Fraction(1, 90))
    assert threshold == Fraction(19, 100) and result.status == "exact"
    assert result.supremum.rational == threshold and "blind-set" in result.condition
    assert threshold - Fraction(1, 1000) <= result.below.w < threshold == result.at_or_above.w
    assert all(_valid(c) for c in result.certificates) and len(result.certificates) == 2


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    a=st.sampled_from([Fraction(3, 2), Fraction(2), Fraction(5, 4), Fraction(-3)]),
    others=st.lists(st.integers(1, 9), min_size=1, max_size=3),
    start=st.integers(1, 8),
    t=st.fractions(0, 1),
)
def test_scalar_supremum_is_one_over_a_squared_and_decides_both_sides(a, others, start, t) -> None:
    """Agent 1 blind, the others sensing (Theorem 6: S-detectable iff a² w < 1): the exact
    supremum is 1/a²; a point inside the certified part decides positively, one past the
    supremum negatively."""
    N = len(others) + 1
    weights = [Fraction(start), *map(Fraction, others)]
    row = [x / sum(weights) for x in weights]
    W = [row] + [[Fraction(int(i == j)) for j in range(N)] for i in range(1, N)]
    case = _scalar_case(a, W, [False] + [True] * (N - 1))
    row = stochastic_matrix(case.spec.W)[0]  # the weights as the case file holds them
    result = self_weight_design(case, width=Fraction(1, 100))
    assert (
        result.status == "exact" and result.supremum.rational == 1 / a**2 and result.agents == (1,)
    )
    inside = t * result.below.w
    past = 1 / a**2 + t * (1 - 1 / a**2)
    for w, truth in ((inside, True), (past, False)):
        family = [[x * (1 - w) / (1 - row[0]) for x in row], *W[1:]]
        family[0][0] = w
        assert decide_s_detectability(case.spec.A, case.spec.C, family).verdict is truth


def test_redundancy_of_example_1_is_one_link_and_one_agent() -> None:
    for links, witness in ((True, [[1, 2]]), (False, [1])):
        result = dkf_redundancy(load_case("ch5-example-1-wg"), links=links)
        data = result.to_json()
        assert (data["k"], data["witness"], data["certified_below"]) == (1, witness, 1)
        assert data["exact"] and all(_valid(c) for c in result.certificates)
        assert result.certificates[-1]["kind"] == "s-detectability-infeasible"


def test_redundancy_of_a_robust_network_certifies_every_removal() -> None:
    result = dkf_redundancy(load_case("ch5-counterexample"), links=True)
    assert result.k is None and result.exact and result.verdict is True
    assert len(result.certificates) == result.checked and all(map(_valid, result.certificates))


def test_redundancy_of_a_network_already_broken_is_zero() -> None:
    result = dkf_redundancy(load_case("ch5-example-1-wc"))
    assert (result.k, result.verdict) == (0, False)


def test_weight_design_beats_the_case_on_its_graph_and_is_certified() -> None:
    result = weight_design(load_case("ch5-example-2-wg"), max_evaluations=60)
    case = next(c for c in result.compared if c.name == "case")
    W = result.designed.W
    assert all(sum(row) == 1 and all(x >= 0 for x in row) for row in W)
    support = [[x != 0 for x in row] for row in load_case("ch5-example-2-wg").spec.W]
    assert [[x != 0 for x in row] for row in W] == support
    assert result.designed.radius <= case.radius < 1
    cert = result.designed.certificate
    assert (
        _valid(cert) and Fraction(cert["claim"]["spectral_radius_below"]) == result.designed.radius
    )
    assert math.isfinite(result.designed.estimate)


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    problem=dkf_problems(max_states=2, max_agents=3, a_bound=2, integer_data=True),
    t=st.fractions(0, 1),
)
def test_a_certified_supremum_is_never_contradicted(problem, t) -> None:
    """Random systems: below a certified S-detectable point the family decides S-detectable or
    inconclusive, past an exact supremum it decides not or inconclusive, never the other way."""
    assume(problem.W[0, 0] < 1)
    case = parse_case(dkf_case(problem))
    result = self_weight_design(case, agents=[0], width=Fraction(1, 100))
    A, C, W = exact_system(case)
    family = self_weight_family_exact(W, [0])
    if result.below is not None:
        assert decide_s_detectability(A, C, family.at(t * result.below.w)).verdict is not False
    if result.status == "exact":
        u = result.supremum.interval[1]
        assert decide_s_detectability(A, C, family.at(u + t * (1 - u))).verdict is not True


def test_without_an_exact_bound_the_bracket_is_bisected_between_certificates() -> None:
    """The bracket route alone (no exact candidate given): the blind-cycle family's threshold
    19/100 lies in a bracket of the width asked, both ends decided by checked certificates."""
    from theory.consensus.design import _Decider, _search

    tenth = Fraction(1, 10)
    W = [[tenth, tenth, 8 * tenth], [tenth, tenth, 8 * tenth], [0, 0, Fraction(1)]]
    case = _scalar_case(Fraction(2), W, [False, False, True])
    A, C, W_q = exact_system(case)
    decider = _Decider(A, C, self_weight_family_exact(W_q, [0]), case.name, "CLARABEL")
    result = _search(decider, None, Fraction(1, 1000), (1,))
    low, high = result.supremum.interval
    assert result.status == "bracket" and not result.supremum.exact
    assert low < Fraction(19, 100) <= high and high - low <= Fraction(1, 1000)
    assert (result.below.w, result.at_or_above.w) == (low, high)
    assert [c["kind"] for c in result.certificates] == [
        "s-detectability", "s-detectability-infeasible",
    ]  # fmt: skip
    assert all(_valid(c) for c in result.certificates)


HAND_WRITTEN = Path(__file__).resolve().parents[1] / "data" / "dkf"
"""Agent 1 blind to a block of ``A`` whose largest ``|λ|²`` is ``(1 + √2)²`` (real), ``2``
(the complex pair ``1 ± i``) or that of the complex pair of ``x³ + x² − x − 3`` (irrational);
agent 2 sees everything, so ``L_2 = A`` gives ``Γ_2 = 0`` and ``r_σ(L) = w r_σ(Γ_1)²``: the
paper's bound ``1/|λ|²`` is the supremum."""


@pytest.mark.parametrize(
    ("name", "polynomial", "rational"),
    [
        ("self-weight-irrational-real", ["1", "-6", "1"], None),  # 3 − 2√2
        ("self-weight-complex-root", None, "1/2"),
        ("self-weight-complex-irrational", ["-1", "-1", "3", "9"], None),
    ],
)
def test_an_irrational_or_complex_bound_is_exact_with_certificates_both_sides(
    name: str, polynomial: list[str] | None, rational: str | None
) -> None:
    result = self_weight_design(load_case(str(HAND_WRITTEN / f"{name}.yaml")), agents=[0])
    sup = result.to_json()["supremum"]
    assert result.status == "exact" and sup.get("polynomial") == polynomial
    assert sup.get("rational") == rational
    low, high = (Fraction(x) for x in sup["interval"])
    assert high - low <= Fraction(1, 10**20) and low - result.width <= result.below.w < low
    kinds = [c["kind"] for c in result.certificates]
    assert kinds == ["s-detectability", "self-weight-necessary-violated"]
    assert all(_valid(c) for c in result.certificates)
    claim = result.at_or_above.certificate["claim"]
    assert claim["exact"] is True
    assert claim.get("threshold_polynomial") == polynomial and claim.get("threshold") == rational
