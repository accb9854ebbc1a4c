"""Generic observability of one agent with TDOA rows: every minor of O, exactly (seed 000 §4.2.1).

With ``k`` TDOA rows the measurement matrix has the structure ``H_λ = [Λ 0]`` with ``Λ`` a
``k × d`` matrix of free symbols (eqs. 4.17, 4.19; ``d = 3``, or 2 in the plane) and the
constant-velocity model ``A^j = [[I, jT I], [0, I]]`` (eq. 4.6). Hence ``H_λ A^j = [Λ, jTΛ]`` and

.. math:: O = [H_λ; H_λ A; …; H_λ A^{2d-1}] = V_T ⊗ Λ,\\qquad V_T = [1\\ \\ jT]_{j=0}^{2d-1},

so ``rank O = rank V_T · rank Λ = 2 rank Λ`` whenever ``T ≠ 0``. The minors are computed by the
generalized Laplace expansion along the ``d`` velocity columns: a ``2d × 2d`` minor with rows
``(j_1, r_1), …, (j_{2d}, r_{2d})`` (power ``j``, row ``r`` of ``Λ``) equals

.. math:: T^d \\sum_{S} ±\\Big(\\prod_{s∈S} j_s\\Big) \\det Λ[r_S]\\, \\det Λ[r_{\\bar S}],

a quadratic form in the ``d × d`` minors ``M_a`` of ``Λ`` with integer coefficients. Enumerating
all ``C(2dk, 2d)`` minors therefore needs integer arithmetic only (vectorised with numpy), and each
expansion is cross-checked against the exact determinant of the same rows of ``O`` at a random
integer point (python-flint). This reproduces eq. (4.20) with every ``α`` and footnote 2.

Exact generic rank at random points (:func:`random_generic_rank`, :func:`exact_rank`) states its
Schwartz–Zippel bound ``degree / sample size`` and the seed.
"""

from __future__ import annotations

import itertools
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from math import comb, prod

import flint
import numpy as np
import sympy as sp

from theory.tdoa.model import cv_discrete_symbolic

__all__ = [
    "MERSENNE_PRIME",
    "MinorExpansions",
    "RandomRank",
    "SingleAgentGenericRank",
    "derivation_markdown",
    "exact_rank",
    "minor_expansions",
    "paper_eq_4_20_determinant",
    "random_generic_rank",
    "single_agent_generic_rank",
    "symbolic_single_agent_matrix",
]

MERSENNE_PRIME = 2**61 - 1
"""Default modulus for rank over a prime field (``nmod_mat``)."""

SAMPLE_BITS = 40
"""Default random integers are drawn uniformly from ``[0, 2**SAMPLE_BITS)``."""


def symbolic_single_agent_matrix(
    dim: int = 3, rows: int = 3
) -> tuple[sp.Matrix, sp.Matrix, sp.Symbol]:
    """``O = [H_λ; H_λ A; …; H_λ A^{2d−1}]`` of seed 000 eq. (4.18) with symbolic ``λ`` and ``T``.

    Parameters
    ----------
    dim : int
        2 or 3 (position dimension ``d``; ``n = 2d`` states).
    rows : int
        Number ``k ≥ 1`` of TDOA rows.

    Returns
    -------
    O : sympy.Matrix, shape (2d·k, 2d)
        Row ``j·k + r`` is row ``r`` of ``H_λ A^j``.
    Lambda : sympy.Matrix, shape (k, d)
        ``λ_1, …, λ_{kd}`` row by row (eqs. 4.17, 4.19).
    T : sympy.Symbol

    References
    ----------
    seed 000, eqs. (4.6), (4.17)–(4.19).
    """
    _check_dims(dim, rows)
    T = sp.Symbol("T")
    symbols = sp.symbols(f"lambda1:{rows * dim + 1}")
    Lambda = sp.Matrix(rows, dim, symbols)
    H = Lambda.row_join(sp.zeros(rows, dim))
    A = cv_discrete_symbolic(T, dim)
    blocks, power = [], sp.eye(2 * dim)
    for _ in range(2 * dim):
        blocks.append(H * power)
        power = power * A
    return sp.Matrix.vstack(*blocks), Lambda, T


