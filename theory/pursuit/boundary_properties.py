"""Never wrong near a threshold (issue 17): seed 003's ISS conditions swept toward each boundary.

The thresholds of ``docs/theory/pursuit-iss.md``: Δ̄ exists iff ``ε₁ ≠ 0`` (§1); the printed
region (72) follows from the proof's argument iff ``λ_min(K) ≥ 1`` (§3); ``K = diag(K_p, k_γ)``
must be positive definite (§2–3), and the certificate's constants must pass exact checks however
small ``λ_min(K)`` is (§7). Examples are seed 003 Table I with three trackers on the directed ring
(``cases/pursuit-table1-n3.yaml``) with the swept gains and offset. "Correct" is computed here
from the decimals as written (``Fraction(repr(x))``), independently of :mod:`theory.pursuit.iss`:

* ``λ_min(K) ≥ 1`` (``k_γ = 5``): for ``K_p = [[a, c], [c, d]]`` iff ``a ≥ 1``, ``d ≥ 1`` and
  ``(a − 1)(d − 1) ≥ c²`` (``K_p − I ⪰ 0``), on diagonal, coupled and rotated ``K_p``;
* the sufficient test of (72), ``c♯ ≤ λ_min(K)·c`` with ``c = √μ + ‖K‖``, ``√μ = 30``,
  ``c♯² = ‖K_p‖² + 1 + 900``: checked in rationals by squaring where ``‖K_p‖`` is rational;
* the ``iss`` certificate: every condition holds exactly iff ``ε₁ ≠ 0`` (the ring is strongly
  connected, ``K ≻ 0``), so a certificate must be issued and accepted by :mod:`proofs_check`,
  or reported inconclusive, when ``ε₁ ≠ 0``; refused (``PropertyFails``) only when ``ε₁ = 0``.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import Any

import yaml
from hypothesis import strategies as st

import proofs_check
from theory.core.case_file import bundled_cases, parse_case
from theory.core.errors import InconclusiveError, PropertyFails
from theory.falsify import Property, register_property
from theory.pursuit.certificates import iss_certificate
from theory.pursuit.iss import iss_conditions, pursuit_iss
from theory.strategy_helpers import boundary_values

__all__ = [
    "CertificatePoint",
    "RegionPoint",
    "certificate_sound",
    "region_case",
    "region_sound",
]

BASE_CASE = "pursuit-table1-n3"
"""The bundled case the examples vary (2-D, Type II, three trackers, r_x = r_y = 30)."""
SHARP_THRESHOLD = Fraction(951340728979, 981035254257)
"""≈ 0.969731439161695, the root of v(30 + v) = √(v² + 901): with K_p = vI and k_γ = v the
sufficient test c♯ ≤ λ_min(K)·c of (72) holds iff v is at least this root (an irrational
number; the sweep is around this rational approximation, the truth is decided exactly)."""


def _decimal(x: float) -> Fraction:
    return Fraction(repr(float(x)))


@cache
def _base() -> dict[str, Any]:
    data = yaml.safe_load(bundled_cases()[BASE_CASE].read_text(encoding="utf-8"))
    data.pop("expect", None)
    return data


def _case(K_p: Any, k_gamma: float, epsilon_1: float, name: str) -> dict[str, Any]:
    data = copy.deepcopy(_base())
    data["name"] = f"boundary-{name}"
    data["source"] = "trackcert falsify (seed 003 boundary sweep, docs/theory/pursuit-iss.md)"
    block = data["pursuit"]
    block.update({"K_p": K_p, "k_gamma": k_gamma, "epsilon": [epsilon_1, block["epsilon"][1]]})
    return data


@dataclass(frozen=True)
class RegionPoint:
    """``K_p`` with its least eigenvalue swept through 1.

    Attributes
    ----------
    form : str
        ``diagonal`` (``K_p = diag(v, 2)``), ``coupled`` (``[[2, v], [v, 2]]``, eigenvalues
        ``2 ± v``), ``rotated`` (``Q diag(v, 2) Qᵀ`` with the 3-4-5 rotation ``Q``, entries
        computed in floats: a matrix whose float eigenvalues land on 1 while its decimals do not),
        all with ``k_γ = 5``; or ``equal`` (``K_p = vI``, ``k_γ = v``, swept through the threshold
        ``v(30 + v) = √(v² + 901)`` of the sufficient test of (72), :data:`SHARP_THRESHOLD`).
    value : float
        The swept ``v``.
    """

    form: str
    value: float


def _gains(point: RegionPoint) -> list[list[float]]:
    v = float(point.value)
    if point.form == "equal":
        return [[v, 0.0], [0.0, v]]
    if point.form == "diagonal":
        return [[v, 0.0], [0.0, 2.0]]
    if point.form == "coupled":
        return [[2.0, v], [v, 2.0]]
    return [[0.36 * v + 1.28, 0.48 * v - 0.96], [0.48 * v - 0.96, 0.64 * v + 0.72]]


def _k_gamma(point: RegionPoint) -> float:
    return float(point.value) if point.form == "equal" else 5.0


def region_case(point: RegionPoint) -> dict[str, Any]:
    """The pursuit case of ``point`` (``ε = (−0.5, 0)``)."""
    return _case(_gains(point), _k_gamma(point), -0.5, f"region-{point.form}")


def _region_truth(point: RegionPoint) -> tuple[bool, bool | None]:
    """(λ_min(K) ≥ 1, c♯ ≤ λ_min(K)·c) in exact rationals (module docstring); the second is
    None for the rotated form, whose eigenvalues are irrational."""
    (a, c), (_, d) = ((_decimal(x) for x in row) for row in _gains(point))
    k_gamma = _decimal(_k_gamma(point))
    sound = k_gamma >= 1 and a >= 1 and d >= 1 and (a - 1) * (d - 1) >= c * c
    if point.form == "rotated":
        return sound, None
    kp = [2 - abs(c), 2 + abs(c)] if point.form == "coupled" else [a, d]
    lam, top = min(*kp, k_gamma), max(*kp, k_gamma)
    shown = lam > 0 and max(kp) ** 2 + 1 + 900 <= (lam * (30 + top)) ** 2
    return sound, shown


def region_sound(point: RegionPoint) -> bool:
    """The exact verdict on ``λ_min(K) ≥ 1`` is right, ``K ≻ 0`` holds, and the sufficient test
    of (72) is claimed only when it is true.

    Parameters
    ----------
    point : RegionPoint

    Returns
    -------
    bool
    """
    spec = parse_case(region_case(point)).spec
    pursuit = pursuit_iss(spec)
    sound, shown = _region_truth(point)
    status = {c.name: c.status for c in iss_conditions(spec)}
    return (
        pursuit.printed_region_sound == sound
        and (shown is not False or not pursuit.printed_region_holds)
        and status["K_positive_definite"] == "holds"
    )


def _region_points() -> st.SearchStrategy[RegionPoint]:
    at_one = st.builds(
        RegionPoint,
        st.sampled_from(["diagonal", "coupled", "rotated"]),
        boundary_values(Fraction(1)),
    )
    at_sharp = boundary_values(SHARP_THRESHOLD).map(lambda v: RegionPoint("equal", v))
    return st.one_of(at_one, at_sharp)


@dataclass(frozen=True)
class CertificatePoint:
    """Gains swept toward 0 and ``ε₁`` toward 0.

    Attributes
    ----------
    k_min : float
        ``K_p = diag(k_min, 0.2)`` (``λ_min(K) = k_min`` when below 0.2 and ``k_γ``).
    k_gamma : float
        ``k_γ > 0``.
    epsilon_1 : float
        The surge component of the offset (0 makes Δ̄ undefined).
    """

    k_min: float
    k_gamma: float
    epsilon_1: float


def _certificate_case(point: CertificatePoint) -> dict[str, Any]:
    return _case([point.k_min, 0.2], point.k_gamma, point.epsilon_1, "certificate")


def certificate_sound(point: CertificatePoint) -> bool:
    """A certificate is issued and accepted by ``proofs_check`` (or reported inconclusive)
    exactly when ``ε₁ ≠ 0``; it is refused only when ``ε₁ = 0``.

    Parameters
    ----------
    point : CertificatePoint

    Returns
    -------
    bool
    """
    spec = parse_case(_certificate_case(point)).spec
    exists = _decimal(point.epsilon_1) != 0
    try:
        cert = iss_certificate(spec)
    except InconclusiveError:
        return exists
    except PropertyFails:
        return not exists
    return exists and proofs_check.check_certificate(cert).valid


def _small() -> st.SearchStrategy[float]:
    return st.integers(0, 11).map(lambda k: 10.0**-k)


def _offsets() -> st.SearchStrategy[float]:
    tiny = st.tuples(st.sampled_from([-1, 1]), st.integers(1, 17)).map(
        lambda t: t[0] * 10.0 ** -t[1]
    )
    return st.one_of(st.just(0.0), st.just(-0.5), tiny)


_ROWS = (
    (
        "seed003.thm1.boundary/corrected",
        "seed003.thm1",
        "Swept through λ_min(K) = 1 (diagonal, coupled and rotated K_p) and through the "
        "threshold of the sufficient test c♯ ≤ λ_min(K)·c, the verdict 'the printed region (72) "
        "follows from the argument' is exact, K ≻ 0 is decided exactly, and the sufficient test "
        "is never claimed when false.",
        _region_points(),
        region_sound,
        region_case,
    ),
    (
        "seed003.thm2.certificate-boundary/corrected",
        "seed003.thm2",
        "With λ_min(K) and k_γ down to 1e-11 and ε₁ down to 1e-17 (and 0), an iss certificate "
        "accepted by proofs_check (or an inconclusive report) exists iff ε₁ ≠ 0.",
        st.builds(CertificatePoint, _small(), _small(), _offsets()),
        certificate_sound,
        _certificate_case,
    ),
)

PROPERTIES = tuple(
    Property(id=i, claim=c, wording="corrected", statement=s, examples=e, holds=h, to_case=t)
    for i, c, s, e, h, t in _ROWS
)
"""The registered properties (corrected wordings, expected to hold)."""

for _prop in PROPERTIES:
    register_property(_prop)
