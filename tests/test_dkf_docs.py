"""Every public function of the dkf modules documents each of its parameters (numpydoc)."""

from __future__ import annotations

import importlib
import inspect

import pytest

MODULES = [
    "theory.dkf_case",
    "theory.consensus_operators",
    "theory.s_detectability",
    "theory.dkf_conditions",
    "theory.self_weight",
    "theory.riccati",
    "theory.dkf_claims",
]


def public_functions():
    for name in MODULES:
        module = importlib.import_module(name)
        for attr in module.__all__:
            obj = getattr(module, attr)
            if inspect.isfunction(obj):
                yield f"{name}.{attr}", obj


@pytest.mark.parametrize(("name", "function"), list(public_functions()))
def test_parameters_documented(name, function):
    doc = inspect.getdoc(function) or ""
    assert doc, f"{name} has no docstring"
    params = [p for p in inspect.signature(function).parameters if p not in ("self", "cls")]
    if len(params) <= 1 and "Parameters" not in doc:
        return  # one-argument helpers state their argument in the summary line
    assert "Parameters\n----------" in doc, f"{name} has no Parameters section"
    section = doc.split("Parameters\n----------", 1)[1].split("\n\n")[0]
    documented = set()
    for line in section.splitlines():
        if " : " in line and not line.startswith(" "):
            documented |= {p.strip() for p in line.split(" : ")[0].split(",")}
    missing = [p for p in params if p not in documented]
    assert not missing, f"{name}: undocumented parameters {missing}"


@pytest.mark.parametrize("name", MODULES)
def test_all_names_exist(name):
    module = importlib.import_module(name)
    for attr in module.__all__:
        assert hasattr(module, attr), f"{name}.__all__ lists missing {attr}"
