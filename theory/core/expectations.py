"""Expectations: a case's ``expect`` block judged against what the analyses observed — one
mechanism for every command and the report (docs/report.md).

1. **Observing.** Every case kind but ``pf`` has one observer, ``observe(case, ctx) ->
   Observed``, given to its ``case.expect.<kind>`` claim (:func:`expectation_claim`): it runs
   the analysis its command runs and returns the value of every expect key it decides (``pf``
   has none: its claims observe). A claim result that observes expect keys puts them in its
   evidence under :data:`EXPECTATIONS_KEY` and the keys it could not decide under
   :data:`UNDECIDED_KEY`.
2. **Gathering.** :func:`observations_from` turns one observer's or claim result's values into
   observations ``(source, values, status)``: undecided keys are ``inconclusive``, the rest take
   the result's status (``verified`` for an observer).
3. **Judging.** :func:`evaluate` gives each expected key one :class:`ExpectationVerdict`:
   ``met`` (a conclusive observation, and every observation matches), ``unmet`` (a conclusive
   observation does not match), ``inconclusive`` (observed only inconclusively) or
   ``unchecked`` (nothing observed it).

Values match by type (:func:`matches`): booleans, integers, strings and ``None`` exactly; an
expected float matches an observed number within half a unit of its last printed digit
(``0.975`` matches ``[0.9745, 0.9755]``: how a case states the digits a paper printed); lists and
mappings element by element. A kind may give a key another :class:`Rule`: ``at_most`` (the
observed number is at most the expected one) or ``at_least``.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from decimal import Decimal
from enum import StrEnum
from typing import Any

from theory.core.claims import Claim, ClaimResult, Status, status_of
from theory.core.verdicts import expectations_verdict

__all__ = [
    "EXPECTATIONS_KEY",
    "UNDECIDED_KEY",
    "Expectation",
    "ExpectationVerdict",
    "Observation",
    "Observed",
    "Rule",
    "evaluate",
    "expectation_claim",
    "judge",
    "matches",
    "observations_from",
]

EXPECTATIONS_KEY = "expectations"
"""Evidence key under which a claim reports the values a case's ``expect`` block may name."""

UNDECIDED_KEY = "undecided_expectations"
"""Evidence key listing the expect keys whose reported value the claim could not decide."""



class ExpectationVerdict(StrEnum):
    """The verdict on one expected key (module docstring, 3)."""

    MET = "met"
    UNMET = "unmet"
    INCONCLUSIVE = "inconclusive"
    UNCHECKED = "unchecked"


class Rule(StrEnum):
    """How an expected value is compared: :func:`matches`, or as an upper / lower bound."""

    EQUAL = "equal"
    AT_MOST = "at_most"
    AT_LEAST = "at_least"


Source = tuple[str, Mapping[str, Any], str]
"""One observation set: (claim id or observer, values by expect key, status)."""


@dataclass(frozen=True)
class Observed:
    """What one analysis found for the expect keys of one case: expect key → observed value
    (plain JSON data), and the keys it could not decide (a margin inside tolerance, a rank not
    computed), judged ``inconclusive``, never ``met`` or ``unmet``."""

    values: dict[str, Any]
    undecided: frozenset[str] = frozenset()

    def evidence(self, keys: Iterable[str] | None = None) -> dict[str, Any]:
        """``{EXPECTATIONS_KEY: values, UNDECIDED_KEY: sorted undecided keys}`` of ``keys``
        (default: all): the evidence entries of a claim reporting these observations."""
        chosen = set(self.values) if keys is None else set(keys) & set(self.values)
        return {
            EXPECTATIONS_KEY: {k: v for k, v in self.values.items() if k in chosen},
            UNDECIDED_KEY: sorted(self.undecided & chosen),
        }


@dataclass(frozen=True)
class Observation:
    """One source's (claim id or observer) value for one expected key, with its status:
    ``inconclusive`` when undecided, else the reporting result's status."""

    claim: str
    value: Any
    status: str


