"""The particle-filter domain's claims (seed 002): the DCRW model's, the Monte Carlo
experiments' and the PF-versus-EKF ones; their falsifiable wordings. No certificates."""

from __future__ import annotations

from theory.particle import dcrw, experiments, pf_vs_ekf, properties

__all__ = ["CERTIFIERS", "CLAIMS", "FIXED_INSTANCES", "PROPERTIES"]

CLAIMS = (*dcrw.claims, *experiments.claims, *pf_vs_ekf.claims)
PROPERTIES = properties.PROPERTIES
FIXED_INSTANCES = properties.FIXED_INSTANCES
CERTIFIERS = {}
