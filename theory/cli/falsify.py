"""``trackcert falsify CLAIM``: search for a counterexample to a claim, in each of its wordings.

A shell over :func:`theory.falsify.falsify`; exit code (:mod:`theory.core.verdicts`) 0 when no
wording has a counterexample in the budget, 1 when one has, 2 on bad input. Each result shows its
finding (``counterexample``, :class:`~theory.core.claims.Finding`); ``--list`` lists the
properties and the claims about one fixed instance, with the reason none can be searched.
"""

from __future__ import annotations

import typer
import yaml
from rich.markup import escape
from rich.table import Table

from theory.cli.common import (
    console,
    print_json,
    reports_errors,
    scheduler_option,
    workers_option,
)
from theory.core.errors import CaseError
from theory.core.parallel import default_workers, engine
from theory.core.validation import check_count
from theory.core.verdicts import exit_code
from theory.falsify import DEFAULT_EXAMPLES, FalsifyResult, falsify_each, fixed_instances
from theory.registry import all_properties, properties_for

__all__ = ["register"]


def register(app: typer.Typer) -> None:
    """Add the ``falsify`` command to ``app``."""

    @app.command("falsify")
    @reports_errors
    def falsify_command(
        claim: str = typer.Argument(None, help="A claim id, or one wording 'CLAIM/paper'."),
        examples: int = typer.Option(DEFAULT_EXAMPLES, "--examples", min=1, help="Search budget."),
        seed: int = typer.Option(0, "--seed", help="Seed of the search."),
        as_json: bool = typer.Option(False, "--json", help="Print JSON."),
        list_only: bool = typer.Option(False, "--list", help="List the claims it can run."),
        workers: int = workers_option(
            "Local worker processes, one wording per task (default: all cores; 1: serial)."
        ),
        scheduler: str = scheduler_option(),
    ) -> None:
        """Run hypothesis against a claim; print the shrunk counterexample as a case file."""
        if list_only:
            _list(as_json)
            return
        check_count("examples", examples, "--examples", file="<command line>")
        if claim is None:
            raise CaseError(
                "CLAIM",
                "a claim id (see 'trackcert falsify --list')",
                "nothing",
                file="<command line>",
            )
        try:
            props = properties_for(claim)
        except KeyError as error:
            raise CaseError(
                "CLAIM", "a claim id listed by 'trackcert falsify --list'", claim
            ) from error
        count = min(workers or default_workers(), len(props))
        with engine(count, scheduler) as runner:
            results = falsify_each(props, examples=examples, seed=seed, runner=runner)
        if as_json:
            print_json({"results": [_record(r) for r in results]})
        else:
            for result in results:
                _show(result)
        raise typer.Exit(exit_code(not any(r.found for r in results)))


def _record(result: FalsifyResult) -> dict:
    prop = result.property
    return {
        "property": prop.id,
        "claim": prop.claim,
        "wording": prop.wording,
        "statement": prop.statement,
        "expected_to_hold": prop.expected_to_hold,
        "examples": result.examples,
        "seed": result.seed,
        "found": result.found,
        "finding": None if result.finding is None else str(result.finding),
        "case": result.case,
    }


def _show(result: FalsifyResult) -> None:
    prop = result.property
    console.print(f"[bold]{prop.id}[/bold] ({prop.wording} wording): {escape(prop.statement)}")
    if not result.found:
        console.print(f"  no counterexample in {result.examples} examples (seed {result.seed})\n")
        return
    console.print(
        f"  finding: {result.finding} to the {prop.wording} wording "
        f"(shrunk; seed {result.seed}); rerun it as this case file:"
    )
    console.print(
        yaml.safe_dump(result.case, sort_keys=False, default_flow_style=None, allow_unicode=True),
        markup=False,
        highlight=False,
    )


def _list(as_json: bool) -> None:
    props, fixed = all_properties(), fixed_instances()
    if as_json:
        print_json(
            {
                "properties": [
                    {"id": p.id, "claim": p.claim, "wording": p.wording, "statement": p.statement}
                    for p in props
                ],
                "fixed_instances": [{"claim": f.claim, "reason": f.reason} for f in fixed],
            }
        )
        return
    table = Table(title="falsifiable claims")
    for column in ("property", "wording", "statement"):
        table.add_column(column)
    for prop in props:
        table.add_row(prop.id, prop.wording, escape(prop.statement))
    console.print(table)
    instances = Table(title="claims about one fixed instance (nothing to search)")
    for column in ("claim", "why not falsifiable"):
        instances.add_column(column)
    for mark in fixed:
        instances.add_row(mark.claim, escape(mark.reason))
    console.print(instances)
