"""The particle-filter domain's claims (seed 002): the DCRW model's, the Monte Carlo
experiments' and the PF-versus-EKF ones. No properties or certificates."""

from __future__ import annotations

from theory.particle import dcrw, experiments, pf_vs_ekf

__all__ = ["CERTIFIERS", "CLAIMS", "PROPERTIES"]

CLAIMS = (*dcrw.claims, *experiments.claims, *pf_vs_ekf.claims)
PROPERTIES = ()
CERTIFIERS = {}
