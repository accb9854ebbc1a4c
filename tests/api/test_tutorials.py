"""The tutorials (``docs/tutorials/*.md``, executed by the documentation build) use only the
documented API: every ``trackcert.<name>`` their code cells mention is public."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import trackcert

TUTORIALS = sorted((Path(__file__).parents[2] / "docs" / "tutorials").glob("*.md"))
CELL = re.compile(r"^```\{code-cell\}[^\n]*\n(.*?)^```", re.S | re.M)


def code(path: Path) -> str:
    return "\n".join(CELL.findall(path.read_text(encoding="utf-8")))


def test_there_is_one_tutorial_per_paper_and_the_6_agent_network() -> None:
    names = {p.stem for p in TUTORIALS}
    assert {
        "network-6-agents",
        "tdoa-topology",
        "consensus-kf",
        "pursuit",
        "particle-filter",
    } <= names


@pytest.mark.parametrize("path", TUTORIALS, ids=[p.stem for p in TUTORIALS])
def test_tutorials_use_only_public_names(path: Path) -> None:
    source = code(path)
    assert source.strip(), f"{path.name} has no code cells"
    public = {*trackcert.__all__, "testing", "strategies", "design"}
    used = set(re.findall(r"\btrackcert\.(\w+)", source))
    assert used and used <= public, f"{path.name}: not public: {sorted(used - public)}"
    assert not re.search(r"^\s*(from|import) theory\b", source, re.M), "imports the library"
