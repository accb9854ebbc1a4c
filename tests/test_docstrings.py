"""Every public callable has a docstring that mentions each of its parameters; a numpydoc
``Parameters`` section lists exactly the signature's parameters (STYLE.md, *Adopt* 3)."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
import re

import pytest

import theory

SKIP_PARAMS = {"self", "cls", "draw"}


def public_callables():
    for info in pkgutil.walk_packages(theory.__path__, "theory."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if inspect.isfunction(obj) or inspect.isclass(obj):
                yield f"{info.name}.{name}", obj


def documented_parameters(doc: str) -> set[str] | None:
    match = re.search(
        r"\n\s*Parameters\n\s*-+\n(.*?)(?:\n\s*\n\s*[A-Z][a-z]+\n\s*-+\n|\Z)", doc, re.S
    )
    if not match:
        return None
    lines = [line for line in match.group(1).splitlines() if line.strip()]
    indent = min(len(line) - len(line.lstrip()) for line in lines) if lines else 0
    names = set()
    for line in lines:
        if len(line) - len(line.lstrip()) == indent:
            head = line.strip().split(":")[0]
            names.update(part.strip().lstrip("*") for part in head.split(","))
    return {n for n in names if n}


CALLABLES = sorted(public_callables(), key=lambda item: item[0])
METHODS = sorted(
    (
        (f"{name}.{key}", value)
        for name, obj in CALLABLES
        if inspect.isclass(obj)
        for key, value in vars(obj).items()
        if inspect.isfunction(value) and not key.startswith("_")
    ),
    key=lambda item: item[0],
)
DATACLASSES = [(n, obj) for n, obj in CALLABLES if dataclasses.is_dataclass(obj)]


@pytest.mark.parametrize(("name", "method"), METHODS, ids=[n for n, _ in METHODS])
def test_public_method_mentions_its_parameters(name: str, method) -> None:
    doc = inspect.getdoc(method)
    assert doc, f"{name} has no docstring"
    for parameter in inspect.signature(method).parameters:
        if parameter not in SKIP_PARAMS:
            assert re.search(rf"\b{re.escape(parameter)}\b", doc), (
                f"{name}: parameter {parameter!r} is not mentioned in the docstring"
            )


@pytest.mark.parametrize(("name", "cls"), DATACLASSES, ids=[n for n, _ in DATACLASSES])
def test_public_dataclass_documents_its_fields(name: str, cls) -> None:
    doc = inspect.getdoc(cls) or ""
    missing = [
        f.name for f in dataclasses.fields(cls) if not re.search(rf"\b{re.escape(f.name)}\b", doc)
    ]
    assert not missing, f"{name}: fields {missing} are not documented"


@pytest.mark.parametrize(("name", "obj"), CALLABLES, ids=[n for n, _ in CALLABLES])
def test_public_callable_is_documented(name: str, obj) -> None:
    doc = inspect.getdoc(obj)
    assert doc, f"{name} has no docstring"
    target = obj.__init__ if inspect.isclass(obj) else obj
    if not inspect.isclass(obj):
        for parameter in inspect.signature(obj).parameters:
            if parameter not in SKIP_PARAMS:
                assert re.search(rf"\b{re.escape(parameter)}\b", doc), (
                    f"{name}: parameter {parameter!r} is not mentioned in the docstring"
                )
    documented = documented_parameters("\n" + doc)
    if documented is None:
        return
    try:
        signature = inspect.signature(getattr(obj, "__wrapped__", target))
    except (TypeError, ValueError):
        return
    actual = {p for p in signature.parameters if p not in SKIP_PARAMS}
    assert actual <= documented, f"{name}: undocumented parameters {sorted(actual - documented)}"
    if not inspect.isclass(obj):
        assert documented <= actual, (
            f"{name}: documents missing parameters {sorted(documented - actual)}"
        )


def test_parser_reads_numpydoc_parameters() -> None:
    doc = """Summary.

    Parameters
    ----------
    alpha : float
        Text mentioning beta : not a parameter.
    gamma, delta : int
        Two at once.

    Returns
    -------
    float
    """
    assert documented_parameters("\n" + inspect.cleandoc(doc)) == {"alpha", "gamma", "delta"}


def test_checked_functions_really_have_parameter_sections() -> None:
    checked = [
        n for n, obj in CALLABLES if documented_parameters("\n" + (inspect.getdoc(obj) or ""))
    ]
    assert "theory.observability.numeric_rank" in checked
    assert "theory.validation.row_stochastic" in checked
