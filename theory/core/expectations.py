"""Expectations: a case's ``expect`` block judged against what the analyses observed.

One mechanism for every command and the report (see ``docs/report.md``):

1. **Observing.** Every case kind but ``pf`` has one observer, ``observe(case, ctx) ->
   Observed``, given to its ``case.expect.<kind>`` claim (:func:`expectation_claim`) in the
   domain's registry: it runs the analysis its command runs and returns the value of every
   expect key it decides (``kind: pf`` has none: its claims observe, see 2). A claim result
   that observes expect keys puts them in its evidence under :data:`EXPECTATIONS_KEY`
   (``{"observable": [True, False]}``) and the keys it could not decide under
   :data:`UNDECIDED_KEY`.
2. **Gathering.** :func:`observations_from` turns one observer's or one claim result's values
   into observations ``(source, values, status)``: listed undecided keys are ``inconclusive``,
   the rest take the result's status (``verified`` for an observer).
3. **Judging.** :func:`evaluate` gives each expected key one verdict of :data:`VERDICTS`:

   - ``met``: at least one conclusive observation, and every observation matches;
   - ``unmet``: some conclusive observation does not match (the source and value are listed);
   - ``inconclusive``: the key was observed only inconclusively;
   - ``unchecked``: nothing observed the key.

Values match by type (:func:`matches`): booleans, integers, strings and ``None`` exactly; an
expected float matches an observed number within half a unit of its last printed digit
(``0.975`` matches ``[0.9745, 0.9755]``), which is how a case states the digits a paper printed;
lists and mappings element by element. A kind may give a key another rule (:data:`RULES`):
``at_most`` (the observed number is at most the expected one) or ``at_least``.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from decimal import Decimal
from typing import Any

from theory.core.claims import Claim, ClaimResult, status_of
from theory.core.verdicts import expectations_verdict

__all__ = [
    "EXPECTATIONS_KEY",
    "RULES",
    "UNDECIDED_KEY",
    "VERDICTS",
    "Expectation",
    "Observation",
    "Observed",
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

VERDICTS = ("met", "unmet", "inconclusive", "unchecked")

RULES = ("equal", "at_most", "at_least")
"""How an expected value is compared: :func:`matches`, or as an upper / lower bound."""

Source = tuple[str, Mapping[str, Any], str]
"""One observation set: (claim id or observer, values by expect key, status)."""


@dataclass(frozen=True)
class Observed:
    """What one analysis found for the expect keys of one case (an observer's answer).

    Attributes
    ----------
    values : dict
        Expect key → observed value (plain JSON data).
    undecided : frozenset of str
        Keys whose value the analysis could not decide (a margin inside tolerance, a rank not
        computed); they are judged ``inconclusive``, never ``met`` or ``unmet``.
    """

    values: dict[str, Any]
    undecided: frozenset[str] = frozenset()

    def evidence(self, keys: Iterable[str] | None = None) -> dict[str, Any]:
        """The evidence entries of a claim reporting these observations.

        Parameters
        ----------
        keys : iterable of str, optional
            Only these keys (default: all).

        Returns
        -------
        dict
            ``{EXPECTATIONS_KEY: values, UNDECIDED_KEY: sorted undecided keys}``.
        """
        chosen = set(self.values) if keys is None else set(keys) & set(self.values)
        return {
            EXPECTATIONS_KEY: {k: v for k, v in self.values.items() if k in chosen},
            UNDECIDED_KEY: sorted(self.undecided & chosen),
        }


@dataclass(frozen=True)
class Observation:
    """One source's value for one expected key (``status`` as in :data:`Source`).

    Attributes
    ----------
    claim : str
        The claim id (or observer) that reported it.
    value : object
        The observed value.
    status : str
        ``inconclusive`` when undecided; otherwise the reporting result's status.
    """

    claim: str
    value: Any
    status: str


@dataclass(frozen=True)
class Expectation:
    """The verdict on one key of one case's ``expect`` block.

    Attributes
    ----------
    case, key : str
        The case and the ``expect`` key.
    expected : object
        The value the case file states.
    observations : tuple of Observation
        What each source that reports this key found.
    verdict : str
        One of :data:`VERDICTS`: ``met``, ``unmet``, ``inconclusive`` or ``unchecked``.
    rule : str
        How values are compared, one of :data:`RULES`.
    """

    case: str
    key: str
    expected: Any
    observations: tuple[Observation, ...]
    verdict: str
    rule: str = "equal"

    @property
    def met(self) -> bool:
        """Whether the verdict is ``met``."""
        return self.verdict == "met"

    @property
    def observed(self) -> Any:
        """The value of the first conclusive observation (else the first; ``None`` if none)."""
        conclusive = [o for o in self.observations if o.status != "inconclusive"]
        chosen = conclusive or list(self.observations)
        return chosen[0].value if chosen else None

    def describe(self) -> str:
        """One line: ``key: expected X, got Y (verdict)``."""
        return f"{self.key}: expected {self.expected!r}, got {self.observed!r} ({self.verdict})"

    def to_json(self) -> dict[str, Any]:
        """The one verdict record, in ``report.json`` and in every command's ``--json``.

        Returns
        -------
        dict
            ``case``, ``key``, ``expected``, ``got`` (:attr:`observed`), ``met``, ``verdict``,
            ``observations`` (each ``claim``, ``value``, ``status``, ``matches``) and, for a
            bound, ``rule``.
        """
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
        if self.rule != "equal":
            out["rule"] = self.rule
        return out


def observations_from(source: str, evidence: Mapping[str, Any], status: str) -> list[Source]:
    """The observation sets of one claim result (or observer) for :func:`evaluate`.

    Parameters
    ----------
    source : str
        Claim id or observer name.
    evidence : mapping
        The result's evidence; only :data:`EXPECTATIONS_KEY` and :data:`UNDECIDED_KEY` are read.
    status : str
        The result's status, given to the decided keys.

    Returns
    -------
    list of Source
        None when the evidence reports no expect keys; the decided keys with ``status`` and the
        undecided ones with ``inconclusive`` otherwise.
    """
    values = evidence.get(EXPECTATIONS_KEY)
    if not isinstance(values, Mapping):
        return []
    undecided = set(evidence.get(UNDECIDED_KEY) or ())
    decided = {k: v for k, v in values.items() if k not in undecided}
    unsure = {k: v for k, v in values.items() if k in undecided}
    return [
        (source, part, part_status)
        for part, part_status in ((decided, status), (unsure, "inconclusive"))
        if part
    ]


def evaluate(
    case: str,
    expect: Mapping[str, Any],
    observations: Iterable[Source],
    rules: Mapping[str, str] | None = None,
) -> list[Expectation]:
    """Verdicts for every key of ``expect``.

    Parameters
    ----------
    case : str
        Case name.
    expect : mapping
        The case's ``expect`` block.
    observations : iterable of (source, values mapping, status)
        What each claim result or observer reported (:func:`observations_from`).
    rules : mapping, optional
        Expect key → rule of :data:`RULES` (default ``equal``), e.g. the kind's
        ``expect_rules``.

    Returns
    -------
    list of Expectation
        One per key of ``expect``, in the block's order.
    """
    seen = list(observations)
    rules = rules or {}
    verdicts = []
    for key, expected in expect.items():
        found = tuple(
            Observation(claim, values[key], status)
            for claim, values, status in seen
            if key in values
        )
        rule = rules.get(key, "equal")
        verdict = _verdict(expected, found, rule)
        verdicts.append(Expectation(case, key, expected, found, verdict, rule))
    return verdicts


def judge(case: Any, observed: Observed, *, source: str) -> list[Expectation]:
    """The verdicts on the keys of ``case``'s ``expect`` block that one observer answers.

    Keys the observer does not report are left to the analyses that do (the report judges
    every key against every claim's observations, :func:`evaluate`): ``trackcert iss`` does not
    vouch for ``simulation_bounded``, nor ``trackcert simulate`` for ``iss``.

    Parameters
    ----------
    case : Case
        A loaded case (its ``name``, ``kind`` and ``expect`` are used).
    observed : Observed
        What the kind's observer found.
    source : str
        Named as the observations' source (e.g. ``trackcert topology``).

    Returns
    -------
    list of Expectation
    """
    found = observations_from(source, observed.evidence(), "verified")
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


def _verdict(expected: Any, found: tuple[Observation, ...], rule: str) -> str:
    if not found:
        return "unchecked"
    if any(not matches(expected, o.value, rule) for o in found if o.status != "inconclusive"):
        return "unmet"
    if all(o.status == "inconclusive" for o in found):
        return "inconclusive"
    return "met"


def matches(expected: Any, observed: Any, rule: str = "equal") -> bool:
    """Whether ``observed`` agrees with ``expected`` (rules in the module docstring).

    Parameters
    ----------
    expected : object
        A value of a case's ``expect`` block (plain YAML data).
    observed : object
        The value a claim reported (plain JSON data).
    rule : str
        One of :data:`RULES`.

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        For an unknown ``rule``.
    """
    if rule != "equal":
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


_BOUNDS: dict[str, Callable[[float, float], bool]] = {
    "at_most": lambda bound, value: value <= bound,
    "at_least": lambda bound, value: value >= bound,
}


def _bound(expected: Any, observed: Any, rule: str) -> bool:
    if rule not in _BOUNDS:
        raise ValueError(f"rule {rule!r} is not one of {RULES}")
    numbers = all(
        isinstance(x, int | float) and not isinstance(x, bool) for x in (expected, observed)
    )
    return numbers and _BOUNDS[rule](float(expected), float(observed))


def _half_last_digit(number: float) -> float:
    exponent = Decimal(repr(number)).as_tuple().exponent
    return 0.5 * 10.0 ** int(exponent) * (1 + 1e-12)
