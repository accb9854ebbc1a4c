"""Property-based falsification of registered claims (``trackcert falsify``).

A :class:`Property` is one wording of a claim — the paper's or our corrected one — as a
hypothesis strategy of examples and a predicate that must hold on each. :func:`falsify` searches
for an example where the predicate fails and returns it shrunk by hypothesis, together with a
ready-to-run case file. A property stating a claim the papers get wrong is registered with
``expected_to_hold=False``: the default budget must find its counterexample (tests check this);
a corrected property must survive.

A module registers properties iff its file name is ``properties.py`` or ends in
``_properties.py`` (:mod:`theory.core.discovery`); :func:`all_properties` imports every such module.
"""

from __future__ import annotations

import importlib
import random
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from typing import Any

from hypothesis import HealthCheck, Phase, find, settings
from hypothesis import strategies as st
from hypothesis.errors import NoSuchExample

from theory.core.discovery import role_modules
from theory.core.parallel import TaskRunner, engine

__all__ = [
    "DEFAULT_EXAMPLES",
    "FalsifyResult",
    "Property",
    "all_properties",
    "falsify",
    "falsify_each",
    "properties_for",
    "register_property",
]

DEFAULT_EXAMPLES = 200

_PROPERTIES: dict[str, Property] = {}


@dataclass(frozen=True)
class Property:
    """One wording of a claim, ready for a counterexample search.

    Attributes
    ----------
    id : str
        ``<claim id>/<wording>``, e.g. ``seed000.thm4.2.3/paper``.
    claim : str
        The registry claim id it belongs to.
    wording : str
        ``paper`` or ``corrected``.
    statement : str
        The property in one sentence.
    examples : SearchStrategy
        Where to search.
    holds : callable
        ``holds(example) -> bool``.
    to_case : callable
        ``to_case(example) -> dict``: a case file (plain data) reproducing the example.
    expected_to_hold : bool
        False for a paper wording known to be wrong.
    """

    id: str
    claim: str
    wording: str
    statement: str
    examples: st.SearchStrategy[Any]
    holds: Callable[[Any], bool]
    to_case: Callable[[Any], dict[str, Any]]
    expected_to_hold: bool = True


@dataclass(frozen=True)
class FalsifyResult:
    """Outcome of :func:`falsify`: ``counterexample`` is ``None`` when none was found.

    Attributes
    ----------
    property : Property
        The property searched.
    examples : int
        The example budget (hypothesis's ``max_examples``).
    seed : int
        Seed of the search (the same seed gives the same result).
    counterexample : object or None
        The shrunk example on which the property fails.
    case : dict or None
        A case file (plain data) reproducing ``counterexample``.
    """

    property: Property
    examples: int
    seed: int
    counterexample: Any = None
    case: dict[str, Any] | None = None

    @property
    def found(self) -> bool:
        """Whether a counterexample was found."""
        return self.case is not None


def register_property(prop: Property) -> Property:
    """Add ``prop`` to the registry (ids must be unique)."""
    if prop.wording not in ("paper", "corrected"):
        raise ValueError(f"wording {prop.wording!r} is not 'paper' or 'corrected'")
    if prop.id in _PROPERTIES:
        raise ValueError(f"property {prop.id!r} registered twice")
    _PROPERTIES[prop.id] = prop
    return prop


def all_properties() -> list[Property]:
    """Every registered property, sorted by id (imports every property module first)."""
    for module in role_modules("properties"):
        importlib.import_module(module)
    return sorted(_PROPERTIES.values(), key=lambda p: p.id)


def properties_for(name: str) -> list[Property]:
    """Properties named ``name``: a property id, or a claim id (all its wordings).

    Raises
    ------
    KeyError
        Listing the known names when ``name`` matches nothing.
    """
    props = all_properties()
    chosen = [p for p in props if name in (p.id, p.claim)]
    if not chosen:
        known = sorted({p.claim for p in props} | {p.id for p in props})
        raise KeyError(f"no property or claim named {name!r}; known: {known}")
    return chosen


def falsify(prop: Property, *, examples: int = DEFAULT_EXAMPLES, seed: int = 0) -> FalsifyResult:
    """Search ``examples`` examples (deterministically from ``seed``) for a counterexample.

    Parameters
    ----------
    prop : Property
        The property to falsify.
    examples : int
        Hypothesis's ``max_examples`` budget.
    seed : int
        Seed of the search (the same seed gives the same result).

    Returns
    -------
    FalsifyResult
        With the shrunk counterexample and its case file, or none.
    """
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

    Parameters
    ----------
    props : sequence of Property
        Registered properties.
    examples : int
        Budget of each search.
    seed : int
        Seed of each search.
    runner : TaskRunner, optional
        An open engine (:func:`theory.core.parallel.engine`); default: this process, serially.

    Returns
    -------
    list of FalsifyResult
        In the order of ``props``.
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
