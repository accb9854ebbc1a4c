"""Modules found by their file names: claims, properties, case kinds, case certificates.

A module of a domain package of :mod:`theory` (every subpackage but the engine packages of
:data:`SKIPPED_PACKAGES`) plays a *role* when its file name says so (:data:`ROLES`):
``claims.py`` or ``*_claims.py`` registers claims (:mod:`theory.core.claims`),
``properties.py`` or ``*_properties.py`` falsifiable properties (:mod:`theory.falsify`),
``case.py`` or ``*_case.py`` a case kind (:mod:`theory.core.case_file`), ``certificates.py`` or
``*_certificates.py`` case certificates (:mod:`theory.certify`). Nothing keeps a list by hand.

The package directories are walked with :mod:`pkgutil` without importing anything, so finding
the modules is cheap; importing them is left to the registry that needs them. Case kinds are
indexed by reading their modules' source (:func:`kind_index`), so loading a case imports the
module of its own kind only (``trackcert topology`` never imports the particle filter).
"""

from __future__ import annotations

import ast
import functools
import pkgutil
from pathlib import Path

import theory

__all__ = ["ROLES", "SKIPPED_PACKAGES", "domain_packages", "kind_index", "role_modules"]

ROLES = ("claims", "properties", "case", "certificates")
"""Roles a module plays by its file name: ``<role>.py`` or ``*_<role>.py``."""

SKIPPED_PACKAGES = ("cli", "core")
"""Subpackages never searched: the command line (the library never imports it) and the core
(it holds the registries, not their entries)."""


def domain_packages() -> tuple[str, ...]:
    """The subpackages of :mod:`theory` searched for role modules, sorted, not imported.

    Returns
    -------
    tuple of str
        Dotted names, e.g. ``("theory.consensus", "theory.particle", …)``.
    """
    return tuple(
        f"theory.{info.name}"
        for info in sorted(pkgutil.iter_modules(theory.__path__), key=lambda i: i.name)
        if info.ispkg and info.name not in SKIPPED_PACKAGES
    )


@functools.cache
def role_modules(role: str) -> tuple[str, ...]:
    """The modules of the domain packages whose file name names ``role``, sorted.

    Parameters
    ----------
    role : str
        One of :data:`ROLES`.

    Returns
    -------
    tuple of str
        Dotted module names (nothing is imported).

    Raises
    ------
    ValueError
        If ``role`` is not one of :data:`ROLES`.
    """
    if role not in ROLES:
        raise ValueError(f"role {role!r} is not one of {ROLES}")
    found = []
    for package in domain_packages():
        folders = [str(Path(p) / package.rpartition(".")[2]) for p in theory.__path__]
        for info in pkgutil.iter_modules(folders):
            if not info.ispkg and (info.name == role or info.name.endswith(f"_{role}")):
                found.append(f"{package}.{info.name}")
    return tuple(sorted(found))


@functools.cache
def kind_index() -> dict[str, str]:
    """Case kind → the module registering it, read from the case modules' source (no import).

    A case module registers its kind by a top-level ``register_kind(KIND, …)`` call whose first
    argument is a string literal or a module-level name bound to one.

    Returns
    -------
    dict
        Sorted by kind, e.g. ``{"dkf": "theory.consensus.case", …}``.

    Raises
    ------
    ValueError
        If two modules register one kind, or a ``register_kind`` call names its kind otherwise.
    """
    index: dict[str, str] = {}
    for module in role_modules("case"):
        for kind in _registered_kinds(_source(module), module):
            if kind in index:
                raise ValueError(f"kind {kind!r} registered by {index[kind]} and {module}")
            index[kind] = module
    return dict(sorted(index.items()))


def _source(module: str) -> str:
    relative = Path(*module.split(".")[1:]).with_suffix(".py")
    for root in theory.__path__:
        path = Path(root) / relative
        if path.is_file():
            return path.read_text(encoding="utf-8")
    raise ValueError(f"no source file for {module}")


def _registered_kinds(source: str, module: str) -> list[str]:
    tree = ast.parse(source, filename=module)
    constants = {
        target.id: node.value.value
        for node in tree.body
        if isinstance(node, ast.Assign)
        and isinstance(node.value, ast.Constant)
        and isinstance(node.value.value, str)
        for target in node.targets
        if isinstance(target, ast.Name)
    }
    kinds = []
    for node in tree.body:
        call = node.value if isinstance(node, ast.Expr) else None
        if not (isinstance(call, ast.Call) and getattr(call.func, "id", "") == "register_kind"):
            continue
        first = call.args[0] if call.args else None
        if isinstance(first, ast.Constant) and isinstance(first.value, str):
            kinds.append(first.value)
        elif isinstance(first, ast.Name) and first.id in constants:
            kinds.append(constants[first.id])
        else:
            raise ValueError(f"{module}: register_kind must name its kind by a string constant")
    return kinds
