"""Seed 003: the authors' published scripts under GNU Octave, for the reference numbers of the
``pursuit-published-*`` cases (issue 27; docs/simulation.md, the published cases).

Needs ``octave-cli`` (``apt-get install -y octave``; never a dependency of trackcert) and a
checkout of github.com/hungrepo/cooperative-distributed-range-based-SLAP. Each ``SLAP_*.m`` is
copied as ``SLAP_*_run.m`` with the seed set (``randn('state', seed)``), the animation and
``save_to_base`` removed and one ``RESULT`` line per tracker printed: the final position error
‖q − q̂‖, the mean and final pursuit error ‖[e_p; e_γ]‖ (the scripts' ``E_Pursuit``) and the
largest localization error (the one-tracker 3-D script's pursuit error with the current
attitude: :data:`STALE_ATTITUDE`); each run's header line gives the CPU seconds of its Octave
process::

    python benchmarks/seed003_octave.py CHECKOUT OUTPUT --seeds 1 2 3 [--scripts SLAP_2D_1Tracker]
"""

from __future__ import annotations

import argparse
import re
import resource
import shutil
import subprocess
from collections.abc import Sequence
from pathlib import Path

SCRIPTS = ("SLAP_2D_1Tracker", "SLAP_2D_3Trackers", "SLAP_3D_1Tracker", "SLAP_3D_3Trackers")

ONE = (
    'printf("RESULT final_pos_err %.6f mean_pursuit %.6f final_pursuit %.6f max_loc %.6f\\n", '
    "norm(q(end,:) - x_hat(end,1:{d})), mean(E_Pursuit), E_Pursuit(end), max(E_Loc));"
)
THREE = (
    "for T = {{Tracker1, Tracker2, Tracker3}}\n  Tr = T{{1}};\n"
    '  printf("RESULT final_pos_err %.6f mean_pursuit %.6f final_pursuit %.6f max_loc %.6f\\n", '
    "norm(Target.q(end,:) - Tr.q_hat(end,:)), mean(Tr.E_Pursuit), Tr.E_Pursuit(end), "
    "max(Tr.E_Loc));\nend"
)


STALE_ATTITUDE = "Rotation_matrix(eta(1),eta(2),eta(3))"
CURRENT_ATTITUDE = "Rotation_matrix(eta(1,end),eta(2,end),eta(3,end))"
"""SLAP_3D_1Tracker.m measures its pursuit error ``E_Pursuit`` with ``eta(1), eta(2), eta(3)`` of
the attitude history ``eta`` (3 × steps): the initial attitude at every step (its controller gets
``eta(:,end)``; the three-tracker script's ``ST_Tracking_3D.m`` uses the current attitude). The
copy measures it with the current attitude, as the paper's e_p (19) and trackcert do; the run is
unchanged (docs/simulation.md, the published cases)."""


def patched(source: str, name: str) -> str:
    """The script ``name`` seeded, without figures, printing its statistics."""
    d = 3 if "_3D_" in name else 2
    report = (THREE if "3Trackers" in name else ONE).format(d=d)
    text = source.replace(
        "function Main", f"function {name}_run(seed)\n    randn('state', seed);", 1
    )
    text = text.replace("save_to_base(1);", report, 1)
    text = text.replace(STALE_ATTITUDE, CURRENT_ATTITUDE)
    return re.sub(r"^\s*animation_\w+\s*$", "", text, flags=re.M)


def prepare(checkout: Path, output: Path, names: Sequence[str]) -> None:
    """Copy the checkout's ``*.m`` files into ``output`` and write each script's ``_run`` copy."""
    output.mkdir(parents=True, exist_ok=True)
    for path in checkout.glob("*.m"):
        shutil.copy(path, output / path.name)
    for name in names:
        source = (checkout / f"{name}.m").read_text(encoding="utf-8")
        (output / f"{name}_run.m").write_text(patched(source, name), encoding="utf-8")


def run(output: Path, name: str, seed: int) -> tuple[float, list[str]]:
    """CPU seconds (user + system) of ``octave-cli`` running ``name`` at ``seed`` in ``output``
    (prepared by :func:`prepare`), and its RESULT lines (one per tracker; none if it failed)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(
        ["octave-cli", "--no-window-system", "--eval", f"{name}_run({seed})"],
        cwd=output, capture_output=True, text=True, check=False,
    )  # fmt: skip
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    return cpu, [line for line in done.stdout.splitlines() if line.startswith("RESULT")]


def main(argv: Sequence[str] | None = None) -> None:
    """Write the patched scripts into OUTPUT and print each run's CPU and RESULT lines."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkout", type=Path)
    parser.add_argument("output", type=Path)
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--scripts", nargs="+", default=list(SCRIPTS), choices=SCRIPTS)
    args = parser.parse_args(argv)
    prepare(args.checkout, args.output, args.scripts)
    for name in args.scripts:
        for seed in args.seeds:
            cpu, results = run(args.output, name, seed)
            print(f"{name} seed={seed} cpu={cpu:.1f}", *results, sep="\n", flush=True)


if __name__ == "__main__":
    main()
