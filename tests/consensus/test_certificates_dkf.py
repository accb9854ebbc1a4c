"""S-detectability certificates from the LMI witness of ``theory.consensus.s_detectability`` (dkf
cases)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from typer.testing import CliRunner

from proofs_check import check_certificate
from theory.cli import app
from theory.consensus.certificates import primal_lyapunov, s_detectability_certificate
from theory.consensus.s_detectability import s_detectability_witness
from theory.core.claims import NotApplicable
from theory.kinds import load_case
from theory.registry import get_claim
from theory.strategies import dkf_problems

runner = CliRunner()


@settings(max_examples=10)
@given(dkf_problems(max_states=3, max_agents=3))
def test_every_verified_lmi_witness_becomes_an_exact_certificate(problem) -> None:
    """Round trip over random systems and networks, agents without measurements included: a
    witness the LMI verified is always rationalized (primal tuple, or the dual as fallback)."""
    witness = s_detectability_witness(problem.A, problem.C, problem.W)
    assume(witness is not None)
    X = primal_lyapunov(problem.A, problem.C, problem.W, witness["gains"], "consensus-then-filter")
    for tuple_, dual in ((X, False), (witness["Y"], True)):
        if tuple_ is None:
            continue
        cert = s_detectability_certificate(
            problem.A,
            problem.C,
            problem.W,
            "consensus-then-filter",
            witness["gains"],
            list(tuple_),
            dual=dual,
        )
        assert check_certificate(json.loads(json.dumps(cert))).valid


def test_agents_without_measurements_get_a_zero_row() -> None:
    A = np.array([[0.5]])
    C = [np.zeros((0, 1)), np.array([[1.0]])]
    W = np.array([[0.5, 0.5], [0.0, 1.0]])
    gains = [np.zeros((1, 0)), np.array([[0.5]])]
    X = primal_lyapunov(A, C, W, gains, "consensus-then-filter")
    cert = s_detectability_certificate(A, C, W, "consensus-then-filter", gains, list(X))
    assert cert["data"]["C"][0] == [["0"]] and cert["witness"]["gains"][0] == [["0"]]
    assert check_certificate(cert).valid


def test_paper_example_1_certified_only_below_the_self_weight_bound(tmp_path: Path) -> None:
    """Seed 000 §5.3.1: W_g (w_ii = 0.24) is certified S-detectable; for W_c (0.25) and W_b
    (0.26) are decided not S-detectable, so nothing is written (exit 1: certify judges no
    expectation; ``trackcert dkf`` decides the same and exits 0 as the cases expect it)."""
    out = tmp_path / "wg.json"
    assert runner.invoke(app, ["certify", "ch5-example-1-wg", "-o", str(out)]).exit_code == 0
    assert runner.invoke(app, ["check", str(out)]).exit_code == 0
    document = json.loads(out.read_text(encoding="utf-8"))
    assert document["certificates"][0]["data"]["W"][0] == ["6/25", "19/25", "0"]
    for name in ("ch5-example-1-wc", "ch5-example-1-wb"):
        bad = tmp_path / f"{name}.json"
        result = runner.invoke(app, ["certify", name, "-o", str(bad)])
        assert result.exit_code == 1
        assert "not S-detectable" in result.stderr and "nothing to certify" in result.stderr
        decided = runner.invoke(app, ["dkf", name, "--json", "--no-self-weight"])
        assert json.loads(decided.stdout)["s_detectable"] is False
        assert decided.exit_code == 0  # the case expects exactly that (docs/cli.md, Exit codes)
        assert not bad.exists()


def test_dkf_certificate_claim_results() -> None:
    claim = get_claim("seed000.def5.2.4.certified")
    good = claim.run(load_case("ch5-example-2-wg"))
    assert [r.status for r in good] == ["verified"]
    assert good[0].method == "exact"
    with pytest.raises(NotApplicable, match="not S-detectable"):
        claim.run(load_case("ch5-example-2-wb"))
