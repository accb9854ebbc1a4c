"""Sweeps end to end: invalid points, the verdict policy, a pursuit k_gamma sweep, the files."""

from __future__ import annotations

import csv
import importlib
import inspect
import json

import pytest

from theory.core.errors import CaseError
from theory.kinds import KINDS, SIMULATED, simulator
from theory.sweep.outputs import write_sweep
from theory.sweep.points import ANALYSIS_MODULES, Row, agreement, analysis_for, point_modules
from theory.sweep.run import Sweep, sweep_case

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def pursuit_sweep() -> Sweep:
    """Type II pursuit, k_gamma from 1 to 400 (Theorem 2 needs only k_gamma > 0)."""
    return sweep_case("pursuit-table1-n3", ["k_gamma=1,400", "seed=0:2"], steps=10, workers=1)


def test_pursuit_k_gamma_sweep_verdict_and_bounded_simulation(pursuit_sweep: Sweep) -> None:
    rows = pursuit_sweep.rows
    assert [r.values for r in rows] == [(1, 0), (1, 1), (400, 0), (400, 1)]
    for row in rows:
        assert row.status == "verified" and row.exit_code == 0
        assert row.margin is not None and row.margin > row.tolerances["margin_tol"]
        assert row.sim_seed == row.values[1]
        assert row.simulated["sim_simulation_bounded"] is True
        assert 0 < row.simulated["sim_final_pursuit_error"] < float("inf")
        assert row.agreement == "agree"
    assert pursuit_sweep.verdict is True and pursuit_sweep.exit_code == 0
    seeds = {r.values[1]: r.simulated["sim_final_localization_error"] for r in rows[:2]}
    assert seeds[0] != seeds[1]  # the seed reaches the simulation


def test_pursuit_k_gamma_changes_the_verdict_margin(pursuit_sweep: Sweep) -> None:
    """The K ≻ 0 margin λ_min/λ_max of K = diag(K_p, k_γ) falls as k_γ grows past K_p."""
    low, high = pursuit_sweep.rows[0], pursuit_sweep.rows[2]
    assert high.margin == pytest.approx(0.2 / 400)
    assert low.margin > high.margin


def test_invalid_points_are_rows_with_the_loader_message() -> None:
    sweep = sweep_case("pursuit-table1-n3", ["k_gamma=-1,5"], steps=5, workers=1)
    bad, good = sweep.rows
    assert bad.status == "invalid" and bad.exit_code == 2
    assert "k_gamma" in bad.message and bad.sim_seed is None
    assert good.status == "verified"
    assert sweep.exit_code == 0  # an invalid point is a finding, not an error of the sweep


def test_a_point_the_simulator_refuses_keeps_its_verdict() -> None:
    """ε₁ = 0: Δ of seed 003 eq. (22) loses rank, the verdict fails and nothing is simulated."""
    sweep = sweep_case("pursuit-table1-n3", ["epsilon.0=0,-0.5"], steps=5, workers=1)
    singular, regular = sweep.rows
    assert singular.status == "refuted" and singular.exit_code == 1
    assert "delta_full_rank fails" in singular.message and "not simulated" in singular.message
    assert singular.sim_seed is None and singular.simulated == {} and singular.agreement == "n/a"
    assert regular.status == "verified" and regular.agreement == "agree"
    assert sweep.exit_code == 0


def test_tdoa_sweep_states_margin_and_tolerances() -> None:
    """Moving agent 3 of Fig. 4.3 (d) along x keeps the path graph localizing (Cor. 4.2.4)."""
    sweep = sweep_case("fig43-case-d", ["agents.2.0=-10,0,10"], workers=1)
    for row in sweep.rows:
        assert row.status == "verified"
        assert row.margin > row.tolerances["inconclusive_factor"]
        assert row.sim_seed is None


def test_a_grid_of_invalid_points_only_is_bad_input() -> None:
    """Any one change of a row of W breaks its row sum: every point is invalid."""
    with pytest.raises(CaseError) as caught:
        sweep_case("ch5-example-1-wb", ["W.0.0=0.1,0.2"], workers=1, simulate=False)
    assert caught.value.field == "--param"
    assert "row" in str(caught.value.got) or "stochastic" in str(caught.value.got)


def test_unknown_path_is_refused_before_any_point_runs() -> None:
    with pytest.raises(CaseError) as caught:
        sweep_case("pursuit-table1-n3", ["k_gama=1:3"], workers=1)
    assert caught.value.field == "--param k_gama"
    assert "k_gamma" in caught.value.hint


def test_no_simulate_needs_a_kind_with_an_analysis() -> None:
    with pytest.raises(CaseError) as caught:
        sweep_case("sim-ch4-fixed-b0", ["b=1,2"], workers=1, simulate=False)
    assert caught.value.field == "--no-simulate"


def test_seed_values_must_be_non_negative_integers() -> None:
    with pytest.raises(CaseError, match="seed"):
        sweep_case("pursuit-table1-n3", ["seed=0.5,1.5"], workers=1)


