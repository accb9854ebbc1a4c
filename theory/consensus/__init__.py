"""Consensus-based distributed Kalman filtering (seed 000 ch. 5, App. C).

Operators on N-tuples of covariances, S-detectability (exact LMI decision), the necessary
conditions of Thm 5.2.10, self-weight bounds, coupled Riccati iterations, the consensus Kalman
filter, certificates, claims and falsifiable properties.
"""
