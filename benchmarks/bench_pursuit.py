"""Speed of ``trackcert simulate`` on the seed 003 Table cases against the authors' Octave run.

Issue 16 item 5: a 450 s seed 003 run must take at most 1/10 of the authors' MATLAB code under GNU
Octave. That code and Octave are not available here: the reference is the issue's figure,
:data:`OCTAVE_SECONDS` = 33 s for ``pursuit-table1-n3`` (2-D, three trackers) on this machine
class, carried to the other Table cases by the same cost per simulated step (every Table case
simulates 450 s, so every reference is 33 s); the column ``/tracker`` gives the stricter reference
of the same cost per tracker-step (11 s for one tracker), should the authors' code loop over
trackers.

For each case it prints

* ``trackcert simulate CASE --seed 2 -o DIR`` in a fresh process (start-up, the 450 s run, ISS
  agreement, data files and figures): wall and CPU time (user + system of the child), exit code
  (1 when the run leaves the case's ``simulation_bounded`` expectation, e.g. a one-tracker
  runaway that stops early) and the ratios reference / wall and reference / CPU;
* where its time goes, measured in this process: the simulation alone (the library run of the
  command's run 0), and the imports, summary (ISS agreement), data files and figures;
* the runaway stop: the library run of the command's run 0 as it is (a runaway stops when the
  localization error passes ``runaway_factor`` curve sizes, docs/theory/pursuit-iss.md §11)
  against the same run with the check off (``runaway_factor = inf``: integrated until the step
  floor, the behaviour before), CPU of both and their ratio, with where each stopped and why;
* the library run with the vectorized vector field against the per-tracker field of the
  regression oracle (``tests/pursuit/dec_oracle.py``: every tracker through
  ``model.closed_loop_rates`` in a Python loop, the pre-vectorization form), both over
  ``--seconds`` of simulated time, and their ratio: a same-run baseline.

Start-up: ``trackcert --help`` and ``python -c "import theory.cli"`` in fresh processes, the
latter against importing every command module (:data:`EAGER`, what registration did before the
commands were loaded lazily) in the same run.
Every time is the best of ``--repeat``; CPU beside wall because the machine is shared (wall time
then includes waiting for a core). :data:`BEFORE` prints the same command measured before the
speed-up (commit 725a9f4), with the date: that code is gone, so it is not re-run.
``--baseline COMMIT`` also runs the command in that commit's tree (``git archive`` of ``theory``,
``cases`` and ``proofs_check`` into a temporary folder), alternating with the working tree, and
prints both and the ratio baseline / working tree: a same-run before/after, which the host's drift
(about 10 % over minutes) cannot fake.
Usage: ``python benchmarks/bench_pursuit.py [--seconds 100] [--repeat 3] [--cases NAME ...]
[--baseline COMMIT]``
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import math
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests" / "pursuit"))

from dec_oracle import per_tracker_field  # noqa: E402

from theory.kinds import load_case  # noqa: E402
from theory.pursuit.closed_loop import build_loop, simulate_dec  # noqa: E402
from theory.pursuit.simulation import DEFAULT_DURATION, RECORD_INTERVAL, dec_arguments  # noqa: E402

CASES = (
    "pursuit-table1-n1",
    "pursuit-table1-n3",
    "pursuit-table2-n1",
    "pursuit-table2-n3",
    "pursuit-table2-n3-kgamma5",
)

OCTAVE_SECONDS = 33.0
"""The authors' code under GNU Octave, ``pursuit-table1-n3`` (issue 16; not re-measurable here)."""

OCTAVE_TRACKERS, OCTAVE_DURATION = 3, 450.0
"""The run the reference figure is for: three trackers, 450 s."""

BEFORE = {
    "date": "2026-12-03 11:44 UTC, load average 0.4 (commit 725a9f4)",
    "--help": (1.91, 1.89),
    "pursuit-table1-n1": (6.52, 4.14),
    "pursuit-table1-n3": (5.83, 3.66),
    "pursuit-table2-n1": (10.23, 5.88),
    "pursuit-table2-n3": (5.96, 3.88),
}
"""(wall, CPU) seconds of the same commands before the speed-up (one run each)."""


def reference(name: str, per_tracker: bool = False) -> float:
    """The Octave reference of a case: :data:`OCTAVE_SECONDS` at the same cost per simulated
    step (or per tracker-step), for the 450 s the command simulates."""
    spec = load_case(name).spec
    trackers = spec.n_trackers / OCTAVE_TRACKERS if per_tracker else 1.0
    return OCTAVE_SECONDS * trackers * DEFAULT_DURATION / OCTAVE_DURATION


