"""Speed of the compiled seed 003 kernels (issue 28 item 1), every figure against a baseline
measured in the same run.

Prints

* **per step**: for each Table case, the library run (``simulate_dec``, 450 s, run 0 of
  ``--seed``) on the ``"numpy"`` engine (the reference, today's code path) and on the ``"numba"``
  engine, CPU seconds, integration steps (accepted + rejected) and µs per step; the ratio
  numpy / numba; and the compiled floor: one step of the kernels (``heun_step`` and the field at
  the new state, what an accepted step costs) repeated in a compiled loop with nothing around
  it, and the ratio run-per-step / floor (target ≤ 3);
* **the command**: ``trackcert simulate CASE --seed S`` in a fresh process (start-up, run,
  summary, files, figures) with ``TRACKCERT_ENGINE=numpy`` and ``=numba``, CPU of the child,
  whether run 0 completed the horizon, and the ratio to the authors' code under GNU Octave
  (:data:`OCTAVE_CPU`, the issue's side-by-side figures; Octave is not a dependency and is not
  re-run here; target ≥ 10 on runs that complete);
* **first run**: the kernels compiled from nothing (an empty ``NUMBA_CACHE_DIR``, a fresh
  process) against the same process loading them from that cache;
* **Monte Carlo**: ``trackcert simulate pursuit-table1-n3 --runs R --workers 2 --no-figures``
  with the numba engine, against ``--baseline-runs`` runs on the numpy engine: wall seconds and
  the CPU seconds of the process tree (command and Dask workers) and of the command alone
  (command + workers / 2: the wall time on two idle cores, "idle wall"), and the per-run CPU
  ratio (target: 1,000 runs in under a minute);
* **breakdown**: where one Monte Carlo run and one sweep point of ``pursuit-table1-n3`` spend
  their CPU (ms, best of ``--repeat``, in this process): the run on the kernels, the DEKF
  metrics of its summary (replay, NEES, NIS, OSPA) with the NumPy replay (the baseline, the
  code path before the compiled replay) and the compiled one, the ISS agreement along the run,
  the summary whole, and a sweep point whole (``evaluate_point``: the case re-validated, the
  ISS verdict, the run, the summary without files) beside its verdict alone; and the three
  pieces the second round cut from a point against their code path before: the summary
  without the metrics replay against with it, and the ISS agreement on an analysed spec against
  on a spec analysed afresh (a new spec object each call: the memo cannot help); the verdict
  alone is measured on a fresh spec each call;
* **sweep**: ``trackcert sweep pursuit-table1-n3`` over a ``k_c`` × ``k_gamma`` grid of
  ``--sweep-points`` points on 2 workers, its progress shown as it runs, wall and CPU seconds.

CPU beside wall: the machine is shared, wall time includes waiting for a core. On two idle
cores (tree CPU / 2, measured under load) the 1,000 Monte Carlo runs take about 40 s, their
100-run NumPy baseline about 50 s, and the 10,000-point sweep about 6 minutes
(docs/simulation.md, *Speed of the kernels*).
Usage: ``python benchmarks/bench_kernels.py [--repeat 3] [--seed 9] [--runs 1000]
[--baseline-runs 100] [--sweep-points 10000] [--skip steps command first breakdown mc sweep]``
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_pursuit import CASES, _best, _simulate  # noqa: E402

from theory.core.engines import ENGINE_SETTING, ENGINES  # noqa: E402
from theory.kinds import load_case  # noqa: E402
from theory.pursuit import kernels  # noqa: E402
from theory.pursuit.closed_loop import build_loop, simulate_dec  # noqa: E402
from theory.pursuit.compiled_run import loop_arrays  # noqa: E402
from theory.pursuit.simulation import dec_arguments  # noqa: E402

OCTAVE_CPU = {
    "pursuit-table1-n3": 85.5,
    "pursuit-table2-n3": 148.5,
    "pursuit-table1-n1": 28.1,
    "pursuit-table2-n1": 46.1,
    "pursuit-table2-n3-kgamma5": 148.5,
}
"""CPU seconds of the authors' scripts under GNU Octave (issue 28's table: 2-D/3-D, three
trackers and one; the k_γ = 5 case is the three-tracker 3-D script with another gain). Octave
measured on this machine in the same sitting is about three times faster:
``benchmarks/bench_octave.py``."""

FLOOR_REPEAT = 20_000
"""Steps of the compiled-floor loop."""


@numba.njit
def _floor_steps(count, t, h, z, R, x_hat, t_hat, loop):
    """``count`` kernel steps from one state: heun_step and the field at the stepped state."""
    z_dot, omega = kernels.rates(t, z, R, x_hat, t_hat, loop)
    error = 0.0
    for _ in range(count):
        z2, R2, error = kernels.heun_step(t, h, z, R, z_dot, omega, x_hat, t_hat, loop)
        z_dot, omega = kernels.rates(t + h, z2, R2, x_hat, t_hat, loop)
    return error


def _floor(name: str) -> float:
    """µs per step of :func:`_floor_steps` at the case's initial state (best of 5)."""
    spec = load_case(name).spec
    arguments = dec_arguments(spec, 10)
    run = simulate_dec(rng=np.random.default_rng(0), engine="numba", **arguments)
    loop = build_loop(
        arguments["settings"], arguments["paths"], arguments["in_neighbours"], spec.dim
    )
    n, d = loop.n, loop.dim
    z = np.concatenate([run.positions[-1].ravel(), run.gammas[-1], run.gamma_errors[-1]])
    R = np.stack([np.eye(d)] * n)
    x_hat = np.tile(run.target[-1], (n, 1))
    args = (0.0, 0.05, z, R, x_hat, 0.0, loop_arrays(loop))
    _floor_steps(1, *args)
    best = math.inf
    for _ in range(5):
        start = time.process_time()
        _floor_steps(FLOOR_REPEAT, *args)
        best = min(best, time.process_time() - start)
    return 1e6 * best / FLOOR_REPEAT


