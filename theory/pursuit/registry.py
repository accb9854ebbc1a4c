"""The pursuit domain's claims, properties and certifiers (seed 003)."""

from __future__ import annotations

from theory.core.expectations import expectation_claim
from theory.pursuit import (
    boundary_properties,
    certificate_claims,
    certificates,
    iss_claims,
    observability_claims,
    properties,
    simulation_claims,
)
from theory.pursuit.iss_report import observe_iss

__all__ = ["CERTIFIERS", "CLAIMS", "PROPERTIES"]

CLAIMS = (
    *iss_claims.claims,
    *observability_claims.claims,
    *certificate_claims.claims,
    *simulation_claims.claims,
    expectation_claim("pursuit", command="iss", observe=observe_iss),
)
PROPERTIES = (*properties.PROPERTIES, *boundary_properties.PROPERTIES)
CERTIFIERS = {"pursuit": (certificates.pursuit_certificates,)}
