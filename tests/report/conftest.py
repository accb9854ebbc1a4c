"""The ``fakes`` fixture: a claim set that is this process's whole registry for one test."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from theory.core.claims import ClaimSet
from theory.registry import claims_replaced


@pytest.fixture
def fakes() -> Iterator[ClaimSet]:
    """An empty :class:`ClaimSet` replacing the domains' claims in this process for the test
    (the report's in-process tasks and ``trackcert report --workers 1`` see only its claims;
    workers in other processes keep the domains'); the registry is restored when the test ends."""
    claims = ClaimSet()
    with claims_replaced(claims):
        yield claims
