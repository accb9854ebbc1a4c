"""The TDOA domain's claims, properties and certifiers (seed 000 ch. 4, App. A; seed 001)."""

from __future__ import annotations

from theory.core.expectations import expectation_claim
from theory.tdoa import model
from theory.tdoa import properties as model_properties
from theory.tdoa.estimation import averaged, simulation, stability
from theory.tdoa.geometry import crb, directions
from theory.tdoa.observability import (
    certificates,
    fig43,
    properties,
    single_agent,
    trajectory,
    weights,
    window,
)

__all__ = ["CERTIFIERS", "CLAIMS", "FIXED_INSTANCES", "PROPERTIES"]

CLAIMS = (
    *model.claims,
    *single_agent.claims,
    *window.claims,
    *directions.claims,
    *fig43.claims,
    *weights.claims,
    *trajectory.claims,
    *certificates.claims,
    *crb.claims,
    *stability.claims,
    *simulation.claims,
    expectation_claim("tdoa", command="topology", observe=trajectory.observe_topology),
    expectation_claim(
        "tdoa-sim", command="simulate", observe=simulation.observe_tdoa_sim, method="simulation"
    ),
)
PROPERTIES = (*properties.PROPERTIES, *averaged.PROPERTIES, *model_properties.PROPERTIES)
FIXED_INSTANCES = model_properties.FIXED_INSTANCES
CERTIFIERS = {"tdoa": (certificates.tdoa_certificates,)}
