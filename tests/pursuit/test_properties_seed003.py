"""Seed 003's model properties (issue 27): the identity check separates the printed S(ω) from
the right one, and the shrunk counterexamples are the errata's."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from theory.falsify import DEFAULT_EXAMPLES, falsify
from theory.pursuit.properties import (
    IDENTITIES,
    IDENTITY_DIGITS,
    IdentityPoint,
    gram_determinant,
    identity_residual,
)
from theory.registry import properties_for


@given(st.sampled_from(sorted(n for n in IDENTITIES if "printed" not in n)), st.integers(0, 99))
def test_true_identities_vanish_to_the_working_precision(name: str, seed: int) -> None:
    assert identity_residual(IdentityPoint(name, seed)) <= 10.0 ** (10 - IDENTITY_DIGITS)


def test_the_printed_skew_matrix_fails_far_above_the_precision() -> None:
    """It equals [ω]ₓ only where p = q, which none of these rational points has."""
    for seed in range(20):
        assert identity_residual(IdentityPoint("eq4-printed-S-3d", seed)) > 1e-6, seed


def test_counterexamples_are_the_errata() -> None:
    (helix,) = properties_for("seed003.eq15.helix/paper")
    assert falsify(helix, examples=DEFAULT_EXAMPLES, seed=0).counterexample == -1.0
    (delta,) = properties_for("seed003.eq22.delta-bar/paper")
    epsilon = falsify(delta, examples=DEFAULT_EXAMPLES, seed=0).counterexample
    assert epsilon[0] == 0 and any(epsilon) and gram_determinant(epsilon) == 0
    assert np.isclose(float(gram_determinant((1, 2, 2))), 9)  # ε₁²‖ε‖² in 3-D
