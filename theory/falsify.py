"""Property-based falsification of registered claims (``trackcert falsify``).

A :class:`Property` is one wording of a claim — the paper's or our corrected one — as a
hypothesis strategy of examples and a predicate that must hold on each. :func:`falsify` searches
for an example where the predicate fails and returns it shrunk by hypothesis, together with a
ready-to-run case file. A property stating a claim the papers get wrong is registered with
``expected_to_hold=False``: the default budget must find its counterexample (tests check this);
a corrected property must survive.

Modules that register properties are listed in :data:`PROPERTY_MODULES`.
"""

from __future__ import annotations

import importlib
import random
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from hypothesis import HealthCheck, Phase, find, settings
from hypothesis import strategies as st
from hypothesis.errors import NoSuchExample

__all__ = [
    "DEFAULT_EXAMPLES",
    "PROPERTY_MODULES",
    "FalsifyResult",
    "Property",
    "all_properties",
    "falsify",
    "properties_for",
    "register_property",
]

DEFAULT_EXAMPLES = 200
PROPERTY_MODULES: tuple[str, ...] = (
    "theory.consensus.properties",
    "theory.consensus.riccati_properties",
    "theory.pursuit.properties",
    "theory.tdoa.networked_properties",
    "theory.tdoa.geometry_properties",
)

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
    """Every registered property, sorted by id."""
    for module in PROPERTY_MODULES:
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
