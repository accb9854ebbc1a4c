"""``trackcert.design``: one explicit public function per design question (issue 24: no
"module:function" strings), each returning a ``DesignResult`` whose JSON and certificates are the
command's, agents 0-based in the call like numpy."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

import trackcert
import trackcert.design
from theory.cli import app
from theory.core.errors import CaseError


def test_self_weight_is_exact_on_example_2_and_agrees_with_the_command() -> None:
    result = trackcert.design.self_weight("ch5-example-2-wg", 2)  # agent 3, 0-based
    data = result.to_json()
    assert isinstance(result, trackcert.DesignResult) and result.exit_code == 0
    assert data["agent"] == [3] and data["supremum"]["rational"] == "4000000/11840481"
    assert all(trackcert.check(c).verdict for c in result.certificates)
    cli = CliRunner().invoke(app, ["design", "self-weight", "ch5-example-2-wg", "--agent", "3",
                                   "--json"])  # fmt: skip
    assert cli.exit_code == 0 and '"4000000/11840481"' in cli.stdout


def test_redundancy_answers_dkf_and_refuses_other_kinds() -> None:
    result = trackcert.design.redundancy("ch5-example-1-wg", links=False)
    assert result.to_json()["k"] == 1 and result.exit_code == 0
    with pytest.raises(CaseError, match="tdoa or dkf"):
        trackcert.design.redundancy("pursuit-table1-n3")


def test_every_question_is_an_explicit_function() -> None:
    assert trackcert.design.__all__ == [
        "gains", "margin", "placement", "redundancy", "self_weight", "weights",
    ]  # fmt: skip
    assert not hasattr(trackcert.design, "ANSWERS") and not hasattr(trackcert.design, "answer")
    with pytest.raises(TypeError):
        trackcert.design.self_weight("ch5-example-1-wg", no_such_option=1)


@pytest.mark.parametrize(
    ("name", "args", "options"),
    [
        ("margin", ("fig43-case-a",), {"search": False}),
        ("placement", (4, 30.0), {"starts": 1, "dim": 2}),
        ("gains", ("pursuit-table1-n1",), {"grid": 1, "depth": 0, "max_cells": 1}),
    ],
)
def test_the_other_answers_return_design_results(name: str, args: tuple, options: dict) -> None:
    result = getattr(trackcert.design, name)(*args, **options)
    assert isinstance(result, trackcert.DesignResult) and result.exit_code == 0
    assert all(trackcert.check(c).verdict for c in result.certificates)
