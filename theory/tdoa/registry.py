"""The TDOA domain's claims, properties and certifiers (seed 000 ch. 4, App. A; seed 001)."""

from __future__ import annotations

from theory.core.expectations import expectation_claim
from theory.tdoa import (
    averaged_properties,
    boundary_properties,
    case_certificates,
    certificate_claims,
    formation_claims,
    geometry_properties,
    model_claims,
    networked_properties,
    observability_claims,
    path_lemma_claims,
    simulation_claims,
    stochastic_stability_claims,
    topology_claims,
    window_observability_claims,
)
from theory.tdoa.sim_summary import observe_tdoa_sim
from theory.tdoa.topology_report import observe_topology

__all__ = ["CERTIFIERS", "CLAIMS", "PROPERTIES"]

CLAIMS = (
    *observability_claims.claims,
    *topology_claims.claims,
    *model_claims.claims,
    *formation_claims.claims,
    *path_lemma_claims.claims,
    *stochastic_stability_claims.claims,
    *window_observability_claims.claims,
    *simulation_claims.claims,
    *certificate_claims.claims,
    expectation_claim("tdoa", command="topology", observe=observe_topology),
    expectation_claim(
        "tdoa-sim", command="simulate", observe=observe_tdoa_sim, method="simulation"
    ),
)
PROPERTIES = (
    *averaged_properties.PROPERTIES,
    *boundary_properties.PROPERTIES,
    *geometry_properties.PROPERTIES,
    *networked_properties.PROPERTIES,
)
CERTIFIERS = {"tdoa": (case_certificates.tdoa_certificates,)}