def paper_eq_4_20_determinant(Lambda: sp.Matrix) -> sp.Expr:
    """The bracket printed in seed 000 eq. (4.20) (its square is the paper's factor).

    Parameters
    ----------
    Lambda : sympy.Matrix, shape (3, 3)
        ``λ_1, …, λ_9`` row by row (eq. 4.19).

    Returns
    -------
    sympy.Expr
        Equal to ``−det Λ``.
    """
    l1, l2, l3, l4, l5, l6, l7, l8, l9 = list(Lambda)
    return l3 * (l5 * l7 - l4 * l8) + l2 * (l4 * l9 - l6 * l7) + l1 * (l6 * l8 - l5 * l9)


@dataclass(frozen=True)
class MinorExpansions:
    """Every ``2d × 2d`` minor of ``O`` as ``T^d Σ c_ab M_a M_b`` (integer ``c``).

    Attributes
    ----------
    dim, rows : int
        ``d`` and ``k``.
    subsets : tuple of tuple of int
        The ``d``-subsets ``a`` of ``Λ``'s rows (0-based), indexing the minors ``M_a``.
    row_sets : ndarray, shape (n_minors, 2d)
        Rows of ``O`` (0-based, row ``j·k + r``) of each minor, in lexicographic order.
    minor : ndarray of int
        For each non-zero coefficient: the index into ``row_sets``.
    pair : ndarray of int, shape (m, 2)
        For each non-zero coefficient: ``(a, b)`` with ``a ≤ b`` indexing ``subsets``.
    coeff : ndarray of int
        The coefficients ``c_ab``.
    """

    dim: int
    rows: int
    subsets: tuple[tuple[int, ...], ...]
    row_sets: np.ndarray
    minor: np.ndarray
    pair: np.ndarray
    coeff: np.ndarray

    @property
    def n_minors(self) -> int:
        """``C(2dk, 2d)``."""
        return int(self.row_sets.shape[0])

    def terms(self, index: int) -> dict[tuple[int, int], int]:
        """``{(a, b): c_ab}`` of minor ``index``.

        Parameters
        ----------
        index : int
            Index into ``row_sets``.

        Returns
        -------
        dict
        """
        lo, hi = np.searchsorted(self.minor, [index, index + 1])
        return {
            (int(a), int(b)): int(c)
            for (a, b), c in zip(self.pair[lo:hi], self.coeff[lo:hi], strict=True)
        }

    def polynomial(self, index: int, Lambda: sp.Matrix, T: sp.Symbol) -> sp.Expr:
        """Minor ``index`` as a sympy expression ``T^d Σ c_ab M_a M_b``.

        Parameters
        ----------
        index : int
            Index into ``row_sets``.
        Lambda : sympy.Matrix, shape (k, d)
            The symbolic ``Λ`` (see :func:`symbolic_single_agent_matrix`).
        T : sympy.Symbol
            The sampling period.

        Returns
        -------
        sympy.Expr
        """
        minors = [Lambda.extract(list(s), list(range(self.dim))).det() for s in self.subsets]
        return T**self.dim * sum(
            (c * minors[a] * minors[b] for (a, b), c in self.terms(index).items()), sp.S.Zero
        )

    def evaluate(self, index_minors: np.ndarray, Lambda: np.ndarray, T: int) -> list[int]:
        """Exact integer values of the minors ``index_minors`` at integer ``Λ`` and ``T``.

        Parameters
        ----------
        index_minors : ndarray of int
            Indices into ``row_sets`` (distinct).
        Lambda : ndarray of int (object dtype allowed), shape (k, d)
            The point.
        T : int
            The sampling period at the point.

        Returns
        -------
        list of int
            In the order of ``index_minors``.
        """
        m = [int(flint.fmpz_mat(Lambda[list(s)].tolist()).det()) for s in self.subsets]
        values = dict.fromkeys(int(i) for i in index_minors)
        sums = dict.fromkeys(values, 0)
        for idx, (a, b), c in zip(self.minor, self.pair, self.coeff, strict=True):
            if int(idx) in sums:
                sums[int(idx)] += int(c) * m[a] * m[b]
        return [T**self.dim * sums[i] for i in values]


