"""The ``published`` variant of seed 003's DEC loop (theory/pursuit/published.py) and the case
fields that select it (issue 27).

* The case schema: ``controller: {law, variant, inputs_min, inputs_max, gamma_ddot}``,
  ``duration``, ``dekf.predict_every`` and ``dekf.edges`` are validated with errors naming the
  field, what was expected and what was found.
* The vehicle step is RK4 on the unicycle (2-D): for constant inputs the exact motion is an arc,
  which four RK4 steps of 0.025 s reproduce to O(h⁵).
* The published 2-D one-tracker case localizes and pursues the target as the authors' script
  does (final position error well below a metre, no runaway).
* Each published case's bands are the range of the authors' scripts under Octave over seeds
  1–10 (the log ``benchmarks/seed003_octave_runs.txt``), and its 10 runs lie in them.
"""

from __future__ import annotations

import copy
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from theory.core.case_file import read_case_data, resolve_case_path
from theory.core.errors import CaseError
from theory.core.expectations import judge
from theory.pursuit import published
from theory.pursuit.case import PURSUIT
from theory.pursuit.simulation import run_pursuit_case, simulation_observed, summarize_pursuit


def _data(name: str = "pursuit-published-2d-n1") -> dict:
    return copy.deepcopy(read_case_data(resolve_case_path(name)))


def _refused(data: dict, field: str) -> str:
    with pytest.raises(CaseError) as info:
        PURSUIT.parse_case(data, file="case.yaml")
    message = str(info.value)
    assert field in message and "case.yaml" in message
    return message


def test_the_published_cases_parse_with_their_clamps_and_prediction_rate() -> None:
    spec = PURSUIT.parse_case(_data()).spec
    assert spec.controller == "II" and spec.duration == 450
    assert np.array_equal(spec.published.inputs_min, [0, -0.4])
    assert np.array_equal(spec.published.inputs_max, [2, 0.4])
    assert spec.published.gamma_ddot == (-0.001, 0.01)
    assert spec.dekf.predictions == 20 and spec.dekf.V == 0.1
    three = PURSUIT.parse_case(_data("pursuit-published-2d-n3")).spec
    assert three.dekf.weights[0, 1] == 0.5 and three.adjacency[0, 2] == 1  # fusion ≠ coordination


def test_an_analysed_controller_given_as_a_mapping_has_no_clamps() -> None:
    data = _data("pursuit-table1-n1")
    data["pursuit"]["controller"] = {"law": "II"}
    assert PURSUIT.parse_case(data).spec.published is None
    data["pursuit"]["controller"]["gamma_ddot"] = [-1, 1]
    _refused(data, "pursuit.controller.gamma_ddot")


@pytest.mark.parametrize(
    ("path", "value", "field"),
    [
        (("controller", "variant"), "fast", "pursuit.controller.variant"),
        (("controller", "law"), "III", "pursuit.controller.law"),
        (("controller", "inputs_min"), [0, -0.4, 1], "pursuit.controller.inputs_min"),
        (("controller", "inputs_max"), [-1, 0.4], "pursuit.controller.inputs_max"),
        (("controller", "gamma_ddot"), [0.01, -0.01], "pursuit.controller.gamma_ddot"),
        (("controller", "speed"), 1, "pursuit.controller"),
        (("dekf", "predict_every"), 0.3, "pursuit.dekf.predict_every"),
        (("dekf", "predict_every"), -1, "pursuit.dekf.predict_every"),
        (("duration",), 0, "pursuit.duration"),
    ],
)
def test_malformed_published_fields_are_refused_by_name(path, value, field) -> None:
    data = _data()
    block = data["pursuit"]
    for key in path[:-1]:
        block = block[key]
    block[path[-1]] = value
    _refused(data, field)


def test_fusion_weights_must_live_on_the_fusion_graph() -> None:
    data = _data("pursuit-published-2d-n3")
    data["pursuit"]["dekf"]["edges"] = [[3, 1], [1, 2], [2, 3]]  # the weights sit on 2→1 …
    _refused(data, "pursuit.dekf.weights")


@settings(max_examples=30, deadline=None)
@given(
    st.floats(0.0, 2.0), st.floats(-0.4, 0.4).filter(lambda r: abs(r) > 1e-3),
    st.floats(-math.pi, math.pi),
)  # fmt: skip
def test_the_vehicle_step_follows_the_unicycle_arc(speed: float, rate: float, yaw: float) -> None:
    """ṗ = v(cos ψ, sin ψ), ψ̇ = r with u held: the arc of radius v/r (seed 003 eqs. (2)–(5))."""
    state = np.array([[1.0, -2.0, yaw]])
    after = published._vehicle_step(state, np.array([[speed, rate]]), 2)[0]
    end = yaw + rate * published.STEP
    exact = [
        1.0 + speed / rate * (math.sin(end) - math.sin(yaw)),
        -2.0 - speed / rate * (math.cos(end) - math.cos(yaw)),
        end,
    ]
    assert np.allclose(after, exact, rtol=0, atol=1e-9)


