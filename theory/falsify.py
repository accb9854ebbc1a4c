"""Property-based falsification of registered claims (``trackcert falsify``).

A :class:`Property` is one wording of a claim — the paper's or our corrected one — as a
hypothesis strategy of examples and a predicate that must hold on each. :func:`falsify` searches
for an example where the predicate fails and returns it shrunk by hypothesis, together with a
ready-to-run case file. A property stating a claim the papers get wrong is registered with
``expected_to_hold=False``: the default budget must find its counterexample (tests check this);
a corrected property must survive.

Each domain lists its properties in its registry (``PROPERTIES``, read by
:func:`theory.registry.all_properties`) and the claims no search can falsify, because they are
about one fixed instance, with the reason (``FIXED_INSTANCES``, read by :func:`fixed_instances`).
Every registered claim is one or the other (:func:`unsearched_claims` is empty; tests check it).

What a search finds is a :class:`~theory.core.claims.Finding`: a shrunk example that meets the
wording's hypotheses and fails its conclusion is a ``counterexample`` to that statement.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial
from typing import Any

from hypothesis import HealthCheck, Phase, find, settings
from hypothesis.errors import NoSuchExample

from theory.core.claims import Finding, FixedInstance, Property
from theory.core.parallel import TaskRunner, engine
from theory.registry import all_claims, all_properties, domains, properties_for

__all__ = [
    "DEFAULT_EXAMPLES",
    "FalsifyResult",
    "falsify",
    "falsify_each",
    "fixed_instances",
    "unsearched_claims",
]

DEFAULT_EXAMPLES = 200


@dataclass(frozen=True)
class FalsifyResult:
    """Outcome of :func:`falsify` with ``examples`` and ``seed``: the shrunk ``counterexample``
    and a ``case`` file (plain data) reproducing it, both ``None`` when none was found."""

    property: Property
    examples: int
    seed: int
    counterexample: Any = None
    case: dict[str, Any] | None = None

    @property
    def found(self) -> bool:
        """Whether a counterexample was found."""
        return self.case is not None

    @property
    def finding(self) -> Finding | None:
        """``counterexample`` when one was found (it meets the wording's hypotheses and fails its
        conclusion), else ``None``: the search found nothing."""
        return Finding.COUNTEREXAMPLE if self.found else None


def fixed_instances() -> tuple[FixedInstance, ...]:
    """Every claim about one fixed instance (the domains' ``FIXED_INSTANCES``), sorted by claim;
    ``ValueError`` if one is marked twice or also has a property."""
    marked = sorted((f for d in domains() for f in d.FIXED_INSTANCES), key=lambda f: f.claim)
    claims = [f.claim for f in marked]
    searched = {p.claim for p in all_properties()}
    if len(set(claims)) != len(claims) or searched & set(claims):
        raise ValueError("a claim is marked as a fixed instance twice, or also has a property")
    return tuple(marked)


def unsearched_claims() -> list[str]:
    """Registered claims with neither a property nor a fixed-instance mark (should be none)."""
    covered = {p.claim for p in all_properties()} | {f.claim for f in fixed_instances()}
    return [c.id for c in all_claims() if c.id not in covered]


def falsify(prop: Property, *, examples: int = DEFAULT_EXAMPLES, seed: int = 0) -> FalsifyResult:
    """Search ``examples`` examples (deterministically from ``seed``) for a counterexample."""
    config = settings(
        max_examples=examples,
        database=None,
        deadline=None,
        phases=(Phase.generate, Phase.shrink),
        suppress_health_check=list(HealthCheck),
    )
    try:
        example = find(
            prop.examples,
            lambda value: not prop.holds(value),
            settings=config,
            random=random.Random(seed),
        )
    except NoSuchExample:
        return FalsifyResult(prop, examples, seed)
    return FalsifyResult(prop, examples, seed, example, _rerunnable(prop, example, examples, seed))


def _rerunnable(prop: Property, example: Any, examples: int, seed: int) -> dict[str, Any]:
    """The example's case file; a record of a claim about the model alone (no case ``kind``)
    says how to reproduce it: the same search, which is deterministic given its seed."""
    case = prop.to_case(example)
    if "kind" not in case:
        case["rerun"] = f"trackcert falsify {prop.id} --seed {seed} --examples {examples}"
    return case


def falsify_each(
    props: Sequence[Property],
    *,
    examples: int = DEFAULT_EXAMPLES,
    seed: int = 0,
    runner: TaskRunner | None = None,
) -> list[FalsifyResult]:
    """:func:`falsify` of each property, the searches as independent tasks on the engine.

    Each search is deterministic given its seed (hypothesis draws from ``random.Random(seed)``),
    so the results are the same whatever the runner. A worker looks its property up by id.
    """
    task = partial(_search, examples=examples, seed=seed)
    ids = [p.id for p in props]
    if runner is None:
        with engine(1) as serial:
            found = serial.map(task, ids)
    else:
        found = runner.map(task, ids)
    return [
        FalsifyResult(p, examples, seed, counterexample, case)
        for p, (counterexample, case) in zip(props, found, strict=True)
    ]


def _search(prop_id: str, *, examples: int, seed: int) -> tuple[Any, dict[str, Any] | None]:
    """The counterexample and its case file for the property ``prop_id`` (a task's payload)."""
    (prop,) = [p for p in properties_for(prop_id) if p.id == prop_id]
    result = falsify(prop, examples=examples, seed=seed)
    return result.counterexample, result.case
