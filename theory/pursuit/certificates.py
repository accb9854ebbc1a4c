"""Exact ``iss`` certificates of pursuit cases (seed 003), in the format of docs/certificates.md.

:func:`iss_certificate` turns :func:`theory.pursuit.iss.iss_certificate_data` (exact rationals,
already verified by theory's own :func:`theory.pursuit.iss.verify_certificate`) into the JSON
certificate and re-checks it with the independent checker :mod:`proofs_check` before returning
it. :func:`pursuit_certificates` is the ``pursuit`` kind's certifier
(:func:`theory.certify.register_certifier`): a case whose conditions fail (a graph that is not
strongly connected, ``ε₁ = 0``) gets no certificate, and the reason says which condition.
The claim ``seed003.thm2.certified`` (:mod:`theory.pursuit.certificate_claims`) reports it.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import proofs_check
from theory.certify import register_certifier
from theory.core.case_file import Case
from theory.core.errors import InconclusiveError
from theory.core.tolerances import ISS_DIGITS
from theory.pursuit.case import PursuitSpec
from theory.pursuit.iss import iss_certificate_data

__all__ = ["STATEMENT", "iss_certificate", "pursuit_certificates"]

STATEMENT = (
    "seed 003 Theorem 2 (corrected): ‖ξ(t)‖ + ‖e(t)‖ ≤ β(‖μ(0)‖, t) + gain·sup‖x̃‖ with "
    "‖e(t)‖ ≤ e^(−λt)‖e(0)‖ + g_e sup‖x̃‖ and ‖ξ(t)‖ ≤ κe^(−αt)‖ξ(0)‖ + (b/ρ)∫e^(−α(t−s))‖e_γ‖ds, "
    "for the witness's λ, g_e, κ, α, b, ρ and gain"
)
"""The claim of every ``iss`` certificate (docs/theory/pursuit-iss.md §5, §7)."""


def _text(value: Any) -> Any:
    """Every rational as its exact string, recursively (integers of the Laplacian included)."""
    if isinstance(value, dict):
        return {key: _text(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_text(item) for item in value]
    return str(Fraction(value))


def iss_certificate(spec: PursuitSpec, *, case: str | None = None) -> dict[str, Any]:
    """The exact ``iss`` certificate of a pursuit case, accepted by ``proofs_check``.

    Parameters
    ----------
    spec : PursuitSpec
        The case.
    case : str, optional
        Case name recorded in the certificate.

    Returns
    -------
    dict
        A ``trackcert-certificate/1`` object of kind ``iss``.

    Raises
    ------
    PropertyFails
        If a condition of the analysis fails (the message names it).
    InconclusiveError
        If a condition lies inside its tolerance.
    RuntimeError
        If ``proofs_check`` rejects the certificate (a bug: theory's own check accepted it).

    References
    ----------
    seed 003, Lemmas 1–4, Theorems 1–2; docs/theory/pursuit-iss.md §7.
    """
    exact = iss_certificate_data(spec)
    source = exact["data"]
    data: dict[str, Any] = {
        "dim": spec.dim,
        "controller": spec.controller,
        "epsilon": _text(source["epsilon"]),
        "K_p": _text(source["K_p"]),
        "paths": _text(source["paths"]),
    }
    if spec.controller == "II":
        data["k_gamma"] = _text(source["K"][spec.dim][spec.dim])
    if spec.n_trackers > 1:
        data |= {"laplacian": _text(source["laplacian"]), "k_c": _text(source["k_c"])}
    cert: dict[str, Any] = {
        "format": proofs_check.FORMAT,
        "kind": "iss",
        "source": "seed 003, Lemmas 1–4 and Theorems 1–2 (corrected)",
        **({"case": case} if case is not None else {}),
        "claim": {"statement": STATEMENT},
        "data": data,
        "witness": _text(exact["witness"]),
        "produced_by": {
            "module": "theory.pursuit.certificates",
            "rounding": f"{ISS_DIGITS} significant digits, then moved in the safe direction "
            "until each exact check passes",
        },
    }
    verdict = proofs_check.check_certificate(cert)
    if not verdict.valid:
        failed = [c.name for c in verdict.checks if not c.valid]
        raise RuntimeError(f"the iss certificate failed proofs_check (a bug): {failed}")
    return cert


@register_certifier("pursuit")
def pursuit_certificates(case: Case, seed: int) -> tuple[list[dict[str, Any]], list[str]]:
    """The ``iss`` certificate of a ``pursuit`` case, or the reason there is none.

    Parameters
    ----------
    case : Case
        A loaded ``pursuit`` case.
    seed : int
        Unused (the certificate involves no random choice); kept for the common signature.

    Returns
    -------
    (list of dict, list of str)
        The certificates and the reasons for missing ones.

    Raises
    ------
    PropertyFails
        If a condition of the analysis fails: there is no ISS estimate to certify.
    """
    del seed
    try:
        return [iss_certificate(case.spec, case=case.name)], []
    except InconclusiveError as error:
        return [], [str(error)]
