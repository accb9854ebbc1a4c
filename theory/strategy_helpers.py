"""Building blocks shared by the public hypothesis strategies of every domain.

:mod:`theory.strategies` (systems, consensus problems, pursuit) and :mod:`theory.tdoa.strategies`
(networks, weights, TDOA scenes) draw their randomness and check their bounds with these, so an
impossible request is refused the same way everywhere (``InvalidArgument`` naming the value).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from theory.core.validation import limit

__all__ = [
    "boundary_values",
    "case_floats",
    "check_range",
    "example_record",
    "flush_tiny",
    "generators",
    "orthonormal_matrix",
]


def check_range(name_low: str, low: int, name_high: str, high: int, floor: int) -> None:
    """Refuse a size range ``[low, high]`` with ``low < floor`` or ``high < low``."""
    if low < floor:
        raise InvalidArgument(f"{name_low}={low} must be at least {floor}")
    if high < low:
        raise InvalidArgument(f"{name_high}={high} must be ≥ {name_low}={low}")


def generators() -> st.SearchStrategy[np.random.Generator]:
    """``numpy.random.Generator``s seeded by a drawn 32-bit integer (shrinks by its seed)."""
    return st.integers(0, 2**32 - 1).map(np.random.default_rng)


def orthonormal_matrix(rng: np.random.Generator, n: int) -> np.ndarray:
    """A random ``n × n`` orthogonal matrix (QR of a Gaussian matrix, signs fixed: Haar)."""
    q, r = np.linalg.qr(rng.standard_normal((n, n)))
    return q * np.sign(np.diag(r))


def boundary_values(
    threshold: Fraction, *, min_exponent: int = 1, max_exponent: int = 17
) -> st.SearchStrategy[float]:
    """Floats ``t (1 ± 10^{-k})`` for ``k`` in ``[min_exponent, max_exponent]``, and ``t``
    itself (``k = 17`` is below float resolution: such draws land on or next to ``t``)."""
    if not threshold > 0:
        raise InvalidArgument(f"threshold={threshold} must be positive")
    check_range("min_exponent", min_exponent, "max_exponent", max_exponent, 1)
    t = float(threshold)
    offsets = st.tuples(st.sampled_from((-1, 1)), st.integers(min_exponent, max_exponent))
    return st.one_of(st.just(t), offsets.map(lambda o: t * (1 + o[0] * 10.0 ** -o[1])))


def case_floats(low: float, high: float) -> st.SearchStrategy[float]:
    """Floats in ``[low, high]`` that a case file accepts: a draw smaller in magnitude than
    ``10^-e`` (the ``exponent`` limit of :mod:`theory.core.validation`) becomes ``0.0``.

    Hypothesis likes tiny floats such as ``5e-152``; a case field refuses them (their products
    underflow), and for every generated quantity they mean 0.
    """
    return st.floats(low, high).map(lambda x: float(flush_tiny(np.float64(x))))


def flush_tiny(values: np.ndarray) -> np.ndarray:
    """``values`` with every entry smaller in magnitude than ``10^-e`` (the ``exponent`` limit of
    :mod:`theory.core.validation`) set to 0, so that computed entries (a rotated gain matrix) are
    accepted by a case file.
    """
    smallest = 10.0 ** -limit("exponent")
    return np.where(np.abs(values) < smallest, 0.0, values)


def example_record(claim: str, example: dict[str, Any]) -> dict[str, Any]:
    """The plain-data record of a counterexample to a claim about the model alone (no case kind
    holds it): the claim and the example's data (:func:`theory.falsify.falsify` adds how to rerun
    the search that found it)."""
    return {
        "name": f"falsify-{claim}",
        "source": "trackcert falsify (shrunk counterexample)",
        "claim": claim,
        "example": example,
    }
