"""Discovery by convention: claims, properties, case kinds and certificates are found by their
modules' file names, never by a hand-kept list (``theory.core.discovery``)."""

from __future__ import annotations

import inspect
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
from theory.core.discovery import ROLES, domain_packages, kind_index, role_modules

import theory
from theory.certify import certifiers
from theory.core import discovery
from theory.core.case_file import kind_spec, known_kinds
from theory.core.claims import all_claims, claim_modules

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
    "seed003.thm1",
    "seed003.thm2",
    "seed003.thm2.certified",
    "seed003.thm2.sim-trajectories",
)
"""The 64 claims registered when discovery replaced ``CLAIM_MODULES`` (each moved claim kept its
id)."""

ROOT = Path(theory.__file__).parent

REGISTRATIONS = {
    "claims": re.compile(r"^\s*@register\(|^\s*expectation_claim\(", re.M),
    "properties": re.compile(r"register_property\(", re.M),
    "case": re.compile(r"^register_kind\(", re.M),
    "certificates": re.compile(r"^@register_certifier\(", re.M),
}


def test_the_discovered_claims_are_exactly_the_registered_ones() -> None:
    assert tuple(c.id for c in all_claims()) == CLAIM_IDS
    assert len(CLAIM_IDS) == 64


def test_the_claim_modules_are_exactly_those_named_by_the_convention() -> None:
    assert set(claim_modules()) == set(role_modules("claims"))
    assert "theory.pursuit.observability" not in claim_modules()


@pytest.mark.parametrize("role", ROLES)
def test_every_module_that_registers_is_named_by_its_role(role: str) -> None:
    """Read every domain module's source: a registration outside a role module is a bug (the
    registry would miss it)."""
    found = set()
    for path in sorted(ROOT.glob("*/*.py")):
        if path.parent.name in discovery.SKIPPED_PACKAGES:
            continue
        if REGISTRATIONS[role].search(path.read_text(encoding="utf-8")):
            found.add(f"theory.{path.parent.name}.{path.stem}")
    allowed = set(role_modules(role))
    assert found <= allowed, sorted(found - allowed)
    assert found, f"no module registers {role}: the pattern is wrong"


def test_role_names_follow_the_file_name_convention() -> None:
    for role in ROLES:
        for module in role_modules(role):
            name = module.rpartition(".")[2]
            assert name == role or name.endswith(f"_{role}"), module
            assert module.split(".")[1] not in discovery.SKIPPED_PACKAGES
    assert "theory.cli" not in domain_packages() and "theory.core" not in domain_packages()


def test_unknown_role_is_refused() -> None:
    with pytest.raises(ValueError, match="role"):
        role_modules("claim")


def test_the_kind_index_read_from_source_matches_what_importing_registers() -> None:
    assert set(kind_index()) == set(known_kinds()) == {"dkf", "pf", "pursuit", "tdoa", "tdoa-sim"}
    assert kind_index()["tdoa-sim"] == "theory.tdoa.sim_case"


def test_a_kind_must_be_named_by_a_constant() -> None:
    source = "from x import register_kind\nregister_kind(make_name(), parse)\n"
    with pytest.raises(ValueError, match="string constant"):
        discovery._registered_kinds(source, "fake")
    named = "KIND = 'k'\nregister_kind(KIND, parse)\nregister_kind('other', parse)\n"
    assert discovery._registered_kinds(named, "fake") == ["k", "other"]


def test_every_kind_with_an_observer_resolves_it() -> None:
    for kind, spec in known_kinds().items():
        if spec.observe is not None:
            assert callable(spec.observer()), kind
    assert kind_spec("pf").observe is None  # its claims observe its keys


def test_certifiers_are_found_by_domain() -> None:
    found = certifiers()
    assert set(found) == {"tdoa", "dkf", "pursuit"}
    assert found["pursuit"][0].__module__ == "theory.pursuit.certificates"
    assert found["tdoa"][0].__module__ == "theory.tdoa.case_certificates"
    assert found["dkf"][0].__module__ == "theory.consensus.case_certificates"


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


def test_the_command_index_read_from_source_matches_what_registering_adds() -> None:
    """``trackcert`` loads commands lazily from :func:`theory.cli.command_index`: every command
    module registers exactly the commands its source declares, with the same help."""
    import importlib

    import typer

    from theory.cli import command_index, command_modules

    registered = {}
    for module in command_modules():
        app = typer.Typer()
        importlib.import_module(module).register(app)
        for info in app.registered_commands:
            registered[info.name] = (module, inspect.getdoc(info.callback))
    index = command_index()
    assert {name: (e.module, e.help) for name, e in index.items()} == registered
    assert {"simulate", "report", "check", "certify"} <= set(index)


def test_help_and_simulate_import_no_heavy_library() -> None:
    """``trackcert --help`` imports no command module; ``trackcert simulate`` of a TDOA case
    neither the report's libraries (jinja2, hypothesis, cvxpy) nor sympy."""
    script = (
        "import json, sys, tempfile\n"
        "from typer.testing import CliRunner\n"
        "from theory.cli import app, command_modules\n"
        "code = CliRunner().invoke(app, ['--help']).exit_code\n"
        "helped = [m for m in command_modules() if m in sys.modules]\n"
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
