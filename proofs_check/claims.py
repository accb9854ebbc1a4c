"""What each kind claims about its own numbers: the range in which a claimed ``ρ`` or rate
implies the claim the kind's name makes. A witness of ``r_σ(L) < ρ`` shows ``r_σ(L) < 1`` only
for ``ρ ≤ 1``; multipliers excluding ``r_σ(L) < ρ`` exclude ``r_σ(L) < 1`` only for ``ρ ≥ 1``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from proofs_check import parse as p

__all__ = ["CLAIMED", "claimed"]

_RHO, _POSITIVE = "spectral_radius_below", "ρ bounds a spectral radius"
CLAIMED = {
    "mjls-stability": (
        _RHO,
        "(0, 1]",
        "the kind claims r_σ(L) < 1, which r_σ(L) < ρ shows only for ρ ≤ 1",
    ),
    "s-detectability": (
        _RHO,
        "(0, 1]",
        "the kind claims S-detectability, gains with r_σ(L) < 1, which gains with r_σ(L) < ρ show "
        "only for ρ ≤ 1 (kind gains-radius-below claims r_σ(L) < ρ for any ρ)",
    ),
    "gains-radius-below": (_RHO, "(0, ∞)", _POSITIVE),
    "s-detectability-infeasible": (
        _RHO,
        "[1, ∞)",
        "the kind claims that no gains give r_σ(L) < 1, which multipliers at ρ show only for "
        "ρ ≥ 1 (kind gains-radius-below-infeasible claims it for any ρ)",
    ),
    "gains-radius-below-infeasible": (_RHO, "(0, ∞)", _POSITIVE),
    "covariance-bound": (
        "rate",
        "(0, 1]",
        "the kind claims bounded covariances, which f₁ⁱ(M, X) ≺ r Xⁱ shows only for r ≤ 1",
    ),
}
"""Kind → (claim field, the range in which it implies the kind's claim, why)."""


def claimed(cert: dict[str, Any]) -> Fraction:
    """The claim's number, refused outside the kind's range (:data:`CLAIMED`)."""
    key, span, why = CLAIMED[cert["kind"]]
    claim = p.fields(cert["claim"], "claim", (key,), ("statement",))
    return p.bounded(claim[key], f"claim.{key}", span, why)
