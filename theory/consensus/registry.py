"""The consensus domain's claims, properties and certifiers (seed 000 ch. 5, App. A, C)."""

from __future__ import annotations

from theory.consensus import (
    boundary_properties,
    case_certificates,
    certificate_claims,
    claims,
    properties,
    riccati_properties,
    simulation_claims,
    suboptimal_gains_claims,
)
from theory.consensus.dkf_report import observe_dkf
from theory.core.expectations import expectation_claim

__all__ = ["CERTIFIERS", "CLAIMS", "PROPERTIES"]

CLAIMS = (
    *claims.claims,
    *certificate_claims.claims,
    *simulation_claims.claims,
    *suboptimal_gains_claims.claims,
    expectation_claim("dkf", command="dkf", observe=observe_dkf),
)
PROPERTIES = (
    *properties.PROPERTIES,
    *boundary_properties.PROPERTIES,
    *riccati_properties.PROPERTIES,
)
CERTIFIERS = {"dkf": (case_certificates.dkf_certificates,)}
