"""Only what a command uses is imported (issue 28 item 2): each command runs in a fresh
interpreter and reports which heavy libraries it loaded. No timing: the import lists are the
guarded property; ``benchmarks/bench_startup.py`` measures the CPU they cost."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from theory.core.parallel import THREAD_SETTINGS

ROOT = Path(__file__).resolve().parents[2]

NEVER = ("sympy", "control", "cvxpy", "numba", "distributed", "matplotlib")
"""What a short ``simulate`` without figures never needs: exact algebra (sympy), python-control,
the LMI solvers, the compiled kernels (a short job runs on NumPy), the Dask cluster (one run),
the figures."""


def imported(
    argv: list[str], folder: Path, watched: tuple[str, ...] = NEVER
) -> tuple[int, list[str]]:
    """Exit code of ``trackcert argv…`` in a fresh interpreter and which of ``watched`` it
    imported (``TRACKCERT_ENGINE`` unset: the default engine rule)."""
    script = (
        "import json, sys\n"
        "from theory.cli import main\n"
        f"sys.argv = ['trackcert', *{argv!r}]\n"
        "try:\n    main()\nexcept SystemExit as stop:\n    code = stop.code or 0\n"
        f"heavy = [m for m in {watched!r} if m in sys.modules]\n"
        "print(json.dumps([code, heavy]), file=sys.stderr)\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "TRACKCERT_ENGINE"}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    done = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        check=True,
        cwd=folder,
        env=env,
    )
    code, heavy = json.loads(done.stderr.strip().splitlines()[-1])
    return code, heavy


BARE = ["--no-figures", "-o", "out"]


@pytest.mark.parametrize(
    "argv",
    [
        ["simulate", "pursuit-table1-n3", "--steps", "1", *BARE],
        ["simulate", "pursuit-table2-n3", "--steps", "5", "--runs", "3", "--workers", "1", *BARE],
        ["simulate", "sim-ch4-fixed-b0", "--steps", "1", *BARE],
        ["simulate", "ch5-example-1-wg", "--steps", "1", *BARE],
        ["simulate", "pf-path3", "--runs", "1", *BARE],
    ],
    ids=["pursuit-2d", "pursuit-3d-runs", "tdoa-sim", "dkf", "pf"],
)
def test_a_short_simulation_imports_none_of_the_heavy_libraries(argv, tmp_path) -> None:
    code, heavy = imported(argv, tmp_path)
    assert code in (0, 1, 3)  # the expectations' verdict on a short run; never bad input
    assert heavy == []
    assert (tmp_path / "out").is_dir() and not list((tmp_path / "out").glob("*.png"))


def test_figures_import_matplotlib_when_written(tmp_path) -> None:
    """The positive control of the list: a run with figures loads matplotlib and writes them."""
    argv = ["simulate", "pursuit-table1-n3", "--steps", "1", "-o", "out"]
    code, heavy = imported(argv, tmp_path)
    assert code in (0, 1, 3)
    assert heavy == ["matplotlib"]
    assert list((tmp_path / "out").glob("*.png"))


def test_dkf_does_without_python_control(tmp_path) -> None:
    """``trackcert dkf`` needs the LMI solver (cvxpy), never python-control (its cross-check is
    a test, tests/consensus)."""
    code, heavy = imported(["dkf", "ch5-example-1-wg", "--json"], tmp_path)
    assert code == 0
    assert "control" not in heavy and "cvxpy" in heavy


@pytest.mark.parametrize(
    ("case", "expected"),
    [("pursuit-table1-n1", []), ("pursuit-table1-n3", ["flint"])],
)
def test_a_short_pursuit_run_imports_exact_algebra_only_where_used(case, expected, tmp_path):
    """The run's ISS agreement needs no sparse graph library (strong connectivity is a small
    search) and, for one tracker (no coordination constants), no python-flint."""
    argv = ["simulate", case, "--steps", "1", *BARE]
    code, heavy = imported(argv, tmp_path, ("flint", "scipy.sparse"))
    assert code in (0, 1, 3)
    assert heavy == expected


POOLS = (
    "import json, os, sys\n"
    "from theory.cli import main\n"
    "sys.argv = ['trackcert', 'simulate', 'pursuit-table1-n3', '--steps', '1', '--no-figures',"
    " '-o', 'out']\n"
    "try:\n    main()\nexcept SystemExit:\n    pass\n"
    "from threadpoolctl import threadpool_info\n"
    "pools = [p['num_threads'] for p in threadpool_info() if p['internal_api'] == 'openblas']\n"
    "print(json.dumps([os.environ.get('OPENBLAS_NUM_THREADS'), pools]), file=sys.stderr)\n"
)
"""A one-step ``trackcert simulate`` in a fresh interpreter, then its OpenBLAS pools' sizes."""


@pytest.mark.parametrize(("setting", "expected"), [(None, "1"), ("2", "2")])
def test_the_command_starts_its_blas_pools_with_one_thread(setting, expected, tmp_path) -> None:
    """``trackcert`` sets the thread-count variables the user left unset to 1 before NumPy loads
    (theory.core.parallel.one_thread_pools): NumPy's and SciPy's OpenBLAS start with one
    thread, as every task runs anyway; a count the user set is kept."""
    env = {k: v for k, v in os.environ.items() if k not in THREAD_SETTINGS}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    if setting is not None:
        env["OPENBLAS_NUM_THREADS"] = setting
    done = subprocess.run(
        [sys.executable, "-c", POOLS], capture_output=True, text=True, check=True,
        cwd=tmp_path, env=env,
    )  # fmt: skip
    value, pools = json.loads(done.stderr.strip().splitlines()[-1])
    assert value == expected
    assert len(pools) == 2  # NumPy's and SciPy's
    if setting is None:
        assert pools == [1, 1]