def _library(name: str, seed: int, engine: str, repeat: int) -> tuple[float, int, bool]:
    """Best CPU of the library run 0 of ``--seed`` on ``engine``, its steps, completed."""
    arguments = dec_arguments(load_case(name).spec)
    runs: list = []

    def call() -> None:
        rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
        runs.append(simulate_dec(rng=rng, engine=engine, **arguments))

    call()  # the kernels loaded (or compiled) outside the timing
    _, cpu = _best(call, repeat)
    return cpu, runs[0].steps + runs[0].rejected, runs[0].completed


def _step_rows(names: list[str], seed: int, repeat: int) -> None:
    print(f"\nper step: library run 0 of --seed {seed} (450 s), CPU s; floor: compiled loop")
    print(
        f"{'case':26} {'numpy':>7} {'numba':>7} {'steps':>6} {'µs/step numpy':>13} "
        f"{'numba':>6} {'floor':>6} {'numpy/numba':>11} {'numba/floor':>11}"
    )
    for name in names:
        slow, steps, _ = _library(name, seed, "numpy", repeat)
        fast, _, _ = _library(name, seed, "numba", repeat)
        floor = _floor(name)
        per = 1e6 * fast / steps
        print(
            f"{name:26} {slow:7.3f} {fast:7.3f} {steps:6d} {1e6 * slow / steps:13.1f} "
            f"{per:6.2f} {floor:6.2f} {slow / fast:11.1f} {per / floor:11.2f}"
        )


def _with_engine(engine: str, call):
    """``call()`` with ``$TRACKCERT_ENGINE`` set to ``engine`` (inherited by child processes)."""
    before = os.environ.get(ENGINE_SETTING)
    os.environ[ENGINE_SETTING] = engine
    try:
        return call()
    finally:
        if before is None:
            del os.environ[ENGINE_SETTING]
        else:
            os.environ[ENGINE_SETTING] = before


def _command_rows(names: list[str], seed: int, repeat: int) -> None:
    print(
        f"\ntrackcert simulate CASE --seed {seed} (450 s), fresh process, CPU s; Octave: the "
        "authors' scripts (issue 28), ratio = Octave / numba"
    )
    print(
        f"{'case':26} {'numpy':>7} {'numba':>7} {'numpy/numba':>11} {'run 0':>10} "
        f"{'Octave':>7} {'ratio':>6}"
    )
    for name in names:
        cpus = []
        for engine in ("numpy", "numba"):
            call = functools.partial(_best, functools.partial(_simulate, name, seed, []), repeat)
            cpus.append(_with_engine(engine, call)[1])
        _, _, completed = _library(name, seed, "numba", 1)
        octave = OCTAVE_CPU[name]
        print(
            f"{name:26} {cpus[0]:7.2f} {cpus[1]:7.2f} {cpus[0] / cpus[1]:11.1f} "
            f"{'completed' if completed else 'stopped':>10} {octave:7.1f} {octave / cpus[1]:6.1f}"
        )


