"""Closed-loop runs reproduce seed 000 §4.4 qualitatively; Monte Carlo is deterministic by seed."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from theory.cli import app
from theory.kinds import load_case
from theory.registry import get_claim
from theory.sim.simulate import monte_carlo
from theory.tdoa.estimation.scenario import TdoaRun, run_tdoa_scenario, run_tdoa_scenarios
from theory.tdoa.estimation.simulation import summarize_runs

runner = CliRunner()


def _spec(name: str, **changes: object):
    return dataclasses.replace(load_case(name).spec, **changes)


def test_runs_are_deterministic_and_independent_of_workers() -> None:
    spec = _spec("sim-ch4-fixed-b0", steps=8)
    serial = monte_carlo(spec, simulate=run_tdoa_scenario, runs=3, seed=11, workers=1)
    parallel = monte_carlo(spec, simulate=run_tdoa_scenario, runs=3, seed=11, workers=2)
    for a, b in zip(serial, parallel, strict=True):
        assert np.array_equal(a.estimates, b.estimates)
        assert np.array_equal(a.paths, b.paths)
    assert not np.array_equal(serial[0].truth, serial[1].truth)


def _same_run(a: TdoaRun, b: TdoaRun) -> bool:
    return all(
        np.array_equal(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a)
    )


def test_lock_step_runs_equal_solo_runs_exactly() -> None:
    """Runs simulated together (mixed b, filters, topologies, seeds) equal each run alone."""
    specs = [_spec("sim-ch4-fixed-b0", steps=6, b=b) for b in (0.0, 3.0, float("inf"))] + [
        _spec("sim-ch4-range21-b0", steps=6, filter=kind)
        for kind in ("decentralized", "centralized")
    ]
    seeds = [0, 1, 2, 3, 0]
    together = run_tdoa_scenarios(specs, [np.random.default_rng(s) for s in seeds])
    for spec, seed, run in zip(specs, seeds, together, strict=True):
        assert _same_run(run, run_tdoa_scenario(spec, np.random.default_rng(seed)))
    assert run.moving.any() and not together[2].moving.any()


def test_lock_step_needs_a_shared_clock() -> None:
    specs = [_spec("sim-ch4-fixed-b0", steps=3), _spec("sim-ch4-fixed-b0", steps=4)]
    rngs = [np.random.default_rng(0), np.random.default_rng(1)]
    with pytest.raises(ValueError, match="share"):
        run_tdoa_scenarios(specs, rngs)
    with pytest.raises(ValueError, match="one generator per scenario"):
        run_tdoa_scenarios(specs[:1], rngs)


def test_larger_b_travels_less_and_estimates_worse() -> None:
    """§4.4, Figs 4.9–4.10: as b grows, total distance falls and covariance norms grow.

    The registered claim checks the paper's ordering on the mean over 3 seeded runs (common
    random numbers) of 60 pings for b ∈ {0, 3, 15, ∞}; single runs can break the distance
    ordering for nearby b (docs/simulation.md, *Findings*).
    """
    result = get_claim("seed000.sec4.4.b-tradeoff").run(load_case("sim-ch4-fixed-b0"))[0]
    assert result.status == "verified", result.evidence
    assert result.evidence["mean_total_distance"][-1] == 0.0


def test_distance_rule_network_localizes_where_lone_agents_cannot() -> None:
    """Cor. 4.2.4: each agent ends with 2 TDOA rows; averaged EKF bounded, decentralized not."""
    results = {}
    for kind in ("averaged", "decentralized", "centralized"):
        spec = _spec("sim-ch4-range21-b0", filter=kind, steps=60)
        results[kind] = run_tdoa_scenario(spec, np.random.default_rng(3))
    averaged = results["averaged"]
    assert (averaged.degrees[-1] == 2).all() and (averaged.degrees[0] == 7).all()
    assert averaged.localization_errors[-1].max() < 5.0
    assert averaged.cov_norms[-1].max() < 2.0
    assert results["decentralized"].cov_norms[-1].max() > 10 * averaged.cov_norms[-1].max()
    assert results["centralized"].cov_norms[-1].max() < averaged.cov_norms[-1].min()


def test_summary_has_the_design_keys() -> None:
    spec = _spec("sim-ch4-fixed-b0", steps=5)
    summary = summarize_runs(
        spec, monte_carlo(spec, simulate=run_tdoa_scenario, runs=2, seed=0, workers=1)
    )
    assert len(summary["agents"]) == 8
    for agent in summary["agents"]:
        assert {"id", "final_localization_error", "mean_localization_error"} <= set(agent)
    assert len(summary["runs_total_distance"]) == 2


def _small_case(tmp_path: Path, **changes: object) -> Path:
    data = yaml.safe_load(Path(load_case("sim-ch4-range21-b0").file).read_text())
    data["tdoa-sim"]["steps"] = 12
    data.update(changes)
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def test_cli_simulate_writes_data_figures_and_json(tmp_path: Path) -> None:
    case = _small_case(tmp_path)
    out = tmp_path / "out"
    result = runner.invoke(
        app,
        [
            "simulate",
            str(case),
            "--runs",
            "2",
            "--seed",
            "5",
            "--workers",
            "1",
            "-o",
            str(out),
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    report = json.loads(result.stdout)
    assert report["runs"] == 2 and report["seed"] == 5
    assert [a["id"] for a in report["agents"]] == list(range(1, 9))
    for name in (
        "runs.npz",
        "agents.csv",
        "timeseries.csv",
        "summary.json",
        "errors.png",
        "trajectories.png",
        "covariance.png",
        "distance.png",
    ):
        assert (out / name).is_file(), name
    data = np.load(out / "runs.npz")
    assert data["estimates"].shape == (2, 13, 8, 6)
    assert json.loads((out / "summary.json").read_text())["agents"] == report["agents"]


def test_cli_simulate_exit_codes(tmp_path: Path) -> None:
    case = _small_case(tmp_path, expect={"max_final_error": 1e-9})
    out = tmp_path / "out"
    args = ["--workers", "1", "--no-figures", "-o", str(out)]
    assert runner.invoke(app, ["simulate", str(case), *args]).exit_code == 1
    bad = runner.invoke(app, ["simulate", "fig43-case-d", *args])
    assert bad.exit_code == 2 and "tdoa-sim" in bad.stderr
    missing = runner.invoke(app, ["simulate", str(tmp_path / "nope.yaml"), *args])
    assert missing.exit_code == 2
