"""The report's design section: per case, the design answers the library gives cheaply for it
(issue 25) — tdoa: the certified displacement margin ρ and the fewest links/agents whose loss
breaks observability (:func:`theory.tdoa.design.design_summary`); pursuit: the ISS conditions
over the default gain box, the certified gain at the case's own gains and its infimum
(:func:`theory.pursuit.design.design_summary`); dkf: the supremum self-weight of the default
agents (:func:`theory.consensus.design.self_weight_design`).

:data:`SUMMARIES` maps a kind to its summary function (which imports its domain only when a
case of that kind is in the report) and to the headline the page prints plainly; a kind
gains a design section by one line there. A summary that raises is reported (type and message)
in place of its answers: the report still completes.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from theory.core.case_file import Case

__all__ = ["SUMMARIES", "Summary", "design_sections", "headline"]


@dataclass(frozen=True)
class Summary:
    """A kind's design summary: ``name`` (the library function that answers, as report.json
    records it), ``function`` (``(case) -> dict``, importing its domain when called) and
    ``headline`` (that dict → the lines printed plainly on the case page)."""

    name: str
    function: Callable[[Case], dict[str, Any]]
    headline: Callable[[dict[str, Any]], list[str]]


def _tdoa_summary(case: Case) -> dict[str, Any]:
    """seed 000 ch. 4: the tdoa design answers (lazy import)."""
    from theory.tdoa.design import design_summary

    return design_summary(case)


def _pursuit_summary(case: Case) -> dict[str, Any]:
    """seed 003: the pursuit design answers (lazy import)."""
    from theory.pursuit.design import design_summary

    return design_summary(case)


def _tdoa_headline(answers: dict[str, Any]) -> list[str]:
    """seed 000 §4.2.2: ρ and the redundancy k, rounded for reading (exact in report.json)."""
    margin = answers["margin"]
    exact = "exact" if margin["exact"] else f"a rank loss exists at {margin['upper_bound']:.4g} m"
    lines = [
        f"Certified displacement margin ρ = {margin['radius']:.4g} m ({exact}): every agent "
        "stays observable while agents and target each move less than ρ."
    ]
    for items in ("links", "agents"):
        answer = answers[f"redundancy_{items}"]
        bound = "exact" if answer["exact"] else f"no smaller set below {answer['certified_below']}"
        lines.append(
            f"Fewest {items} whose loss breaks observability: k = {answer['k']} "
            f"({bound}); e.g. {answer['witness']}."
        )
    return lines


def _pursuit_headline(answers: dict[str, Any]) -> list[str]:
    """seed 003 Thm 1/2: the conditions over the default box and the ISS gain."""
    failing = [
        f"{c['name']} {c['status']}" for c in answers["box_conditions"] if c["status"] != "holds"
    ]
    lines = ["Gain-independent conditions: " + (", ".join(failing) or "all hold")]
    if "gain_at_case" in answers:
        gain = answers["gain_at_case"]
        lines.append(
            f"Certified ISS gain at the case's own gains: between {gain['lo_approx']:.9g}"
            f" and {gain['hi_approx']:.9g}."
        )
        infimum = answers["gain_infimum"]
        lines.append(
            f"No gains do better than {infimum['value']} ∈ [{infimum['lo_approx']:.6g}, "
            f"{infimum['hi_approx']:.6g}] ({infimum['approached']})."
        )
    box = answers["map"]
    axes = ", ".join(f"{p['path']} ∈ [{p['lo']}, {p['hi']}]" for p in box["parameters"])
    counts = ", ".join(f"{n} {s}" for s, n in box["counts"].items())
    lines.append(f"Gain box {axes} (a tenth to ten times the case's gains): cells {counts}.")
    return lines


def _dkf_summary(case: Case) -> dict[str, Any]:
    """seed 000 ch. 5: the supremum self-weight of the default agents (lazy import)."""
    from theory.consensus.design import self_weight_design

    return self_weight_design(case).to_json()


def _dkf_headline(answers: dict[str, Any]) -> list[str]:
    """seed 000 Thm 5.2.10: the self-weight supremum, exact or as a certified bracket."""
    agents = ", ".join(str(a) for a in answers["agent"])
    supremum = answers["supremum"]
    if answers["status"] == "always":
        return [f"Self-weight of agent(s) {agents}: S-detectable over the whole family (w ≤ 1)."]
    if supremum is None:
        return [f"Self-weight of agent(s) {agents}: {answers['status']} ({answers['note']})."]
    exact = supremum.get("rational") or (
        "root of " + " ".join(supremum["polynomial"]) if "polynomial" in supremum else None
    )
    told = f"exactly {exact}" if supremum["exact"] else "bracket " + ", ".join(supremum["interval"])
    return [
        f"Largest self-weight of agent(s) {agents} (row rescaled) keeping S-detectability: "
        f"w* ≈ {supremum['value']:.6g} ({told}); certified S-detectable at "
        f"{answers['below']['w'] if answers['below'] else 'no probed w'}."
    ]


SUMMARIES: dict[str, Summary] = {
    "tdoa": Summary("theory.tdoa.design:design_summary", _tdoa_summary, _tdoa_headline),
    "pursuit": Summary("theory.pursuit.design:design_summary", _pursuit_summary, _pursuit_headline),
    "dkf": Summary("theory.consensus.design:self_weight_design", _dkf_summary, _dkf_headline),
}
"""Case kind → its design summary."""


def design_sections(cases: Sequence[Case]) -> dict[str, dict[str, Any]]:
    """``report.json``'s ``design``: case name → ``{"kind", "function", "answers"}`` (or
    ``"error"`` when the summary raised), for the cases whose kind has a summary."""
    sections = {}
    for case in cases:
        summary = SUMMARIES.get(case.kind)
        if summary is None:
            continue
        section: dict[str, Any] = {"kind": case.kind, "function": summary.name}
        try:
            section["answers"] = summary.function(case)
        except Exception as error:  # a summary's failure is reported, not fatal
            section["error"] = f"{type(error).__name__}: {error}"
        sections[case.name] = section
    return sections


def headline(section: dict[str, Any]) -> list[str]:
    """The lines a case page prints plainly for its design ``section``."""
    if "error" in section:
        return [f"The design summary failed: {section['error']}"]
    return SUMMARIES[section["kind"]].headline(section["answers"])
