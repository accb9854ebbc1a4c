"""The shared core: errors, case files and validation, networks, rank, rationals, claim registry.

Nothing here knows a particular system; the domain packages (:mod:`theory.tdoa`,
:mod:`theory.consensus`, :mod:`theory.pursuit`, :mod:`theory.particle`) build on it.
"""