def test_dkf_sweep_judges_s_detectability_without_simulation() -> None:
    """Seed 000 Example 1 with W_b (w_11 = 0.26 > 1/r(A_u)² = 0.25): not S-detectable at A = 2I
    (the case's expectation); a stable A = I/2 is S-detectable whatever W."""
    sweep = sweep_case(
        "ch5-example-1-wb", ["A.0.0=0.5,2", "A.1.1=0.5,2"], simulate=False, workers=1
    )
    status = {r.values: r.status for r in sweep.rows}
    assert status[(0.5, 0.5)] == "verified"
    assert status[(2, 2)] == "refuted"
    assert all(r.sim_seed is None and r.agreement == "n/a" for r in sweep.rows)
    assert "lmi_margin" in sweep.rows[0].tolerances
    assert sweep.exit_code == 0


def row(status: str, agreement: str) -> Row:
    return Row(0, (1.0,), status, agreement=agreement)


@pytest.mark.parametrize(
    ("rows", "verdict"),
    [
        ([row("verified", "agree"), row("refuted", "n/a")], True),
        ([row("verified", "agree"), row("invalid", "n/a")], True),
        ([row("verified", "disagree"), row("inconclusive", "n/a")], False),
        ([row("verified", "agree"), row("inconclusive", "inconclusive")], None),
        ([row("verified", "inconclusive")], None),
    ],
)
def test_sweep_verdict_policy(rows: list[Row], verdict) -> None:
    sweep = Sweep("c", "pursuit", "f", (), {}, tuple(rows))
    assert sweep.verdict is verdict
    assert sweep.exit_code == {True: 0, False: 1, None: 3}[verdict]


def checked(status: str) -> dict:
    return {"iss_agreement": {"status": status, "message": f"run {status}"}}


@pytest.mark.parametrize(
    ("verdict", "summary", "expected"),
    [
        (True, checked("verified"), "agree"),
        (True, checked("refuted"), "disagree"),
        (True, checked("inconclusive"), "inconclusive"),
        (True, {"iss_agreement": None}, "inconclusive"),
        (None, checked("verified"), "inconclusive"),
        (False, {"iss_agreement": None}, "n/a"),
        (True, None, "n/a"),
    ],
)
def test_pursuit_agreement(verdict, summary, expected) -> None:
    """Theorem 2 (seed 003): a holding ISS verdict predicts μ stays within the certified
    estimate; a run stopped inside it (x̃ ran away) contradicts nothing."""
    assert agreement("pursuit", verdict, summary)[0] == expected


def test_kinds_without_a_prediction_never_disagree() -> None:
    assert agreement("dkf", True, {"agents": []}) == ("n/a", "")


def test_files_csv_json_png(pursuit_sweep: Sweep, tmp_path) -> None:
    files = write_sweep(pursuit_sweep, tmp_path / "out")
    assert [f.name for f in files] == ["sweep.csv", "sweep.json", "sweep.png"]
    with files[0].open(newline="") as handle:
        table = list(csv.DictReader(handle))
    assert len(table) == 4
    assert list(table[0])[:3] == ["point", "k_gamma", "seed"]
    assert {"status", "exit_code", "margin", "agreement", "message"} <= set(table[0])
    assert float(table[2]["margin"]) == pursuit_sweep.rows[2].margin  # repr round-trips
    record = json.loads(files[1].read_text())
    assert record["summary"]["exit_code"] == 0
    assert record["tolerances"]["margin_tol"] == pursuit_sweep.rows[0].tolerances["margin_tol"]
    assert [r["point"] for r in record["rows"]] == [0, 1, 2, 3]
    assert files[2].read_bytes()[:8] == PNG
    assert not [p for p in tmp_path.iterdir() if p.name != "out"]  # no staging folder left


def test_nothing_is_written_when_the_figure_fails(
    pursuit_sweep: Sweep, tmp_path, monkeypatch
) -> None:
    import theory.sweep.outputs as outputs

    def broken(sweep, path):
        raise RuntimeError("figure failed")

    monkeypatch.setattr(outputs, "write_sweep_figure", broken)
    with pytest.raises(RuntimeError):
        write_sweep(pursuit_sweep, tmp_path / "out")
    assert list(tmp_path.iterdir()) == []


def test_rows_do_not_depend_on_the_batching(monkeypatch) -> None:
    """One batch of every point, or one batch per point: the same rows in grid order."""
    import theory.sweep.run as run

    args = ("fig43-case-d", ["agents.2.0=-10:10:lin4", "agents.1.1=-2,2"])
    monkeypatch.setattr(run, "TASKS_PER_WORKER", 1)
    one_batch = sweep_case(*args, workers=1)
    monkeypatch.setattr(run, "TASKS_PER_WORKER", 64)
    many = sweep_case(*args, workers=1)
    assert one_batch.to_json() == many.to_json()
    assert [r.point for r in many.rows] == list(range(8))


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_a_points_modules_are_the_ones_its_analysis_and_simulator_import(kind: str) -> None:
    """The engine's preload for a sweep (every name importable; the analysis module is the one
    its judgement function imports, the simulator's the one the kind's simulator is in)."""
    modules = point_modules(kind)
    for module in modules:
        importlib.import_module(module)
    assert modules[:2] == ("theory.sweep.points", KINDS[kind].parse.__module__)
    analysis = analysis_for(kind)
    if analysis is not None:
        assert f"from {ANALYSIS_MODULES[kind]} import" in inspect.getsource(analysis)
        assert ANALYSIS_MODULES[kind] in modules
    if kind in SIMULATED:
        assert simulator(kind).__module__ in modules
