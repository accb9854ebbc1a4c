"""The case kinds, each defined by its domain's ``case`` module, and the simulator of each
simulated kind.

Both tables are explicit and lazy: loading a case imports the parser of its own kind only, and a
simulator is imported when a case of its kind is simulated (``trackcert topology`` never imports
the particle filter).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from theory.core import case_file
from theory.core.case_file import Case, KindSpec
from theory.core.errors import CaseError

if TYPE_CHECKING:
    from theory.sim.simulate import Simulator

__all__ = [
    "KINDS",
    "SIMULATED",
    "load_case",
    "parse_case",
    "simulator",
    "simulator_for",
]


def _tdoa() -> KindSpec:
    from theory.tdoa.case import TDOA

    return TDOA


def _tdoa_sim() -> KindSpec:
    from theory.tdoa.case import TDOA_SIM

    return TDOA_SIM


def _dkf() -> KindSpec:
    from theory.consensus.case import DKF

    return DKF


def _pursuit() -> KindSpec:
    from theory.pursuit.case import PURSUIT

    return PURSUIT


def _pf() -> KindSpec:
    from theory.particle.case import PF

    return PF


class _Kinds(Mapping[str, KindSpec]):
    """Kind name → its :class:`KindSpec`, each imported when first looked up."""

    def __init__(self, loaders: dict[str, Callable[[], KindSpec]]) -> None:
        self._loaders = loaders

    def __getitem__(self, kind: str) -> KindSpec:
        return self._loaders[kind]()

    def __iter__(self) -> Iterator[str]:
        return iter(sorted(self._loaders))

    def __len__(self) -> int:
        return len(self._loaders)


KINDS: Mapping[str, KindSpec] = _Kinds(
    {"tdoa": _tdoa, "tdoa-sim": _tdoa_sim, "dkf": _dkf, "pursuit": _pursuit, "pf": _pf}
)
"""Every case kind by name (looking one up imports that kind's module only)."""

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
        from theory.consensus.kalman_filter import dkf_simulator

        return dkf_simulator
    if kind == "pursuit":
        from theory.pursuit.simulation import pursuit_simulator

        return pursuit_simulator
    if kind == "tdoa-sim":
        from theory.tdoa.estimation.simulation import tdoa_simulator

        return tdoa_simulator
    raise ValueError(f"kind {kind!r} is not simulated; simulated kinds: {SIMULATED}")


def simulator_for(case: Case, steps: int | None = None, runs: int | None = None) -> Simulator:
    """The simulator of ``case``'s kind, ``steps`` overriding the case's number of steps (a kind
    ``trackcert simulate`` does not run is a :class:`CaseError`); ``runs``, the Monte Carlo runs
    planned, chooses the pursuit loop's default engine (a short job runs without numba:
    :func:`theory.core.engines.resolve_engine`)."""
    if case.kind not in SIMULATED:
        raise CaseError("kind", "a kind trackcert simulate runs", case.kind, file=case.file)
    if case.kind == "pursuit":
        return simulator(case.kind)(case, steps, runs)
    return simulator(case.kind)(case, steps)
