"""TDOA observability that survives displacements (``tdoa-observability-margin``) and losses of
links or agents (``tdoa-loss-tolerance``); the proofs are in ``docs/design.md``.

Agent ``i``'s block column ``O_i`` has rank ``2d`` iff the directions ``u_j = (p − p_j)/‖p − p_j‖``
of a set of its receivers connected by its rows span an affine space of dimension ``d`` (seed 000
eqs. (4.36)–(4.37); Theorems 1 and 4 of ``docs/theory/tdoa-observability.md``). Both kinds show it
with rational unit ``û_j``, ``‖û_j − u_j‖ ≤ e_j`` (checked with squares), and the exact test
``C − τI − T ≻ 0`` of the centred Gram matrix ``C = Σ_j (û_j − m)(û_j − m)ᵀ`` (``m`` the mean):
no hyperplane ``{x·u = c}`` then comes within reach of every direction, the rounding costing
``τ`` and the displacement ``T``.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations
from math import comb
from typing import Any

from proofs_check import linalg as la
from proofs_check import parse as p
from proofs_check.checks import Check, definite, show
from proofs_check.linalg import Matrix

__all__ = ["heard_lists", "loss_tolerance", "observability_margin", "receivers"]

MAX_SUBSETS = 20_000
"""Most removal sets a ``tdoa-loss-tolerance`` certificate may ask the checker to enumerate."""
MAX_WORK = 20_000_000
"""Largest accepted graph work of the enumeration: sets × (agents + 2 links) searches, times the
agents on directed links (one search per agent; on undirected links one per component)."""
MAX_AGENTS = 1000
"""Most agents of a scene (their positions, directions and errors are lists, not matrices)."""
MAX_LINKS = 20_000
"""Most links of a scene."""


def _scene(data: dict[str, Any]) -> tuple[int, list[Fraction], Matrix, list[tuple[int, int]], bool]:
    """``dim``, target, agents, 0-based links ``(s, r)`` ("r hears s") and whether undirected."""
    dim = p.index(data["dim"], "data.dim", 2, 3)
    target = p.matrix([data["target"]], "data.target", 1, dim)[0]
    agents = _points(data["agents"], "data.agents", None, dim)
    undirected = p.text(data["graph"], "data.graph", ("undirected", "directed")) == "undirected"
    raw = data["links"]
    if not isinstance(raw, list) or len(raw) > MAX_LINKS:
        why = f"data.links: expected a list of at most {MAX_LINKS} [s, r] pairs (r hears s)"
        raise p.MalformedError(why)
    links = []
    for k, pair in enumerate(raw):
        where = f"data.links[{k + 1}]"
        if not isinstance(pair, list) or len(pair) != 2:
            raise p.MalformedError(f"{where}: expected a pair [s, r] of 1-based agent ids")
        s, r = (p.index(x, where, 1, len(agents)) - 1 for x in pair)
        if s == r:
            raise p.MalformedError(f"{where}: an agent does not hear itself")
        links.append((s, r))
    key = [frozenset(link) if undirected else link for link in links]
    if len(set(key)) != len(key):
        raise p.MalformedError("data.links: a link is listed twice")
    return dim, target, agents, links, undirected


def heard_lists(n: int, links: list[tuple[int, int]], undirected: bool) -> list[set[int]]:
    """``heard[r]``: the agents ``r`` hears."""
    heard: list[set[int]] = [set() for _ in range(n)]
    for s, r in links:
        heard[r].add(s)
        if undirected:
            heard[s].add(r)
    return heard


def receivers(i: int, heard: list[set[int]]) -> tuple[set[int], list[tuple[int, int]]]:
    """The agents whose TDOA rows enter ``O_i`` and those rows ``(r, s)``: ``R(i)`` is ``i`` and
    every ``r`` hearing an agent of ``R(i)`` (seed 000 Lemma 4.2.2); a row of ``r ∈ R(i)`` is each
    ``s`` it hears."""
    hears_from: list[set[int]] = [set() for _ in heard]
    for r, sources in enumerate(heard):
        for s in sources:
            hears_from[s].add(r)
    reach, frontier = {i}, [i]
    while frontier:
        for r in hears_from[frontier.pop()] - reach:
            reach.add(r)
            frontier.append(r)
    rows = [(r, s) for r in reach for s in heard[r]]
    return reach | {s for _, s in rows}, rows


def _connected(members: set[int], rows: list[tuple[int, int]]) -> bool:
    """Whether ``rows`` with both ends in ``members`` connect ``members``."""
    near: dict[int, set[int]] = {a: set() for a in members}
    for r, s in rows:
        if r in members and s in members:
            near[r].add(s)
            near[s].add(r)
    start = min(members)
    seen, frontier = {start}, [start]
    while frontier:
        for b in near[frontier.pop()] - seen:
            seen.add(b)
            frontier.append(b)
    return seen == members


def _offset(target: list[Fraction], point: list[Fraction]) -> tuple[list[Fraction], Fraction]:
    """``v = p − p_j`` and ``‖v‖²``."""
    v = [t - x for t, x in zip(target, point, strict=True)]
    return v, sum(x * x for x in v)


def _at_least_root(a: Fraction, k: Fraction, q: Fraction) -> bool:
    """Whether ``a ≥ k √q`` (``q ≥ 0``), with squares only."""
    if k <= 0:
        return a >= 0 or a * a <= k * k * q
    return a >= 0 and a * a >= k * k * q


def _directions(
    name: str, target: list[Fraction], agents: Matrix, ids: list[int], u: Matrix, e: list[Fraction]
) -> list[Check]:
    """``‖û_j‖ = 1`` and ``‖û_j − u_j‖ ≤ e_j``: ``‖û − v/‖v‖‖² = 2 − 2 û·v/‖v‖ ≤ e²`` iff
    ``û·v ≥ (1 − e²/2)‖v‖``."""
    checks = []
    for j, u_j, e_j in zip(ids, u, e, strict=True):
        norm = sum(x * x for x in u_j)
        checks.append(Check(f"{name}‖û_{j + 1}‖² = 1", norm == 1, f"‖û_{j + 1}‖² = {show(norm)}"))
        v, q = _offset(target, agents[j])
        dot = sum(x * y for x, y in zip(u_j, v, strict=True))
        ok = q > 0 and e_j >= 0 and _at_least_root(dot, 1 - e_j * e_j / 2, q)
        detail = f"e = {show(e_j)}, û·v = {show(dot)}, ‖v‖² = {show(q)}"
        checks.append(Check(f"{name}‖û_{j + 1} − u_{j + 1}‖ ≤ e_{j + 1}", ok, detail))
    return checks


def _gram(u: Matrix) -> Matrix:
    """``Σ_j (û_j − m)(û_j − m)ᵀ`` with ``m`` the mean of the rows ``û_j``."""
    mean = [sum(column) / len(u) for column in zip(*u, strict=True)]
    centred = [[x - c for x, c in zip(row, mean, strict=True)] for row in u]
    return la.matmul(la.transpose(centred), centred)


def _spread(name: str, u: Matrix, tau: Fraction, turn: Matrix | None = None) -> Check:
    """``C − τI − T ≻ 0``: for every unit ``x`` and every ``c``, ``Σ_j (x·u'_j − c)² > 0``."""
    shifted = la.sub(_gram(u), la.scale(tau, la.identity(len(u[0]))))
    if turn is not None:
        shifted = la.sub(shifted, turn)
    return definite(f"{name}C − τI − T ≻ 0 (τ = {show(tau)})", shifted)


def _turns(target: list[Fraction], points: Matrix, h: list[Fraction], kappa: Fraction) -> Matrix:
    """``Q = Σ_j (1 + κ)h_j²(I − P_j) + (1 + 1/κ)(h_j⁴/4)P_j``, ``P_j = v_jv_jᵀ/‖v_j‖² = u_ju_jᵀ``:
    for unit ``x``, ``xᵀQx ≥ Σ_j (x·Δu_j)²`` when ``‖Δu_j‖ ≤ h_j``, since ``u·Δu = −‖Δu‖²/2``
    gives ``|x·Δu| ≤ √(1 − (x·u)²)‖Δu‖ + |x·u|‖Δu‖²/2`` (Young's inequality with ``κ``)."""
    eye = la.identity(len(target))
    total = la.scale(Fraction(0), eye)
    for point, h_j in zip(points, h, strict=True):
        v, q = _offset(target, point)
        P = [[a * b / q for b in v] for a in v]
        total = la.add(total, la.scale((1 + kappa) * h_j * h_j, la.sub(eye, P)))
        total = la.add(total, la.scale((1 + 1 / kappa) * h_j**4 / 4, P))
    return total


def _points(raw: Any, where: str, count: int | None, dim: int) -> Matrix:
    return p.matrix(raw, where, count, dim, max_rows=MAX_AGENTS)


def _rationals(raw: Any, where: str, count: int) -> list[Fraction]:
    return p.matrix([raw], where, 1, count, max_cols=MAX_AGENTS)[0]


def _ids(raw: Any, where: str, agents: int) -> list[int]:
    if not isinstance(raw, list) or not raw or len(raw) > agents:
        raise p.MalformedError(f"{where}: expected a non-empty list of distinct 1-based agent ids")
    ids = [p.index(x, where, 1, agents) - 1 for x in raw]
    if len(set(ids)) != len(ids):
        raise p.MalformedError(f"{where}: agent ids must be distinct")
    return ids


def observability_margin(cert: dict[str, Any]) -> list[Check]:
    """Each claimed agent keeps ``rank O_i = 2d`` for every displacement of the target and of
    every agent by less than ``radius`` (Euclidean, each point), the listed links kept (given
    ``comm_range``: links by the rule, the listed ones at most ``R − 2·radius`` long)."""
    claim = p.fields(cert["claim"], "claim", ("radius", "agents"), ("statement",))
    keys = ("dim", "target", "agents", "links", "graph")
    data = p.fields(cert["data"], "data", keys, ("comm_range",))
    witness = p.fields(cert["witness"], "witness", ("sets",))
    dim, target, agents, links, undirected = _scene(data)
    radius = p.bounded(claim["radius"], "claim.radius", "(0, ∞)", "a radius is positive")
    claimed = _ids(claim["agents"], "claim.agents", len(agents))
    checks = []
    if "comm_range" in data:
        checks += _persistent(data["comm_range"], agents, links, undirected, radius)
    heard, covered, work = heard_lists(len(agents), links, undirected), set(), 0
    checks.append(_off_target(target, agents, radius))
    sets = witness["sets"]
    if not isinstance(sets, list) or not sets or len(sets) > p.MAX_ITEMS:
        raise p.MalformedError(f"witness.sets: expected 1 to {p.MAX_ITEMS} sets")
    for k, raw in enumerate(sets):
        where = f"witness.sets[{k + 1}]"
        keys = ("agents", "covers", "directions", "errors", "motion_bounds", "kappa", "mu")
        item = p.fields(raw, where, keys)
        members = _ids(item["agents"], f"{where}.agents", len(agents))
        covers = _ids(item["covers"], f"{where}.covers", len(agents))
        u = _points(item["directions"], f"{where}.directions", len(members), dim)
        e = _rationals(item["errors"], f"{where}.errors", len(members))
        h = _rationals(item["motion_bounds"], f"{where}.motion_bounds", len(members))
        name = f"set {k + 1}: "
        work += len(covers) * (len(agents) + 2 * len(links))  # one search per covered agent
        if work > MAX_WORK:
            raise p.MalformedError(f"refused: covering work {work:.3g} (limit {MAX_WORK:.3g})")
        checks += [_covers(name, i, set(members), heard) for i in covers]
        checks += _directions(name, target, agents, members, u, e)
        checks += _motions(name, target, agents, members, h, radius)
        kappa = p.bounded(item["kappa"], f"{where}.kappa", "(0, ∞)", "a Young weight")
        mu = p.bounded(item["mu"], f"{where}.mu", "(0, ∞)", "a Young weight")
        turn = _turns(target, [agents[j] for j in members], h, kappa)
        tau = (1 + mu) * sum((x * x for x in e), Fraction(0))  # (E + B)² ≤ (1+μ)E² + (1+1/μ)B²
        checks.append(_spread(name, u, tau, la.scale(1 + 1 / mu, turn)))
        covered |= set(covers)
    missing = [i + 1 for i in claimed if i not in covered]
    detail = f"agents {missing} are covered by no set" if missing else "every claimed agent"
    return [*checks, Check("every claimed agent is covered by a set", not missing, detail)]


def _covers(name: str, i: int, members: set[int], heard: list[set[int]]) -> Check:
    """The set lies among agent ``i``'s receivers and is connected by rows of ``O_i``."""
    reached, rows = receivers(i, heard)
    ok = members <= reached and _connected(members, rows)
    detail = f"receivers of agent {i + 1}: {sorted(x + 1 for x in reached)}"
    return Check(f"{name}connected by rows of O_{i + 1}", ok, detail)


def _motions(
    name: str,
    target: list[Fraction],
    agents: Matrix,
    ids: list[int],
    h: list[Fraction],
    rho: Fraction,
) -> list[Check]:
    """Points moved by less than ``ρ`` turn ``u_j`` by less than ``h_j``: with
    ``s² = 4ρ²/‖v‖² < 1``, ``‖Δu‖² < 2 − 2√(1 − s²) ≤ 2s²/(2 − s²) ≤ h_j²``."""
    checks = []
    for j, h_j in zip(ids, h, strict=True):
        s2 = 4 * rho * rho / _offset(target, agents[j])[1]
        ok = s2 < 1 and h_j >= 0 and h_j * h_j * (2 - s2) >= 2 * s2
        detail = f"s² = 4ρ²/‖v‖² = {show(s2)}, h = {show(h_j)}"
        checks.append(Check(f"{name}s_{j + 1} < 1, h_{j + 1}² ≥ 2s²/(2 − s²)", ok, detail))
    return checks


def _off_target(target: list[Fraction], agents: Matrix, rho: Fraction) -> Check:
    """No agent can reach the target (TDOAs stay defined): ``‖p − p_j‖² > 4ρ²`` for all ``j``."""
    near = [j + 1 for j, a in enumerate(agents) if _offset(target, a)[1] <= 4 * rho * rho]
    detail = f"agents {near} are within 2ρ of the target" if near else "all farther than 2ρ"
    return Check("every agent farther than 2ρ from the target", not near, detail)


def _persistent(
    raw: Any, agents: Matrix, links: list[tuple[int, int]], undirected: bool, rho: Fraction
) -> list[Check]:
    """Listed links survive the displacement under the rule "closer than ``R``":
    ``‖p_a − p_b‖ ≤ R − 2ρ``; links that appear only enlarge each agent's receivers."""
    R = p.bounded(raw, "data.comm_range", "(0, ∞)", "a range is positive")
    room = R - 2 * rho
    far = [(s, r) for s, r in links if room < 0 or _offset(agents[s], agents[r])[1] > room * room]
    detail = f"R − 2ρ = {show(room)}"
    if far:
        detail += f"; link {far[0][0] + 1}–{far[0][1] + 1} is longer"
    return [
        Check("data: comm_range needs an undirected graph", undirected, "the rule is symmetric"),
        Check("every listed link is at most R − 2ρ long", not far, detail),
    ]


def loss_tolerance(cert: dict[str, Any]) -> list[Check]:
    """Removing any ``fewer_than − 1`` or fewer links (or agents, with their links) leaves every
    remaining agent with ``rank O_i = 2d``, at the stated positions."""
    claim = p.fields(cert["claim"], "claim", ("items", "fewer_than"), ("statement",))
    data = p.fields(cert["data"], "data", ("dim", "target", "agents", "links", "graph"))
    witness = p.fields(cert["witness"], "witness", ("directions", "errors"))
    dim, target, agents, links, undirected = _scene(data)
    items = p.text(claim["items"], "claim.items", ("links", "agents"))
    pool = links if items == "links" else list(range(len(agents)))
    k = p.index(claim["fewer_than"], "claim.fewer_than", 1, len(pool) + 1)
    u = _points(witness["directions"], "witness.directions", len(agents), dim)
    e = _rationals(witness["errors"], "witness.errors", len(agents))
    subsets = sum(comb(len(pool), size) for size in range(k))
    searches = 1 if undirected else len(agents)
    work = subsets * searches * (len(agents) + 2 * len(links))
    if subsets > MAX_SUBSETS or work > MAX_WORK:
        why = f"{subsets} removal sets, work {work:.3g} (limits {MAX_SUBSETS}, {MAX_WORK:.3g})"
        raise p.MalformedError(f"refused: {why}")
    ids = list(range(len(agents)))
    checks = _directions("", target, agents, ids, u, e)
    verdicts: dict[frozenset[int], Check] = {}
    for size in range(k):
        checks.append(_removals(size, items, pool, links, undirected, dim, u, e, verdicts))
    return checks


def _removals(
    size: int,
    items: str,
    pool: list,
    links: list[tuple[int, int]],
    undirected: bool,
    dim: int,
    u: Matrix,
    e: list[Fraction],
    verdicts: dict[frozenset[int], Check],
) -> Check:
    """Every removal of ``size`` items keeps every remaining agent's receivers of full rank. On
    undirected links the receivers of ``i`` are its component, the same for each of its agents,
    so the agents of a component found already are skipped."""
    count = 0
    for removed in combinations(pool, size):
        count += 1
        gone = set(removed) if items == "agents" else set()
        kept = [x for x in links if (x not in removed if items == "links" else not set(x) & gone)]
        heard, seen = heard_lists(len(u), kept, undirected), set(gone)
        for i in (j for j in range(len(u)) if j not in seen):
            members = frozenset(receivers(i, heard)[0])
            seen |= members if undirected else set()
            if members not in verdicts:
                verdicts[members] = _set_rank(members, dim, u, e)
            if not verdicts[members].valid:
                what = [x + 1 for x in removed] if gone else [[a + 1, b + 1] for a, b in removed]
                why = f"removing {items} {what}: agent {i + 1}: {verdicts[members].detail}"
                return Check(f"any {size} {items} removed: every agent observable", False, why)
    detail = f"{count} removal sets, {len(verdicts)} receiver sets of full rank"
    return Check(f"any {size} {items} removed: every agent observable", True, detail)


def _set_rank(members: frozenset[int], dim: int, u: Matrix, e: list[Fraction]) -> Check:
    """Full affine rank of ``u_j``, ``j ∈ members``: at least ``d + 1`` agents and
    ``C − (Σ e_j²) I ≻ 0``."""
    ids = sorted(members)
    if len(ids) <= dim:
        return Check("", False, f"receivers {[j + 1 for j in ids]}: at most d = {dim} agents")
    check = _spread("", [u[j] for j in ids], sum((e[j] * e[j] for j in ids), Fraction(0)))
    return Check("", check.valid, f"receivers {[j + 1 for j in ids]}: {check.detail}")