def _best(function, repeat: int) -> tuple[float, float]:
    """Best wall time and best CPU time (this process and its children) of ``repeat`` calls."""
    walls, cpus = [], []
    for _ in range(repeat):
        start, cpu = time.perf_counter(), _cpu()
        function()
        walls.append(time.perf_counter() - start)
        cpus.append(_cpu() - cpu)
    return min(walls), min(cpus)


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def _cli(arguments: list[str], codes: list[int] | None = None, tree: Path = ROOT) -> None:
    """``python -m theory.cli ARGUMENTS`` in a fresh process, with the ``theory`` package of
    ``tree`` (the working directory comes first on the path); its exit code goes to ``codes``."""
    done = subprocess.run(
        [sys.executable, "-m", "theory.cli", *arguments], cwd=tree, capture_output=True
    )
    if codes is not None:
        codes.append(done.returncode)


def _simulate(name: str, seed: int, codes: list[int], tree: Path = ROOT) -> None:
    with tempfile.TemporaryDirectory() as folder:
        _cli(["simulate", name, "--seed", str(seed), "-o", folder], codes, tree)


def _unpack(commit: str, folder: Path) -> Path:
    """The ``theory``, ``cases`` and ``proofs_check`` folders of ``commit`` in ``folder``."""
    archive = subprocess.run(
        ["git", "archive", commit, "theory", "cases", "proofs_check"],
        cwd=ROOT, capture_output=True, check=True,
    ).stdout  # fmt: skip
    subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    return folder


def _alternating(calls: list, repeat: int) -> list[tuple[float, float]]:
    """Best wall and CPU of each call, the calls alternating ``repeat`` times (same load)."""
    times: list[list[tuple[float, float]]] = [[] for _ in calls]
    for _ in range(repeat):
        for call, record in zip(calls, times, strict=True):
            record.append(_best(call, 1))
    return [(min(w for w, _ in record), min(c for _, c in record)) for record in times]


def _baseline_rows(names: list[str], seed: int, repeat: int, commit: str) -> None:
    print(
        f"\nsame run, alternating: trackcert simulate CASE --seed {seed} in the tree of {commit} "
        "(before) and the working tree (after), best of each, seconds; ratio = before / after"
    )
    print(
        f"{'case':26} {'before wall':>11} {'CPU':>6} {'after wall':>10} {'CPU':>6} "
        f"{'ratio wall':>10} {'CPU':>5}"
    )
    with tempfile.TemporaryDirectory() as folder:
        tree = _unpack(commit, Path(folder))
        for name in names:
            codes: list[int] = []
            before, after = _alternating(
                [functools.partial(_simulate, name, seed, codes, tree),
                 functools.partial(_simulate, name, seed, codes)],
                repeat,
            )  # fmt: skip
            print(
                f"{name:26} {before[0]:11.2f} {before[1]:6.2f} {after[0]:10.2f} {after[1]:6.2f} "
                f"{before[0] / after[0]:10.2f} {before[1] / after[1]:5.2f}"
            )


EAGER = (
    "import importlib, theory.cli\n"
    "for module in theory.cli.command_modules(): importlib.import_module(module)"
)
"""The former start-up, re-created: every command module imported (as registration did)."""


def _python(code: str) -> None:
    subprocess.run([sys.executable, "-c", code], cwd=ROOT, check=True)


def _startup(repeat: int) -> None:
    """``--help`` against the recorded figure, and the lazy import against the eager one."""
    helped = _best(lambda: _cli(["--help"]), repeat)
    lazy = _best(lambda: _python("import theory.cli"), repeat)
    eager = _best(lambda: _python(EAGER), repeat)
    before = BEFORE["--help"]
    print(
        f"start-up: trackcert --help wall {helped[0]:.2f} s, CPU {helped[1]:.2f} s "
        f"(before: {before[0]:.2f} s, {before[1]:.2f} s)\n"
        f"  import theory.cli: wall {lazy[0]:.2f} s, CPU {lazy[1]:.2f} s; with every command "
        f"module imported (the former eager registration): wall {eager[0]:.2f} s, CPU "
        f"{eager[1]:.2f} s; ratio (CPU) {eager[1] / lazy[1]:.1f}"
    )


def _phases(name: str, seed: int) -> dict[str, float]:
    """CPU seconds of the command's phases in this process: simulation (run 0 of ``--seed``),
    summary with the ISS agreement, data files, figures (the first call of each also imports
    what it needs, as the command does)."""
    from theory.pursuit.simulation import (
        run_pursuit_case,
        summarize_pursuit,
        write_pursuit_data,
        write_pursuit_figures,
    )

    spec = load_case(name).spec
    rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
    times, start = {}, time.process_time()
    run = run_pursuit_case(spec, rng)
    times["simulation"], start = time.process_time() - start, time.process_time()
    summary = summarize_pursuit(spec, [run])
    times["summary"], start = time.process_time() - start, time.process_time()
    with tempfile.TemporaryDirectory() as folder:
        write_pursuit_data([run], summary, Path(folder))
        times["data"], start = time.process_time() - start, time.process_time()
        write_pursuit_figures([run], Path(folder))
        times["figures"] = time.process_time() - start
    times["steps"] = run.steps + run.rejected
    return times


