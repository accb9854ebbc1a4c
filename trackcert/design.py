"""Certified design: "what will work?" answered with certificates (``trackcert design …``).

Each answer is the library function the ``trackcert design`` subcommand of the same name calls,
given a case the way every trackcert function takes one (a path, a bundled case name, a mapping
in the case-file format, a :func:`trackcert.load_case` result or a result) and returning a
:class:`trackcert.DesignResult` around the library's frozen answer (``to_json()`` gives the
command's JSON keys, ``certificates`` the documents :func:`trackcert.check` re-verifies).

:data:`ANSWERS` lists them: a new design function is one line there, ``"name":
"theory.<domain>.design:function"``. Its numpydoc docstring is the one users read here.
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable
from typing import Any

ANSWERS: dict[str, str] = {}
"""Design answer name → ``"module:function"`` of the library function it calls."""

__all__ = ["ANSWERS", "answer", *ANSWERS]


def answer(target: str) -> Callable[..., Any]:
    """The public form of the library design function ``target`` (``"module:function"``).

    Parameters
    ----------
    target : str
        ``"theory.<domain>.design:function"``; the function takes a ``Case`` first (or, like
        ``placement``, a plain value), then its options, and returns a frozen answer with
        ``to_json()``.

    Returns
    -------
    callable
        ``f(case, *args, **options) -> DesignResult``, documented by the library function.
    """
    module, name = target.split(":")
    function = getattr(importlib.import_module(module), name)

    @functools.wraps(function)
    def designed(case: Any, *args: Any, **options: Any) -> Any:
        from trackcert import DesignResult, _is_case, _resolve

        if not _is_case(case):  # e.g. placement's number of agents
            return DesignResult(function(case, *args, **options))
        loaded, data = _resolve(case)
        return DesignResult(function(loaded, *args, **options), loaded, data)

    return designed


def __getattr__(name: str) -> Callable[..., Any]:
    """``trackcert.design.<name>`` for every entry of :data:`ANSWERS`, built on first use."""
    if name in ANSWERS:
        return answer(ANSWERS[name])
    raise AttributeError(f"trackcert.design has no answer {name!r}; answers: {sorted(ANSWERS)}")


def __dir__() -> list[str]:
    """The module's names and every design answer."""
    return sorted({*globals(), *ANSWERS})
