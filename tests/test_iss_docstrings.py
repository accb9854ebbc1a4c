"""Every public function of the seed 003 modules documents each of its parameters (STYLE.md 3)."""

from __future__ import annotations

import importlib
import inspect

import pytest

MODULES = [
    "theory.pursuit_case",
    "theory.pursuit_model",
    "theory.iss",
    "theory.iss_symbolic",
    "theory.iss_counterexamples",
    "theory.iss_claims",
    "theory.cli.iss",
]


def _public_functions():
    for name in MODULES:
        module = importlib.import_module(name)
        for attr in module.__all__:
            obj = getattr(module, attr)
            if inspect.isfunction(obj):
                yield f"{name}.{attr}", obj


@pytest.mark.parametrize(("name", "function"), list(_public_functions()))
def test_public_parameters_are_documented(name: str, function) -> None:
    doc = inspect.getdoc(function) or ""
    assert doc, f"{name} has no docstring"
    for parameter in inspect.signature(function).parameters:
        assert parameter in doc, f"{name}: parameter {parameter!r} is not documented"


@pytest.mark.parametrize("name", MODULES)
def test_all_names_exist(name: str) -> None:
    module = importlib.import_module(name)
    for attr in module.__all__:
        assert hasattr(module, attr)
