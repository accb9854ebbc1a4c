"""Every public function of the topology modules documents each of its parameters (numpydoc)."""

from __future__ import annotations

import importlib
import inspect
import re

import pytest

MODULES = [
    "theory.topology",
    "theory.time_varying",
    "theory.network_spectral_rank",
    "theory.tdoa_uniqueness",
    "theory.topology_claims",
    "theory.cli.topology",
]


def public_functions():
    for name in MODULES:
        module = importlib.import_module(name)
        for attribute in module.__all__:
            value = getattr(module, attribute)
            if inspect.isfunction(value):
                yield f"{name}.{attribute}", value


@pytest.mark.parametrize(("name", "function"), list(public_functions()))
def test_every_parameter_is_documented(name, function) -> None:
    doc = inspect.getdoc(function) or ""
    assert "Parameters\n----------" in doc, f"{name} has no Parameters section"
    section = doc.split("Parameters\n----------", 1)[1]
    for parameter in inspect.signature(function).parameters.values():
        label = ("**" if parameter.kind is parameter.VAR_KEYWORD else "") + parameter.name
        pattern = rf"^{re.escape(label)}( :|$)"
        assert re.search(pattern, section, re.M), f"{name}: parameter {label!r} is not documented"