@dataclass(frozen=True)
class Expectation:
    """The verdict on one key of one case's ``expect`` block: the value the case states, what
    each source reporting the key found, and the :class:`Rule` the values were compared by."""

    case: str
    key: str
    expected: Any
    observations: tuple[Observation, ...]
    verdict: ExpectationVerdict
    rule: Rule = Rule.EQUAL

    @property
    def met(self) -> bool:
        """Whether the verdict is ``met``."""
        return self.verdict == ExpectationVerdict.MET

    @property
    def observed(self) -> Any:
        """The value of the first conclusive observation (else the first; ``None`` if none)."""
        conclusive = [o for o in self.observations if o.status != Status.INCONCLUSIVE]
        chosen = conclusive or list(self.observations)
        return chosen[0].value if chosen else None

    def describe(self) -> str:
        """One line: ``key: expected X, got Y (verdict)``."""
        return f"{self.key}: expected {self.expected!r}, got {self.observed!r} ({self.verdict})"

    def to_json(self) -> dict[str, Any]:
        """The one verdict record of ``report.json`` and every command's ``--json``: ``case``,
        ``key``, ``expected``, ``got`` (:attr:`observed`), ``met``, ``verdict``, ``observations``
        (each ``claim``, ``value``, ``status``, ``matches``) and, for a bound, ``rule``."""
        out = {
            "case": self.case,
            "key": self.key,
            "expected": self.expected,
            "got": self.observed,
            "met": self.met,
            "verdict": self.verdict,
            "observations": [
                {
                    "claim": o.claim,
                    "value": o.value,
                    "status": o.status,
                    "matches": matches(self.expected, o.value, self.rule),
                }
                for o in self.observations
            ],
        }
        if self.rule != Rule.EQUAL:
            out["rule"] = self.rule
        return out


def observations_from(source: str, evidence: Mapping[str, Any], status: str) -> list[Source]:
    """The observation sets of one claim result (or observer ``source``) for :func:`evaluate`:
    the decided keys of its evidence with ``status``, the undecided ones ``inconclusive`` (none
    when the evidence reports no expect keys)."""
    values = evidence.get(EXPECTATIONS_KEY)
    if not isinstance(values, Mapping):
        return []
    undecided = set(evidence.get(UNDECIDED_KEY) or ())
    decided = {k: v for k, v in values.items() if k not in undecided}
    unsure = {k: v for k, v in values.items() if k in undecided}
    return [
        (source, part, part_status)
        for part, part_status in ((decided, status), (unsure, Status.INCONCLUSIVE))
        if part
    ]


def evaluate(
    case: str,
    expect: Mapping[str, Any],
    observations: Iterable[Source],
    rules: Mapping[str, str] | None = None,
) -> list[Expectation]:
    """One :class:`Expectation` per key of the case's ``expect`` block, in its order, from what
    each claim result or observer reported (:func:`observations_from`); ``rules`` maps an expect
    key to its :class:`Rule` (default ``equal``), e.g. the kind's ``expect_rules``."""
    seen = list(observations)
    rules = rules or {}
    verdicts = []
    for key, expected in expect.items():
        found = tuple(
            Observation(claim, values[key], status)
            for claim, values, status in seen
            if key in values
        )
        rule = Rule(rules.get(key, Rule.EQUAL))
        verdict = _verdict(expected, found, rule)
        verdicts.append(Expectation(case, key, expected, found, verdict, rule))
    return verdicts


def judge(case: Any, observed: Observed, *, source: str) -> list[Expectation]:
    """The verdicts on the keys of ``case``'s ``expect`` block that one observer (named
    ``source``) answers; the others are left to the analyses that do (``trackcert iss`` does not
    vouch for ``simulation_bounded``, nor ``trackcert simulate`` for ``iss``)."""
    found = observations_from(source, observed.evidence(), Status.VERIFIED)
    answered = {k: v for k, v in case.expect.items() if k in observed.values}
    return evaluate(case.name, answered, found, case.expect_rules)


