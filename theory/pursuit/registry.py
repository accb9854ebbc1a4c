"""The pursuit domain's claims, properties and certifiers (seed 003)."""

from __future__ import annotations

from theory.core.expectations import expectation_claim
from theory.pursuit import certificates, derivations, iss, observability, properties, simulation

__all__ = ["CERTIFIERS", "CLAIMS", "FIXED_INSTANCES", "PROPERTIES"]

CLAIMS = (
    *derivations.claims,
    *observability.claims,
    *iss.claims,
    *certificates.claims,
    *simulation.claims,
    expectation_claim("pursuit", command="iss", observe=iss.observe_iss),
)
PROPERTIES = (*properties.PROPERTIES, *properties.MODEL_PROPERTIES)
FIXED_INSTANCES = properties.FIXED_INSTANCES
CERTIFIERS = {"pursuit": (certificates.pursuit_certificates,)}
