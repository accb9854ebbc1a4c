"""What ``trackcert pf`` (and ``trackcert simulate`` on a ``kind: pf`` case) reports.

:func:`pf_report` runs the case's Monte Carlo (seed 002 §3.3, :mod:`theory.particle.experiments`)
and every ``pf`` claim of the domain's registry on it; the claims observe the case's ``expect``
keys in their evidence (``kind: pf`` has no separate observer), and the block is judged from
those observations with :mod:`theory.core.expectations`, exactly as ``trackcert report`` judges
it. With a folder it writes ``pf.json`` and the figures, replacing the folder whole
(:func:`theory.core.atomic_output.replaced_folder`).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from theory.core.atomic_output import check_replaceable, replaced_folder
from theory.core.case_file import Case
from theory.core.claims import ClaimResult, Context, RunCache
from theory.core.consistency import agent_columns
from theory.core.expectations import Expectation, evaluate, observations_from
from theory.core.jsonable import plain
from theory.core.parallel import TaskRunner
from theory.core.verdicts import Verdict, expectations_verdict
from theory.particle.case import require_pf
from theory.particle.experiments import (
    MonteCarlo,
    monte_carlo,
    node_summary,
    pf_metrics,
    shared_monte_carlo,
    write_figures,
)
from theory.particle.registry import CLAIMS

__all__ = ["MARKER", "SNAPSHOT_STEPS", "PfReport", "pf_report"]

MARKER = "pf.json"
"""The file every ``pf`` folder has: a folder without it is not replaced (unless empty)."""

SNAPSHOT_STEPS = (0, 5, 20)
"""Steps whose particle clouds the figures show."""

PF_CLAIMS = tuple(sorted((c for c in CLAIMS if "pf" in c.kinds), key=lambda c: c.id))
SOURCES = {c.id: c.source for c in PF_CLAIMS}


@dataclass(frozen=True)
class PfReport:
    """The record ``trackcert pf`` prints (and writes as ``pf.json``): the case with the runs and
    seed used, the per-node error summary, the ``pf`` claims' results, the expectations judged
    from them, the figures written, and the filter metrics (NEES/NIS bands, OSPA/GOSPA:
    :func:`theory.particle.experiments.pf_metrics`)."""

    case: Case
    agents: list[dict[str, Any]]
    claims: tuple[ClaimResult, ...]
    expectations: tuple[Expectation, ...]
    figures: tuple[str, ...] = ()
    metrics: dict[str, Any] = field(default_factory=dict)

    @property
    def verdict(self) -> Verdict:
        """The expectations' verdict (:func:`theory.core.verdicts.expectations_verdict`)."""
        return expectations_verdict(self.expectations)

    def to_json(self) -> dict[str, Any]:
        """``case``, ``runs``, ``seed``, ``model``, ``share``, ``config``, ``agents``, ``metrics``,
        ``claims``, ``expectations`` (the verdict records) and ``figures``."""
        spec = self.case.spec
        return {
            "case": self.case.name,
            "runs": spec.runs,
            "seed": spec.seed,
            "model": spec.model,
            "share": spec.config.share,
            "config": plain(vars(spec.config)),
            "agents": self.agents,
            "metrics": self.metrics,
            "claims": [r.to_json(SOURCES[r.claim]) for r in self.claims],
            "expectations": [e.to_json() for e in self.expectations],
            "figures": list(self.figures),
        }


def pf_report(
    case: Case,
    *,
    runs: int | None = None,
    seed: int | None = None,
    out: Path | None = None,
    runner: TaskRunner | None = None,
    progress: Callable[[int], None] | None = None,
    figures: bool = True,
) -> PfReport:
    """Run ``case`` (``kind: pf``, else a :class:`CaseError`), its claims and its expectations.

    ``runs`` and ``seed`` default to the case's; the Monte Carlo runs go to ``runner`` (default:
    this process) and are shared by the claims; ``progress`` is called with the number of runs
    finished; ``out`` is the folder for ``pf.json`` and (when ``figures``) the figures, replaced
    whole (``None``: write nothing; :class:`CaseError` if it holds files but no ``pf.json``,
    :class:`OutputError` if writing fails, leaving it as it was).
    """
    require_pf(case)
    if out is not None:
        check_replaceable(out, MARKER)
    spec = replace(
        case.spec, runs=runs or case.spec.runs, seed=case.spec.seed if seed is None else seed
    )
    case = replace(case, spec=spec)
    ctx = Context(RunCache(runner))
    mc = shared_monte_carlo(spec, ctx, progress=progress)
    claims = [result for claim in PF_CLAIMS for result in claim.results(case, ctx)]
    observed = [
        found for r in claims for found in observations_from(r.claim, plain(r.evidence), r.status)
    ]
    expectations = evaluate(case.name, plain(case.expect), observed)
    metrics = pf_metrics(mc, spec)
    agents = [{**row, **agent_columns(metrics, i)} for i, row in enumerate(node_summary(mc, spec))]
    report = PfReport(case, agents, tuple(claims), tuple(expectations), (), metrics)
    if out is None:
        return report
    with replaced_folder(out, MARKER) as staging:
        drawn = _figures(case, mc, staging) if figures else ()
        report = replace(report, figures=tuple(str(Path(out) / Path(f).name) for f in drawn))
        (staging / MARKER).write_text(json.dumps(plain(report.to_json()), indent=2) + "\n")
    return report


def _figures(case: Case, mc: MonteCarlo, folder: Path) -> tuple[str, ...]:
    first = monte_carlo(case.spec, runs=1, snapshot_steps=SNAPSHOT_STEPS)  # = run 0 of mc
    snapshots = replace(mc, snapshots=first.snapshots)
    return tuple(write_figures(snapshots, case.spec, folder, case.name))
