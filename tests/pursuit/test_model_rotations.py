"""exp(S(ω)) of theory.pursuit.model against the matrix exponential (seed 003, eq. (3)).

``exp_skew`` evaluates Rodrigues' formula in half angles through the unit quaternion
(Euler–Rodrigues, one product with a constant basis); the integrator's attitude step
R·exp(½hS(ω₀ + ω₁)) relies on it being the exact rotation, to rounding, at every angle.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from theory.pursuit.model import exp_skew, skew

SCALES = (0.0, 1e-200, 1e-9, 1e-3, 0.3, 1.0, 3.1, np.pi, 10.0)
"""Rotation angles (rad): zero, below the 1e-150 floor, small, the integrator's, near π, beyond."""


@pytest.mark.parametrize("scale", SCALES)
def test_exp_skew_is_the_matrix_exponential_in_3d(scale: float) -> None:
    rng = np.random.default_rng(5)
    axes = rng.normal(size=(6, 3))
    omega = scale * axes / np.linalg.norm(axes, axis=1, keepdims=True)
    expected = np.array([scipy.linalg.expm(skew(w)) for w in omega])
    got = exp_skew(omega)
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-14 * max(1.0, scale))
    identity = np.broadcast_to(np.eye(3), got.shape)
    np.testing.assert_allclose(got @ got.transpose(0, 2, 1), identity, rtol=0, atol=4e-15)
    np.testing.assert_allclose(np.linalg.det(got), 1.0, rtol=0, atol=4e-15)


def test_exp_skew_2d_and_stacked_shapes() -> None:
    """2-D: the rotation by the angle, [[cos, −sin], [sin, cos]] (sin as cos(ψ − π/2): within
    4e-15 at 40 rad; scipy's expm is the less accurate one there, 2e-13); any leading axes, lists
    accepted."""
    angles = np.linspace(-40.0, 40.0, 17)
    cos, sin = np.cos(angles), np.sin(angles)
    expected = np.stack([np.stack([cos, -sin], -1), np.stack([sin, cos], -1)], -2)
    np.testing.assert_allclose(exp_skew(angles[:, None]), expected, rtol=0, atol=4e-15)
    assert exp_skew([0.3]).shape == (2, 2)
    assert exp_skew(np.zeros((2, 5, 3))).shape == (2, 5, 3, 3)
    np.testing.assert_array_equal(exp_skew([0.0, 0.0, 0.0]), np.eye(3))
