"""Every module of ``theory`` and ``proofs_check`` declares ``__all__``, and every name it lists
exists (STYLE.md: ``__all__`` in each module; the docstring checks walk these lists)."""

from __future__ import annotations

import importlib
import pkgutil

import pytest

import proofs_check
import theory
import theory.sim


def modules() -> list[str]:
    names = ["proofs_check"]
    for package in (theory, proofs_check):
        prefix = f"{package.__name__}."
        names += [
            info.name
            for info in pkgutil.walk_packages(package.__path__, prefix)
            if not info.name.endswith("__main__")
        ]
    return sorted(names)


MODULES = modules()


@pytest.mark.parametrize("name", MODULES)
def test_all_names_exist(name: str) -> None:
    module = importlib.import_module(name)
    is_package = hasattr(module, "__path__")
    exported = getattr(module, "__all__", None)
    assert exported or is_package, f"{name} declares no (or an empty) __all__"
    missing = [attr for attr in exported or () if not hasattr(module, attr)]
    assert not missing, f"{name}.__all__ lists missing {missing}"


def test_modules_include_those_checked_before() -> None:
    """The modules the per-area ``__all__`` tests (certificates, dkf, sim) used to list."""
    earlier = {
        "proofs_check",
        "theory.registry",
        "theory.consensus.certificates",
        "theory.cli.certify",
        "theory.cli.simulate",
        "theory.consensus.operators",
        "theory.consensus.case",
        "theory.consensus.analysis",
        "theory.consensus.conditions",
        "theory.core.exact",
        "theory.consensus.riccati",
        "theory.consensus.s_detectability",
        "theory.tdoa.observability.certificates",
    }
    earlier |= {f"theory.sim.{info.name}" for info in pkgutil.iter_modules(theory.sim.__path__)}
    assert earlier <= set(MODULES), sorted(earlier - set(MODULES))
