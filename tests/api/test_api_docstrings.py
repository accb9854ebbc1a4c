"""The public API is documented where users read it (python-control's rule): every function of
``trackcert``, ``trackcert.testing`` and ``trackcert.design`` has numpydoc ``Parameters`` listing
exactly its signature's parameters (``*args``/``**kwargs`` with their stars) and a ``Returns``
section; every result class and each of its public members has a docstring; and an unknown
keyword argument raises ``TypeError`` instead of being swallowed."""

from __future__ import annotations

import inspect
import re

import pytest
from docstring_sections import documented_parameters, parameters_section

import trackcert
import trackcert.design
import trackcert.testing

MODULES = (trackcert, trackcert.testing, trackcert.design)
DESIGN = ("self_weight", "weights", "gains", "margin", "placement", "redundancy")


def public_functions() -> list[tuple[str, object]]:
    found = [
        (f"{module.__name__}.{name}", getattr(module, name))
        for module in MODULES
        for name in module.__all__
    ]
    return [(n, f) for n, f in found if inspect.isfunction(f)]


def result_members() -> list[tuple[str, object]]:
    classes = [getattr(trackcert, n) for n in trackcert.__all__]
    members = []
    for cls in (c for c in classes if inspect.isclass(c) and issubclass(c, trackcert.Result)):
        for name, member in vars(cls).items():
            if (not name.startswith("_") and callable(member)) or isinstance(member, property):
                members.append((f"{cls.__name__}.{name}", member))
    return members


FUNCTIONS = public_functions()
MEMBERS = result_members()


@pytest.mark.parametrize(("name", "function"), FUNCTIONS, ids=[n for n, _ in FUNCTIONS])
def test_every_parameter_is_documented(name: str, function) -> None:
    assert_documented(name, function)


@pytest.mark.parametrize(("name", "member"), MEMBERS, ids=[n for n, _ in MEMBERS])
def test_every_result_member_is_documented(name: str, member) -> None:
    if isinstance(member, property):
        assert inspect.getdoc(member), f"{name} has no docstring"
    else:
        assert_documented(name, member)


def assert_documented(name: str, function) -> None:
    doc = "\n" + (inspect.getdoc(function) or "")
    assert doc.strip(), f"{name} has no docstring"
    assert re.search(r"\n\s*Returns\n\s*-+\n", doc), f"{name}: no Returns section"
    parameters = [
        p for p in inspect.signature(function).parameters.values() if p.name not in ("self",)
    ]
    if not parameters:
        return
    documented = documented_parameters(doc)
    assert documented is not None, f"{name}: no Parameters section"
    actual = {p.name for p in parameters}
    assert actual == documented, (
        f"{name}: undocumented {sorted(actual - documented)}, "
        f"documented but absent {sorted(documented - actual)}"
    )
    section = parameters_section(doc) or ""
    for p in parameters:
        star = {p.VAR_POSITIONAL: "*", p.VAR_KEYWORD: "**"}.get(p.kind)
        if star:
            label = re.escape(star + p.name)
            assert re.search(rf"(^\s*|,\s*){label}\s*(:|,|$)", section, re.M), (
                f"{name}: list {star}{p.name} with its stars in Parameters"
            )


def test_the_check_catches_an_undocumented_parameter() -> None:
    def offender(alpha: int, beta: int) -> int:
        """Summary.

        Parameters
        ----------
        alpha : int
            A.

        Returns
        -------
        int
        """
        return alpha + beta

    with pytest.raises(AssertionError, match=r"undocumented \['beta'\]"):
        assert_documented("offender", offender)
    offender.__doc__ = "Summary, no sections."
    with pytest.raises(AssertionError, match="no Returns section"):
        assert_documented("offender", offender)


def test_the_whole_surface_is_checked() -> None:
    names = {n for n, _ in FUNCTIONS}
    assert {"trackcert.topology", "trackcert.dkf", "trackcert.iss", "trackcert.simulate",
            "trackcert.pf", "trackcert.certify", "trackcert.check", "trackcert.load_case",
            "trackcert.testing.assert_observable", "trackcert.testing.assert_s_detectable",
            "trackcert.testing.assert_iss"} <= names  # fmt: skip
    assert {f"trackcert.design.{n}" for n in DESIGN} == {n for n in names if ".design." in n}
    assert {"Result.to_json", "Result.to_case", "Certificate.write"} <= {n for n, _ in MEMBERS}


def _placeholders(function) -> list[None]:
    """``None`` for every required positional parameter (the keyword is refused first)."""
    return [
        None
        for p in inspect.signature(function).parameters.values()
        if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) and p.default is p.empty
    ]


@pytest.mark.parametrize(("name", "function"), FUNCTIONS, ids=[n for n, _ in FUNCTIONS])
def test_an_unknown_keyword_raises(name: str, function) -> None:
    with pytest.raises(TypeError, match=r"unexpected keyword|unknown fields"):
        function(*_placeholders(function), no_such_option=1)
