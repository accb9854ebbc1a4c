"""Seed 003: what makes the Table cases run away (issue 27; docs/errata.md, "What makes the Table
cases run away").

From a published case (``pursuit-published-*``, the authors' scripts as they run) to its Table
case (``pursuit-table*``), one difference at a time: each row copies the fields of one difference
from the other case (a field the other case lacks is removed) and counts the runs stopped as
runaways among ``--runs`` seeds, run i drawing from child i of ``SeedSequence(--seed)`` as
``trackcert simulate --runs`` does, over the published script's horizon. ``--direction
to-table`` changes the published case, ``to-published`` the Table case. With ``--cumulative``
each row keeps the differences of the rows above it (in ``--only``'s order), a chain from one case
to the other; its last line names what still differs (the horizon is the published one)::

    PYTHONPATH=. python benchmarks/seed003_ablation.py pursuit-published-2d-n1 \\
        pursuit-table1-n1 --runs 20 [--direction to-published] [--only V,prediction] [--cumulative]
"""

from __future__ import annotations

import argparse
import copy
from collections.abc import Sequence
from typing import Any

import numpy as np

from theory.core.case_file import read_case_data, resolve_case_path
from theory.pursuit.case import PURSUIT
from theory.pursuit.closed_loop import StopCause
from theory.pursuit.simulation import default_steps, run_pursuit_case

DIFFERENCES: dict[str, tuple[str, ...]] = {
    "V": ("dekf.V",),
    "prediction": ("dekf.predict_every",),
    "P0": ("dekf.P0", "dekf.x0"),
    "covariance": ("dekf.P0",),
    "epsilon": ("epsilon",),
    "gains": ("K_p", "k_gamma", "k_c"),
    "initial": ("trackers",),
    "graph": ("edges", "dekf.edges", "dekf.weights"),
    "target": ("target",),
    "saturation": ("controller.inputs_min", "controller.inputs_max"),
    "clamp": ("controller.gamma_ddot",),
    "law": ("controller",),
}
"""Each difference between a published and a Table case: the dotted paths it consists of."""


def _load(name: str) -> dict[str, Any]:
    return read_case_data(resolve_case_path(name))


def _lookup(block: dict[str, Any], path: str) -> tuple[dict[str, Any] | None, str]:
    """The mapping holding the last key of ``path`` (``None`` if absent) and that key."""
    *parents, last = path.split(".")
    for key in parents:
        block = block.get(key) if isinstance(block, dict) else None
    return (block if isinstance(block, dict) else None), last


def _copied(target: dict[str, Any], source: dict[str, Any], paths: Sequence[str]) -> bool:
    """Copy ``paths`` of the pursuit block ``source`` into ``target`` (in place); False when
    nothing differs or a path cannot be set (e.g. a clamp into an analysed controller)."""
    changed = False
    for path in paths:
        into, key = _lookup(target, path)
        origin, _ = _lookup(source, path)
        value = origin.get(key) if origin is not None else None
        if into is None:
            if value is not None:
                return False
            continue
        if into.get(key) != value:
            changed = True
            if value is None:
                into.pop(key, None)
            else:
                into[key] = copy.deepcopy(value)
    return changed


def _differing(first: dict[str, Any], second: dict[str, Any], prefix: str = "") -> list[str]:
    """The dotted paths at which two pursuit blocks differ (nested mappings compared key by key)."""
    paths = []
    for key in sorted(set(first) | set(second)):
        a, b = first.get(key), second.get(key)
        if isinstance(a, dict) and isinstance(b, dict):
            paths += _differing(a, b, f"{prefix}{key}.")
        elif a != b:
            paths.append(f"{prefix}{key}")
    return paths


def runaways(data: dict[str, Any], runs: int, seed: int, steps: int) -> tuple[int, int, float]:
    """Runs stopped as runaways, runs whose state overflowed (non-finite records, e.g. γ̇ under
    an unstable explicit update), and the median over the other runs of the largest final
    localization error (m; NaN if there is none)."""
    spec = PURSUIT.parse_case(data).spec
    stopped, overflowed, finals = 0, 0, []
    for sequence in np.random.SeedSequence(seed).spawn(runs):
        run = run_pursuit_case(spec, np.random.default_rng(sequence), steps)
        final = run.localization_errors[-1]
        if run.stop_cause == StopCause.RUNAWAY:
            stopped += 1
        elif not np.all(np.isfinite(run.gamma_rates[-1])) or not np.all(np.isfinite(final)):
            overflowed += 1
        elif run.completed:
            finals.append(float(np.max(final)))
    return stopped, overflowed, float(np.median(finals)) if finals else float("nan")


def main(argv: Sequence[str] | None = None) -> None:
    """Print one row per difference: name, runaways/runs, overflows, median final error."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("published")
    parser.add_argument("table")
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--direction", choices=("to-table", "to-published"), default="to-table")
    parser.add_argument("--only", default="", help="comma-separated differences (default: all)")
    parser.add_argument(
        "--cumulative", action="store_true",
        help="each row adds its difference to the row above (a chain from one case to the other)",
    )  # fmt: skip
    args = parser.parse_args(argv)
    published, table = _load(args.published), _load(args.table)
    steps = default_steps(PURSUIT.parse_case(published).spec)
    base, other = (published, table) if args.direction == "to-table" else (table, published)
    chosen = [n for n in args.only.split(",") if n] or list(DIFFERENCES)
    print(f"{base['name']} ({steps} steps of 0.1 s), {args.runs} runs from seed {args.seed}")
    rows = [("none", copy.deepcopy(base))]
    chain = copy.deepcopy(base)
    for name in chosen:
        variant = copy.deepcopy(chain if args.cumulative else base)
        if _copied(variant["pursuit"], other["pursuit"], DIFFERENCES[name]):
            rows.append((f"{'+ ' if args.cumulative else ''}{name} as in {other['name']}", variant))
            chain = variant if args.cumulative else chain
    if args.cumulative:
        left = _differing(chain["pursuit"], other["pursuit"])
        print(f"the chain's last row differs from {other['name']} in: {', '.join(left) or '-'}")
    for label, data in rows:
        data["expect"] = {}
        stopped, overflowed, final = runaways(data, args.runs, args.seed, steps)
        print(f"| {label} | {stopped}/{args.runs} | {overflowed} | {final:.3g} |", flush=True)


if __name__ == "__main__":
    main()
