"""The one-tracker runaway of the DEC loop (seed 003; docs/theory/pursuit-iss.md §11).

* ``pursuit-table2-n1 --seed 2`` runs away and is stopped at the first sampling instant where the
  localization error exceeds ``runaway_factor`` curve sizes, with its cause and reason, in the
  library run and in ``trackcert simulate --json``;
* the check does not change a trajectory: before the stop the run equals the run without it;
* bounded runs (seed 0 with one tracker, the three-tracker Table cases) are not stopped;
* :func:`runaway_reason` fires exactly when the largest localization error exceeds the threshold
  and names that tracker (hypothesis).
"""

from __future__ import annotations

import dataclasses
import json
import math
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from theory.cli import app
from theory.core.tolerances import RUNAWAY_FACTOR
from theory.kinds import load_case
from theory.pursuit.closed_loop import build_loop, runaway_reason, simulate_dec
from theory.pursuit.simulation import dec_arguments

STOP_STEPS = 300
"""30 s: seed 2 of ``pursuit-table2-n1`` is stopped at 22 s (its error passes 5 × 80 m at 20.5 s,
between two samples)."""
BOUNDED_STEPS = 600
"""60 s: every runaway of the Table cases over seeds 0–9 passed the threshold by 38 s."""


def _cli_rng(seed: int) -> np.random.Generator:
    """Run 0's generator under ``trackcert simulate --seed seed`` (child 0 of the root seed)."""
    return np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])


def _arguments(name: str, steps: int, **settings) -> dict:
    arguments = dec_arguments(load_case(name).spec, steps)
    arguments["settings"] = dataclasses.replace(arguments["settings"], **settings)
    return arguments


def test_one_tracker_seed_2_is_stopped_as_a_runaway_with_its_cause() -> None:
    arguments = _arguments("pursuit-table2-n1", STOP_STEPS)
    run = simulate_dec(rng=_cli_rng(2), **arguments)
    assert not run.completed and run.stop_cause == "runaway" and run.stopped_at == 22.0
    assert "tracker 1's localization error" in run.stop_reason
    assert f"runaway_factor {RUNAWAY_FACTOR:g} × 80 m" in run.stop_reason
    assert "bearing error" in run.stop_reason and "λ_min(Ω)" in run.stop_reason
    assert 'docs/errata.md, "What makes the Table cases run away"' in run.stop_reason
    stop = round(run.stopped_at / 0.1)
    limit = RUNAWAY_FACTOR * 80.0  # Table II: the largest semi-axis is r_x = r_y = 80 m
    assert run.localization_errors[stop, 0] > limit
    assert np.all(run.localization_errors[: stop - 19, 0] <= limit)  # the samples before (t ≤ 20 s)
    assert np.isnan(run.localization_errors[stop + 1 :]).all()


def test_the_check_does_not_change_the_trajectory_before_the_stop() -> None:
    checked = simulate_dec(rng=_cli_rng(2), **_arguments("pursuit-table2-n1", STOP_STEPS))
    free = simulate_dec(
        rng=_cli_rng(2), **_arguments("pursuit-table2-n1", STOP_STEPS, runaway_factor=math.inf)
    )
    assert free.completed and np.nanmax(free.localization_errors) > 2 * RUNAWAY_FACTOR * 80.0
    stop = round(checked.stopped_at / 0.1) + 1
    for key in ("positions", "gammas", "localization_errors", "pursuit_errors"):
        np.testing.assert_array_equal(getattr(checked, key)[:stop], getattr(free, key)[:stop])


@pytest.mark.parametrize(
    ("name", "seed"),
    [
        ("pursuit-table2-n1", 0),
        ("pursuit-table1-n1", 0),
        ("pursuit-table1-n3", 2),
        ("pursuit-table2-n3", 2),
        ("pursuit-table2-n3-kgamma5", 2),
    ],
)
def test_bounded_runs_are_not_stopped(name: str, seed: int) -> None:
    arguments = _arguments(name, BOUNDED_STEPS)
    run = simulate_dec(rng=_cli_rng(seed), **arguments)
    scale = build_loop(arguments["settings"], arguments["paths"], arguments["in_neighbours"],
                       load_case(name).spec.dim).scale  # fmt: skip
    assert run.completed and run.stop_cause == "" and run.stop_reason == ""
    assert run.localization_errors.max() < scale  # far from the threshold of RUNAWAY_FACTOR·scale


