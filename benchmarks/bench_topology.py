"""Benchmark: ``trackcert topology`` on seeded random connected 3-D networks, N = 100 … 10,000.

Run from the repository root: ``python -m benchmarks.bench_topology [--seed S] [--sizes …]``.

For each N it writes a ``kind: tdoa`` case (agents uniform in a cube of side 100, a
communication radius giving a mean degree of about 8, agents of small components moved next to
an agent of the largest one until the network is connected; coordinates rounded to 3 decimals, as
a user writes them) and runs ``trackcert topology CASE --json --no-network-rank`` as a user
does, on the default limits, in a fresh process: parse, links by the distance rule, every
agent's exact verdict, detectability and the JSON record. It prints the wall and CPU seconds of
the process, the size of the JSON, and the growth exponent ``log(t₂/t₁)/log(N₂/N₁)`` of the
CPU time between consecutive sizes and from the first size to the last: of the whole process,
and of the work above start-up (the CPU of the same command on a 10-agent network, measured in
the same run, subtracted), and the least-squares slope of log CPU against log N over all sizes.

Same-run baseline: in this process, for each N, the CPU seconds of reading the case and deciding
every agent (``load_case`` + ``analyze_topology(..., network_rank=False)``) with the weights held
by their entries (``TdoaSpec.links``, ``O(N + E)``), against the same with the dense ``N × N``
``hears`` and ``W`` made as well (what the parser built for every case before, ``9 B × N²``),
and their ratio.

It then runs the default command (with the network rank) on each size and prints its exit code
and time: components of up to 500 agents are ranked by an eigen-decomposition of ``W`` (cubic),
larger ones by the blind agents' invariant subspace and sparse factorizations of ``W``
(``theory/tdoa/observability/sparse_rank.py``).

No assertion: the numbers are the result (target: N = 10,000 in ≤ 10 s of wall time on 2 cores).
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from theory.core.network import adjacency_from_range, component_labels
from theory.kinds import load_case
from theory.tdoa.observability.topology import analyze_topology

SIDE = 100.0
MEAN_DEGREE = 8.0


def connected_scene(n: int, rng: np.random.Generator) -> tuple[np.ndarray, float, np.ndarray]:
    """``n`` agents (3 decimals) with a connecting radius, and a target inside the cube."""
    radius = round(SIDE * (3 * MEAN_DEGREE / (4 * math.pi * max(n - 1, 1))) ** (1 / 3), 3)
    positions = np.round(rng.uniform(0, SIDE, size=(n, 3)), 3)
    while True:
        labels = component_labels(adjacency_from_range(positions, radius))
        largest = np.bincount(labels).argmax()
        stray = np.flatnonzero(labels != largest)
        if not stray.size:
            break
        anchors = rng.choice(np.flatnonzero(labels == largest), size=stray.size)
        step = rng.normal(size=(stray.size, 3))
        step *= 0.5 * radius / np.linalg.norm(step, axis=1, keepdims=True)
        positions[stray] = np.round(positions[anchors] + step, 3)
    target = np.round(rng.uniform(0.25 * SIDE, 0.75 * SIDE, size=3), 3) + 0.0005
    return positions, radius, target


def write_case(path: Path, positions: np.ndarray, radius: float, target: np.ndarray) -> None:
    """The scene as a ``kind: tdoa`` case file (JSON is valid YAML)."""
    case = {
        "name": path.stem,
        "source": "benchmarks/bench_topology.py (seeded random connected network)",
        "kind": "tdoa",
        "tdoa": {
            "T": 1.0,
            "agents": positions.tolist(),
            "target": target.tolist(),
            "comm_range": radius,
        },
    }
    path.write_text(json.dumps(case), encoding="utf-8")


def run(case: Path, *options: str) -> tuple[float, float, int, int]:
    """Wall seconds, CPU seconds, exit code and stdout bytes of ``trackcert topology``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "theory.cli", "topology", str(case), "--json", *options],
        capture_output=True,
        check=False,
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if done.returncode not in (0, 1, 3):
        sys.stderr.write(done.stderr.decode()[-2000:])
    return wall, cpu, done.returncode, len(done.stdout)


