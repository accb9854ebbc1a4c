"""Certified design answers for TDOA networks (seed 000 §4.2.2): redundancy, and the per-case
design summary the report shows (margin: :mod:`~theory.tdoa.geometry.margin`; placement:
:mod:`~theory.tdoa.geometry.placement`).

:func:`tdoa_redundancy` finds the fewest links (or agents) whose loss leaves some agent with
``rank O_i < 2d`` by exact enumeration of every smaller set (each receivers set decided by
:func:`~theory.tdoa.geometry.exact.exact_direction_rank`), with a ``tdoa-loss-tolerance``
certificate; past :data:`MAX_SUBSETS` removal sets the answer is a bracket.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import combinations
from typing import Any

from proofs_check.observability import MAX_SUBSETS, heard_lists, receivers
from theory.core.case_file import Case
from theory.core.certificate_format import checked, envelope
from theory.core.exact import fraction_strings
from theory.tdoa.geometry.margin import Scene, rational_directions, scenes, tdoa_margin

__all__ = ["MAX_SUBSETS", "Redundancy", "design_summary", "tdoa_redundancy"]

SOURCE = "seed 000 §4.2.2, eq. (4.37); docs/design.md (redundancy)"


@dataclass(frozen=True)
class _StepAnswer:
    """One step's enumeration: the first breaking set, or the size reached within the budget."""

    step: int
    certified_below: int
    witness: tuple | None
    broken: tuple[int, ...]
    checked: int


@dataclass(frozen=True)
class Redundancy:
    """The fewest ``items`` (``links`` or ``agents``) whose loss breaks every agent's
    observability, at the weakest step.

    Every set of fewer than ``certified_below`` items keeps every remaining agent observable
    (exact enumeration); removing ``witness`` (``k`` items, 1-based) at 0-based ``step`` leaves
    ``broken`` agents with ``rank O_i < 2d`` (exact). ``exact`` when ``k == certified_below``.
    ``verdict``: False when an agent is unobservable already (``k = 0``), else True."""

    case: str
    items: str
    k: int
    witness: tuple
    step: int
    certified_below: int
    broken: tuple[int, ...]
    reason: str
    checked: int
    certificates: tuple[dict[str, Any], ...]
    note: str

    @property
    def exact(self) -> bool:
        """Whether the enumeration reached ``k`` (the minimum is known)."""
        return self.k == self.certified_below

    @property
    def verdict(self) -> bool:
        """True unless an agent is unobservable with nothing removed."""
        return self.k > 0

    def to_json(self) -> dict[str, Any]:
        """The ``trackcert design redundancy --json`` record."""
        return {
            "case": self.case,
            "items": self.items,
            "k": self.k,
            "witness": [list(x) if isinstance(x, tuple) else x for x in self.witness],
            "certified_below": self.certified_below,
            "exact": self.exact,
            "step": self.step + 1,
            "broken_agents": list(self.broken),
            "reason": self.reason,
            "sets_checked": self.checked,
            "verdict": self.verdict,
            "note": self.note,
            "tolerances": {"max_subsets": MAX_SUBSETS},
            "certificates": list(self.certificates),
        }


def _kept(scene: Scene, removed: tuple, links: bool) -> tuple[tuple[int, ...], set[int]]:
    """The links left after removing ``removed`` (links, or agents with theirs) and the agents
    gone."""
    if links:
        return tuple(x for x in scene.links if x not in removed), set()
    gone = set(removed)
    return tuple(x for x in scene.links if not gone & set(x)), gone


def _broken(scene: Scene, removed: tuple, links: bool) -> tuple[int, ...]:
    """0-based agents left with ``rank O_i < 2d`` after the removal (exact)."""
    kept, gone = _kept(scene, removed, links)
    members = _receiver_sets(scene, kept)
    return tuple(
        i for i in range(len(scene.agents)) if i not in gone and scene.deficient(members[i])
    )


def _receiver_sets(scene: Scene, kept: tuple) -> list[tuple[int, ...]]:
    """Every agent's receivers over the links ``kept`` (seed 000 Lemma 4.2.2), the heard lists
    built once; on undirected links an agent's receivers are its component, searched once."""
    heard = heard_lists(len(scene.agents), list(kept), scene.undirected)
    out: list[tuple[int, ...] | None] = [None] * len(scene.agents)
    for i in range(len(scene.agents)):
        if out[i] is None:
            members = tuple(sorted(receivers(i, heard)[0]))
            for j in members if scene.undirected else (i,):
                out[j] = members
    return out  # type: ignore[return-value]


def _isolating(scene: Scene, links: bool) -> tuple[tuple, tuple[int, ...]]:
    """The smallest breaking set among "every link (or neighbour) of one agent"."""
    best: tuple[tuple, tuple[int, ...]] | None = None
    for i in range(len(scene.agents)):
        touching = tuple(x for x in scene.links if i in x)
        removed = touching if links else tuple(sorted({j for x in touching for j in x} - {i}))
        broken = _broken(scene, removed, links)
        if broken and (best is None or len(removed) < len(best[0])):
            best = (removed, broken)
    assert best is not None  # an agent with no link has rank 0
    return best


