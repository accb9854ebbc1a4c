"""``trackcert report`` wall and CPU time at 1 and 2 workers, the speed-up, the cost before this
work, and peak memory (issue 16 items 1 and 4).

Targets (issue 16): the whole report ≤ 90 s wall on 2 cores, a speed-up of 1.8–2× from 1 to 2
workers, no worker over 1 GiB. Each configuration runs the command as a user does
(``python -m theory.cli report -o DIR --workers N``) in a fresh process; the baseline of every
ratio is measured in the same run: the speed-up against ``--workers 1``, the cost removal against
the code at ``--before REV`` (default: the commit before the report ran on the engine), exported
with ``git archive`` to a temporary folder and run serially the same way. CPU seconds are those of
the command (``RUSAGE_CHILDREN``; LocalCluster workers are forked by a forkserver, which the
command does not wait for, so their CPU is not in it) and those of its checks wherever they ran
(``timings.json``): on a shared machine they are the figures to compare, wall time is what the lead
reruns on a quiet one; the 1-minute load average before and after each run says how quiet it
was. Peak memory: the report process's and each worker's, from ``timings.json``. The two reports
are compared byte for byte.

Run from the repository root: ``python -m benchmarks.bench_report [--before REV] [--skip-before]
[--keep DIR] [--repeat N] [--write-costs] [CASES…] [--only PATTERN …]`` (``--keep`` leaves the
reports and their ``timings.json`` in ``DIR/w1``, ``DIR/w2``, ``DIR/before``; ``--repeat``
alternates 1- and 2-worker runs N times and prints the median speed-up, since the host's speed
drifts between runs; ``--write-costs`` stores the first 1-worker run's check costs as the
report's bundled schedule estimates, ``theory/report/check_costs.json``).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from theory.report.runner import bundled_costs_path, costs_document  # noqa: E402

BEFORE = "725a9f44028b"
"""The commit before issue 16 item 1 (the report ran serially in one process)."""

GIB = 1024**3


def run_report(source: Path, out: Path, workers: int | None, extra: list[str]) -> dict:
    """Run the report from the tree ``source``; wall and CPU seconds and its timings.json."""
    options = [] if workers is None else ["--workers", str(workers)]
    command = [sys.executable, "-m", "theory.cli", "report", "-o", str(out), *options, *extra]
    env = {**os.environ, "PYTHONPATH": str(source), "OPENBLAS_NUM_THREADS": "1"}
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=source, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 1, 3):
        raise SystemExit(f"report failed ({done.returncode}):\n{done.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    timings_path = out / "timings.json"
    timings = json.loads(timings_path.read_text()) if timings_path.exists() else {}
    loads = (load, os.getloadavg()[0])
    rss = after.ru_maxrss * 1024
    return {"wall": wall, "cpu": cpu, "timings": timings, "rss": rss, "load": loads}


def export(revision: str, folder: Path) -> Path:
    """The tree at ``revision`` (``git archive``) under ``folder``."""
    archive = folder / "before.tar"
    with archive.open("wb") as handle:
        subprocess.run(["git", "archive", revision], cwd=ROOT, stdout=handle, check=True)
    tree = folder / "before"
    with tarfile.open(archive) as tar:
        tar.extractall(tree, filter="data")
    return tree


def describe(name: str, result: dict) -> str:
    timings = result["timings"]
    workers = timings.get("worker_peak_rss", {})
    worst = max(workers.values(), default=0)
    parent = timings.get("parent_peak_rss", result["rss"])
    checks = timings.get("cpu_seconds", float("nan"))
    return (
        f"{name:<22} wall {result['wall']:7.1f} s   CPU command {result['cpu']:6.1f} s, "
        f"checks {checks:6.1f} s   peak RSS parent {parent / 2**20:4.0f} MiB, worst worker "
        f"{worst / 2**20:4.0f} MiB ({len(workers)} workers)   load {result['load'][0]:.1f}"
        f"→{result['load'][1]:.1f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", help="Cases (default: every bundled case).")
    parser.add_argument("--only", action="append", default=[], help="Claim id pattern.")
    parser.add_argument("--before", default=BEFORE, help="Revision measured as the before-cost.")
    parser.add_argument("--skip-before", action="store_true", help="Do not measure it.")
    parser.add_argument("--keep", type=Path, help="Keep the reports (and timings.json) here.")
    parser.add_argument(
        "--repeat", type=int, default=1, help="Alternate 1- and 2-worker runs this many times."
    )
    parser.add_argument(
        "--write-costs",
        action="store_true",
        help=f"Write the first 1-worker run's check costs to {bundled_costs_path().name}.",
    )
    args = parser.parse_args()
    extra = [*args.cases, *(f"--only={p}" for p in args.only)]
    with tempfile.TemporaryDirectory(prefix="bench-report-") as tmp:
        folder = Path(tmp) if args.keep is None else args.keep
        folder.mkdir(parents=True, exist_ok=True)
        serial, spread = compare_workers(folder, extra, args.repeat)
        if args.write_costs:
            write_costs(serial["timings"])
        if args.skip_before:
            return
        tree = export(args.before, folder)
        before = run_report(tree, folder / "before", None, extra)
        print(describe(f"before ({args.before[:12]})", before))
        print(f"cost removed: before / after, serial: {before['cpu'] / serial['cpu']:.2f}× CPU, "
              f"{before['wall'] / serial['wall']:.2f}× wall; before serial / after 2 workers: "
              f"{before['wall'] / spread['wall']:.2f}× wall")  # fmt: skip


def compare_workers(folder: Path, extra: list[str], repeat: int) -> tuple[dict, dict]:
    """Alternate ``--workers 1`` and ``--workers 2`` runs ``repeat`` times, each in a fresh
    folder; print each pair's speed-up and their median. The host's speed drifts by 10 % and
    more within minutes, so a ratio compares two runs made one right after the other.

    Returns
    -------
    (dict, dict)
        The first 1-worker and 2-worker results (:func:`run_report`).
    """
    pairs = []
    for k in range(repeat):
        suffix = "" if k == 0 else f"-{k + 1}"
        serial = run_report(ROOT, folder / f"w1{suffix}", 1, extra)
        print(describe("after, 1 worker", serial), flush=True)
        spread = run_report(ROOT, folder / f"w2{suffix}", 2, extra)
        print(describe("after, 2 workers", spread), flush=True)
        same = (folder / f"w1{suffix}/report.json").read_bytes() == (
            folder / f"w2{suffix}/report.json"
        ).read_bytes()
        print(f"speed-up 1 → 2 workers: {serial['wall'] / spread['wall']:.2f}× wall "
              f"(target 1.8–2×); report.json identical: {same}")  # fmt: skip
        print(f"2-worker wall {spread['wall']:.1f} s (target ≤ 90 s on 2 quiet cores)")
        worst = max(spread["timings"].get("worker_peak_rss", {}).values(), default=0)
        print(f"worst worker peak RSS {worst / GIB:.2f} GiB (target ≤ 1 GiB)")
        pairs.append((serial, spread))
    if repeat > 1:
        ratios = sorted(s["wall"] / p["wall"] for s, p in pairs)
        print(f"speed-up over {repeat} pairs: median {statistics.median(ratios):.2f}×, "
              f"range {ratios[0]:.2f}–{ratios[-1]:.2f}×")  # fmt: skip
    return pairs[0]


def write_costs(timings: dict) -> None:
    """Write ``timings`` (a 1-worker run's) as the bundled estimates of the report's schedule."""
    path = bundled_costs_path()
    source = (
        f"CPU seconds of each check, `trackcert report --workers 1` on the bundled cases, "
        f"{time.strftime('%Y-%m-%d', time.gmtime())} (python -m benchmarks.bench_report "
        "--write-costs); only the order of the report's tasks depends on them"
    )
    document = costs_document(timings, source)
    path.write_text(json.dumps(document, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    print(f"wrote {len(document['seconds'])} check costs to {path}")


if __name__ == "__main__":
    main()
