"""Every public function of the simulation modules documents each of its parameters (STYLE.md 3)."""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import theory.sim

MODULES = [f"theory.sim.{info.name}" for info in pkgutil.iter_modules(theory.sim.__path__)] + [
    "theory.cli.simulate"
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
    assert module.__all__
    for attr in module.__all__:
        assert hasattr(module, attr)
