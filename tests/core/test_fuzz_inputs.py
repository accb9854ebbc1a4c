"""Hostile input through the CLI: every answer is an exit code of DESIGN.md, never a traceback.

Two parts (issue 17, items 2–5):

* regression cases — each input of the issue (``tests/data/hostile/`` and generated ones: binary,
  UTF-16, deep nesting, oversized files, 10⁶ agents, 100,000 trackers, a certificate with a key
  twice, bad ``-o`` paths, ``--runs``/``--steps`` beyond the limits) gets its right answer: exit 2
  naming the right field, nothing written;
* a hypothesis fuzzer — random mutations of every bundled case (keys deleted or repeated, types
  swapped, huge / negative / NaN numbers, deep nesting, aliases, tags, garbage bytes, truncation)
  run in-process through the commands that fit the kind, asserting exit ∈ {0, 1, 2, 3}, no
  traceback, exit-2 messages naming a field and nothing written in the ``-o`` folder on exit 2.
  Time per input is bounded by hypothesis' ``deadline`` in the ``thorough`` profile only.
"""

from __future__ import annotations

import copy
import math
import os
import re
import tempfile
from datetime import timedelta
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from theory.cli import app
from theory.core.case_file import bundled_cases
from theory.core.errors import CaseError
from theory.kinds import load_case, parse_case

HOSTILE = Path(__file__).resolve().parents[1] / "data" / "hostile"
CERTIFICATES = Path(__file__).resolve().parents[1] / "data" / "certificates" / "valid"
THOROUGH = os.environ.get("HYPOTHESIS_PROFILE") == "thorough"
FIELD = re.compile(r"field '[^']+'")
RUNNER = CliRunner()


def run(*args: str) -> tuple[int, str]:
    """Run ``trackcert ARGS`` in-process; fail on a traceback; return (exit code, all output)."""
    result = RUNNER.invoke(app, list(args))
    output = result.output  # stdout and stderr, interleaved
    assert result.exception is None or isinstance(result.exception, SystemExit), (
        f"{args}: {type(result.exception).__name__}: {result.exception}"
    )
    assert "Traceback" not in output, output
    assert result.exit_code in (0, 1, 2, 3), (result.exit_code, output)
    return result.exit_code, output


def refused(args: tuple[str, ...], field: str) -> str:
    """Assert ``trackcert ARGS`` exits 2 with a one-line message naming ``field`` (or a field
    inside it, such as ``tdoa.agents[1][1]`` for ``tdoa.agents``)."""
    code, output = run(*args)
    assert code == 2, output
    lines = [line for line in output.splitlines() if line.startswith("error:")]
    assert len(lines) == 1 and f"field '{field}" in lines[0], output
    return output


# --- regression cases: the inputs of issue 17 ------------------------------------------------

FILES = [
    ("topology", "python-tag.yaml", "tdoa.T", "tags are not allowed"),
    ("topology", "custom-tag.yaml", "tdoa.weights", "tags are not allowed"),
    ("dkf", "duplicate-key.yaml", "dkf.W", "on lines 10 and 11"),
    ("dkf", "alias-bomb.yaml", "dkf.A", "limit 'yaml_nodes'"),
    ("topology", "huge-int-coordinate.yaml", "tdoa.agents[1][3]", "finite number"),
    ("topology", "float-overflow.yaml", "tdoa.agents[1][3]", "no NaN or inf"),
    ("topology", "agent-at-1e308.yaml", "tdoa.agents[3][1]", "limit 'exponent'"),
    ("dkf", "negative-weight.yaml", "dkf.W[1][1]", "got -0.24"),
    ("pf", "pf-particles-1e12.yaml", "pf.particles", "TRACKCERT_MAX_PARTICLES"),
    ("pf", "pf-runs-1e9.yaml", "pf.runs", "TRACKCERT_MAX_RUNS"),
    ("pf", "pf-coincident-nodes.yaml", "pf.nodes[2]", "identically 0"),
]


@pytest.mark.parametrize(("command", "name", "field", "says"), FILES, ids=[f[1] for f in FILES])
def test_hostile_file_is_refused_naming_the_field(command, name, field, says) -> None:
    output = " ".join(refused((command, str(HOSTILE / name)), field).split())
    assert says in output
    assert "np.float64" not in output


def test_duplicate_key_would_have_changed_the_verdict() -> None:
    """The second ``W`` (w = 0.24) is what plain YAML kept: it makes the case S-detectable."""
    text = (HOSTILE / "duplicate-key.yaml").read_text(encoding="utf-8")
    data = yaml.safe_load(text)
    assert data["dkf"]["W"][0][0] == 0.24
    assert load_case("ch5-example-1-wb").spec.W[0, 0] == 0.26


