"""Distributed particle filtering of a fish's correlated random walk (seed 002).

The DCRW target model, the distributed TDOA particle filter, online learning of the motion
model, Monte Carlo experiments, claims and figures.
"""
