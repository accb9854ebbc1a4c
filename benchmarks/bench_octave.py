"""Issue 28: every seed 003 Table case against the authors' code under GNU Octave, side by side.

For each Table case and the published script with the same dimension and number of trackers
(:data:`PAIRS`), in one sitting:

* ``trackcert simulate CASE --seed S --steps N -o DIR`` in a fresh process (start-up, run,
  summary, files, figures), and the same with ``--no-figures`` (the like-for-like column: the
  scripts run with their figures off); the engine of ``$TRACKCERT_ENGINE`` (by default the
  rule of :func:`theory.core.engines.resolve_engine`), CPU seconds of the child, best of
  ``--repeat``; ``N`` covers the script's horizon (450 s in 2-D, 200 s in 3-D)
  and ``S`` is the first seed from ``--seed`` whose run 0 completes that horizon (the Table cases
  can run away, and a run stopped early costs less: docs/errata.md, "What makes the Table cases
  run away");
* the script under ``octave-cli`` (:mod:`seed003_octave`: seeded, figures off), CPU seconds of the
  Octave process, one run at ``--octave-seed`` (the scripts never run away);
* the ratios Octave / trackcert with and without figures (issue 28's target: ≥ 10 on runs that
  complete the horizon).

Octave is never a dependency: without ``octave-cli`` on the path or without ``--checkout`` (a
checkout of github.com/hungrepo/cooperative-distributed-range-based-SLAP) the Octave column is
skipped with a message and only trackcert's CPU is printed. Run Octave under ``nice``, one process
at a time, on a shared machine. Usage::

    python benchmarks/bench_octave.py [--checkout SLAP] [--repeat 2] [--seed 0]
        [--octave-seed 1] [--cases pursuit-table1-n3 ...]
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import seed003_octave  # noqa: E402
from bench_pursuit import _best, _cli  # noqa: E402

from theory.kinds import load_case  # noqa: E402
from theory.pursuit.simulation import RECORD_INTERVAL, run_pursuit_case  # noqa: E402

PAIRS = {
    "pursuit-table1-n1": ("SLAP_2D_1Tracker", 450.0),
    "pursuit-table1-n3": ("SLAP_2D_3Trackers", 450.0),
    "pursuit-table2-n1": ("SLAP_3D_1Tracker", 200.0),
    "pursuit-table2-n3": ("SLAP_3D_3Trackers", 200.0),
    "pursuit-table2-n3-kgamma5": ("SLAP_3D_3Trackers", 200.0),
}
"""Each Table case: the authors' script of its dimension and tracker count, and that script's
horizon ``tf`` (s)."""

SEED_TRIES = 50
"""Seeds tried from ``--seed`` for a run 0 that completes the horizon."""


def completing_seed(name: str, steps: int, first: int) -> int | None:
    """The first ``trackcert simulate --seed`` from ``first`` whose run 0 (child 0 of
    ``SeedSequence(seed)``) completes ``steps`` records; ``None`` within :data:`SEED_TRIES`."""
    spec = load_case(name).spec
    for seed in range(first, first + SEED_TRIES):
        rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
        if run_pursuit_case(spec, rng, steps).completed:
            return seed
    return None


def trackcert_cpu(name: str, seed: int, steps: int, repeat: int, figures: bool = True) -> float:
    """Best CPU seconds of ``trackcert simulate NAME --seed SEED --steps STEPS`` (fresh process),
    with ``--no-figures`` unless ``figures``."""
    arguments = ["simulate", name, "--seed", str(seed), "--steps", str(steps)]
    arguments += [] if figures else ["--no-figures"]

    def call() -> None:
        with tempfile.TemporaryDirectory() as folder:
            _cli([*arguments, "-o", folder])

    return _best(call, repeat)[1]


def octave_folder(checkout: Path | None, folder: Path) -> Path | None:
    """``folder`` prepared with the patched scripts, or ``None`` (with a message) when Octave or
    the checkout is missing."""
    if shutil.which("octave-cli") is None:
        print("octave-cli not found (apt-get install -y octave): the Octave column is skipped")
        return None
    if checkout is None or not (checkout / "SLAP_2D_1Tracker.m").is_file():
        print("no checkout of the authors' scripts (--checkout): the Octave column is skipped")
        return None
    seed003_octave.prepare(checkout, folder, sorted({s for s, _ in PAIRS.values()}))
    return folder


def main(argv: Sequence[str] | None = None) -> None:
    """Print one row per Table case: seed, steps, trackcert CPU (with and without figures),
    Octave CPU, the ratios."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--checkout", type=Path)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--octave-seed", type=int, default=1)
    parser.add_argument("--cases", nargs="+", default=list(PAIRS), choices=list(PAIRS))
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as scratch:
        folder = octave_folder(args.checkout, Path(scratch))
        octave: dict[str, float] = {}
        print(f"{'case':26} {'script':18} {'seed':>4} {'steps':>5} {'trackcert':>9} "
              f"{'no figs':>7} {'Octave':>7} {'ratio':>6} {'no figs':>7}")  # fmt: skip
        for name in args.cases:
            script, horizon = PAIRS[name]
            steps = round(horizon / RECORD_INTERVAL)
            seed = completing_seed(name, steps, args.seed)
            if seed is None:
                print(f"{name:26} no run 0 completes {horizon:g} s in {SEED_TRIES} seeds")
                continue
            ours = trackcert_cpu(name, seed, steps, args.repeat)
            bare = trackcert_cpu(name, seed, steps, args.repeat, figures=False)
            if folder is not None and script not in octave:
                cpu, results = seed003_octave.run(folder, script, args.octave_seed)
                octave[script] = cpu if results else float("nan")
            theirs = octave.get(script, float("nan"))
            print(
                f"{name:26} {script:18} {seed:4d} {steps:5d} {ours:9.2f} {bare:7.2f} "
                f"{theirs:7.1f} {theirs / ours:6.1f} {theirs / bare:7.1f}",
                flush=True,
            )
    print("CPU seconds (user + system of the child process); ratio = Octave / trackcert")


if __name__ == "__main__":
    main()