def minor_expansions(dim: int = 3, rows: int = 3, *, chunk: int = 200_000) -> MinorExpansions:
    """Enumerate every ``2d × 2d`` minor of ``O`` by the generalized Laplace expansion.

    Parameters
    ----------
    dim : int
        2 or 3.
    rows : int
        Number ``k`` of TDOA rows.
    chunk : int
        Minors processed per vectorised batch (memory bound).

    Returns
    -------
    MinorExpansions

    References
    ----------
    seed 000, §4.2.1, eqs. (4.18)–(4.20) and footnotes 1–2.
    """
    _check_dims(dim, rows)
    n, k = 2 * dim, rows
    subsets = tuple(itertools.combinations(range(k), dim))
    lookup = np.full(k**dim, -1, dtype=np.int64)
    for index, subset in enumerate(subsets):
        lookup[sum(r * k**t for t, r in enumerate(subset))] = index
    splits = list(itertools.combinations(range(n), dim))
    velocity_cols = sum(range(dim, n))
    row_sets = np.fromiter(
        itertools.chain.from_iterable(itertools.combinations(range(n * k), n)),
        dtype=np.int64,
        count=comb(n * k, n) * n,
    ).reshape(-1, n)
    size = max(len(subsets), 1)
    parts = []
    for start in range(0, row_sets.shape[0], chunk):
        block = row_sets[start : start + chunk]
        parts.append(_expand_block(block, start, k, dim, splits, velocity_cols, lookup, size))
    minor, pair_code, coeff = (np.concatenate(p) for p in zip(*parts, strict=True))
    key = minor * size * size + pair_code
    unique, inverse = np.unique(key, return_inverse=True)
    sums = np.zeros(unique.shape[0], dtype=np.int64)
    np.add.at(sums, inverse, coeff)
    keep = sums != 0
    unique, sums = unique[keep], sums[keep]
    minor_idx, code = np.divmod(unique, size * size)
    pair = np.stack(np.divmod(code, size), axis=1)
    return MinorExpansions(dim, rows, subsets, row_sets, minor_idx, pair, sums)


