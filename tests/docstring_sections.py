"""The numpydoc ``Parameters`` section of a docstring, read the way the docstring tests read it
(``tests/core/test_docstrings.py`` for the library, ``tests/api/test_api_docstrings.py`` for the
public API)."""

from __future__ import annotations

import re


def parameters_section(doc: str) -> str | None:
    match = re.search(
        r"\n\s*Parameters\n\s*-+\n(.*?)(?:\n\s*\n\s*[A-Z][a-z]+\n\s*-+\n|\Z)", doc, re.S
    )
    return match.group(1) if match else None


def documented_parameters(doc: str) -> set[str] | None:
    section = parameters_section(doc)
    if section is None:
        return None
    lines = [line for line in section.splitlines() if line.strip()]
    indent = min(len(line) - len(line.lstrip()) for line in lines) if lines else 0
    names = set()
    for line in lines:
        if len(line) - len(line.lstrip()) == indent:
            head = line.strip().split(":")[0]
            names.update(part.strip().lstrip("*") for part in head.split(","))
    return {n for n in names if n}
