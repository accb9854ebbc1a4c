"""Explicit registration: the claims, properties, case kinds, certifiers and commands are listed
by hand (each domain's ``registry`` module, :mod:`theory.registry`, :mod:`theory.kinds`,
:data:`theory.cli.COMMANDS`), and these lists are complete."""

from __future__ import annotations

import importlib
import inspect
import json
import subprocess
import sys
from pathlib import Path

import pytest
import typer

import theory
from theory.cli import COMMANDS
from theory.core.claims import ClaimSet
from theory.kinds import KINDS, SIMULATED, simulator
from theory.registry import all_claims, all_properties, certifiers, domains

CLAIM_IDS = (
    "case.expect.dkf",
    "case.expect.pursuit",
    "case.expect.tdoa",
    "case.expect.tdoa-sim",
    "seed000.appC.2",
    "seed000.cor4.2.4",
    "seed000.counterexample5.2",
    "seed000.def5.2.4",
    "seed000.def5.2.4.certified",
    "seed000.eq4.16.window",
    "seed000.eq4.20",
    "seed000.eq4.36.certified",
    "seed000.eq4.36.rank-sum",
    "seed000.eq4.6",
    "seed000.ex5.1",
    "seed000.ex5.2",
    "seed000.fn2",
    "seed000.fn5",
    "seed000.lem4.2.2",
    "seed000.lem5.2.2",
    "seed000.lem5.2.3",
    "seed000.lemA.1.1",
    "seed000.lemA.1.2",
    "seed000.lemA.2.1",
    "seed000.sec4.2.1.coplanar",
    "seed000.sec4.2.1.planar",
    "seed000.sec4.2.1.two-rows",
    "seed000.sec4.2.2.metropolis",
    "seed000.sec4.3.1.platonic",
    "seed000.sec4.3.1.uniform-array",
    "seed000.sec4.4.b-tradeoff",
    "seed000.sec5.3.sim-examples",
    "seed000.thm4.2.3",
    "seed000.thm4.2.3.heuristic",
    "seed000.thm4.2.3.network",
    "seed000.thm5.2.10",
    "seed000.thm5.2.10.blindset",
    "seed002.eq3.1",
    "seed002.eq3.17",
    "seed002.eq3.2",
    "seed002.fig3.6",
    "seed002.sec3.consensus",
    "seed002.sec3.convergence",
    "seed002.sec3.learning",
    "seed002.sec3.measurements",
    "seed002.sec4.pf_vs_ekf",
    "seed003.eq15.helix",
    "seed003.eq21",
    "seed003.eq22.delta-bar",
    "seed003.eq4",
    "seed003.eq70",
    "seed003.eq71",
    "seed003.eq72",
    "seed003.eq74",
    "seed003.eq75",
    "seed003.lem2",
    "seed003.lem3",
    "seed003.lem4",
    "seed003.result2",
    "seed003.result3",
    "seed003.sec6.published-statistics",
    "seed003.thm1",
    "seed003.thm2",
    "seed003.thm2.certified",
    "seed003.thm2.sim-trajectories",
)
"""The 65 claims registered (every claim kept its id through the move to explicit registries;
``seed003.sec6.published-statistics`` added by issue 27)."""

ROOT = Path(theory.__file__).parent


def test_the_registered_claims_are_exactly_the_known_ones() -> None:
    assert tuple(c.id for c in all_claims()) == CLAIM_IDS
    assert len(CLAIM_IDS) == 65


def _claim_sets() -> dict[str, ClaimSet]:
    """Every module-level ClaimSet of a domain module, read by importing every domain module."""
    found = {}
    for path in sorted(ROOT.glob("*/**/*.py")):
        parts = path.relative_to(ROOT.parent).with_suffix("").parts
        if parts[1] in ("cli",) or parts[-1] == "__main__":
            continue
        module = importlib.import_module(".".join(p for p in parts if p != "__init__"))
        for name, value in vars(module).items():
            if isinstance(value, ClaimSet) and value.__class__ is ClaimSet:
                found[f"{module.__name__}.{name}"] = value
    return found


def test_every_claim_set_is_listed_by_its_domain_registry() -> None:
    """A ClaimSet no registry lists would silently drop its claims from the report."""
    registered = {c.id for c in all_claims()}
    for name, claims in _claim_sets().items():
        missing = [c.id for c in claims if c.id not in registered]
        assert not missing, f"{name} is not listed by its domain's registry: {missing}"


def test_every_claim_lives_in_the_domain_of_its_registry() -> None:
    for domain in domains():
        package = domain.__name__.rpartition(".")[0]
        for claim in domain.CLAIMS:
            assert claim.check.__module__.startswith((package, "theory.core.")), claim.id


