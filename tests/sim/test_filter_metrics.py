"""NEES/NIS bands and OSPA/GOSPA in ``trackcert simulate``'s summaries (issue 26 item 4): every
simulated filter reports them, a consistent Kalman filter passes, and the same filter with its
covariances scaled by 0.1 fails on the unsafe side."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import trackcert
from theory.consensus.kalman_filter import run_dkf_case, summarize_dkf
from theory.core.consistency import chi2_band
from theory.kinds import load_case
from theory.tdoa.estimation.scenario import run_tdoa_scenario
from theory.tdoa.estimation.simulation import summarize_runs

ALONE = 2
"""Agent 3 of ch5-example-1-wg sees the whole state and has w_33 = 1: a plain Kalman filter."""


def _dkf_runs(count: int, steps: int) -> tuple:
    case = load_case("cases/ch5-example-1-wg.yaml")
    return case.spec, [
        run_dkf_case(case.spec, np.random.default_rng(seed), steps) for seed in range(count)
    ]


def _check_test_record(test: dict, runs: int) -> None:
    """A band is the χ² band of its dof and samples, and the verdict is the value's side."""
    band = test["band"]
    expected = chi2_band(band["dof"], band["samples"], band["probability"])
    assert (band["lower"], band["upper"]) == pytest.approx((expected.lower, expected.upper))
    assert band["samples"] % runs == 0 and band["probability"] == 0.95
    inside = band["lower"] < test["value"] < band["upper"]
    assert test["verdict"] in {"consistent", "inconclusive"} if inside else True
    if test["verdict"] == "optimistic":
        assert test["value"] > band["upper"] and test["margin"] < 0
    if test["verdict"] == "pessimistic":
        assert test["value"] < band["lower"] and test["margin"] < 0


def test_consensus_kf_summary_reports_bands_and_the_isolated_kalman_filter_passes() -> None:
    spec, runs = _dkf_runs(6, 150)
    summary = summarize_dkf(spec, runs)
    metrics = summary["metrics"]
    assert metrics["positions"] is None  # the dkf state is not a position
    assert [t["band"]["dof"] for t in metrics["nis"]] == [6 * 150 * c.shape[0] for c in spec.C]
    for test in metrics["nees"] + metrics["nis"]:
        _check_test_record(test, 6)
    assert metrics["nees"][ALONE]["verdict"] == "consistent"
    assert metrics["nis"][ALONE]["verdict"] == "consistent"
    assert summary["agents"][ALONE]["anees"] == metrics["nees"][ALONE]["value"]


def test_inconsistent_consensus_kf_fails_its_band() -> None:
    """Issue 26 'Done when': P_i and S_i scaled by 0.1 (the filter believes its errors ten times
    smaller in variance than they are) fail the bands above, the unsafe side: every agent's
    NEES and the Kalman filter's NIS. (Agents 1 and 2 average their covariances with a
    neighbour's and overstate their innovations' variance more than tenfold: their NIS, ten
    times larger, stays below the band.)"""
    spec, runs = _dkf_runs(6, 150)
    shrunk = [
        dataclasses.replace(
            run,
            covariances=0.1 * run.covariances,
            innovation_covariances=0.1 * run.innovation_covariances,
        )
        for run in runs
    ]
    before = summarize_dkf(spec, runs)["metrics"]
    after = summarize_dkf(spec, shrunk)["metrics"]
    assert [t["verdict"] for t in after["nees"]] == ["optimistic"] * 3
    assert after["nis"][ALONE]["verdict"] == "optimistic"
    for name in ("nees", "nis"):
        for old, new in zip(before[name], after[name], strict=True):
            assert new["value"] == pytest.approx(10 * old["value"])
            assert new["band"] == old["band"]


@pytest.mark.parametrize("name", ["sim-ch4-fixed-b0", "sim-ch4-range21-centralized"])
def test_tdoa_summary_reports_nees_nis_and_ospa(name: str) -> None:
    case = load_case(f"cases/{name}.yaml")
    spec = dataclasses.replace(case.spec, steps=20)
    runs = [run_tdoa_scenario(spec, np.random.default_rng(seed)) for seed in range(2)]
    summary = summarize_runs(spec, runs)
    metrics = summary["metrics"]
    n = spec.n_agents
    assert len(metrics["nees"]) == len(metrics["nis"]) == n
    for test in metrics["nees"] + metrics["nis"]:
        _check_test_record(test, 2)
    assert {t["band"]["dof"] for t in metrics["nees"]} == {6 * 2 * 21}
    positions = metrics["positions"]
    cutoff = positions["tolerance"]["ospa_cutoff"]
    errors = np.stack([run.localization_errors for run in runs])
    # one estimate, one target: OSPA = GOSPA = min(c, ‖p̄_i − p‖) at every ping
    expected = np.minimum(errors, cutoff).mean(axis=(0, 1))
    assert positions["ospa"] == pytest.approx(list(expected), rel=1e-12)
    assert positions["gospa"] == pytest.approx(list(expected), rel=1e-12)
    if spec.filter == "centralized":  # one update, held by everyone
        assert len({t["value"] for t in metrics["nis"]}) == 1


def test_api_results_carry_the_metrics(tmp_path) -> None:
    result = trackcert.simulate(
        "cases/ch5-example-1-wg.yaml", runs=2, steps=40, folder=tmp_path / "out", figures=False
    )
    assert result.metrics == result.to_json()["metrics"]
    assert {"nees", "nis", "positions", "tolerance"} <= set(result.metrics)
    assert all(math.isfinite(t["value"]) for t in result.metrics["nees"])
    assert "anees" in result.agents[0] and "nees_verdict" in result.agents[0]
