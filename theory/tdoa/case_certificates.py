"""The certificates of a ``kind: tdoa`` case (``trackcert certify``, :mod:`theory.certify`).

Today one certificate kind: ``generic-rank`` of the network observability matrix and of each
agent's block column (:mod:`theory.tdoa.rank_certificates`), one group per distinct network of
the scene.
"""

from __future__ import annotations

from theory.certify import Certified, register_certifier
from theory.core.case_file import Case
from theory.core.exact import RationalizationError
from theory.tdoa.rank_certificates import generic_rank_certificates

__all__ = ["tdoa_certificates"]


@register_certifier("tdoa")
def tdoa_certificates(case: Case, seed: int) -> Certified:
    """The ``generic-rank`` certificates of ``case`` (seed 000 eqs. (4.36)–(4.37)).

    Parameters
    ----------
    case : Case
        A ``kind: tdoa`` case.
    seed : int
        Seed of the random rational evaluation point.

    Returns
    -------
    (list of dict, list of str)
        The certificates, or none and the reason (a point that cannot be rationalized).
    """
    try:
        return generic_rank_certificates(case.spec, seed=seed, case=case.name), []
    except RationalizationError as error:
        return [], [str(error)]
