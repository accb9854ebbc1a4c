"""What ``trackcert pf`` (and ``trackcert simulate`` on a ``kind: pf`` case) reports.

:func:`pf_report` runs the case's Monte Carlo (seed 002 §3.3, :mod:`theory.particle.experiments`)
and every registered claim of kind ``pf``; the claims observe the case's ``expect`` keys in their
evidence (``kind: pf`` has no separate observer), and the block is judged from those
observations with :mod:`theory.core.expectations`, exactly as ``trackcert report`` judges it.
With a folder it writes ``pf.json`` and the figures, replacing the folder whole
(:func:`theory.core.atomic_output.replaced_folder`). The command only prints the record and
exits with the expectations' verdict (:mod:`theory.core.verdicts`).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from theory.core.atomic_output import check_replaceable, replaced_folder
from theory.core.case_file import Case
from theory.core.claims import ClaimResult, all_claims, applicable_results, get_claim
from theory.core.errors import CaseError
from theory.core.expectations import Expectation, evaluate, observations_from
from theory.core.jsonable import plain
from theory.core.parallel import TaskRunner
from theory.core.run_cache import RunCache
from theory.core.verdicts import Verdict, expectations_verdict

__all__ = ["MARKER", "SNAPSHOT_STEPS", "PfReport", "pf_report"]

MARKER = "pf.json"
"""The file every ``pf`` folder has: a folder without it is not replaced (unless empty)."""

SNAPSHOT_STEPS = (0, 5, 20)
"""Steps whose particle clouds the figures show."""


@dataclass(frozen=True)
class PfReport:
    """The record ``trackcert pf`` prints (and writes as ``pf.json``).

    Attributes
    ----------
    case : Case
        The case, with the runs and seed used.
    agents : list of dict
        Per-node error summary (:func:`theory.particle.experiments.node_summary`).
    claims : tuple of ClaimResult
        Every registered ``pf`` claim's results on the case.
    expectations : tuple of Expectation
        The case's ``expect`` block judged against the claims' observations.
    figures : tuple of str
        Figure files written (none without a folder).
    """

    case: Case
    agents: list[dict[str, Any]]
    claims: tuple[ClaimResult, ...]
    expectations: tuple[Expectation, ...]
    figures: tuple[str, ...] = ()

    @property
    def verdict(self) -> Verdict:
        """The expectations' verdict (:func:`theory.core.verdicts.expectations_verdict`)."""
        return expectations_verdict(self.expectations)

    def to_json(self) -> dict[str, Any]:
        """``case``, ``runs``, ``seed``, ``model``, ``share``, ``config``, ``agents``,
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
            "claims": [r.to_json(get_claim(r.claim).source) for r in self.claims],
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
) -> PfReport:
    """Run ``case`` (``kind: pf``), its claims and its expectations; write ``out`` if given.

    Parameters
    ----------
    case : Case
        A loaded case; anything but ``kind: pf`` is refused.
    runs, seed : int, optional
        Monte Carlo runs and base seed (``None``: the case's own).
    out : Path, optional
        Folder for ``pf.json`` and figures, replaced whole (``None``: write nothing).
    runner : TaskRunner, optional
        An open engine for the Monte Carlo runs (default: this process, serially); the claims
        share them through one :class:`~theory.core.run_cache.RunCache`.
    progress : callable, optional
        Called with the number of the case's runs finished.

    Returns
    -------
    PfReport

    Raises
    ------
    CaseError
        If the case is not ``kind: pf``, or ``out`` holds files but no ``pf.json``.
    OutputError
        If writing ``out`` fails (it is left as it was).
    """
    from theory.particle.experiments import node_summary, shared_monte_carlo

    if case.kind != "pf":
        raise CaseError(
            "kind", "pf (this command runs particle-filter cases)", case.kind, file=case.file
        )
    if out is not None:
        check_replaceable(out, MARKER)
    spec = replace(
        case.spec, runs=runs or case.spec.runs, seed=case.spec.seed if seed is None else seed
    )
    case = replace(case, spec=spec)
    cache = RunCache(runner)
    mc = shared_monte_carlo(spec, cache=cache, progress=progress)
    claims = [
        result
        for claim in all_claims()
        if "pf" in claim.kinds
        for result in applicable_results(claim, case, cache=cache)
    ]
    observed = [
        found for r in claims for found in observations_from(r.claim, plain(r.evidence), r.status)
    ]
    expectations = evaluate(case.name, plain(case.expect), observed)
    report = PfReport(case, node_summary(mc, spec), tuple(claims), tuple(expectations), ())
    if out is None:
        return report
    with replaced_folder(out, MARKER) as staging:
        figures = tuple(str(Path(out) / Path(f).name) for f in _figures(case, mc, staging))
        report = replace(report, figures=figures)
        (staging / MARKER).write_text(json.dumps(plain(report.to_json()), indent=2) + "\n")
    return report


def _figures(case: Case, mc: Any, folder: Path) -> tuple[str, ...]:
    from theory.particle.experiments import monte_carlo
    from theory.particle.figures import write_figures

    first = monte_carlo(case.spec, runs=1, snapshot_steps=SNAPSHOT_STEPS)  # = run 0 of mc
    snapshots = replace(mc, snapshots=first.snapshots)
    return tuple(write_figures(snapshots, case.spec, folder, case.name))
