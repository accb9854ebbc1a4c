"""TDOA-based distributed localization of a moving target (seed 000 ch. 4, App. A–B; seed 001).

The model (constant-velocity target, TDOA measurements and Jacobians, averaged EKF, steering
agents), its observability theory (generic rank, topology, geometry), its certificates, claims,
falsifiable properties and closed-loop scenario.
"""
