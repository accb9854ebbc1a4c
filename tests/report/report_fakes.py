"""Fake claims and case files for the report's tests (registered on the ``fakes`` fixture)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml

from theory.core.claims import ClaimResult, ClaimSet

CASE = {
    "name": "four-path",
    "source": "test: the Fig. 4.3 (d) geometry",
    "kind": "tdoa",
    "tdoa": {
        "T": 1.0,
        "target": [17, -5, -15],
        "agents": [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]],
        "edges": [[1, 2], [2, 3], [3, 4]],
        "weights": "metropolis",
    },
    "expect": {"observable": [True, True, True, True]},
}


def write_case(folder: Path, name: str = "four-path", **changes: object) -> Path:
    """A tdoa case file in ``folder`` (``changes`` replace top-level fields)."""
    data = {**CASE, "name": name, **changes}
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def result(status: str = "verified", **fields) -> ClaimResult:
    """A ClaimResult (the claim id and the case are stamped by ``Claim.run``)."""
    fields.setdefault("method", "numeric")
    return ClaimResult(status=status, **fields)


def register_standard_fakes(fakes: ClaimSet, *, observable=(True, True, True, True), crash=False):
    """Three fake claims: a model claim, a tdoa claim reporting ``observable``, a seeded one."""

    @fakes.register("seed000.fake.model", source="seed 000 eq. (9.9)", statement="model fact")
    def model(case, ctx):
        return [result(evidence={"value": np.float64(1 / 3)})]

    @fakes.register(
        "seed001.fake.observable",
        source="seed 001 Thm 1",
        statement="every agent observes",
        kinds=("tdoa",),
    )
    def observe(case, ctx):
        if crash:
            raise ZeroDivisionError("division by zero in the fake check")
        return [
            result(
                margin=12.5,
                tolerance={"rank_tol": 1e-9},
                evidence={"expectations": {"observable": list(observable)}},
            )
        ]

    @fakes.register(
        "seed003.fake.random", source="seed 003 eq. (4)", statement="seeded", kinds=("tdoa",),
        seeded=True,
    )  # fmt: skip
    def seeded(case, ctx):
        draw = np.random.default_rng(ctx.seed).normal(size=3)
        evidence = {"draw": draw, "probability_bound": 1e-12}
        return [result(method="exact-random", evidence=evidence)]
