"""The case kinds: each domain's :class:`~theory.core.case_file.KindSpec`, and their simulators.

Loading a case imports the parsers only (numpy and the core); a simulator is imported when a
case of its kind is simulated.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from theory.consensus.case import DKF
from theory.core import case_file
from theory.core.case_file import Case, KindSpec
from theory.core.errors import CaseError
from theory.particle.case import PF
from theory.pursuit.case import PURSUIT
from theory.tdoa.case import TDOA
from theory.tdoa.sim_case import TDOA_SIM

if TYPE_CHECKING:
    from theory.sim.simulate import Simulator

__all__ = ["KINDS", "SIMULATED", "load_case", "parse_case", "simulator", "simulator_for"]

KINDS: dict[str, KindSpec] = {k.name: k for k in (TDOA, TDOA_SIM, DKF, PURSUIT, PF)}

SIMULATED = ("dkf", "pursuit", "tdoa-sim")
"""Kinds ``trackcert simulate`` runs (``pf`` has its own command, ``trackcert pf``)."""


def load_case(path: str | Path) -> Case:
    """Load and validate a case file, or a bundled case by name, of any kind."""
    return case_file.load_case(path, KINDS)


def parse_case(data: object, *, file: str = "<data>") -> Case:
    """Validate a case given as plain data (the parsed YAML), of any kind."""
    return case_file.parse_case(data, KINDS, file=file)


def simulator(kind: str) -> Callable[[Case, int | None], Any]:
    """``simulate(case, steps)`` of a kind of :data:`SIMULATED` (imported now)."""
    if kind == "dkf":
        from theory.consensus.dkf_report import dkf_simulator

        return dkf_simulator
    if kind == "pursuit":
        from theory.pursuit.simulation import pursuit_simulator

        return pursuit_simulator
    if kind == "tdoa-sim":
        from theory.tdoa.sim_summary import tdoa_simulator

        return tdoa_simulator
    raise ValueError(f"kind {kind!r} is not simulated; simulated kinds: {SIMULATED}")


def simulator_for(case: Case, steps: int | None = None) -> Simulator:
    """The simulator of ``case``'s kind, ``steps`` overriding the case's number of steps.

    Raises
    ------
    CaseError
        If ``trackcert simulate`` does not run the case's kind.
    """
    if case.kind not in SIMULATED:
        raise CaseError("kind", "a kind trackcert simulate runs", case.kind, file=case.file)
    return simulator(case.kind)(case, steps)
