"""The consensus domain's claims, properties and certifiers (seed 000 ch. 5, App. A, C)."""

from __future__ import annotations

from theory.consensus import analysis, kalman_filter, properties, suboptimal_gains

__all__ = ["CERTIFIERS", "CLAIMS", "FIXED_INSTANCES", "PROPERTIES"]

CLAIMS = (*analysis.claims, *kalman_filter.claims, *suboptimal_gains.claims)
PROPERTIES = properties.PROPERTIES
FIXED_INSTANCES = properties.FIXED_INSTANCES
CERTIFIERS = {"dkf": (analysis.dkf_certificates,)}