FIRST_RUN = (
    "import time, numpy as np\n"
    "from theory.kinds import load_case\n"
    "from theory.pursuit.closed_loop import simulate_dec\n"
    "from theory.pursuit.simulation import dec_arguments\n"
    "arguments = dec_arguments(load_case('pursuit-table1-n3').spec, 10)\n"
    "start = time.process_time()\n"
    "simulate_dec(rng=np.random.default_rng(0), engine='numba', **arguments)\n"
    "print(time.process_time() - start)\n"
)
"""A 1 s run in a fresh process: the CPU of its first call (import of numba, kernels compiled or
loaded from the cache)."""


def _first_run() -> None:
    with tempfile.TemporaryDirectory() as cache:
        environment = {**os.environ, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(ROOT)}
        times = []
        for _ in range(2):  # compiled into the empty cache, then loaded from it
            done = subprocess.run(
                [sys.executable, "-c", FIRST_RUN], env=environment, capture_output=True,
                text=True, check=True, cwd=tempfile.gettempdir(),
            )  # fmt: skip
            times.append(float(done.stdout.split()[-1]))
    print(
        f"\nfirst call of the numba engine in a fresh process, CPU s: compiling {times[0]:.2f}, "
        f"from the cache {times[1]:.2f} (ratio {times[0] / times[1]:.0f})"
    )


def _timed(arguments: list[str], engine: str, show: bool = False) -> tuple[float, float, float]:
    """Wall seconds of ``python -m theory.cli ARGUMENTS`` on ``engine``, the CPU seconds of its
    process tree (the Dask workers included: polled with psutil, each process's last reading
    summed) and of the command's own process; stderr shown if ``show`` (the progress)."""
    import psutil  # distributed's dependency

    command = [sys.executable, "-m", "theory.cli", *arguments]
    environment = {**os.environ, ENGINE_SETTING: engine}
    start, seen = time.perf_counter(), {}
    child = subprocess.Popen(
        command, cwd=ROOT, env=environment, stdout=subprocess.DEVNULL,
        stderr=None if show else subprocess.DEVNULL,
    )  # fmt: skip
    root = psutil.Process(child.pid)
    while child.poll() is None:
        for process in [root, *root.children(recursive=True)]:
            try:
                times = process.cpu_times()
                seen[process.pid] = times.user + times.system
            except psutil.Error:
                pass
        time.sleep(0.2)
    if child.returncode not in (0, 1):
        raise RuntimeError(f"{' '.join(arguments)} exited {child.returncode}")
    return time.perf_counter() - start, sum(seen.values()), seen.get(child.pid, 0.0)


def _monte_carlo(runs: int, baseline: int) -> None:
    print("\nMonte Carlo: trackcert simulate pursuit-table1-n3 --workers 2 --no-figures, wall s")
    with tempfile.TemporaryDirectory() as folder:
        walls = {}
        for engine, count in (("numpy", baseline), ("numba", runs)):
            arguments = ["simulate", "pursuit-table1-n3", "--runs", str(count), "--workers", "2"]
            arguments += ["--no-figures", "-o", str(Path(folder) / engine)]
            walls[engine] = (count, *_timed(arguments, engine))
    print(
        f"{'engine':6} {'runs':>5} {'wall':>7} {'CPU':>7} {'command':>7} {'idle wall':>9} "
        f"{'CPU a run':>9}"
    )
    for engine, (count, wall, cpu, own) in walls.items():
        idle = own + (cpu - own) / 2
        print(
            f"{engine:6} {count:5d} {wall:7.1f} {cpu:7.1f} {own:7.1f} {idle:9.1f} "
            f"{cpu / count:9.3f}"
        )
    (slow_runs, _, slow, _), (fast_runs, _, fast, _) = walls["numpy"], walls["numba"]
    print(
        f"CPU a run, numpy / numba: {(slow / slow_runs) / (fast / fast_runs):.1f}; idle wall = "
        "command CPU + workers' CPU / 2, the wall time two idle cores would need; load average "
        f"{os.getloadavg()[0]:.1f}"
    )


def _ms(call, repeat: int) -> float:
    """Best CPU ms of ``call()`` over ``repeat`` calls (after one call outside the timing)."""
    call()
    return 1e3 * _best(call, repeat)[1]


