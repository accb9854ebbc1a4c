"""Seed 003: the ``expect`` bands of the ``pursuit-published-*`` cases from the authors' scripts
under GNU Octave (issue 27; docs/simulation.md, "The published cases").

Reads a log of :mod:`seed003_octave` (``benchmarks/seed003_octave_runs.txt``: per run a line
``SCRIPT seed=S cpu=C`` and one ``RESULT`` line per tracker) and prints, per published case:

* the per-seed table of the authors' final position error ‖q − q̂‖ and mean pursuit error
  ‖[e_p; e_γ]‖ per tracker (markdown);
* per tracker, over the seeds: the authors' min–max and mean ± standard deviation, and the same
  for trackcert's runs 0–9 (``trackcert simulate CASE --runs 10``), with z = the difference of the
  means over its standard error (Welch);
* the band of each statistic, :func:`band`: [min, max] over every seed and tracker of the
  authors' runs, rounded outward to :data:`ROUNDING` m. It is the range the authors' code
  produces, which the case's ``expect`` block applies to each tracker's run-mean (one band for all
  trackers: the expect rule ``within`` takes one [low, high]); and whether trackcert's run-means
  lie in it::

    PYTHONPATH=. python benchmarks/seed003_bands.py [benchmarks/seed003_octave_runs.txt]
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from theory.kinds import load_case  # noqa: E402
from theory.pursuit.closed_loop import StopCause  # noqa: E402
from theory.pursuit.simulation import SIMULATION_SEED, run_pursuit_case  # noqa: E402
from theory.sim.simulate import run_seeds  # noqa: E402

CASES = {
    "SLAP_2D_1Tracker": "pursuit-published-2d-n1",
    "SLAP_2D_3Trackers": "pursuit-published-2d-n3",
    "SLAP_3D_1Tracker": "pursuit-published-3d-n1",
    "SLAP_3D_3Trackers": "pursuit-published-3d-n3",
}
"""Each script and the published case that reproduces it."""

ROUNDING = 0.05
"""Bands are rounded outward to a multiple of this (m)."""

RUNS = 10
"""trackcert's runs per case (children 0–9 of ``SeedSequence(0)``, as the claim
``seed003.sec6.published-statistics``)."""

HEADER = re.compile(r"^(\w+) seed=(\d+)")
RESULT = re.compile(r"^RESULT final_pos_err (\S+) mean_pursuit (\S+)")


def read_log(path: Path) -> dict[str, dict[int, np.ndarray]]:
    """Script → seed → array (trackers × 2) of (final position error, mean pursuit error)."""
    runs: dict[str, dict[int, list[list[float]]]] = {}
    current: list[list[float]] = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if header := HEADER.match(line):
            current = runs.setdefault(header[1], {}).setdefault(int(header[2]), [])
        elif result := RESULT.match(line):
            current.append([float(result[1]), float(result[2])])
    return {s: {k: np.array(v) for k, v in seeds.items() if v} for s, seeds in runs.items()}


def band(values: np.ndarray) -> tuple[float, float]:
    """[min, max] of ``values`` rounded outward to :data:`ROUNDING`."""
    low = math.floor(float(np.min(values)) / ROUNDING) * ROUNDING
    high = math.ceil(float(np.max(values)) / ROUNDING) * ROUNDING
    return round(low, 2), round(high, 2)


def trackcert_runs(name: str) -> tuple[np.ndarray, int]:
    """Runs × trackers × 2 of trackcert's (final localization error, mean pursuit error) over
    :data:`RUNS` runs, and how many ran away."""
    spec = load_case(name).spec
    runs = [
        run_pursuit_case(spec, np.random.default_rng(sequence))
        for sequence in run_seeds(SIMULATION_SEED, RUNS)
    ]
    stats = [np.stack([r.localization_errors[-1], r.pursuit_errors.mean(axis=0)], 1) for r in runs]
    return np.array(stats), sum(r.stop_cause == StopCause.RUNAWAY for r in runs)


def _spread(values: np.ndarray) -> str:
    return f"{values.min():.2f}–{values.max():.2f}, {values.mean():.2f} ± {values.std(ddof=1):.2f}"


def report(script: str, seeds: dict[int, np.ndarray]) -> None:
    """Print the per-seed table, the per-tracker comparison and the bands of one script."""
    name = CASES[script]
    order = sorted(seeds)
    theirs = np.array([seeds[s] for s in order])  # seeds × trackers × 2
    trackers = theirs.shape[1]
    print(f"\n{name} ({script}, Octave seeds {order[0]}–{order[-1]})\n")
    print(
        "| seed | " + " | ".join(f"final {i + 1} | pursuit {i + 1}" for i in range(trackers)) + " |"
    )
    print("|---" * (1 + 2 * trackers) + "|")
    for seed, row in zip(order, theirs, strict=True):
        print(f"| {seed} | " + " | ".join(f"{f:.2f} | {p:.2f}" for f, p in row) + " |")
    ours, runaways = trackcert_runs(name)
    print(f"\ntrackcert runs 0–{RUNS - 1}: {runaways} runaways")
    for k, statistic in enumerate(("final position error", "mean pursuit error")):
        low, high = band(theirs[..., k])
        means = ours[..., k].mean(axis=0)
        verdict = "inside" if all(low <= m <= high for m in means) else "OUTSIDE"
        listed = ", ".join(f"{m:.2f}" for m in means)
        print(f"{statistic}: band [{low:g}, {high:g}] m; trackcert run-means {listed}: {verdict}")
        for i in range(trackers):
            a, b = theirs[:, i, k], ours[:, i, k]
            error = math.sqrt(a.var(ddof=1) / len(a) + b.var(ddof=1) / len(b))
            z = (b.mean() - a.mean()) / error if error > 0 else math.inf
            print(f"  tracker {i + 1}: Octave {_spread(a)}; trackcert {_spread(b)}; z = {z:+.1f}")


def main(argv: Sequence[str] | None = None) -> None:
    """Print every script's table, comparison and bands found in the log."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = Path(__file__).resolve().parent / "seed003_octave_runs.txt"
    parser.add_argument("log", type=Path, nargs="?", default=default)
    args = parser.parse_args(argv)
    for script, seeds in read_log(args.log).items():
        report(script, seeds)


if __name__ == "__main__":
    main()