def test_simulate_reports_the_runaway_and_the_factor(tmp_path) -> None:
    """``trackcert simulate``: ``stopped_at`` as before, plus ``stop_causes``, ``stop_reasons``,
    ``tolerances.runaway_factor``; the run is a warning, the ISS agreement inconclusive and the
    case's ``simulation_bounded`` unmet (exit 1)."""
    args = ["simulate", "pursuit-table2-n1", "--seed", "2", "--steps", str(STOP_STEPS)]
    out = ["--workers", "1", "--no-figures", "-o", str(tmp_path), "--json"]
    result = CliRunner().invoke(app, [*args, *out])
    assert result.exit_code == 1, result.output
    summary = json.loads(result.stdout)
    assert summary["stopped_at"] == [22.0] and summary["stop_causes"] == ["runaway"]
    assert summary["stop_reasons"][0].startswith("runaway: tracker 1's localization error")
    assert summary["tolerances"] == {"runaway_factor": RUNAWAY_FACTOR}
    assert "t = 22 s, runaway" in summary["warnings"][0]
    assert summary["iss_agreement"]["status"] == "inconclusive"


def test_a_case_sets_its_runaway_factor_in_tolerances(tmp_path) -> None:
    """``tolerances: {runaway_factor: 2}`` stops the same run earlier and is reported."""
    import yaml

    from theory.core.case_file import resolve_case_path

    data = yaml.safe_load(resolve_case_path("pursuit-table2-n1").read_text(encoding="utf-8"))
    data["tolerances"] = {**(data.get("tolerances") or {}), "runaway_factor": 2}
    case = tmp_path / "strict.yaml"
    case.write_text(yaml.safe_dump(data), encoding="utf-8")
    args = ["simulate", str(case), "--seed", "2", "--steps", str(STOP_STEPS), "--no-figures"]
    result = CliRunner().invoke(app, [*args, "--workers", "1", "-o", str(tmp_path / "o"), "--json"])
    summary = json.loads(result.stdout)
    assert summary["tolerances"] == {"runaway_factor": 2.0}
    assert summary["stop_causes"] == ["runaway"] and summary["stopped_at"][0] < 22.0
    assert "runaway_factor 2 × 80 m" in summary["stop_reasons"][0]


LOOPS = {
    name: build_loop(a["settings"], a["paths"], a["in_neighbours"], load_case(name).spec.dim)
    for name, a in ((n, dec_arguments(load_case(n).spec, 1)) for n in
                    ("pursuit-table1-n1", "pursuit-table1-n3", "pursuit-table2-n3"))
}  # fmt: skip


@st.composite
def _instants(draw):
    """A loop, tracker positions, estimates, the target's state and a factor."""
    loop = LOOPS[draw(st.sampled_from(sorted(LOOPS)))]
    n, d = loop.n, loop.dim
    coordinate = st.floats(-1e4, 1e4, allow_nan=False)
    arrays = [np.array(draw(st.lists(coordinate, min_size=k, max_size=k))) for k in
              (n * d, n * 2 * d, 2 * d)]  # fmt: skip
    factor = draw(st.floats(0.5, 50.0))
    return loop, arrays[0].reshape(n, d), arrays[1].reshape(n, 2 * d), arrays[2], factor


@given(_instants())
def test_runaway_reason_fires_exactly_above_the_threshold(instant) -> None:
    loop, positions, x_hat, truth, factor = instant
    information = np.broadcast_to(np.eye(2 * loop.dim), (loop.n, 2 * loop.dim, 2 * loop.dim))
    reason = runaway_reason(loop, positions, x_hat, truth, information, factor)
    errors = np.linalg.norm(x_hat[:, : loop.dim] - truth[: loop.dim], axis=1)
    assert bool(reason) == bool(errors.max() > factor * loop.scale)
    if reason:
        assert f"tracker {int(np.argmax(errors)) + 1}'s" in reason


@pytest.mark.parametrize("on", ["target", "estimate"])
def test_a_tracker_on_the_target_or_its_estimate_has_no_bearing_error(on: str) -> None:
    """The bearing is the angle between two rays; a tracker at either end has none to state."""
    loop = LOOPS["pursuit-table1-n1"]
    truth = np.zeros(2 * loop.dim)
    x_hat = np.full((loop.n, 2 * loop.dim), 10 * loop.scale)
    positions = np.zeros((loop.n, loop.dim)) if on == "target" else x_hat[:, : loop.dim].copy()
    information = np.broadcast_to(np.eye(2 * loop.dim), (loop.n, 2 * loop.dim, 2 * loop.dim))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        reason = runaway_reason(loop, positions, x_hat, truth, information, 5.0)
    assert "bearing error undefined" in reason and "nan" not in reason
