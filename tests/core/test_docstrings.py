"""Every callable a module exports has a docstring; where it has a numpydoc ``Parameters``
section, the section lists exactly the signature's parameters (no stale documentation).

"Exports" means listed in the ``__all__`` of a module under ``theory/`` (every module is walked;
``tests/core/test_exports.py`` makes every module declare one). Docstrings are in proportion:
one line citing the paper's equation is enough inside the library; the user-facing API carries
numpydoc sections, checked where it is defined. ``*args`` and ``**kwargs`` in a ``Parameters``
section are listed with their stars.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from pathlib import Path

import pytest
from docstring_sections import documented_parameters, parameters_section

import theory

SKIP_PARAMS = {"self", "cls", "draw"}


def theory_modules() -> list[str]:
    """Every module under ``theory/`` except ``__main__`` scripts (importing one runs the CLI)."""
    return [
        info.name
        for info in pkgutil.walk_packages(theory.__path__, "theory.")
        if not info.name.endswith("__main__")
    ]


def public_callables():
    for module_name in theory_modules():
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if inspect.isfunction(obj) or inspect.isclass(obj):
                yield f"{module_name}.{name}", obj


CALLABLES = sorted(public_callables(), key=lambda item: item[0])


def _own_parameters(function) -> list[inspect.Parameter]:
    signature = inspect.signature(function)
    return [p for p in signature.parameters.values() if p.name not in SKIP_PARAMS]


@pytest.mark.parametrize(("name", "obj"), CALLABLES, ids=[n for n, _ in CALLABLES])
def test_public_callable_is_documented(name: str, obj) -> None:
    doc = inspect.getdoc(obj)
    assert doc, f"{name} has no docstring"
    target = obj.__init__ if inspect.isclass(obj) else obj
    parameters = [] if inspect.isclass(obj) else _own_parameters(obj)
    documented = documented_parameters("\n" + doc)
    if documented is None:
        return
    section = parameters_section("\n" + doc) or ""
    for parameter in parameters:
        star = {parameter.VAR_POSITIONAL: "*", parameter.VAR_KEYWORD: "**"}.get(parameter.kind)
        if star:
            label = re.escape(star + parameter.name)
            assert re.search(rf"(^\s*|,\s*){label}\s*(:|,|$)", section, re.M), (
                f"{name}: list {star}{parameter.name} with its stars in Parameters"
            )
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
    assert "theory.core.observability.numeric_rank" in checked
    assert "theory.core.validation.row_stochastic" in checked


def test_walk_reaches_every_module() -> None:
    root = Path(theory.__file__).parent
    on_disk = {
        ".".join(("theory", *path.relative_to(root).with_suffix("").parts)).removesuffix(
            ".__init__"
        )
        for path in root.rglob("*.py")
        if path.name != "__main__.py"
    } - {"theory"}
    walked = set(theory_modules())
    assert on_disk == walked
    assert {"theory.pursuit.simulation", "theory.cli.simulate", "theory.cli.common"} <= walked


def test_parameters_rules_catch_offenders() -> None:
    def offender(alpha: int, *rest: int, **options: int) -> None:
        """Summary naming alpha, rest and options.

        Parameters
        ----------
        alpha : int
            A.
        rest, options : int
            Listed without their stars.
        """

    doc = "\n" + inspect.getdoc(offender)
    assert documented_parameters(doc) == {"alpha", "rest", "options"}
    with pytest.raises(AssertionError, match="with its stars"):
        test_public_callable_is_documented("offender", offender)
    offender.__doc__ = "Summary naming alpha, rest and options."
    test_public_callable_is_documented("offender", offender)  # one line is enough
    offender.__doc__ = ""
    with pytest.raises(AssertionError, match="no docstring"):
        test_public_callable_is_documented("offender", offender)
