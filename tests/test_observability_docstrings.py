"""STYLE.md Adopt 3 for the observability modules: every public parameter is documented."""

from __future__ import annotations

import importlib
import inspect

import pytest

MODULES = [
    "theory.generic_rank",
    "theory.networked_observability",
    "theory.tdoa_geometry",
    "theory.fig43",
    "theory.observability_claims",
]


def _public_callables():
    for name in MODULES:
        module = importlib.import_module(name)
        for attr in module.__all__:
            obj = getattr(module, attr)
            if inspect.isclass(obj):
                for key, value in vars(obj).items():
                    if callable(value) and not key.startswith("_"):
                        yield f"{name}.{attr}.{key}", value
            elif callable(obj):
                yield f"{name}.{attr}", obj


@pytest.mark.parametrize(("name", "function"), list(_public_callables()))
def test_every_parameter_is_documented(name, function) -> None:
    parameters = [p for p in inspect.signature(function).parameters if p != "self"]
    doc = inspect.getdoc(function) or ""
    assert doc, f"{name} has no docstring"
    if parameters:
        assert "Parameters" in doc, f"{name} lacks a Parameters section"
        missing = [p for p in parameters if f"{p} :" not in doc and f"{p}," not in doc]
        assert not missing, f"{name}: undocumented {missing}"