def generated_files() -> dict[str, tuple[bytes, str, str]]:
    """Name → (content, field, text the message says) for the generated hostile inputs."""
    fig = (bundled_cases()["fig43-case-d"]).read_text(encoding="utf-8")
    return {
        "binary.yaml": (bytes(range(256)) * 4, "<file>", "not UTF-8 text"),
        "utf16.yaml": (fig.encode("utf-16"), "<file>", "not UTF-8 text"),
        "utf16-no-bom.yaml": (fig.encode("utf-16-le"), "<file>", "not UTF-8 text"),
        "nul.yaml": (fig.encode() + b"\x00", "<file>", "control character U+0000"),
        "deep.yaml": (
            ("name: d\nkind: tdoa\ntdoa:\n  agents: " + "[" * 20000 + "]" * 20000).encode(),
            "tdoa.agents",
            "limit 'yaml_depth'",
        ),
        "deep-block.yaml": (
            "".join(f"{'  ' * k}k{k}:\n" for k in range(200)).encode(),
            "k0.k1",
            "limit 'yaml_depth'",
        ),
        "oversized.yaml": ((fig + "#" * (1 << 20)).encode(), "<file>", "TRACKCERT_MAX_CASE_BYTES"),
        "trackers-100k.yaml": (
            _trackers_file(100_000).encode(),
            "pursuit.trackers",
            "TRACKCERT_MAX_TRACKERS",
        ),
        "two-documents.yaml": ((fig + "---\n" + fig).encode(), "<yaml>", "a single YAML document"),
        "merge-key.yaml": (
            fig.replace("  T: 1.0", "  <<: {T: 1.0}").encode(),
            "tdoa",
            "no merge keys",
        ),
        "huge-digits.yaml": (
            fig.replace("T: 1.0", "T: 1" + "0" * 5000).encode(),
            "tdoa.T",
            "a valid int",
        ),
    }


def _trackers_file(count: int) -> str:
    """A pursuit case whose ``count`` trackers are aliases of one (about 4 bytes each)."""
    body = yaml.safe_load(bundled_cases()["pursuit-table1-n3"].read_text(encoding="utf-8"))
    del body["pursuit"]["dekf"]
    body["pursuit"].update(edges=[], trackers="TRACKERS")
    text = yaml.safe_dump(body, sort_keys=False)
    aliases = ", ".join(["*t"] * (count - 1))
    return text.replace("trackers: TRACKERS", f"trackers: [&t {{r_x: 30, r_y: 30}}, {aliases}]")


GENERATED = generated_files()


@pytest.mark.parametrize("name", sorted(GENERATED))
def test_generated_hostile_file_is_refused(name: str, tmp_path: Path) -> None:
    content, field, says = GENERATED[name]
    path = tmp_path / name
    path.write_bytes(content)
    kind = "iss" if "trackers" in name else "topology"
    output = " ".join(refused((kind, str(path)), field).split())
    assert says in output


def test_a_million_agents_are_refused_before_reading_them() -> None:
    agents = [[float(k), 0.0, 1.0] for k in range(10**6)]
    data = {"name": "big", "kind": "tdoa", "tdoa": {"T": 1, "agents": agents, "target": [0, 1, 2]}}
    with pytest.raises(CaseError, match="TRACKCERT_MAX_AGENTS") as info:
        parse_case(data)
    assert info.value.field == "tdoa.agents"


def test_a_certificate_with_a_key_twice_is_malformed(tmp_path: Path) -> None:
    source = CERTIFICATES / "generic-rank-fig43-case-d.json"
    text = source.read_text(encoding="utf-8")
    twice = re.sub(r'\{"format"', '{"format": "x", "format"', text, count=1)
    if twice == text:  # key order differs: repeat the first key of the top object
        first = re.search(r'^\{\s*("[^"]+")\s*:', text).group(1)
        twice = text.replace("{", "{" + first + ': "x", ', 1)
    path = tmp_path / "twice.json"
    path.write_text(twice, encoding="utf-8")
    code, output = run("check", str(path))
    assert code == 2 and "appears twice" in output
    assert run("check", str(source))[0] == 0


