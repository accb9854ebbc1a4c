"""``trackcert schema KIND [--write-docs DIR]``: a case kind's schema as JSON Schema, and its
generated reference page.

A shell over :mod:`theory.case_schemas` and :func:`theory.core.schema.reference_files`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from theory.cli.common import console, reports_errors
from theory.core.atomic_output import write_file
from theory.core.errors import COMMAND_LINE, CaseError

__all__ = ["register"]

EVERY = "all"


def register(app: typer.Typer) -> None:
    """Add the ``schema`` command to ``app``."""

    @app.command("schema")
    @reports_errors
    def schema(
        kind: Annotated[
            str, typer.Argument(help=f"Case kind (tdoa, tdoa-sim, dkf, pursuit, pf) or {EVERY}.")
        ],
        write_docs: Annotated[
            Path | None,
            typer.Option(
                "--write-docs",
                help="Write DIR/cases/KIND.md and DIR/schema/KIND.json instead of printing.",
            ),
        ] = None,
    ) -> None:
        """Print a case kind's JSON Schema, or write its reference page and schema file.

        With --write-docs DIR, writes DIR/cases/KIND.md (field, meaning, unit, default) and
        DIR/schema/KIND.json, each whole or not at all; KIND 'all' does every kind. Exit 0, or 2
        for an unknown kind or a folder that cannot be written.
        """
        from theory.case_schemas import SCHEMAS, kind_schema
        from theory.core.schema import json_text, reference_files

        kinds = list(SCHEMAS) if kind == EVERY else [kind]
        schemas = [kind_schema(k) for k in kinds]
        if write_docs is None:
            if len(schemas) != 1:
                raise CaseError(
                    "KIND", "one case kind (all only with --write-docs)", kind, file=COMMAND_LINE
                )
            console.file.write(json_text(schemas[0]))
            return
        files = {p: t for s in schemas for p, t in reference_files(s).items()}
        _check_folder(write_docs)
        for relative, text in files.items():
            target = write_docs / relative
            target.parent.mkdir(exist_ok=True)
            write_file(target, text)
            console.print(f"wrote {target}", markup=False, highlight=False)


def _check_folder(folder: Path) -> None:
    """Refuse, before writing, a --write-docs folder that is missing or holds files where the
    cases/ and schema/ folders go."""
    if not folder.is_dir():
        raise CaseError("--write-docs", "an existing folder", str(folder), file=COMMAND_LINE)
    for name in ("cases", "schema"):
        if (folder / name).exists() and not (folder / name).is_dir():
            raise CaseError(
                "--write-docs", f"a folder whose {name} is a folder", str(folder), file=COMMAND_LINE
            )
