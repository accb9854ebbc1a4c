"""Generic observability of one agent with TDOA rows: every minor of O, exactly (seed 000 §4.2.1),
the claims it decides and what ``trackcert generic`` reports.

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
from typing import Any

import flint
import numpy as np
import sympy as sp

from theory.core.claims import ClaimResult, ClaimSet, Context, Method, status_of
from theory.core.errors import CaseError
from theory.core.exact import to_fmpq
from theory.tdoa.model import cv_discrete_symbolic

__all__ = [
    "MAX_ROWS",
    "MERSENNE_PRIME",
    "GenericReport",
    "MinorExpansions",
    "RandomRank",
    "SingleAgentGenericRank",
    "claims",
    "derivation_markdown",
    "eq_4_20_claim",
    "exact_rank",
    "footnote_2_claim",
    "generic_report",
    "minor_expansions",
    "paper_eq_4_20_determinant",
    "planar_claim",
    "random_generic_rank",
    "single_agent_generic_rank",
    "symbolic_single_agent_matrix",
    "two_rows_claim",
]

claims = ClaimSet()

MERSENNE_PRIME = 2**61 - 1
"""Default modulus for rank over a prime field (``nmod_mat``)."""

SAMPLE_BITS = 40
"""Default random integers are drawn uniformly from ``[0, 2**SAMPLE_BITS)``."""


def symbolic_single_agent_matrix(
    dim: int = 3, rows: int = 3
) -> tuple[sp.Matrix, sp.Matrix, sp.Symbol]:
    """``O = [H_λ; H_λ A; …; H_λ A^{2d−1}]`` of seed 000 eq. (4.18) with symbolic ``λ`` (the
    ``rows × dim`` matrix ``Λ``, eqs. (4.17), (4.19)) and ``T``; row ``j·k + r`` is row ``r`` of
    ``H_λ A^j``. Returns ``(O, Λ, T)``."""
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
    """The bracket printed in seed 000 eq. (4.20) for the 3 × 3 ``Λ`` (it equals ``−det Λ``)."""
    l1, l2, l3, l4, l5, l6, l7, l8, l9 = list(Lambda)
    return l3 * (l5 * l7 - l4 * l8) + l2 * (l4 * l9 - l6 * l7) + l1 * (l6 * l8 - l5 * l9)


@dataclass(frozen=True)
class MinorExpansions:
    """Every ``2d × 2d`` minor of ``O`` as ``T^d Σ c_ab M_a M_b`` (integer ``c``).

    ``subsets`` are the ``d``-subsets of ``Λ``'s rows indexing the minors ``M_a``; ``row_sets`` the
    rows of ``O`` of each minor (lexicographic); for each non-zero coefficient, ``minor`` indexes
    ``row_sets``, ``pair`` is ``(a, b)`` with ``a ≤ b`` and ``coeff`` is ``c_ab``."""

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
        """``{(a, b): c_ab}`` of minor ``index``."""
        lo, hi = np.searchsorted(self.minor, [index, index + 1])
        return {
            (int(a), int(b)): int(c)
            for (a, b), c in zip(self.pair[lo:hi], self.coeff[lo:hi], strict=True)
        }

    def polynomial(self, index: int, Lambda: sp.Matrix, T: sp.Symbol) -> sp.Expr:
        """Minor ``index`` as the sympy expression ``T^d Σ c_ab M_a M_b``."""
        minors = [Lambda.extract(list(s), list(range(self.dim))).det() for s in self.subsets]
        return T**self.dim * sum(
            (c * minors[a] * minors[b] for (a, b), c in self.terms(index).items()), sp.S.Zero
        )

    def evaluate(self, index_minors: np.ndarray, Lambda: np.ndarray, T: int) -> list[int]:
        """Exact values of the (distinct) minors ``index_minors`` at integer ``Λ`` and ``T``."""
        m = [int(flint.fmpz_mat(Lambda[list(s)].tolist()).det()) for s in self.subsets]
        values = dict.fromkeys(int(i) for i in index_minors)
        sums = dict.fromkeys(values, 0)
        for idx, (a, b), c in zip(self.minor, self.pair, self.coeff, strict=True):
            if int(idx) in sums:
                sums[int(idx)] += int(c) * m[a] * m[b]
        return [T**self.dim * sums[i] for i in values]


def minor_expansions(dim: int = 3, rows: int = 3, *, chunk: int = 200_000) -> MinorExpansions:
    """Every ``2d × 2d`` minor of ``O`` by the generalized Laplace expansion, ``chunk`` minors per
    vectorised batch (seed 000 §4.2.1, eqs. (4.18)–(4.20), footnotes 1–2)."""
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
    """An exact rank at a random point (a lower bound on the generic rank), with its
    Schwartz–Zippel bound: ``error_bound = degree_bound / sample_size`` is the probability that
    the generic rank exceeds ``rank`` (over a prime field, for the minors modulo ``modulus``)."""

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
    """Exact rank of an integer or rational matrix, over ℚ or ``GF(modulus)`` (python-flint);
    ``ValueError`` for an unknown field or a denominator divisible by ``modulus``."""
    rows = [list(r) for r in matrix]
    if not rows or not rows[0]:
        return 0
    if field == "rationals":
        return int(to_fmpq(rows).rref()[1])
    if field == "prime":
        entries = []
        for x in (Fraction(x) for r in rows for x in r):
            if x.denominator % modulus == 0:
                raise ValueError(f"denominator {x.denominator} vanishes modulo {modulus}")
            entries.append(x.numerator * pow(x.denominator, -1, modulus) % modulus)
        return int(flint.nmod_mat(len(rows), len(rows[0]), entries, modulus).rank())
    raise ValueError(f"field must be 'rationals' or 'prime'; got {field!r}")


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

    ``λ`` and ``T`` are uniform on ``[0, 2**sample_bits)`` (below ``modulus`` over a prime field).
    Each ``2d × 2d`` minor has total degree ≤ ``3d``, so by Schwartz–Zippel the rank found is the
    generic rank except with probability ≤ ``3d / 2**sample_bits`` (seed 000 §4.2.1)."""
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

    ``n_nonzero`` of the ``n_minors = C(2dk, 2d)`` minors are non-zero polynomials. For ``k = d``:
    ``alphas`` lists ``(rows of O, α)`` of every non-zero minor ``α T^d det(Λ)²``, ``alpha_counts``
    their frequencies, ``closed_form_alpha`` whether every ``α = ±Π_r (j_{r,2} − j_{r,1})``.
    ``witnesses`` gives, per ``d``-subset ``a`` of ``Λ``'s rows, a minor ``α T^d M_a²``
    (footnote 2's ``⇔``). ``paper_factor_matches``: (eq. 4.20's bracket)² = det(Λ)² (only
    ``d = k = 3``).
    ``cross_check`` compares every expansion with the exact determinant at a random point;
    ``kronecker_rank = 2·min(k, d)`` from ``O = V_T ⊗ Λ``."""

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
        """The readable derivation (:func:`derivation_markdown`)."""
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
    """Reproduce seed 000 §4.2.1 for ``rows`` TDOA rows: all minors of ``O``, exactly.

    ``rows`` 1, 2: every minor vanishes in 3-D; 3: eq. (4.20); > 3: footnote 2. At most
    ``cross_check_limit`` minors are cross-checked (a seeded sample beyond it)."""
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
    """A readable derivation of §4.2.1 for ``result.dim``, ``result.rows`` (markdown)."""
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


@claims.register(
    "seed000.sec4.2.1.two-rows",
    source="seed 000, §4.2.1 (after eq. 4.18) and footnote 1",
    statement="With 1 or 2 TDOA rows every 6×6 minor of O vanishes identically: one agent "
    "cannot observe the target.",
)
def two_rows_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """Every minor of ``O`` vanishes with 1 or 2 rows in 3-D (footnote 1)."""
    results = [single_agent_generic_rank(3, rows) for rows in (1, 2)]
    ok = all(r.n_nonzero == 0 and r.cross_check["all_agree"] for r in results)
    evidence = {
        f"rows={r.rows}": {
            "minors": r.n_minors,
            "nonzero": r.n_nonzero,
            "generic_rank": r.random_rank.rank,
            "cross_check": r.cross_check,
        }
        for r in results
    }
    message = "All C(6,6)=1 and C(12,6)=924 minors vanish identically; generic ranks 2, 4."
    return [ClaimResult(status_of(ok), Method.SYMBOLIC, evidence, message=message)]


@claims.register(
    "seed000.eq4.20",
    source="seed 000, eq. (4.20)",
    statement="3 TDOA rows: the non-zero 6×6 minors of O are α·T³·det(Λ)².",
)
def eq_4_20_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """With 3 rows every non-zero minor is ``α·T³·det(Λ)²``, ``α`` in closed form."""
    r = single_agent_generic_rank(3, 3)
    ok = bool(
        r.closed_form_alpha
        and r.paper_factor_matches
        and r.cross_check["all_agree"]
        and r.random_rank.rank == 6
    )
    evidence = {
        "minors": r.n_minors,
        "nonzero": r.n_nonzero,
        "alpha_counts": {str(a): c for a, c in sorted(r.alpha_counts.items())},
        "alpha_closed_form": "±Π_r (j'_r − j_r)",
        "printed_bracket": "−det Λ",
        "cross_check": r.cross_check,
        "random_rank": dict(r.random_rank.__dict__),
        "derivation": r.markdown(),
    }
    message = (
        f"{r.n_nonzero} of {r.n_minors} minors are non-zero, each α·T³·det(Λ)² "
        f"with α in [{min(r.alpha_counts)}, {max(r.alpha_counts)}]."
    )
    margin = r.random_rank.error_bound
    return [ClaimResult(status_of(ok), Method.SYMBOLIC, evidence, margin=margin, message=message)]


@claims.register(
    "seed000.fn2",
    source="seed 000, §4.2.1 footnote 2",
    statement="With more than 3 TDOA rows, rank O = 6 iff rank Λ ≥ 3.",
)
def footnote_2_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """With 4 rows, a witness minor ``α T³ M_a²`` for each 3-subset of rows (footnote 2)."""
    r = single_agent_generic_rank(3, 4)
    ok = len(r.witnesses) == 4 and r.cross_check["all_agree"] and r.random_rank.rank == 6
    evidence = {
        "rows": 4,
        "minors": r.n_minors,
        "nonzero": r.n_nonzero,
        "witnesses": r.witnesses,
        "cross_check": r.cross_check,
        "kronecker": "O = V_T ⊗ Λ, rank O = 2 rank Λ",
    }
    message = (
        "Every minor lies in the ideal of the 3×3 minors of Λ, and each 3×3 minor "
        "squared is (up to α T³) a minor of O."
    )
    return [ClaimResult(status_of(ok), Method.SYMBOLIC, evidence, message=message)]


@claims.register(
    "seed000.sec4.2.1.planar",
    source="seed 000, §4.2.1 (planar analogue; not stated in the paper)",
    statement="In the plane (4 states) one agent needs 2 TDOA rows: minors vanish with 1 row "
    "and are α·T²·det(Λ)² with 2.",
)
def planar_claim(case: None, ctx: Context) -> list[ClaimResult]:
    """The planar analogue: 1 row never suffices, 2 rows give ``α·T²·det(Λ)²``."""
    one, two, three = (single_agent_generic_rank(2, k) for k in (1, 2, 3))
    ok = (
        one.n_nonzero == 0
        and two.closed_form_alpha
        and len(three.witnesses) == 3
        and all(r.cross_check["all_agree"] for r in (one, two, three))
    )
    evidence = {
        "rows=1": {"minors": one.n_minors, "nonzero": one.n_nonzero},
        "rows=2": {
            "minors": two.n_minors,
            "nonzero": two.n_nonzero,
            "alpha_counts": {str(a): c for a, c in sorted(two.alpha_counts.items())},
        },
        "rows=3": {"witnesses": three.witnesses},
    }
    message = (
        "Planar analogue: 1 row never suffices; 2 rows give α·T²·det(Λ)² "
        f"({two.n_nonzero} of {two.n_minors} minors non-zero); more rows: rank Λ ≥ 2."
    )
    return [ClaimResult(status_of(ok), Method.SYMBOLIC, evidence, message=message)]


MAX_ROWS = {2: 8, 3: 4}
"""Largest ``rows`` per dimension: C(32, 4) = 35960 and C(24, 6) = 134596 minors."""


@dataclass(frozen=True)
class GenericReport:
    """What ``trackcert generic`` prints: a derivation (:class:`SingleAgentGenericRank`, or the
    Fig. 4.3 dict) and whether every check reproduces the statement."""

    result: Any
    holds: bool


def generic_report(dim: int = 3, rows: int | None = None, *, seed: int = 0) -> GenericReport:
    """The single-agent derivation of seed 000 §4.2.1 (eq. (4.20), footnotes 1–2).

    It holds when the random-point rank equals the Kronecker rank, the cross-check agrees, ``O``
    is generically full rank iff ``rows ≥ dim``, and eq. (4.20)'s closed form and factor match
    where they apply. ``CaseError`` if ``dim`` or ``rows`` (default ``dim``, at most
    :data:`MAX_ROWS`) is out of range.
    """
    if dim not in (2, 3):
        raise CaseError("--dim", "2 or 3", dim, file="<command line>")
    rows = dim if rows is None else rows
    limit = MAX_ROWS[dim]
    if rows < 1 or rows > limit:
        raise CaseError(
            "--rows",
            f"an integer between 1 and {limit} for dim {dim} (all C(2·dim·rows, 2·dim) "
            "minors are enumerated; footnote 2 needs only rows = dim + 1)",
            rows,
            file="<command line>",
        )
    result = single_agent_generic_rank(dim, rows, seed=seed)
    holds = (
        result.cross_check["all_agree"]
        and result.random_rank.rank == result.kronecker_rank
        and result.generically_full_rank == (rows >= dim)
        and result.closed_form_alpha in (None, True)
        and result.paper_factor_matches in (None, True)
    )
    return GenericReport(result, bool(holds))