@pytest.mark.parametrize(
    ("make", "args", "field"),
    [
        ("file", ("certify", "fig43-case-d", "-o", "{p}/sub/x.json"), "-o/--output"),
        ("none", ("certify", "fig43-case-d", "-o", "{p}/missing/x.json"), "-o/--output"),
        ("dir", ("certify", "fig43-case-d", "-o", "{p}/sub"), "-o/--output"),
        ("file", ("simulate", "pursuit-table1-n1", "--steps", "2", "-o", "{p}/sub"), "-o/--output"),
        ("file", ("pf", "pf-path3", "--runs", "1", "-o", "{p}/sub/deeper"), "-o/--out"),
        ("file", ("report", "fig43-case-d", "--only", "x", "-o", "{p}/sub"), "-o/--out"),
    ],
)
def test_bad_output_path_is_reported_against_the_option(make, args, field, tmp_path) -> None:
    if make == "file":
        (tmp_path / "sub").write_text("in the way")
    elif make == "dir":
        (tmp_path / "sub").mkdir()
    before = sorted(tmp_path.rglob("*"))
    output = refused(tuple(a.format(p=tmp_path) for a in args), field)
    assert "<command line>" in output and "<data>" not in output
    assert sorted(tmp_path.rglob("*")) == before


@pytest.mark.parametrize(
    "args",
    [
        ("simulate", "pursuit-table1-n1", "--runs", "1000000000"),
        ("simulate", "pursuit-table1-n1", "--steps", "1000000000"),
        ("pf", "pf-path3", "--runs", "1000000000"),
        ("falsify", "seed000.thm4.2.3", "--examples", "1000000000"),
    ],
)
def test_options_are_checked_against_the_limits(args, tmp_path) -> None:
    option = next(a for a in args if a.startswith("--"))
    out = tmp_path / "out"
    extra = ("-o", str(out)) if args[0] == "simulate" else ()
    output = refused((*args, *extra), option)
    assert f"TRACKCERT_MAX_{option[2:].upper()}" in " ".join(output.split())
    assert not out.exists()


def _changed(name: str, block: str, **values: object) -> dict:
    data = yaml.safe_load(bundled_cases()[name].read_text(encoding="utf-8"))
    data[block].update(values)
    return data


FIG43_AGENTS = [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]]
EXTREMES = [
    ("topology", _changed("fig43-case-d", "tdoa", T=1e300), "tdoa.T", "exponent"),
    ("dkf", _changed("ch5-example-1-wb", "dkf", A=[[1e300, 0], [0, 2]]), "dkf.A[1][1]", "exponent"),
    ("pf", _changed("pf-path3", "pf", noise_sigma=1e-300), "pf.noise_sigma", "exponent"),
    ("iss", _changed("pursuit-table1-n3", "pursuit", k_gamma=1e300), "pursuit.k_gamma", "exponent"),
    (
        "topology",
        _changed(
            "fig43-case-d", "tdoa", agents=[*FIG43_AGENTS[:2], [5e20, -1, 4], FIG43_AGENTS[3]]
        ),
        "tdoa.agents[3][1]",
        "coordinate",
    ),
]


@pytest.mark.parametrize(
    ("command", "data", "field", "limit"), EXTREMES, ids=[e[2] for e in EXTREMES]
)
def test_numbers_beyond_a_range_limit_are_refused(command, data, field, limit, tmp_path) -> None:
    """Squares of these overflow or underflow (an OverflowError, or an IndexError from particle
    weights that all underflowed to 0, before the ``exponent`` limit); a far agent made the
    others look coincident (before the ``coordinate`` limit and the per-pair coincidence rule)."""
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    assert f"limit '{limit}'" in " ".join(refused((command, str(path)), field).split())


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")
@pytest.mark.filterwarnings("ignore:invalid value encountered:RuntimeWarning")
def test_a_numerical_failure_inside_the_range_is_inconclusive(tmp_path) -> None:
    """A = 1e100·e₁e₁ᵀ + 2e₂e₂ᵀ is accepted, but its LMIs and SVDs fail in floating point: exit 3
    naming the failure (never a verdict, never a traceback)."""
    path = tmp_path / "case.yaml"
    data = _changed("ch5-example-1-wb", "dkf", A=[[1e100, 0], [0, 2]])
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    code, output = run("dkf", str(path))
    assert code in (1, 3), output
    if code == 3:
        assert "floating-point computation failed" in output


# --- the fuzzer -------------------------------------------------------------------------------

CASES = bundled_cases()
BY_KIND: dict[str, list[str]] = {}
for _name, _path in CASES.items():
    BY_KIND.setdefault(yaml.safe_load(_path.read_text(encoding="utf-8"))["kind"], []).append(_name)