def test_the_published_one_tracker_run_localizes_and_pursues_the_target() -> None:
    """SLAP_2D_1Tracker.m under Octave: final position error 0.4–0.6 m, mean pursuit error
    3.4–3.5 m (seeds 1–2); the reproduction stays in that neighbourhood and never runs away."""
    spec = PURSUIT.parse_case(_data()).spec
    run = run_pursuit_case(spec, np.random.default_rng(3))
    assert run.completed and run.stop_cause == ""
    assert run.localization_errors[0, 0] > 20  # x̂(0) is 25 m off
    assert run.localization_errors[-1, 0] < 1.5
    assert 2.0 < np.mean(run.pursuit_errors) < 5.0
    speeds = np.linalg.norm(np.diff(run.positions[:, 0], axis=0), axis=1) / published.STEP
    assert speeds.max() <= 2.0 + 1e-9  # v₁ clamped to [0, 2] m/s


def test_simulate_observes_runaways_and_the_banded_statistics() -> None:
    """The expect keys of the published cases are what ``trackcert simulate`` observes: the
    runaway count and, per tracker, the run-mean final localization and mean pursuit errors,
    judged by the ``within`` rule (a 5 s run is far outside the 2-D bands)."""
    case = PURSUIT.parse_case(_data("pursuit-published-2d-n3"))
    runs = [run_pursuit_case(case.spec, np.random.default_rng(seed), 50) for seed in (0, 1)]
    summary = summarize_pursuit(case.spec, runs)
    observed = simulation_observed(summary)
    assert observed.values["runaways"] == 0
    assert len(observed.values["final_localization_error"]) == 3
    verdicts = {e.key: e for e in judge(case, observed, source="trackcert simulate")}
    assert verdicts["runaways"].met
    assert verdicts["final_localization_error"].rule == "within"
    assert not verdicts["final_localization_error"].met  # x̂(0) is 15–25 m off at 5 s


@pytest.mark.parametrize(
    "name",
    [
        "pursuit-published-2d-n1",
        "pursuit-published-2d-n3",
        "pursuit-published-3d-n1",
        "pursuit-published-3d-n3",
    ],
)
def test_the_published_statistics_claim_judges_runaways_and_bands(name: str) -> None:
    """``seed003.sec6.published-statistics`` on each published case: no runaway in 10 runs and
    both bands met, the bands being the range of the authors' scripts under Octave over seeds
    1–10 (benchmarks/seed003_octave_runs.txt, docs/simulation.md); it says nothing about a Table
    case (the analysed laws)."""
    from theory.core.claims import NotApplicable
    from theory.pursuit.simulation import check_published_statistics

    case = PURSUIT.parse_case(_data(name))
    (result,) = check_published_statistics(case, None)
    assert result.status == "verified", result.message
    assert result.evidence["expectations"]["runaways"] == 0 and result.margin > 0
    with pytest.raises(NotApplicable, match="analysed laws"):
        check_published_statistics(PURSUIT.parse_case(_data("pursuit-table1-n1")), None)


def _bands_module():
    """``benchmarks/seed003_bands.py``, the derivation of the bands from the Octave log."""
    path = Path(__file__).resolve().parents[2] / "benchmarks" / "seed003_bands.py"
    spec = importlib.util.spec_from_file_location("seed003_bands", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_published_bands_are_the_range_of_ten_octave_seeds() -> None:
    """Every published case's ``expect`` bands are [min, max] over seeds 1–10 and every tracker
    of the authors' script under Octave (rounded outward to 0.05 m), from the committed log."""
    bands = _bands_module()
    runs = bands.read_log(bands.Path(bands.__file__).with_name("seed003_octave_runs.txt"))
    assert set(runs) == set(bands.CASES)
    for script, seeds in runs.items():
        assert sorted(seeds) == list(range(1, 11)), script
        theirs = np.array([seeds[s] for s in sorted(seeds)])
        expect = read_case_data(resolve_case_path(bands.CASES[script]))["expect"]
        for k, key in enumerate(("final_localization_error", "mean_pursuit_error")):
            assert expect[key] == list(bands.band(theirs[..., k])), (script, key)