def _library_runs(name: str, seconds: float, repeat: int) -> tuple[float, float]:
    """Best CPU times of the vectorized and the per-tracker library run over ``seconds``."""
    spec = load_case(name).spec
    arguments = dec_arguments(spec, round(seconds / RECORD_INTERVAL))
    loop = build_loop(
        arguments["settings"], arguments["paths"], arguments["in_neighbours"], spec.dim
    )
    oracle = per_tracker_field(loop, arguments["paths"], spec.controller)
    _, fast = _best(lambda: simulate_dec(rng=np.random.default_rng(2), **arguments), repeat)
    _, slow = _best(
        lambda: simulate_dec(rng=np.random.default_rng(2), field=oracle, **arguments), repeat
    )
    return fast, slow


def _command_rows(names: list[str], seed: int, repeat: int) -> None:
    print(
        f"\ntrackcert simulate CASE --seed {seed} (450 s): seconds; ratio = Octave reference / "
        f"time (reference {OCTAVE_SECONDS:g} s a case; /tracker: {OCTAVE_SECONDS:g}·N/3 s)"
    )
    print(
        f"{'case':26} {'wall':>6} {'CPU':>6} {'exit':>4} {'ref/wall':>8} {'ref/CPU':>8} "
        f"{'/tracker':>8}   before (wall, CPU)"
    )
    for name in names:
        codes: list[int] = []
        wall, cpu = _best(lambda name=name, codes=codes: _simulate(name, seed, codes), repeat)
        ref, strict = reference(name), reference(name, per_tracker=True)
        before = BEFORE.get(name)
        then = "" if before is None else f"   {before[0]:.2f}, {before[1]:.2f}"
        print(
            f"{name:26} {wall:6.2f} {cpu:6.2f} {codes[0]:4d} {ref / wall:8.1f} {ref / cpu:8.1f} "
            f"{strict / cpu:8.1f}{then}"
        )
    print(f"before: {BEFORE['date']}")


def _phase_rows(names: list[str], seed: int) -> None:
    print("\nwhere the command's CPU goes (this process, run 0 of the same seed), seconds")
    print(
        f"{'case':26} {'simulation':>10} {'steps':>6} {'µs/step':>7} {'summary':>8} {'data':>6} "
        f"{'figures':>8}"
    )
    for name in names:
        t = _phases(name, seed)
        per_step = 1e6 * t["simulation"] / t["steps"]
        print(
            f"{name:26} {t['simulation']:10.2f} {t['steps']:6.0f} {per_step:7.0f} "
            f"{t['summary']:8.2f} {t['data']:6.2f} {t['figures']:8.2f}"
        )


def _command_run(name: str, seed: int, settings_change: dict):
    """The library run 0 of ``trackcert simulate NAME --seed SEED``, settings changed."""
    arguments = dec_arguments(load_case(name).spec)
    arguments["settings"] = dataclasses.replace(arguments["settings"], **settings_change)
    rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
    return simulate_dec(rng=rng, **arguments)


def _runaway_rows(names: list[str], seed: int, repeat: int) -> None:
    print("\nrunaway stop against the step floor (library run 0 of the same seed), CPU s")
    print(f"{'case':26} {'checked':>8} {'stop':>14} {'unchecked':>9} {'stop':>17} {'ratio':>6}")
    for name in names:
        cpus, stops = [], []
        for change in ({}, {"runaway_factor": math.inf}):
            runs: list = []
            call = functools.partial(_command_run, name, seed, change)
            cpus.append(_best(lambda call=call, runs=runs: runs.append(call()), repeat)[1])
            run = runs[0]
            stops.append("completed" if run.completed else f"{run.stop_cause} {run.stopped_at:g}")
        print(
            f"{name:26} {cpus[0]:8.2f} {stops[0]:>14} {cpus[1]:9.2f} {stops[1]:>17} "
            f"{cpus[1] / cpus[0]:6.1f}"
        )


def _oracle_rows(names: list[str], seconds: float, repeat: int) -> None:
    print(f"\nlibrary run over {seconds:g} s simulated, CPU s: vectorized vs per-tracker field")
    print(f"{'case':26} {'vectorized':>10} {'per-tracker':>11} {'ratio':>6}")
    for name in names:
        fast, slow = _library_runs(name, seconds, repeat)
        print(f"{name:26} {fast:10.3f} {slow:11.3f} {slow / fast:6.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=100.0, help="simulated s per library run")
    parser.add_argument("--repeat", type=int, default=3, help="repetitions (best is printed)")
    parser.add_argument("--cases", nargs="*", default=list(CASES), help="bundled case names")
    parser.add_argument("--seed", type=int, default=2, help="--seed of trackcert simulate")
    parser.add_argument("--baseline", help="commit to run the command of too, alternating")
    args = parser.parse_args()
    _startup(args.repeat)
    _command_rows(args.cases, args.seed, args.repeat)
    if args.baseline:
        _baseline_rows(args.cases, args.seed, args.repeat, args.baseline)
    _phase_rows(args.cases, args.seed)
    _runaway_rows(args.cases, args.seed, args.repeat)
    _oracle_rows(args.cases, args.seconds, args.repeat)


if __name__ == "__main__":
    main()