COMMANDS = {
    "tdoa": [("topology",), ("certify",)],
    "dkf": [("dkf",)],
    "pursuit": [("iss",), ("certify",)],
    "pf": [("pf", "--runs", "1", "-o", "{out}")],
    "tdoa-sim": [
        ("simulate", "--steps", "2", "--runs", "1", "--workers", "1", "--no-figures", "-o", "{out}")
    ],
}
VALUES = [
    0,
    -1,
    0.5,
    1e-300,
    1e300,
    1e-100,
    1e100,
    1e9,
    2**31,
    10**400,
    1e308,
    -1e308,
    math.nan,
    math.inf,
    -math.inf,
    "text",
    None,
    True,
    [],
    {},
    [[1, 2], [3]],
]
DEEP = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]


def _paths(node: object, prefix: tuple = ()) -> list[tuple]:
    """Every path (tuple of keys / indices) in the parsed case, the root excluded."""
    out = []
    children = (
        node.items()
        if isinstance(node, dict)
        else enumerate(node)
        if isinstance(node, list)
        else ()
    )
    for key, child in children:
        out.append((*prefix, key))
        out.extend(_paths(child, (*prefix, key)))
    return out


def _mutate_data(data: dict, draw) -> dict:
    """One structural mutation at a random place of the parsed case."""
    paths = _paths(data)
    path = paths[draw(st.integers(0, len(paths) - 1))]
    *parents, last = path
    parent = data
    for key in parents:
        parent = parent[key]
    operation = draw(
        st.sampled_from(["delete", "value", "deep", "wrap", "unwrap", "alias", "extra"])
    )
    if operation == "delete":
        del parent[last]
    elif operation == "value":
        parent[last] = copy.deepcopy(draw(st.sampled_from(VALUES)))
    elif operation == "deep":
        parent[last] = copy.deepcopy(DEEP)
    elif operation == "wrap":
        parent[last] = [parent[last]]
    elif operation == "unwrap" and isinstance(parent[last], list) and parent[last]:
        parent[last] = parent[last][0]
    elif operation == "alias" and isinstance(parent[last], list):
        parent[last] = [parent[last]] * draw(st.sampled_from([2, 50, 5000]))  # shared: &id / *id
    elif operation == "extra" and isinstance(parent, dict):
        parent[f"unknown_{len(parent)}"] = 1
    return data


def _mutate_text(text: str, draw) -> bytes:
    """One textual mutation: a repeated line, a tag, garbage bytes or truncation."""
    lines = text.splitlines(keepends=True)
    k = draw(st.integers(0, max(len(lines) - 1, 0)))
    operation = draw(st.sampled_from(["none", "repeat", "tag", "garbage", "truncate", "none"]))
    if operation == "repeat" and lines:
        lines.insert(k, lines[k])
    elif operation == "tag" and lines and ": " in lines[k]:
        tag = draw(st.sampled_from(["!!python/object/apply:os.getcwd []", "!custom", "!!str"]))
        lines[k] = lines[k].replace(": ", f": {tag} ", 1)
    raw = "".join(lines).encode()
    at = draw(st.integers(0, len(raw)))
    if operation == "garbage":
        raw = raw[:at] + draw(st.binary(min_size=1, max_size=8)) + raw[at:]
    elif operation == "truncate":
        raw = raw[:at]
    return raw


def _check_run(args: tuple[str, ...], out: Path) -> None:
    code, output = run(*args)
    event(f"{args[0]}: exit {code}")  # --hypothesis-show-statistics
    if code == 2:
        assert FIELD.search(" ".join(output.split())), output
        assert not out.exists() or not any(out.iterdir()), "exit 2 but files were written"


FUZZ = settings(
    deadline=timedelta(seconds=60) if THOROUGH else None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


@FUZZ
@given(data=st.data())
def test_mutated_bundled_cases_get_an_exit_code(data) -> None:
    kind = data.draw(st.sampled_from(sorted(BY_KIND)), label="kind")
    name = data.draw(st.sampled_from(BY_KIND[kind]), label="case")
    text = CASES[name].read_text(encoding="utf-8")
    parsed = yaml.safe_load(text)
    for _ in range(data.draw(st.integers(0, 2), label="structural mutations")):
        parsed = _mutate_data(parsed, data.draw)
    raw = _mutate_text(yaml.safe_dump(parsed, sort_keys=False), data.draw)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "case.yaml"
        path.write_bytes(raw)
        for command in COMMANDS[kind]:
            out = Path(folder) / "out"
            args = tuple(a.format(out=out) for a in command)
            _check_run((args[0], str(path), *args[1:]), out)


def test_every_bundled_kind_is_fuzzed() -> None:
    assert set(BY_KIND) == set(COMMANDS)
