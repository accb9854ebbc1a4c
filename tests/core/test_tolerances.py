"""The tolerance table: one entry per named tolerance, each constant its entry's default, and the
values the modules use are the table's (``theory.core.tolerances``)."""

from __future__ import annotations

import numpy as np
import pytest

from theory.core import tolerances
from theory.core.observability import RankResult, numeric_rank
from theory.core.tolerances import TOLERANCES, Tolerance, defaults, table


def test_every_constant_is_its_table_entry() -> None:
    exported = [name for name in tolerances.__all__ if isinstance(getattr(tolerances, name), float)]
    values = {getattr(tolerances, name) for name in exported}
    assert values <= {t.default for t in TOLERANCES.values()}
    by_name = {name: getattr(tolerances, name) for name in exported}
    for t in TOLERANCES.values():
        constant = t.name.upper()
        if constant in by_name:
            assert by_name[constant] == t.default, constant


def test_every_entry_states_unit_meaning_and_why() -> None:
    assert len(TOLERANCES) == len(table()) >= 25
    for row in table():
        assert set(row) == {"name", "default", "unit", "meaning", "why"}
        assert row["default"] > 0 and row["unit"] and row["meaning"] and row["why"]


def test_defaults_names_unknown_tolerances() -> None:
    assert defaults("rank_tol", "inconclusive_factor") == {
        "rank_tol": 1e-9,
        "inconclusive_factor": 1e3,
    }
    with pytest.raises(KeyError, match="rank_tolerance"):
        defaults("rank_tolerance")


def test_the_unified_values() -> None:
    assert TOLERANCES["unit_circle_tol"].default == 1e-6
    assert TOLERANCES["lmi_margin"].default == 1e-8
    assert TOLERANCES["certificate_margin"].default == 1e-9
    assert isinstance(TOLERANCES["rank_tol"], Tolerance)


def test_modules_use_the_table_values() -> None:
    """The domain modules' own names for their tolerances are the table's objects."""
    from theory.consensus import certificates, conditions, properties, s_detectability
    from theory.particle.experiments import DEFAULT_TOLERANCES
    from theory.tdoa.geometry import uniqueness
    from theory.tdoa.observability import network, spectral

    assert s_detectability.LMI_MARGIN == tolerances.LMI_MARGIN
    assert certificates.CERTIFICATE_MARGIN == tolerances.CERTIFICATE_MARGIN
    assert properties.UNIT_CIRCLE_TOL == network.UNIT_CIRCLE_TOL == 1e-6
    assert conditions.VALUE_TOL == tolerances.VALUE_TOL
    assert spectral.CLUSTER_TOL == tolerances.CLUSTER_TOL
    assert uniqueness.UNIQUENESS_TOL == tolerances.UNIQUENESS_TOL
    assert DEFAULT_TOLERANCES == {k: TOLERANCES[k].default for k in DEFAULT_TOLERANCES}


def test_numeric_rank_echoes_the_table_default() -> None:
    result = numeric_rank(np.diag([1.0, 1e-12]))
    assert isinstance(result, RankResult)
    assert result.rank_tol == tolerances.RANK_TOL
    assert result.rank == 1  # 1e-12 < rank_tol · σ_max
    assert result.conclusive() is result.conclusive(tolerances.INCONCLUSIVE_FACTOR)