NAMED_BEFORE_REGISTRATION = {
    "seed000.sec5.2.detectability",
    "seed000.thm4.2.3.averaged-filter",
    "seed000.thm4.2.3.boundary-collinear",
    "seed000.thm4.2.3.boundary-mirror",
    "seed000.thm4.2.3.boundary-plane",
    "seed000.thm4.2.3.boundary-split",
    "seed000.thm4.2.3.invariance",
}
"""Property names that are not (yet) registered claim ids: statements searched by
``trackcert falsify`` that no report check states. The set may only shrink."""


def test_properties_name_registered_claims() -> None:
    ids = {c.id for c in all_claims()}
    props = all_properties()
    assert props, "no property registered"
    for prop in props:
        assert prop.claim in ids | NAMED_BEFORE_REGISTRATION, prop.id
        assert prop.id == f"{prop.id.rpartition('/')[0]}/{prop.wording}", prop.id
        assert prop.id.startswith(prop.claim), prop.id
    assert NAMED_BEFORE_REGISTRATION <= {p.claim for p in props} - ids


def test_the_kinds_are_the_five_case_blocks() -> None:
    assert list(KINDS) == ["dkf", "pf", "pursuit", "tdoa", "tdoa-sim"]
    for name, spec in KINDS.items():
        assert spec.name == name
    for kind in SIMULATED:
        assert callable(simulator(kind))
    with pytest.raises(ValueError, match="not simulated"):
        simulator("pf")


def test_certifiers_are_listed_by_domain() -> None:
    found = certifiers()
    assert set(found) == {"tdoa", "dkf", "pursuit"}
    for kind, builds in found.items():
        assert builds and all(callable(b) for b in builds), kind


def test_loading_a_tdoa_case_imports_neither_the_particle_filter_nor_the_solvers() -> None:
    """``trackcert topology`` stays cheap: only the tdoa kind module is imported."""
    script = (
        "import json, sys\n"
        "from typer.testing import CliRunner\n"
        "from theory.cli import app\n"
        "result = CliRunner().invoke(app, ['topology', 'fig43-case-d', '--json'])\n"
        "heavy = ['theory.particle.filter', 'theory.particle.case', 'cvxpy']\n"
        "print(json.dumps([result.exit_code, [m for m in heavy if m in sys.modules]]))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT.parent,
    )
    code, imported = json.loads(done.stdout.strip().splitlines()[-1])
    assert code == 0
    assert imported == []


def test_the_command_table_matches_what_the_modules_register() -> None:
    """Every command module registers exactly the commands :data:`COMMANDS` gives it, and the
    table's summary is the first line of the command's own help."""
    registered = {}
    for module in sorted({entry.module for entry in COMMANDS.values()}):
        app = typer.Typer()
        importlib.import_module(module).register(app)
        for info in app.registered_commands:
            help_text = info.help or inspect.getdoc(info.callback) or ""
            registered[info.name] = (module, help_text.splitlines()[0])
        for group in app.registered_groups:  # a sub-application such as ``design``
            help_text = group.help or group.typer_instance.info.help or ""
            registered[group.name] = (module, help_text.splitlines()[0])
    assert {name: (e.module, e.help) for name, e in COMMANDS.items()} == registered
    modules = {p.stem for p in (ROOT / "cli").glob("*.py")} - {"__init__", "__main__", "common"}
    assert {e.module.rpartition(".")[2] for e in COMMANDS.values()} == modules


def test_help_and_simulate_import_no_heavy_library() -> None:
    """``trackcert --help`` imports no command module; ``trackcert simulate`` of a TDOA case
    neither the report's libraries (jinja2, hypothesis, cvxpy) nor sympy."""
    script = (
        "import json, sys, tempfile\n"
        "from typer.testing import CliRunner\n"
        "from theory.cli import app, COMMANDS\n"
        "code = CliRunner().invoke(app, ['--help']).exit_code\n"
        "helped = sorted({e.module for e in COMMANDS.values()} & set(sys.modules))\n"
        "out = tempfile.mkdtemp()\n"
        "args = ['simulate', 'sim-ch4-fixed-b5', '--steps', '3', '--no-figures', '-o', out]\n"
        "simulated = CliRunner().invoke(app, args).exit_code\n"
        "heavy = ['jinja2', 'hypothesis', 'cvxpy', 'sympy', 'theory.cli.report']\n"
        "print(json.dumps([code, helped, simulated, [m for m in heavy if m in sys.modules]]))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True, cwd=ROOT.parent
    )
    code, helped, simulated, imported = json.loads(done.stdout.strip().splitlines()[-1])
    assert (code, helped, simulated, imported) == (0, [], 0, [])