def expectation_claim(
    kind: str,
    *,
    command: str,
    observe: Callable[[Any, Any], Observed],
    method: str = "numeric",
) -> Claim:
    """The claim ``case.expect.<kind>``: a case's expect block judged by the kind's observer.

    It runs ``observe(case, ctx)`` (what ``trackcert <command>`` runs) and judges each expected
    key with :func:`judge`: ``refuted`` when one is unmet, ``inconclusive`` when one is
    inconclusive or unchecked, ``verified`` when all are met; its evidence carries the observed
    values for the report to judge with the other claims' observations.
    """

    def check(case: Any, ctx: Any) -> list[ClaimResult]:
        observed = observe(case, ctx)
        verdicts = judge(case, observed, source=f"case.expect.{kind}")
        shown = [e.describe() for e in verdicts if not e.met]
        return [
            ClaimResult(
                status_of(expectations_verdict(verdicts)),
                method,
                observed.evidence(case.expect),
                message="; ".join(shown) or f"{len(verdicts)} expectation(s) met",
            )
        ]

    return Claim(
        f"case.expect.{kind}",
        f"the case file's expect block (checked as trackcert {command} checks it)",
        f"Every expectation a {kind} case states is what trackcert {command} finds.",
        (kind,),
        check,
        shares_work=True,
    )


def _verdict(expected: Any, found: tuple[Observation, ...], rule: Rule) -> ExpectationVerdict:
    if not found:
        return ExpectationVerdict.UNCHECKED
    undecided = Status.INCONCLUSIVE
    if any(not matches(expected, o.value, rule) for o in found if o.status != undecided):
        return ExpectationVerdict.UNMET
    if all(o.status == undecided for o in found):
        return ExpectationVerdict.INCONCLUSIVE
    return ExpectationVerdict.MET


def matches(expected: Any, observed: Any, rule: str = Rule.EQUAL) -> bool:
    """Whether ``observed`` (plain JSON) agrees with ``expected`` (plain YAML) by ``rule`` (module
    docstring); ``ValueError`` for an unknown rule."""
    if rule not in _RULES:
        raise ValueError(f"rule {rule!r} is not one of {[r.value for r in Rule]}")
    if rule != Rule.EQUAL:
        return _bound(expected, observed, rule)
    if isinstance(expected, bool) or isinstance(observed, bool):
        return isinstance(expected, bool) and isinstance(observed, bool) and expected == observed
    if isinstance(expected, float) and isinstance(observed, int | float):
        return abs(observed - expected) <= _half_last_digit(expected)
    if isinstance(expected, int) and isinstance(observed, int | float):
        return observed == expected
    if isinstance(expected, list) and isinstance(observed, list):
        return len(expected) == len(observed) and all(
            matches(e, o) for e, o in zip(expected, observed, strict=True)
        )
    if isinstance(expected, Mapping) and isinstance(observed, Mapping):
        return set(expected) == set(observed) and all(
            matches(expected[k], observed[k]) for k in expected
        )
    return type(expected) is type(observed) and expected == observed


_RULES = frozenset(Rule)

_BOUNDS: dict[str, Callable[[float, float], bool]] = {
    Rule.AT_MOST: lambda bound, value: value <= bound,
    Rule.AT_LEAST: lambda bound, value: value >= bound,
}


def _bound(expected: Any, observed: Any, rule: str) -> bool:
    numbers = all(
        isinstance(x, int | float) and not isinstance(x, bool) for x in (expected, observed)
    )
    return numbers and _BOUNDS[rule](float(expected), float(observed))


def _half_last_digit(number: float) -> float:
    exponent = Decimal(repr(number)).as_tuple().exponent
    return 0.5 * 10.0 ** int(exponent) * (1 + 1e-12)