def _breakdown(repeat: int) -> None:
    from theory.core.case_file import read_case_data, resolve_case_path
    from theory.pursuit.filter_metrics import dekf_metrics
    from theory.pursuit.simulation import (
        run_pursuit_case,
        simulation_agreement,
        summarize_pursuit,
    )
    from theory.sweep.points import SweepSetup, evaluate_point, pursuit_judgement

    case = load_case("pursuit-table1-n3")
    spec, rng = case.spec, np.random.default_rng
    runs = [run_pursuit_case(spec, rng(0))]
    arguments = dec_arguments(spec, len(runs[0].times) - 1)
    replay = {e: _ms(lambda e=e: dekf_metrics(runs, arguments, e), repeat) for e in ENGINES}
    parts = {
        "the run (numba)": _ms(lambda: run_pursuit_case(spec, rng(0)), repeat),
        "DEKF metrics, numpy (baseline)": replay["numpy"],
        "DEKF metrics, compiled replay": replay["numba"],
        "ISS agreement along the run": _ms(lambda: simulation_agreement(spec, runs[0]), repeat),
        "summary whole (compiled replay)": _ms(lambda: summarize_pursuit(spec, runs), repeat),
    }
    data = read_case_data(resolve_case_path("pursuit-table1-n3"))
    setup = SweepSetup(data, case.file, (), None, True)
    parts["sweep point whole"] = _ms(lambda: evaluate_point(setup, 0, ()), repeat)
    fresh = functools.partial(dataclasses.replace, case)  # a new spec: the ISS memo cannot help
    parts["its ISS verdict alone"] = _ms(
        lambda: pursuit_judgement(fresh(spec=dataclasses.replace(spec))), repeat
    )
    print("\nbreakdown: one run / one sweep point of pursuit-table1-n3 (450 s), CPU ms")
    for name, ms in parts.items():
        print(f"  {name:34} {ms:8.1f}")
    ratio = replay["numpy"] / replay["numba"]
    print(f"  DEKF metrics (replay, NEES, NIS, OSPA) numpy / compiled: {ratio:.1f}")
    _point_pieces(spec, runs, repeat)


def _point_pieces(spec, runs, repeat: int) -> None:
    """A sweep point's pieces of the second round against their code path before (module
    docstring): each pair measured here, its ratio printed."""
    from dataclasses import replace

    from theory.pursuit.simulation import simulation_agreement, summarize_pursuit

    pairs = {
        "point summary, metrics replayed / not": (
            lambda: summarize_pursuit(spec, runs),
            lambda: summarize_pursuit(spec, runs, metrics=False),
        ),
        "ISS agreement, analysed afresh / once": (
            lambda: simulation_agreement(replace(spec), runs[0]),
            lambda: simulation_agreement(spec, runs[0]),
        ),
    }
    print("  sweep point pieces (before / after, CPU ms, ratio):")
    for name, (before, after) in pairs.items():
        old, new = _ms(before, repeat), _ms(after, repeat)
        print(f"  {name:40} {old:7.2f} / {new:6.2f}  {old / new:5.1f}x")


def _sweep(points: int) -> None:
    side = max(2, round(math.sqrt(points)))
    grid = ["-p", f"k_c=0.05:0.5:lin{side}", "-p", f"k_gamma=5:500:log{side}"]
    print(f"\nsweep: trackcert sweep pursuit-table1-n3 {' '.join(grid)} --workers 2 (progress:)")
    with tempfile.TemporaryDirectory() as folder:
        arguments = ["sweep", "pursuit-table1-n3", *grid, "--workers", "2", "-o", folder]
        wall, cpu, own = _timed(arguments, "numba", show=True)
    print(
        f"{side * side} points: {wall:.1f} s wall, {cpu:.1f} s CPU, of which the command "
        f"{own:.1f} s (idle wall {own + (cpu - own) / 2:.1f} s; {1e3 * cpu / side**2:.1f} ms CPU a "
        f"point); load average {os.getloadavg()[0]:.1f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="repetitions (best is printed)")
    parser.add_argument("--cases", nargs="*", default=list(CASES), help="bundled case names")
    parser.add_argument(
        "--seed", type=int, default=9, help="--seed (run 0 completes in every case)"
    )
    parser.add_argument("--runs", type=int, default=1000, help="Monte Carlo runs (numba)")
    parser.add_argument("--baseline-runs", type=int, default=100, help="… on the numpy engine")
    parser.add_argument("--sweep-points", type=int, default=10_000, help="sweep grid size")
    parser.add_argument(
        "--skip", nargs="*", default=[],
        choices=["steps", "command", "first", "breakdown", "mc", "sweep"],
    )  # fmt: skip
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} at the start")
    if "steps" not in args.skip:
        _step_rows(args.cases, args.seed, args.repeat)
    if "command" not in args.skip:
        _command_rows(args.cases, args.seed, args.repeat)
    if "first" not in args.skip:
        _first_run()
    if "breakdown" not in args.skip:
        _breakdown(args.repeat)
    if "mc" not in args.skip:
        _monte_carlo(args.runs, args.baseline_runs)
    if "sweep" not in args.skip:
        _sweep(args.sweep_points)


if __name__ == "__main__":
    main()