def _step(scene: Scene, links: bool, budget: int, limit: int) -> _StepAnswer:
    """Enumerate removals of sizes ``0 … limit`` until one breaks observability (``witness``
    set) or the budget runs out (then the smallest isolating set is the witness)."""
    pool = scene.links if links else tuple(range(len(scene.agents)))
    count = 0
    for size in range(min(limit, len(pool)) + 1):
        if count + math.comb(len(pool), size) > budget:
            removed, broken = _isolating(scene, links)
            return _StepAnswer(scene.step, size, removed, broken, count)
        for removed in combinations(pool, size):
            count += 1
            broken = _broken(scene, removed, links)
            if broken:
                return _StepAnswer(scene.step, size, removed, broken, count)
    return _StepAnswer(scene.step, limit + 1, None, (), count)


def tdoa_redundancy(case: Case, *, links: bool, max_subsets: int = MAX_SUBSETS) -> Redundancy:
    """The fewest links (``links=True``) or agents whose loss leaves an agent unobservable.

    Each step is enumerated separately (up to ``max_subsets`` removal sets); the answer is the
    weakest step. Seed 000 §4.2.2, eq. (4.37); ``docs/design.md``."""
    items = "links" if links else "agents"
    all_scenes = scenes(case.spec)
    answers: list[_StepAnswer] = []
    limit = len(all_scenes[0].agents) + max(len(s.links) for s in all_scenes)
    for scene in sorted(all_scenes, key=lambda s: (len(s.links), s.step)):  # sparse steps first
        answers.append(_step(scene, links, max_subsets, limit))
        if answers[-1].witness is not None:
            limit = min(limit, len(answers[-1].witness) - 1)
    below = min(a.certified_below for a in answers)
    best = min(
        (a for a in answers if a.witness is not None), key=lambda a: (len(a.witness), a.step)
    )
    scene = all_scenes[best.step]
    certificates, note = _certificates(all_scenes, items, below, case.name)
    if len(best.witness) > below:
        note = (
            f"bracket: the {max_subsets} removal sets allowed cover the sizes below {below}; "
            f"the witness removes every {items[:-1]} around one agent. " + note
        ).strip()
    return Redundancy(
        case.name,
        items,
        len(best.witness),
        _ids(best.witness, links),
        best.step,
        below,
        tuple(i + 1 for i in best.broken),
        _reason(scene, best, links),
        sum(a.checked for a in answers),
        certificates,
        note,
    )


def _ids(removed: tuple, links: bool) -> tuple:
    return tuple((a + 1, b + 1) for a, b in removed) if links else tuple(j + 1 for j in removed)


def _reason(scene: Scene, answer: _StepAnswer, links: bool) -> str:
    i = answer.broken[0]
    members = scene.receivers(i, _kept(scene, answer.witness, links)[0])
    ids = "{" + ", ".join(str(j + 1) for j in members) + "}"
    if len(members) <= scene.dim:
        return (
            f"agent {i + 1}'s receivers are then {ids}: fewer than d + 1 = {scene.dim + 1} "
            "directions never span (rank < d)"
        )
    return (
        f"agent {i + 1}'s receivers {ids} then lie on one circular cone with apex at the "
        "target (affine rank of the directions < d, exact)"
    )


def _certificates(
    all_scenes: list[Scene], items: str, below: int, case: str
) -> tuple[tuple[dict, ...], str]:
    """A ``tdoa-loss-tolerance`` certificate per step (nothing to certify when ``below = 0``)."""
    if below == 0:
        return (), ""
    out = []
    for scene in all_scenes:
        cert = _certificate(scene, items, below, case)
        why = checked(cert)
        if why is not None:
            return (), f"no certificate at step {scene.step + 1}: {why}"
        out.append(cert)
    return tuple(out), ""


def _certificate(scene: Scene, items: str, below: int, case: str) -> dict[str, Any]:
    units, errors = rational_directions(scene, tuple(range(len(scene.agents))))
    claim = {
        "statement": f"step {scene.step + 1}: removing any {below - 1} or fewer {items} leaves "
        "every remaining agent with rank O_i = 2d",
        "items": items,
        "fewer_than": below,
    }
    data = {
        "dim": scene.dim,
        "target": fraction_strings(scene.exact_target),
        "agents": fraction_strings(scene.exact_agents),
        "links": [[s + 1, r + 1] for s, r in scene.links],
        "graph": "undirected" if scene.undirected else "directed",
    }
    witness = {"directions": fraction_strings(units), "errors": fraction_strings(errors)}
    return envelope("tdoa-loss-tolerance", claim, data, witness, source=SOURCE, case=case)


def design_summary(case: Case) -> dict[str, Any]:
    """The design section of a tdoa case in the report: margin and redundancy (seconds)."""
    margin = tdoa_margin(case).to_json()
    keep = ("radius", "exact", "upper_bound", "gap", "per_agent", "verdict", "note")
    out: dict[str, Any] = {"margin": {k: margin[k] for k in keep}}
    witness = margin["witness_displacement"]
    if witness is not None:
        out["margin"]["witness"] = {k: witness[k] for k in ("step", "agent", "size", "mechanism")}
    for links in (True, False):
        answer = tdoa_redundancy(case, links=links).to_json()
        out[f"redundancy_{answer['items']}"] = {
            k: answer[k] for k in ("k", "witness", "certified_below", "exact", "reason")
        }
    return out
