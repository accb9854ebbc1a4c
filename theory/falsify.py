"""Property-based falsification of registered claims (``trackcert falsify``).

A :class:`Property` is one wording of a claim — the paper's or our corrected one — as a
hypothesis strategy of examples and a predicate that must hold on each. :func:`falsify` searches
for an example where the predicate fails and returns it shrunk by hypothesis, together with a
ready-to-run case file. A property stating a claim the papers get wrong is registered with
``expected_to_hold=False``: the default budget must find its counterexample (tests check this);
a corrected property must survive.

Each domain lists its properties in its registry (``PROPERTIES``, read by
:func:`theory.registry.all_properties`).
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial
from typing import Any

from hypothesis import HealthCheck, Phase, find, settings
from hypothesis.errors import NoSuchExample

from theory.core.claims import Property
from theory.core.parallel import TaskRunner, engine
from theory.registry import properties_for

__all__ = ["DEFAULT_EXAMPLES", "FalsifyResult", "falsify", "falsify_each"]

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
    return FalsifyResult(prop, examples, seed, example, prop.to_case(example))


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
