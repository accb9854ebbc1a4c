"""The simulation engine is generic: Monte Carlo of any ``run(spec, rng)``, deterministic by
seed whatever the worker count, and it loads no model package."""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from theory.sim.simulate import monte_carlo, run_seeds


@dataclass(frozen=True)
class Drift:
    """A toy scenario that is none of the papers' models."""

    mean: float
    size: int


def drift_run(spec: Drift, rng: np.random.Generator) -> np.ndarray:
    return spec.mean + rng.standard_normal(spec.size)


def test_run_i_uses_child_i_of_the_seed_sequence() -> None:
    spec = Drift(2.0, 4)
    runs = monte_carlo(spec, simulate=drift_run, runs=5, seed=7, workers=1)
    for run, sequence in zip(runs, run_seeds(7, 5), strict=True):
        np.testing.assert_array_equal(run, drift_run(spec, np.random.default_rng(sequence)))


def test_results_do_not_depend_on_the_worker_count() -> None:
    spec = Drift(-1.0, 3)
    serial = monte_carlo(spec, simulate=drift_run, runs=4, seed=3, workers=1)
    parallel = monte_carlo(spec, simulate=drift_run, runs=4, seed=3, workers=2)
    for a, b in zip(serial, parallel, strict=True):
        np.testing.assert_array_equal(a, b)


def test_progress_counts_finished_runs_and_bad_counts_raise() -> None:
    seen: list[int] = []
    monte_carlo(Drift(0, 1), simulate=drift_run, runs=3, workers=1, progress=seen.append)
    assert seen == [1, 2, 3]
    with pytest.raises(ValueError, match="runs"):
        monte_carlo(Drift(0, 1), simulate=drift_run, runs=0)
    with pytest.raises(ValueError, match="workers"):
        monte_carlo(Drift(0, 1), simulate=drift_run, runs=2, workers=0)


def test_the_engine_imports_no_model_package() -> None:
    """``theory.sim.{simulate,outputs}`` hold no model: importing them loads none of the domain
    packages."""
    code = (
        "import sys, theory.sim.simulate, theory.sim.outputs\n"
        "print(sorted(m for m in sys.modules if m.split('.')[:2] in "
        "[['theory', p] for p in ('tdoa', 'consensus', 'pursuit', 'particle')]))"
    )
    root = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": str(root)}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=root, env=env
    )
    assert out.stdout.strip() == "[]"
