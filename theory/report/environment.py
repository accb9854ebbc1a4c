"""What a reader needs to reproduce a report: versions, platform, seeds, cases, tolerances.

Nothing here depends on the time of day, so two runs on one machine give the same record.
"""

from __future__ import annotations

import hashlib
import json
import platform
import subprocess
from collections.abc import Sequence
from importlib import metadata
from pathlib import Path
from typing import Any

import theory
from theory.core.case_file import Case, bundled_case_dir
from theory.core.tolerances import table
from theory.registry import all_claims
from theory.report.records import Record
from theory.report.time_limit import clock_name, enforceable

__all__ = ["PACKAGES", "SEED_RULE", "environment"]

PACKAGES = (
    "numpy",
    "scipy",
    "sympy",
    "networkx",
    "control",
    "cvxpy",
    "clarabel",
    "scs",
    "python-flint",
    "typer",
    "rich",
    "matplotlib",
    "jinja2",
    "pyyaml",
    "hypothesis",
    "threadpoolctl",
)
"""Distributions whose versions the report records (trackcert's runtime dependencies)."""

SEED_RULE = 'claim seed = first 4 bytes (big-endian) of SHA-256("{seed}:{claim id}:{case}")'


def environment(
    seed: int,
    cases: Sequence[Case],
    records: Sequence[Record],
    time_limit: float | None = None,
) -> dict[str, Any]:
    """The environment section of ``report.json``.

    Parameters
    ----------
    seed : int
        The report's seed.
    cases : sequence of Case
        The cases reported on.
    records : sequence of Record
        The results (their tolerances are summarised).
    time_limit : float or None
        CPU seconds allowed to each check (``None``: no limit).

    Returns
    -------
    dict
        ``python``, ``implementation``, ``platform``, ``packages`` (name → version or
        ``"not installed"``), ``trackcert`` (version and source revision), ``seed``,
        ``seed_rule``, ``cases`` (name, kind, file, SHA-256, tolerance overrides),
        ``claim_modules``, ``claims_registered``, ``tolerances`` (name → the distinct
        values used by the claims), ``tolerance_table`` (every named tolerance with its default,
        unit, meaning and why: :func:`theory.core.tolerances.table`), ``time_limit`` (CPU
        seconds or ``None``), ``time_limit_clock`` (what is counted:
        :func:`theory.report.time_limit.clock_name`) and ``time_limit_enforced`` (whether this
        platform can interrupt a check).
    """
    return {
        "python": platform.python_version(),
        "implementation": platform.python_implementation(),
        "platform": platform.platform(),
        "packages": {name: _version(name) for name in PACKAGES},
        "trackcert": {"version": theory.__version__, "revision": _revision()},
        "seed": seed,
        "seed_rule": SEED_RULE,
        "cases": [_case(case) for case in cases],
        "claim_modules": sorted({c.check.__module__ for c in all_claims()}),
        "claims_registered": len(all_claims()),
        "tolerances": _tolerances(records),
        "tolerance_table": table(),
        "time_limit": time_limit,
        "time_limit_clock": clock_name(),
        "time_limit_enforced": time_limit is not None and enforceable(),
    }


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def _revision() -> str | None:
    """``git describe --always --dirty`` of a source checkout; ``None`` for an installed copy."""
    root = Path(theory.__file__).resolve().parent.parent
    if not (root / ".git").exists():
        return None
    try:
        done = subprocess.run(
            ["git", "-C", str(root), "describe", "--always", "--dirty", "--abbrev=12"],
            capture_output=True,
            text=True,
            timeout=30,
            check=False,
        )
    except (OSError, subprocess.SubprocessError):
        return None
    text = done.stdout.strip()
    return text if done.returncode == 0 and text else None


def _case(case: Case) -> dict[str, Any]:
    path = Path(case.file)
    digest = hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else None
    return {
        "name": case.name,
        "kind": case.kind,
        "source": case.source,
        "file": _shown_path(path),
        "sha256": digest,
        "tolerances": dict(case.tolerances),
    }


def _shown_path(path: Path) -> str:
    """``bundled:NAME.yaml`` for bundled cases (their folder differs between installs)."""
    folder = bundled_case_dir().resolve()
    resolved = path.resolve()
    return f"bundled:{resolved.name}" if resolved.parent == folder else str(path)


def _tolerances(records: Sequence[Record]) -> dict[str, list[Any]]:
    used: dict[str, dict[str, Any]] = {}
    for record in records:
        for name, value in record.tolerance.items():
            used.setdefault(name, {})[json.dumps(value, sort_keys=True)] = value
    return {name: [values[k] for k in sorted(values)] for name, values in sorted(used.items())}