def growth(sizes: list[int], seconds: list[float], label: str) -> None:
    """Print the growth exponents of ``seconds`` between consecutive sizes, end to end, and the
    least-squares slope in log-log over all sizes."""
    pairs = list(zip(sizes, seconds, strict=True))
    for (n1, t1), (n2, t2) in [*itertools.pairwise(pairs), (pairs[0], pairs[-1])]:
        exponent = math.log(t2 / t1) / math.log(n2 / n1)
        print(f"growth ({label}) N = {n1} → {n2}: exponent {exponent:.2f}")
    if len(pairs) > 2:
        slope = np.polyfit(np.log(sizes), np.log(seconds), 1)[0]
        print(f"growth ({label}) log-log fit over N = {sizes[0]} … {sizes[-1]}: {slope:.2f}")


def in_process(case: Path, *, dense: bool) -> float:
    """CPU seconds of reading ``case`` and every agent's verdict, in this process; ``dense``
    also makes the ``N × N`` ``hears`` and ``W`` (the baseline)."""
    start = time.process_time()
    spec = load_case(str(case)).spec
    if dense:
        _ = spec.hears, spec.weights
    analyze_topology(spec, 0, network_rank=False)
    return time.process_time() - start


def baseline(sizes: list[int], cases: list[Path]) -> None:
    """Print the entry-held against the dense path, measured alternately in this process (best
    of three each, after one warm-up run)."""
    print("same run, in process: load + every agent's verdict (CPU s)")
    print(f"{'N':>6} {'entries':>8} {'dense':>8} {'dense/entries':>14}")
    sparse_times = []
    in_process(cases[0], dense=True)  # warm-up: imports and first-call costs out of the figures
    for n, case in zip(sizes, cases, strict=True):
        pairs = [(in_process(case, dense=False), in_process(case, dense=True)) for _ in range(3)]
        sparse, dense = min(p[0] for p in pairs), min(p[1] for p in pairs)
        sparse_times.append(sparse)
        print(f"{n:6d} {sparse:7.3f}s {dense:7.3f}s {dense / sparse:13.1f}×")
    growth(sizes, sparse_times, "in process, entries")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=20261207)
    parser.add_argument("--sizes", type=int, nargs="+", default=[100, 300, 1000, 3000, 10000])
    args = parser.parse_args()
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    rng = np.random.default_rng(args.seed)
    cpu_times = []
    with tempfile.TemporaryDirectory(dir=".") as folder:
        tiny = Path(folder) / "random-3d-10.yaml"
        write_case(tiny, *connected_scene(10, rng))
        startup = min(run(tiny, "--no-network-rank")[1] for _ in range(3))
        cases = []
        for n in args.sizes:
            case = Path(folder) / f"random-3d-{n}.yaml"
            write_case(case, *connected_scene(n, rng))
            cases.append(case)
        print("trackcert topology CASE --json --no-network-rank (default limits)")
        print(f"{'N':>6} {'case':>8} {'wall':>8} {'CPU':>8} {'exit':>4} {'JSON':>9}")
        for n, case in zip(args.sizes, cases, strict=True):
            wall, cpu, code, size = run(case, "--no-network-rank")
            cpu_times.append(cpu)
            kb = case.stat().st_size / 1e3
            print(f"{n:6d} {kb:6.0f}kB {wall:7.2f}s {cpu:7.2f}s {code:4d} {size / 1e6:7.2f}MB")
        print(f"start-up (N = 10): {startup:.2f} s CPU")
        growth(args.sizes, cpu_times, "whole process")
        growth(args.sizes, [max(t - startup, 1e-3) for t in cpu_times], "above start-up")
        baseline(args.sizes, cases)
        print("trackcert topology CASE --json (with the network rank)")
        for n, case in zip(args.sizes, cases, strict=True):
            wall, cpu, code, _ = run(case)
            print(f"{n:6d} wall {wall:6.2f}s CPU {cpu:6.2f}s exit {code}")


if __name__ == "__main__":
    main()
