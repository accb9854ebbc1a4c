"""Expectations: a case's ``expect`` block compared with what the claims observed.

The mechanism (see ``docs/report.md``): a claim that computes a quantity a case may expect puts
it in its result's evidence under :data:`EXPECTATIONS_KEY`, keyed like the ``expect`` block,
e.g. ``evidence={"expectations": {"observable": [True, True, False]}, ...}``. The report gathers
every observation of every expected key and gives each expectation one verdict of
:data:`VERDICTS`:

- ``met``: at least one conclusive claim observed the key, and every observation matches;
- ``unmet``: some observation does not match (the claim and the value are listed);
- ``inconclusive``: the key was observed only by inconclusive results;
- ``unchecked``: no claim observed the key (nothing can vouch for it).

Values match by type: booleans, integers, strings and ``None`` exactly; an expected float
matches an observed number within half a unit of its last printed digit (``0.975`` matches
``[0.9745, 0.9755]``), which is how a case states the digits a paper printed; lists and
mappings element by element.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from decimal import Decimal
from typing import Any

__all__ = [
    "EXPECTATIONS_KEY",
    "VERDICTS",
    "Expectation",
    "Observation",
    "evaluate",
    "matches",
]

EXPECTATIONS_KEY = "expectations"
"""Evidence key under which a claim reports the values a case's ``expect`` block may name."""

VERDICTS = ("met", "unmet", "inconclusive", "unchecked")


@dataclass(frozen=True)
class Observation:
    """One claim's value for one expected key (``status`` is the claim result's status)."""

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
        What each claim that reports this key found.
    verdict : str
        One of :data:`VERDICTS`: ``met``, ``unmet``, ``inconclusive`` or ``unchecked``.
    """

    case: str
    key: str
    expected: Any
    observations: tuple[Observation, ...]
    verdict: str

    def to_json(self) -> dict[str, Any]:
        """Plain data for ``report.json``.

        Returns
        -------
        dict
            ``case``, ``key``, ``expected``, ``observations`` (each ``claim``, ``value``,
            ``status``, ``matches``) and ``verdict``.
        """
        return {
            "case": self.case,
            "key": self.key,
            "expected": self.expected,
            "observations": [
                {"claim": o.claim, "value": o.value, "status": o.status, "matches": m}
                for o, m in zip(
                    self.observations,
                    (matches(self.expected, o.value) for o in self.observations),
                    strict=True,
                )
            ],
            "verdict": self.verdict,
        }


def evaluate(
    case: str, expect: Mapping[str, Any], observations: Iterable[tuple[str, Mapping[str, Any], str]]
) -> list[Expectation]:
    """Verdicts for every key of ``expect``.

    Parameters
    ----------
    case : str
        Case name.
    expect : mapping
        The case's ``expect`` block.
    observations : iterable of (claim id, expectations mapping, status)
        What each claim result reported under :data:`EXPECTATIONS_KEY`.

    Returns
    -------
    list of Expectation
        One per key of ``expect``, in the block's order.
    """
    seen = list(observations)
    verdicts = []
    for key, expected in expect.items():
        found = tuple(
            Observation(claim, values[key], status)
            for claim, values, status in seen
            if key in values
        )
        verdicts.append(Expectation(case, key, expected, found, _verdict(expected, found)))
    return verdicts


def _verdict(expected: Any, found: tuple[Observation, ...]) -> str:
    if not found:
        return "unchecked"
    if any(not matches(expected, o.value) for o in found if o.status != "inconclusive"):
        return "unmet"
    if all(o.status == "inconclusive" for o in found):
        return "inconclusive"
    return "met"


def matches(expected: Any, observed: Any) -> bool:
    """Whether ``observed`` agrees with ``expected`` (rules in the module docstring).

    Parameters
    ----------
    expected : object
        A value of a case's ``expect`` block (plain YAML data).
    observed : object
        The value a claim reported (plain JSON data).

    Returns
    -------
    bool
    """
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


def _half_last_digit(number: float) -> float:
    exponent = Decimal(repr(number)).as_tuple().exponent
    return 0.5 * 10.0 ** int(exponent) * (1 + 1e-12)
