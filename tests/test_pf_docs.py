"""Every public function and dataclass of the PF modules documents each of its parameters."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import re

import pytest

MODULES = (
    "theory.dcrw",
    "theory.dcrw_claims",
    "theory.model_learning",
    "theory.particle_filter",
    "theory.pf_case",
    "theory.pf_experiments",
    "theory.pf_figures",
    "theory.pf_motion",
    "theory.pf_vs_ekf",
)


def _public(module_name: str):
    module = importlib.import_module(module_name)
    for name in module.__all__:
        yield f"{module_name}.{name}", getattr(module, name)


@pytest.mark.parametrize("module_name", MODULES)
def test_public_parameters_are_documented(module_name: str):
    missing = []
    for qualified, obj in _public(module_name):
        if inspect.isfunction(obj):
            names = [p for p in inspect.signature(obj).parameters if p not in ("self", "_")]
        elif dataclasses.is_dataclass(obj):
            names = [f.name for f in dataclasses.fields(obj)]
        else:
            continue
        doc = inspect.getdoc(obj) or ""
        if not doc:
            missing.append(f"{qualified}: <no docstring>")
        for name in names:
            if not re.search(rf"\b{re.escape(name)}\b", doc):
                missing.append(f"{qualified}: {name}")
    assert not missing, missing
