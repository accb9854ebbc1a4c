"""Shared by the closed-loop and kernel tests: a case's DEC loop and random states of it."""

from __future__ import annotations

import numpy as np

from theory.pursuit.closed_loop import LoopState, build_loop
from theory.pursuit.model import exp_skew
from theory.pursuit.simulation import dec_arguments


def dec_loop(spec, steps):
    """``simulate_dec``'s arguments for ``steps`` records of ``spec`` and the loop they build."""
    arguments = dec_arguments(spec, steps)
    loop = build_loop(
        arguments["settings"], arguments["paths"], arguments["in_neighbours"], spec.dim
    )
    return arguments, loop


def random_state(loop, rng):
    """Trackers anywhere in a 120 m box, any heading, γ in [−5, 5], γ̇ around 0."""
    n, d = loop.n, loop.dim
    angles = rng.uniform(-np.pi, np.pi, (n, 1 if d == 2 else 3))
    return LoopState.of(
        rng.uniform(-60, 60, (n, d)), exp_skew(angles), rng.uniform(-5, 5, n), rng.normal(0, 0.3, n)
    )
