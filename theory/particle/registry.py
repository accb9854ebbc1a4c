"""The particle-filter domain's claims (seed 002)."""

from __future__ import annotations

from theory.particle import claims, dcrw_claims, pf_vs_ekf_claims

__all__ = ["CERTIFIERS", "CLAIMS", "PROPERTIES"]

CLAIMS = (*claims.claims, *dcrw_claims.claims, *pf_vs_ekf_claims.claims)
PROPERTIES = ()
CERTIFIERS = {}
