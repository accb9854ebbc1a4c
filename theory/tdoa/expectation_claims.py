"""Claims ``case.expect.tdoa`` and ``case.expect.tdoa-sim``: each case's expect block checked.

Each runs its kind's observer (:func:`theory.tdoa.topology_report.observe_topology`, what
``trackcert topology`` runs; :func:`theory.tdoa.sim_summary.observe_tdoa_sim`, one seeded run of
``trackcert simulate``) and judges the block with :mod:`theory.core.expectations`.
"""

from __future__ import annotations

from theory.core.expectations import expectation_claim

__all__ = ["EXPECTATION_CLAIMS"]

EXPECTATION_CLAIMS = ("case.expect.tdoa", "case.expect.tdoa-sim")
"""The claims this module registers."""

expectation_claim("tdoa", command="topology")
expectation_claim("tdoa-sim", command="simulate", method="simulation")
