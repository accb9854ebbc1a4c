"""Claim ``case.expect.dkf``: each dkf case's expect block checked as ``trackcert dkf`` does.

It runs the kind's observer (:func:`theory.consensus.dkf_report.observe_dkf`) and judges the block
with :mod:`theory.core.expectations`.
"""

from __future__ import annotations

from theory.core.expectations import expectation_claim

__all__ = ["EXPECTATION_CLAIMS"]

EXPECTATION_CLAIMS = ("case.expect.dkf",)
"""The claims this module registers."""

expectation_claim("dkf", command="dkf")
