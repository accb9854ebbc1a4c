"""Distributed particle filtering of a fish's correlated random walk (seed 002).

The case kind (:mod:`~theory.particle.case`), the DCRW target model (:mod:`~theory.particle.dcrw`),
the distributed TDOA particle filter with its motion models (:mod:`~theory.particle.filter`), the
Monte Carlo experiments (:mod:`~theory.particle.experiments`), the PF-versus-EKF comparison
(:mod:`~theory.particle.pf_vs_ekf`) and ``trackcert pf``'s record (:mod:`~theory.particle.report`).
"""

__all__: list[str] = []
