"""Generic observability of one agent (seed 000 §4.2.1, eq. (4.20), footnotes 1–2): every minor."""

from __future__ import annotations

import json
from math import comb

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from theory.cli import app
from theory.tdoa.observability.single_agent import (
    exact_rank,
    minor_expansions,
    paper_eq_4_20_determinant,
    random_generic_rank,
    single_agent_generic_rank,
    symbolic_single_agent_matrix,
)


@pytest.mark.parametrize(("dim", "rows"), [(3, 1), (3, 2), (2, 1)])
def test_too_few_rows_make_every_minor_vanish(dim: int, rows: int) -> None:
    result = single_agent_generic_rank(dim, rows)
    assert result.n_minors == comb(2 * dim * rows, 2 * dim)
    assert result.n_nonzero == 0 and not result.generically_full_rank
    assert result.cross_check["all_agree"]
    assert result.random_rank.rank == 2 * rows == result.kronecker_rank


def test_one_row_single_minor_is_det_O_and_vanishes_symbolically() -> None:
    """Footnote 1: with one TDOA row the only minor is det O, identically zero."""
    O, _, _ = symbolic_single_agent_matrix(3, 1)
    assert O.shape == (6, 6)
    assert sp.expand(O.det(method="berkowitz")) == 0


@pytest.mark.parametrize("dim", [2, 3])
def test_d_rows_give_alpha_T_d_det_squared(dim: int) -> None:
    """Eq. (4.20) (and its planar analogue): non-zero minors are α T^d det(Λ)², α closed form."""
    result = single_agent_generic_rank(dim, dim)
    assert result.n_nonzero == comb(2 * dim, 2) ** dim  # each Λ row at two of 2d powers
    assert result.closed_form_alpha
    assert len(result.alphas) == result.n_nonzero and 0 not in result.alpha_counts
    assert result.random_rank.rank == 2 * dim
    if dim == 3:
        assert result.paper_factor_matches


def test_expansions_agree_with_sympy_determinants_of_sampled_minors() -> None:
    """Independent of the Laplace code: sympy determinants of actual rows of O, then factor."""
    expansions = minor_expansions(3, 3)
    O, Lambda, T = symbolic_single_agent_matrix(3, 3)
    rng = np.random.default_rng(7)
    nonzero = np.unique(expansions.minor)
    picks = [*rng.choice(nonzero, 4, replace=False), *rng.choice(expansions.n_minors, 4)]
    det = Lambda.det()
    for index in picks:
        rows = [int(r) for r in expansions.row_sets[index]]
        direct = sp.expand(O.extract(rows, list(range(6))).det(method="berkowitz"))
        assert sp.expand(direct - expansions.polynomial(int(index), Lambda, T)) == 0
        terms = expansions.terms(int(index))
        alpha = terms.get((0, 0), 0)
        assert sp.expand(direct - alpha * T**3 * det**2) == 0


def test_paper_bracket_is_minus_det_lambda() -> None:
    _, Lambda, _ = symbolic_single_agent_matrix(3, 3)
    assert sp.expand(paper_eq_4_20_determinant(Lambda) + Lambda.det()) == 0


@pytest.mark.parametrize(("dim", "rows"), [(2, 3), (2, 4)])
def test_more_rows_full_rank_iff_some_d_minor_nonzero(dim: int, rows: int) -> None:
    """Footnote 2: every d-subset of Λ's rows has a witness minor α T^d M_a² with α ≠ 0."""
    result = single_agent_generic_rank(dim, rows)
    assert len(result.witnesses) == comb(rows, dim)
    assert all(w["alpha"] != 0 for w in result.witnesses.values())
    assert result.generically_full_rank and result.random_rank.rank == 2 * dim


@pytest.mark.slow
def test_four_rows_in_space_footnote_2() -> None:
    result = single_agent_generic_rank(3, 4)
    assert len(result.witnesses) == 4 and result.cross_check["all_agree"]
    assert result.random_rank.rank == 6


@given(
    st.sampled_from([2, 3]),
    st.integers(1, 5),
    st.integers(1, 3),
    st.integers(0, 2**32),
    st.integers(1, 50),
)
def test_rank_O_is_twice_rank_lambda_exactly(dim, rows, inner, seed, T) -> None:
    """O = V_T ⊗ Λ, so rank O = 2·rank Λ for every integer Λ (of any rank) and T ≠ 0."""
    rng = np.random.default_rng(seed)
    inner = min(inner, dim)
    Lambda = rng.integers(-9, 10, (rows, inner)) @ rng.integers(-9, 10, (inner, dim))
    O = [
        [int(x) for x in Lambda[r]] + [j * T * int(x) for x in Lambda[r]]
        for j in range(2 * dim)
        for r in range(rows)
    ]
    assert exact_rank(O) == 2 * exact_rank(Lambda.tolist())
    assert exact_rank(O, field="prime") == exact_rank(O)


@pytest.mark.parametrize("field", ["rationals", "prime"])
def test_random_generic_rank_reports_seed_and_bound(field: str) -> None:
    result = random_generic_rank(3, 3, seed=11, field=field)
    assert result.rank == 6 and result.seed == 11 and result.field == field
    assert result.error_bound == result.degree_bound / result.sample_size < 1e-9


def test_cli_generic_prints_the_derivation_and_json() -> None:
    runner = CliRunner()
    text = runner.invoke(app, ["generic", "--dim", "2"])
    assert text.exit_code == 0 and "det(Λ)²" in text.stdout
    out = runner.invoke(app, ["generic", "--rows", "2", "--json"])
    assert out.exit_code == 0
    data = json.loads(out.stdout)
    assert data["n_nonzero"] == 0 and data["holds"] and data["n_minors"] == 924


def test_cli_generic_rejects_bad_dimension() -> None:
    result = CliRunner().invoke(app, ["generic", "--dim", "4"])
    assert result.exit_code == 2 and "--dim" in result.stderr
