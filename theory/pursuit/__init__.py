"""Range-based cooperative pursuit of a moving target (seed 003).

Tracker kinematics, S-T curves, the information-form DEKF, the closed DEC loop, the ISS analysis
of pursuit and coordination, certificates, claims and falsifiable properties.
"""