def _expand_block(
    block: np.ndarray,
    start: int,
    k: int,
    dim: int,
    splits: Sequence[tuple[int, ...]],
    velocity_cols: int,
    lookup: np.ndarray,
    size: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n = 2 * dim
    powers, lam_rows = np.divmod(block, k)
    index = np.arange(start, start + block.shape[0])
    out_minor, out_pair, out_coeff = [], [], []
    for split in splits:
        rest = [p for p in range(n) if p not in split]
        laplace = -1 if (sum(split) + velocity_cols) % 2 else 1
        r_vel, r_pos = lam_rows[:, list(split)], lam_rows[:, rest]
        sign = laplace * _perm_sign(r_vel) * _perm_sign(r_pos)
        coeff = sign * np.prod(powers[:, list(split)], axis=1)
        alive = coeff != 0
        if not alive.any():
            continue
        a = lookup[_code(np.sort(r_vel[alive], axis=1), k)]
        b = lookup[_code(np.sort(r_pos[alive], axis=1), k)]
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        out_minor.append(index[alive])
        out_pair.append(lo * size + hi)
        out_coeff.append(coeff[alive])
    empty = np.zeros(0, dtype=np.int64)
    if not out_minor:
        return empty, empty, empty
    return np.concatenate(out_minor), np.concatenate(out_pair), np.concatenate(out_coeff)


def _perm_sign(r: np.ndarray) -> np.ndarray:
    """Sign of the permutation sorting each row (0 if a value repeats)."""
    sign = np.ones(r.shape[0], dtype=np.int64)
    for i, j in itertools.combinations(range(r.shape[1]), 2):
        sign *= np.sign(r[:, j] - r[:, i])
    return sign


def _code(sorted_rows: np.ndarray, k: int) -> np.ndarray:
    return (sorted_rows * (k ** np.arange(sorted_rows.shape[1]))).sum(axis=1)


@dataclass(frozen=True)
class RandomRank:
    """An exact rank at a random point, with its Schwartz–Zippel bound.

    Attributes
    ----------
    rank : int
        Exact rank of the matrix at the point (a lower bound on the generic rank, always).
    n_columns : int
        Number of columns.
    field : str
        ``"rationals"`` (``fmpz_mat``) or ``"prime"`` (``nmod_mat`` modulo ``modulus``).
    modulus : int or None
        The prime, for ``field="prime"``.
    seed : int
        Seed of the ``numpy.random.Generator`` that drew the point.
    sample_size : int
        Each free parameter was drawn uniformly from a set of this size.
    degree_bound : int
        Degree bound ``D`` of any minor of the size of the generic rank.
    error_bound : float
        ``D / sample_size``: the probability that the generic rank exceeds ``rank`` (i.e. that a
        verdict "rank-deficient" is wrong). Over a prime field this holds for the minors reduced
        modulo the prime.
    """

    rank: int
    n_columns: int
    field: str
    modulus: int | None
    seed: int
    sample_size: int
    degree_bound: int
    error_bound: float


def exact_rank(
    matrix: Sequence[Sequence[int | Fraction]],
    *,
    field: str = "rationals",
    modulus: int = MERSENNE_PRIME,
) -> int:
    """Exact rank of an integer or rational matrix (python-flint).

    Parameters
    ----------
    matrix : sequence of sequences of int or Fraction
        The matrix, row by row.
    field : {"rationals", "prime"}
        Rank over ℚ (``fmpq_mat``) or over ``GF(modulus)`` (``nmod_mat``).
    modulus : int
        The prime for ``field="prime"``.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        For an unknown field, or a denominator divisible by ``modulus``.
    """
    rows = [list(r) for r in matrix]
    if not rows or not rows[0]:
        return 0
    if field == "rationals":
        q = flint.fmpq_mat(len(rows), len(rows[0]), [_fmpq(x) for r in rows for x in r])
        return int(q.rref()[1])
    if field == "prime":
        entries = []
        for x in (Fraction(x) for r in rows for x in r):
            if x.denominator % modulus == 0:
                raise ValueError(f"denominator {x.denominator} vanishes modulo {modulus}")
            entries.append(x.numerator * pow(x.denominator, -1, modulus) % modulus)
        return int(flint.nmod_mat(len(rows), len(rows[0]), entries, modulus).rank())
    raise ValueError(f"field must be 'rationals' or 'prime'; got {field!r}")


def _fmpq(x: int | Fraction) -> flint.fmpq:
    x = Fraction(x)
    return flint.fmpq(x.numerator, x.denominator)


def random_generic_rank(
    dim: int = 3,
    rows: int = 3,
    *,
    seed: int = 0,
    field: str = "rationals",
    sample_bits: int = SAMPLE_BITS,
    modulus: int = MERSENNE_PRIME,
) -> RandomRank:
    """Generic rank of the single-agent ``O`` from one random point, exactly.

    ``λ`` and ``T`` are drawn uniformly from ``[0, 2**sample_bits)`` (below ``modulus`` over a
    prime field). Each ``2d × 2d`` minor has total degree ≤ ``3d`` (``d`` columns of degree 1 in
    ``λ`` and ``d`` of degree 2 in ``(λ, T)``), so by Schwartz–Zippel the rank found is the generic
    rank except with probability ≤ ``3d / 2**sample_bits``.

    Parameters
    ----------
    dim : int
        2 or 3.
    rows : int
        Number of TDOA rows ``k``.
    seed : int
        Seed for ``numpy.random.default_rng``.
    field : {"rationals", "prime"}
        Exact rank over ℚ or over ``GF(modulus)``.
    sample_bits : int
        Size of the sample set, ``2**sample_bits``.
    modulus : int
        The prime for ``field="prime"``.

    Returns
    -------
    RandomRank

    References
    ----------
    seed 000, §4.2.1; Schwartz (1980), Zippel (1979).
    """
    _check_dims(dim, rows)
    sample = min(2**sample_bits, modulus) if field == "prime" else 2**sample_bits
    rng = np.random.default_rng(seed)
    values = _draw(rng, rows * dim + 1, sample)
    O, Lambda, T = symbolic_single_agent_matrix(dim, rows)
    point = dict(zip([*Lambda, T], values, strict=True))
    numeric = [[int(entry.subs(point)) for entry in O.row(i)] for i in range(O.rows)]
    rank = exact_rank(numeric, field=field, modulus=modulus)
    degree = 3 * dim
    return RandomRank(
        rank,
        2 * dim,
        field,
        modulus if field == "prime" else None,
        seed,
        sample,
        degree,
        degree / sample,
    )


def _draw(rng: np.random.Generator, count: int, sample: int) -> list[int]:
    """``count`` integers uniform on ``[0, sample)`` (via 32-bit limbs, any ``sample``)."""
    out = []
    limbs = max(1, (sample - 1).bit_length() // 32 + 1)
    for _ in range(count):
        value = 0
        for _ in range(limbs):
            value = (value << 32) | int(rng.integers(0, 2**32))
        out.append(value % sample)
    return out


@dataclass(frozen=True)
class SingleAgentGenericRank:
    """Everything §4.2.1 claims about one agent, reproduced exactly.

    Attributes
    ----------
    dim, rows, n_states : int
        ``d``, ``k`` and ``n = 2d``.
    n_minors : int
        ``C(2dk, 2d)``: every ``n × n`` minor of ``O``.
    n_nonzero : int
        Minors that are not identically zero.
    generically_full_rank : bool
        Whether some minor is a non-zero polynomial (``k ≥ d``).
    alphas : list of tuple
        For ``k = d``: ``(rows of O (1-based), α)`` of every non-zero minor ``α T^d det(Λ)²``.
    alpha_counts : dict
        How often each ``α`` occurs (``k = d``).
    closed_form_alpha : bool
        Whether every ``α`` equals ``± Π_r (j_{r,2} − j_{r,1})`` (each row of ``Λ`` used at two
        powers ``j``), and every other minor vanishes (``k = d``).
    witnesses : dict
        For each ``d``-subset ``a`` of ``Λ``'s rows (1-based, as a string): a minor equal to
        ``α T^d M_a²`` (rows and ``α``): with footnote 2's ``⇔`` this shows ``rank O = n`` iff
        some ``M_a ≠ 0``, i.e. ``rank Λ ≥ d`` (``k ≥ d``).
    paper_factor_matches : bool
        ``(eq. 4.20's bracket)² = det(Λ)²`` (``d = k = 3`` only; ``None`` otherwise).
    cross_check : dict
        Every expansion compared with the exact determinant of the same rows of ``O`` at a random
        integer point: seed, sample size, number compared, all agree, Schwartz–Zippel bound.
    random_rank : RandomRank
        Generic rank of ``O`` by random evaluation.
    kronecker_rank : int
        ``2·min(k, d)``: the generic rank from ``O = V_T ⊗ Λ``.
    """

    dim: int
    rows: int
    n_states: int
    n_minors: int
    n_nonzero: int
    generically_full_rank: bool
    alphas: list[tuple[tuple[int, ...], int]]
    alpha_counts: dict[int, int]
    closed_form_alpha: bool | None
    witnesses: dict[str, dict]
    paper_factor_matches: bool | None
    cross_check: dict
    random_rank: RandomRank
    kronecker_rank: int

    def to_json(self) -> dict:
        """JSON-ready summary (``alphas`` included)."""
        data = dict(self.__dict__)
        data["random_rank"] = dict(self.random_rank.__dict__)
        data["alpha_counts"] = {str(a): c for a, c in sorted(self.alpha_counts.items())}
        data["alphas"] = [{"rows": list(r), "alpha": a} for r, a in self.alphas]
        return data

    def markdown(self) -> str:
        """The readable derivation (see :func:`derivation_markdown`)."""
        return derivation_markdown(self)


def single_agent_generic_rank(
    dim: int = 3,
    rows: int = 3,
    *,
    seed: int = 0,
    sample_bits: int = 62,
    cross_check_limit: int = 200_000,
    field: str = "rationals",
) -> SingleAgentGenericRank:
    """Reproduce seed 000 §4.2.1: all minors of ``O`` for ``k`` TDOA rows, exactly.

    Parameters
    ----------
    dim : int
        2 or 3.
    rows : int
        Number of TDOA rows ``k`` (1, 2: all minors vanish in 3D; 3: eq. (4.20); > 3: footnote 2).
    seed : int
        Seed of the random points (cross-check and random rank).
    sample_bits : int
        Random integers are drawn from ``[0, 2**sample_bits)``.
    cross_check_limit : int
        At most this many minors are cross-checked (a seeded random sample beyond it).
    field : {"rationals", "prime"}
        Field of the random generic-rank evaluation.

    Returns
    -------
    SingleAgentGenericRank

    References
    ----------
    seed 000, eqs. (4.17)–(4.20), footnotes 1–2; seed 001 (same result).
    """
    expansions = minor_expansions(dim, rows)
    nonzero = _nonzero_minors(expansions, seed=seed)
    alphas, counts, closed = _alphas(expansions) if rows == dim else ([], {}, None)
    paper = None
    if dim == 3 and rows == 3:
        _, Lambda, _ = symbolic_single_agent_matrix(dim, rows)
        paper = sp.expand(paper_eq_4_20_determinant(Lambda) ** 2 - Lambda.det() ** 2) == 0
    return SingleAgentGenericRank(
        dim=dim,
        rows=rows,
        n_states=2 * dim,
        n_minors=expansions.n_minors,
        n_nonzero=len(nonzero),
        generically_full_rank=bool(nonzero),
        alphas=alphas,
        alpha_counts=counts,
        closed_form_alpha=closed,
        witnesses=_witnesses(expansions),
        paper_factor_matches=paper,
        cross_check=_cross_check(expansions, seed=seed, bits=sample_bits, limit=cross_check_limit),
        random_rank=random_generic_rank(dim, rows, seed=seed, field=field),
        kronecker_rank=2 * min(rows, dim),
    )


def _nonzero_minors(expansions: MinorExpansions, *, seed: int) -> list[int]:
    """Minors whose quadratic form in the ``M_a`` is a non-zero polynomial.

    A non-empty coefficient list is non-zero unless the Plücker relations cancel it; it is
    decided by an exact evaluation at a random integer ``Λ`` (non-zero value: certainly non-zero)
    and, for the rare zero value, by sympy expansion.
    """
    candidates = np.unique(expansions.minor)
    if candidates.size == 0:
        return []
    rng = np.random.default_rng(seed + 1)
    Lambda = np.array(_draw(rng, expansions.rows * expansions.dim, 2**40), dtype=object)
    Lambda = Lambda.reshape(expansions.rows, expansions.dim)
    values = expansions.evaluate(candidates, Lambda, 1)
    out = []
    _, L_sym, T = symbolic_single_agent_matrix(expansions.dim, expansions.rows)
    for index, value in zip(candidates, values, strict=True):
        if value != 0 or sp.expand(expansions.polynomial(int(index), L_sym, T)) != 0:
            out.append(int(index))
    return out


def _alphas(
    expansions: MinorExpansions,
) -> tuple[list[tuple[tuple[int, ...], int]], dict[int, int], bool]:
    """``α`` per non-zero minor when ``k = d`` and the closed form ``±Π_r (j_{r,2} − j_{r,1})``."""
    k = expansions.rows
    alphas = []
    closed = True
    nonzero = set(int(i) for i in expansions.minor)
    for index in range(expansions.n_minors):
        rows = expansions.row_sets[index]
        powers, lam = np.divmod(rows, k)
        uses = Counter(int(r) for r in lam)
        twice = all(uses[r] == 2 for r in range(k))
        if index not in nonzero:
            closed &= not twice
            continue
        alpha = expansions.terms(index)[(0, 0)]
        magnitude = prod(abs(int(np.ptp(powers[lam == r]))) for r in range(k))
        closed &= twice and abs(alpha) == magnitude
        alphas.append((tuple(int(r) + 1 for r in rows), alpha))
    return alphas, dict(Counter(a for _, a in alphas)), bool(closed)


def _witnesses(expansions: MinorExpansions) -> dict[str, dict]:
    """For each ``d``-subset ``a``: the first minor equal to ``α T^d M_a²``."""
    out: dict[str, dict] = {}
    single = np.bincount(expansions.minor, minlength=expansions.n_minors) == 1
    for index, (a, b), c in zip(expansions.minor, expansions.pair, expansions.coeff, strict=True):
        label = ",".join(str(r + 1) for r in expansions.subsets[a])
        if a == b and single[index] and label not in out:
            rows = tuple(int(r) + 1 for r in expansions.row_sets[index])
            out[label] = {"rows": rows, "alpha": int(c)}
    return out


def _cross_check(expansions: MinorExpansions, *, seed: int, bits: int, limit: int) -> dict:
    """Compare every expansion with ``det`` of the same rows of ``O`` at a random integer point."""
    dim, k = expansions.dim, expansions.rows
    rng = np.random.default_rng(seed)
    values = _draw(rng, k * dim + 1, 2**bits)
    Lambda = np.array(values[:-1], dtype=object).reshape(k, dim)
    T = values[-1]
    O = [
        [int(x) for x in Lambda[r]] + [j * T * int(x) for x in Lambda[r]]
        for j in range(2 * dim)
        for r in range(k)
    ]
    indices = np.arange(expansions.n_minors)
    if indices.size > limit:
        indices = np.sort(rng.choice(indices, size=limit, replace=False))
    predicted = expansions.evaluate(indices, Lambda, T)
    agree = all(
        int(flint.fmpz_mat([O[r] for r in expansions.row_sets[i]]).det()) == value
        for i, value in zip(indices, predicted, strict=True)
    )
    degree = 3 * dim
    return {
        "seed": seed,
        "sample_size": 2**bits,
        "compared": int(indices.size),
        "all_agree": bool(agree),
        "error_bound": indices.size * degree / 2**bits,
        "note": "each disagreement-free minor could still differ as a polynomial with "
        "probability ≤ degree/sample; error_bound is the union bound over all compared",
    }


def _check_dims(dim: int, rows: int) -> None:
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3; got {dim!r}")
    if isinstance(rows, bool) or not isinstance(rows, int) or rows < 1:
        raise ValueError(f"rows must be an integer ≥ 1; got {rows!r}")


def derivation_markdown(result: SingleAgentGenericRank) -> str:
    """A readable derivation of §4.2.1's result for ``result.dim``, ``result.rows``.

    Parameters
    ----------
    result : SingleAgentGenericRank
        From :func:`single_agent_generic_rank`.

    Returns
    -------
    str
        Markdown, embeddable in the report.
    """
    d, k, n = result.dim, result.rows, result.n_states
    lines = [
        f"### Generic observability of one agent: d = {d}, {k} TDOA row(s)",
        "",
        f"The measurement matrix is H_λ = [Λ 0] with Λ a {k}×{d} matrix of free symbols "
        "(seed 000 eqs. 4.17, 4.19) and A^j = [[I, jT I], [0, I]] (eq. 4.6), so "
        "H_λ A^j = [Λ, jTΛ] and",
        "",
        f"    O = [H_λ; H_λA; …; H_λA^{n - 1}] = V_T ⊗ Λ,   V_T = [1  jT] (j = 0…{n - 1}).",
        "",
        f"Hence rank O = rank V_T · rank Λ = 2·rank Λ for T ≠ 0, and O has full rank {n} iff "
        f"T ≠ 0 and rank Λ = {d}. Generic rank: {result.kronecker_rank}.",
        "",
        f"**Every minor.** The {result.n_minors} minors of size {n} (C({n * k},{n})) were expanded "
        f"by Laplace along the {d} velocity columns: each is T^{d}·Σ c_ab M_a M_b with M_a the "
        f"{d}×{d} minors of Λ and integer c_ab. Non-zero minors: {result.n_nonzero}; identically "
        f"zero: {result.n_minors - result.n_nonzero}.",
    ]
    if k < d:
        lines += _too_few_rows(d, k)
    elif k == d:
        lines += _square(result)
    else:
        lines += _more_rows(result)
    cc, rr = result.cross_check, result.random_rank
    lines += [
        "",
        f"**Checks.** {cc['compared']} expansions were compared with the exact determinant of the "
        f"same rows of O at a random integer point (seed {cc['seed']}, entries < 2^"
        f"{cc['sample_size'].bit_length() - 1}): all agree = {cc['all_agree']} (union "
        f"Schwartz–Zippel bound {cc['error_bound']:.1e}). Exact rank at a random point over "
        f"{rr.field}: {rr.rank} (seed {rr.seed}; P(generic rank larger) ≤ {rr.degree_bound}/"
        f"{rr.sample_size} = {rr.error_bound:.1e}).",
    ]
    return "\n".join(lines) + "\n"


def _too_few_rows(d: int, k: int) -> list[str]:
    """Lines of :func:`derivation_markdown` for ``k < d`` rows (every minor vanishes)."""
    return [
        "",
        f"With {k} < {d} rows Λ has no {d}×{d} minor, so every term vanishes: all minors are "
        f"identically zero and the agent can never observe the target alone "
        f"(seed 000 §4.2.1{', footnote 1' if k == 1 else ''}).",
    ]


def _square(result: SingleAgentGenericRank) -> list[str]:
    """Lines of :func:`derivation_markdown` for ``k = d`` rows (eq. 4.20 and its α values)."""
    d, k = result.dim, result.rows
    values = ", ".join(f"{a} (×{c})" for a, c in sorted(result.alpha_counts.items()))
    lines = [
        "",
        f"With {k} = {d} rows every non-zero minor is α·T^{d}·det(Λ)² "
        f"({'eq. 4.20' if d == 3 else 'the planar analogue of eq. 4.20'}). A minor is "
        f"non-zero iff it uses every row of Λ at exactly two powers j < j', and then "
        f"α = ±Π_r (j'_r − j_r) (closed form confirmed: {result.closed_form_alpha}).",
        "",
        f"α values (count): {values}.",
    ]
    if result.paper_factor_matches is not None:
        lines += [
            "",
            "The bracket printed in eq. (4.20) equals −det Λ; its square equals det(Λ)² "
            f"(checked symbolically: {result.paper_factor_matches}).",
        ]
    lines += ["", "| rows of O (1-based) | α |", "|---|---|"]
    lines += [f"| {list(r)} | {a} |" for r, a in result.alphas[:12]]
    if len(result.alphas) > 12:
        lines.append(f"| … {len(result.alphas) - 12} more (see the JSON output) | |")
    wording = (
        "the 4 agents being coplanar: it means they lie on one circular cone with apex at "
        "the target"
        if d == 3
        else "the 3 agents being collinear: it means they lie on at most two rays from the target"
    )
    lines += [
        "",
        "Note: det Λ = 0 means the TDOA rows (differences of unit vectors from the agents "
        f"to the target) are linearly dependent; this is not the same as {wording} "
        "(docs/theory/tdoa-observability.md, Theorem 2).",
    ]
    return lines


def _more_rows(result: SingleAgentGenericRank) -> list[str]:
    """Lines of :func:`derivation_markdown` for ``k > d`` rows (footnote 2 and its witnesses)."""
    d, k, n = result.dim, result.rows, result.n_states
    lines = [
        "",
        f"With {k} > {d} rows every minor lies in the ideal of the {d}×{d} minors M_a of Λ "
        f"(each term carries a product M_a M_b), so rank Λ < {d} ⇒ rank O < {n}. Conversely, "
        f"for every {d}-subset a of Λ's rows there is a minor equal to α·T^{d}·M_a² with "
        f"α ≠ 0 (witnesses below), so rank Λ = {d} and T ≠ 0 ⇒ rank O = {n} (footnote 2).",
        "",
        "| rows of Λ | witness rows of O | α |",
        "|---|---|---|",
    ]
    lines += [f"| {a} | {list(w['rows'])} | {w['alpha']} |" for a, w in result.witnesses.items()]
    return lines
