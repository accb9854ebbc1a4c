"""Claim ``case.expect.pursuit``: a pursuit case's expect block checked as ``trackcert iss`` does.

It runs the kind's observer (:func:`theory.pursuit.iss_report.observe_iss`) and judges the
block with :mod:`theory.core.expectations`; ``simulation_bounded`` is observed by the claim
``seed003.thm2.sim-trajectories`` (:mod:`theory.pursuit.simulation_claims`).
"""

from __future__ import annotations

from theory.core.expectations import expectation_claim

__all__ = ["EXPECTATION_CLAIMS"]

EXPECTATION_CLAIMS = ("case.expect.pursuit",)
"""The claims this module registers."""

expectation_claim("pursuit", command="iss")
