"""``trackcert iss CASE``: ISS Lyapunov analysis of the pursuit/coordination loop (seed 003).

Exit codes (DESIGN.md): 0 every condition holds, 1 a condition fails (e.g. ε₁ = 0 so ΔΔᵀ is
singular, or a graph without the strong connectivity Lemma 3 needs), 2 bad input, 3 a margin lies
inside ``margin_tol`` (inconclusive; the output says which condition).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import typer
from rich.table import Table

from theory.cli.common import (
    case_argument,
    console,
    finish,
    json_option,
    reports_errors,
    verdict_exit_code,
)
from theory.core.case_file import load_case
from theory.core.claims import get_claim
from theory.core.errors import CaseError

__all__ = ["SCOPE", "iss_report", "register"]


def iss_report(case: Any, *, margin_tol: float | None = None) -> dict[str, Any]:
    """The ``trackcert iss`` record of a ``kind: pursuit`` case (plain JSON-able data).

    Parameters
    ----------
    case : theory.core.case_file.Case
        A loaded pursuit case.
    margin_tol : float, optional
        Overrides the case's ``tolerances.margin_tol`` (default 1e-9).

    Returns
    -------
    dict
        ``{"case","controller","lyapunov","decay_rate","iss_gain","conditions","claims",…}``.

    Raises
    ------
    CaseError
        If the case is not of kind ``pursuit``.
    """
    from theory.pursuit.iss import (  # sympy/scipy: imported on use
        DEFAULT_MARGIN_TOL,
        coordination_iss,
        iss_bound,
        iss_conditions,
        pursuit_iss,
    )
    from theory.pursuit.iss_claims import run_case_claims
    from theory.pursuit.iss_symbolic import lyapunov_derivative_check

    if case.kind != "pursuit":
        raise CaseError(
            "kind", "pursuit (trackcert iss analyses seed 003 cases)", case.kind, file=case.file
        )
    tol = _margin_tol(case, margin_tol, DEFAULT_MARGIN_TOL)
    spec = case.spec
    conditions = iss_conditions(spec, margin_tol=tol)
    pursuit, coordination = pursuit_iss(spec), coordination_iss(spec)
    statuses = {c.status for c in conditions}
    holds = "fails" not in statuses and "inconclusive" not in statuses
    gains: dict[str, Any] = {"pursuit": pursuit.gain, "pursuit_paper": pursuit.paper_gain}
    gains["coordination"] = coordination.gain
    gains["cascade"] = iss_bound(spec).gain if "fails" not in statuses else None
    r = [float(x) for x in coordination.r] if coordination.r else None
    identity = lyapunov_derivative_check(spec.dim, spec.controller, True)
    return {
        "case": case.name,
        "source": case.source,
        "controller": spec.controller,
        "dim": spec.dim,
        "n_trackers": spec.n_trackers,
        "holds": holds,
        "scope": SCOPE,
        "lyapunov": _lyapunov(spec, len(pursuit.K), r, identity.holds),
        "decay_rate": {
            "pursuit": pursuit.decay_rate,
            "pursuit_lyapunov": 2 * pursuit.decay_rate,
            "coordination": coordination.decay_rate,
            "coordination_spectral": coordination.spectral_rate,
            "coordination_printed_eq75": coordination.printed_decay_coefficient,
        },
        "iss_gain": gains,
        "constants": _constants(pursuit, coordination, r),
        "conditions": [c.to_json(tol) for c in conditions],
        "expectations": _expectations(case.expect, holds, conditions),
        "claims": [r.to_json(get_claim(r.claim).source) for r in run_case_claims(case)],
        "tolerances": {"margin_tol": tol},
    }


SCOPE = (
    "the pursuit and coordination errors μ = (ξ, e) are ISS with respect to the DEKF's "
    "estimation error x̃ (Theorem 2, corrected); x̃ is the input: whether the DEKF keeps it "
    "bounded in closed loop is not part of the certificate"
)
"""What a ``holds`` verdict of ``trackcert iss`` covers (and what it does not)."""


def _margin_tol(case: Any, margin_tol: float | None, default: float) -> float:
    if margin_tol is not None and not margin_tol > 0:
        raise CaseError("--margin-tol", "a number > 0", margin_tol, file=case.file)
    tol = margin_tol if margin_tol is not None else case.tolerances.get("margin_tol")
    return default if tol is None else float(tol)


def _lyapunov(spec: Any, size: int, r: list[float] | None, identity: bool) -> dict[str, Any]:
    return {
        "pursuit": {
            "function": "V_e = ½‖e‖² = eᵀ P_e e, e = col(e_p^[i], e_γ^[i])",
            "P_e": 0.5 * np.eye(size * spec.n_trackers),
            "derivative_identity_eq70": identity,
        },
        "coordination": {
            "function": "V_c = ½ ξᵀ R ξ, ξ = (I − 1rᵀ)γ, R = diag(r)",
            "R": np.diag(r) if r else None,
        },
    }


def _constants(pursuit: Any, coordination: Any, r: list[float] | None) -> dict[str, Any]:
    return pursuit.constants() | {
        "printed_region_eq72_argument_sound": pursuit.printed_region_sound,
        "printed_region_eq72_holds_by_sharp_bound": pursuit.printed_region_holds,
        "a_L": coordination.a_L,
        "r": r,
        "kappa": coordination.kappa,
        "b": coordination.b,
    }


def _expectations(expect: dict[str, Any], holds: bool, conditions: list) -> list[dict[str, Any]]:
    """Compare the case's ``expect`` block with what was found (``simulation_bounded`` is
    observed by ``trackcert simulate`` and claim ``seed003.thm2.sim-trajectories``, not here)."""
    found = {c.name: c.status == "holds" for c in conditions}
    actual = {
        "iss": holds,
        "delta_full_rank": found.get("delta_full_rank"),
        "strongly_connected": found.get("graph_strongly_connected", True),
    }
    return [
        {"key": key, "expected": value, "actual": actual[key], "met": actual[key] == value}
        for key, value in expect.items()
        if key in actual
    ]


def _exit_code(record: dict[str, Any]) -> int:
    statuses = {c["status"] for c in record["conditions"]}
    return verdict_exit_code(
        False if "fails" in statuses else None if "inconclusive" in statuses else True
    )


def _print_table(record: dict[str, Any]) -> None:
    console.print(
        f"{record['case']}: Type {record['controller']}, {record['dim']}D, "
        f"N = {record['n_trackers']}",
        markup=False,
        highlight=False,
    )
    table = Table(title="conditions")
    for column in ("condition", "status", "value", "margin", "source"):
        table.add_column(column)
    for c in record["conditions"]:
        margin = "" if c["margin"] is None else f"{c['margin']:.3g}"
        table.add_row(c["name"], c["status"], str(c["value"]), margin, c["source"])
    console.print(table)
    rates, gains = record["decay_rate"], record["iss_gain"]
    console.print(
        f"decay rates: pursuit {rates['pursuit']}, coordination {rates['coordination']}\n"
        f"ISS gains: pursuit {gains['pursuit']}, coordination {gains['coordination']}, "
        f"cascade {gains['cascade']}\nscope: {record['scope']}",
        markup=False,
        highlight=False,
    )
    claims = Table(title="claims")
    for column in ("id", "status", "message"):
        claims.add_column(column)
    for claim in record["claims"]:
        claims.add_row(claim["id"], claim["status"], claim["message"])
    console.print(claims)


def register(app: typer.Typer) -> None:
    """Add the ``iss`` command to ``app``."""

    @app.command("iss")
    @reports_errors
    def iss(
        case: str = case_argument("Case file or bundled case name (kind: pursuit)."),
        as_json: bool = json_option(),
        margin_tol: float = typer.Option(
            None, "--margin-tol", help="Relative margin under which a condition is inconclusive."
        ),
    ) -> None:
        """ISS Lyapunov analysis of the pursuit/coordination loop (seed 003)."""
        record = iss_report(load_case(case), margin_tol=margin_tol)
        finish(record, _exit_code(record), as_json=as_json, show=lambda: _print_table(record))
